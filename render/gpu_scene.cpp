#include "render/gpu_scene.h"

#include <array>

#include "bake/light_pack.h"
#include "bake/light_texture_layout.h"
#include "gl/context.h"
#include "gl/texture_buffer.h"
#include "image/image.h"
#include "scene/shading_model.h"

namespace manylight {

using namespace gl::api;

namespace {

template <typename T>
gl::Buffer uploadAttribute(const std::vector<T>& data, GLuint location, GLint components) {
  gl::Buffer buffer;
  glBindBuffer(GL_ARRAY_BUFFER, buffer.id());
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(T)), data.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, 0, nullptr);
  return buffer;
}

gl::Texture uploadTexture(const Texture& t) {
  gl::Texture tex;
  glBindTexture(GL_TEXTURE_2D, tex.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (t.srgb) {
    // Decoded from sRGB on the CPU with the exact curve (drivers' sRGB samplers approximate
    // it: llvmpipe is off by up to 1% in dark codes), stored as half floats (relative error
    // <= 2^-11), so filtering and mipmaps work on linear values.
    static const std::array<float, 256> kLinear = [] {
      std::array<float, 256> table{};
      for (int i = 0; i < 256; ++i) table[i] = float(decodeSrgb8(std::uint8_t(i)));
      return table;
    }();
    std::vector<float> linear(t.rgba.size());
    for (std::size_t i = 0; i < t.rgba.size(); ++i) {
      linear[i] = (i % 4 == 3) ? t.rgba[i] / 255.0f : kLinear[t.rgba[i]];
    }
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, t.width, t.height, 0, GL_RGBA, GL_FLOAT,
                 linear.data());
  } else {
    // Data (normals, metallic-roughness, occlusion) is linear: stored as 16-bit codes
    // c · 257, which the sampler reads as c / 255 exactly (a half float would move a
    // roughness by up to 2^-11 relative, and a Phong exponent by four times that; 8-bit
    // storage is exact too, but llvmpipe filters it in 8-bit steps).
    std::vector<std::uint16_t> wide(t.rgba.begin(), t.rgba.end());
    for (std::uint16_t& c : wide) c = std::uint16_t(c * 257);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16, t.width, t.height, 0, GL_RGBA, GL_UNSIGNED_SHORT,
                 wide.data());
  }
  auto wrap = [](bool repeat, bool mirror) {
    return GLint(mirror ? GL_MIRRORED_REPEAT : repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE);
  };
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap(t.repeatS, t.mirrorS));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap(t.repeatT, t.mirrorT));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, t.linearMag ? GL_LINEAR : GL_NEAREST);
  GLint minFilter = t.linearMin ? GL_LINEAR : GL_NEAREST;
  if (t.mipmaps) {
    minFilter = t.linearMin ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR;
    glGenerateMipmap(GL_TEXTURE_2D);
  }
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, minFilter);
  return tex;
}

}  // namespace

GpuScene::GpuScene(const Scene& scene, const std::vector<Light>& lights) {
  for (const Mesh& mesh : scene.meshes) {
    std::vector<GpuPrimitive>& prims = meshes_.emplace_back();
    for (const Primitive& p : mesh.primitives) {
      GpuPrimitive& g = prims.emplace_back();
      glBindVertexArray(g.vao.id());
      g.buffers.push_back(uploadAttribute(p.positions, 0, 3));
      g.hasNormals = !p.normals.empty();
      g.hasTexcoords = !p.texcoords.empty();
      g.hasColours = !p.colours.empty();
      g.hasTexcoords1 = !p.texcoords1.empty();
      g.hasTangents = !p.tangents.empty();
      if (g.hasNormals) g.buffers.push_back(uploadAttribute(p.normals, 1, 3));
      if (g.hasTexcoords) g.buffers.push_back(uploadAttribute(p.texcoords, 2, 2));
      if (g.hasColours) g.buffers.push_back(uploadAttribute(p.colours, 3, 4));
      if (g.hasTexcoords1) g.buffers.push_back(uploadAttribute(p.texcoords1, 4, 2));
      if (g.hasTangents) g.buffers.push_back(uploadAttribute(p.tangents, 5, 4));
      g.mode = p.mode == PrimitiveMode::Points  ? GL_POINTS
               : p.mode == PrimitiveMode::Lines ? GL_LINES
                                                : GL_TRIANGLES;
      gl::Buffer& indices = g.buffers.emplace_back();
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices.id());
      glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(p.indices.size() * 4), p.indices.data(),
                   GL_STATIC_DRAW);
      g.indexCount = GLsizei(p.indices.size());
      g.material = p.material;
      Bounds b;
      for (const glm::vec3& v : p.positions) b.add(v);
      g.centre = 0.5f * (b.min + b.max);
    }
  }
  glBindVertexArray(0);
  for (const Texture& t : scene.textures) textures_.push_back(uploadTexture(t));
  for (const MeshInstance& inst : scene.instances) {
    for (const GpuPrimitive& g : meshes_[inst.mesh]) {
      if (g.material >= 0) {
        const Material& m = scene.materials[g.material];
        // A metallic-roughness texture can lower the roughness below its factor's.
        const bool mapped = m.metallicRoughnessTexture.texture >= 0;
        const bool specular = m.specularGlossiness
                                  ? m.specularFactor != glm::vec3(0.0f)
                                  : mapped || shading::hasSpecularTerm(m.metallic, m.roughness);
        hasSpecular_ = hasSpecular_ || (!m.unlit && specular);
      }
      const glm::mat3 linear(inst.world);
      const bool blended =
          g.material >= 0 && scene.materials[g.material].alphaMode == AlphaMode::Blend;
      hasBlended_ = hasBlended_ || blended;
      draws_.push_back({&g.vao, g.indexCount, g.mode, g.hasNormals, g.hasTexcoords, g.hasTexcoords1,
                        g.hasTangents, g.hasColours, g.material, inst.world,
                        glm::transpose(glm::inverse(linear)), glm::determinant(linear) < 0.0f,
                        blended, glm::vec3(inst.world * glm::vec4(g.centre, 1.0f))});
    }
  }

  replaceLights(lights);
}

void GpuScene::replaceLights(const std::vector<Light>& lights) {
  // The light texture holds exactly the scene's lights (one zero light when there are none,
  // so the sampler is always complete).
  PackedLights packedLights = packLights(lights);
  auto& packed = packedLights.texels;
  const std::size_t texels = std::max<std::size_t>(lights.size(), 1) * layout::kTexelsPerLight;
  packed.resize(texels * 4, 0.0f);
  pointStart_ = packedLights.pointStart;
  spotStart_ = packedLights.spotStart;
  lightTexture_ = gl::uploadTextureBuffer(packed.data(), texels, GL_RGBA32F,
                                          std::to_string(lights.size()) + " lights");
  lightCount_ = int(lights.size());
}

}  // namespace manylight
