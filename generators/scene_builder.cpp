#include "generators/scene_builder.h"

#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/quaternion.hpp>

#include "base/error.h"
#include "scene/image_io.h"

namespace manylight {

struct GltfBuilder::Impl {
  tinygltf::Model model;
  std::vector<unsigned char> bytes;

  int addView(const void* data, std::size_t size, int target) {
    while (bytes.size() % 4) bytes.push_back(0);
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = bytes.size();
    v.byteLength = size;
    v.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    bytes.insert(bytes.end(), p, p + size);
    model.bufferViews.push_back(v);
    return int(model.bufferViews.size()) - 1;
  }

  int addAccessor(const void* data, std::size_t count, int type, int components, int target,
                  bool bounds = false) {
    tinygltf::Accessor a;
    a.bufferView = addView(data, count * components * 4, target);
    a.componentType = type;
    a.count = count;
    a.type = components == 1   ? TINYGLTF_TYPE_SCALAR
             : components == 2 ? TINYGLTF_TYPE_VEC2
                               : TINYGLTF_TYPE_VEC3;
    if (bounds) {
      const float* f = static_cast<const float*>(data);
      a.minValues.assign(3, 1e30);
      a.maxValues.assign(3, -1e30);
      for (std::size_t i = 0; i < count; ++i) {
        for (int c = 0; c < 3; ++c) {
          a.minValues[c] = std::min(a.minValues[c], double(f[i * 3 + c]));
          a.maxValues[c] = std::max(a.maxValues[c], double(f[i * 3 + c]));
        }
      }
    }
    model.accessors.push_back(a);
    return int(model.accessors.size()) - 1;
  }

  // A PNG image, a LINEAR / REPEAT sampler and a texture of them; returns the texture.
  int addTexture(const BuilderTexture& t) {
    const RawImage<std::uint8_t> pixels{t.width, t.height, 4, t.rgba};
    std::vector<unsigned char> png;
    std::string error;
    if (!imageIo().encodePng8(pixels, &png, &error))
      throw SceneError("cannot encode texture: " + error);
    tinygltf::Image img;
    img.bufferView = addView(png.data(), png.size(), 0);
    img.mimeType = "image/png";
    model.images.push_back(img);
    tinygltf::Sampler s;
    s.magFilter = t.nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
    s.minFilter = t.nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
    s.wrapS = s.wrapT = TINYGLTF_TEXTURE_WRAP_REPEAT;
    model.samplers.push_back(s);
    tinygltf::Texture tex;
    tex.source = int(model.images.size()) - 1;
    tex.sampler = int(model.samplers.size()) - 1;
    model.textures.push_back(tex);
    return int(model.textures.size()) - 1;
  }

  // KHR_materials_pbrSpecularGlossiness of `m`, its textures added.
  tinygltf::Value specularGlossiness(const BuilderMaterial& m) {
    auto numbers = [](std::initializer_list<float> v) {
      tinygltf::Value::Array a;
      for (float x : v) a.emplace_back(double(x));
      return tinygltf::Value(a);
    };
    auto texture = [&](const BuilderTexture& t) {
      tinygltf::Value::Object o;
      o["index"] = tinygltf::Value(addTexture(t));
      return tinygltf::Value(o);
    };
    tinygltf::Value::Object x;
    const glm::vec4 d = m.baseColor;
    x["diffuseFactor"] = numbers({d.r, d.g, d.b, d.a});
    x["specularFactor"] = numbers({m.specularFactor.r, m.specularFactor.g, m.specularFactor.b});
    x["glossinessFactor"] = tinygltf::Value(double(m.glossiness));
    if (!m.textureRgba.empty()) {
      BuilderTexture base;
      base.width = m.textureWidth, base.height = m.textureHeight, base.rgba = m.textureRgba;
      x["diffuseTexture"] = texture(base);
    }
    if (!m.specularGlossinessTexture.rgba.empty())
      x["specularGlossinessTexture"] = texture(m.specularGlossinessTexture);
    use("KHR_materials_pbrSpecularGlossiness");
    return tinygltf::Value(x);
  }

  // Lists `extension` in extensionsUsed and extensionsRequired, once.
  void use(const std::string& extension) {
    auto& used = model.extensionsUsed;
    if (std::find(used.begin(), used.end(), extension) != used.end()) return;
    used.push_back(extension);
    model.extensionsRequired.push_back(extension);
  }

  int addMesh(const std::vector<glm::vec3>& pos, const std::vector<glm::vec3>& nrm,
              const std::vector<glm::vec2>& uv, const std::vector<std::uint32_t>& idx, int material,
              const std::vector<glm::vec2>& uv1 = {}) {
    tinygltf::Primitive p;
    if (!uv1.empty())
      p.attributes["TEXCOORD_1"] = addAccessor(
          uv1.data(), uv1.size(), TINYGLTF_COMPONENT_TYPE_FLOAT, 2, TINYGLTF_TARGET_ARRAY_BUFFER);
    p.attributes["POSITION"] = addAccessor(pos.data(), pos.size(), TINYGLTF_COMPONENT_TYPE_FLOAT, 3,
                                           TINYGLTF_TARGET_ARRAY_BUFFER, true);
    p.attributes["NORMAL"] = addAccessor(nrm.data(), nrm.size(), TINYGLTF_COMPONENT_TYPE_FLOAT, 3,
                                         TINYGLTF_TARGET_ARRAY_BUFFER);
    p.attributes["TEXCOORD_0"] = addAccessor(uv.data(), uv.size(), TINYGLTF_COMPONENT_TYPE_FLOAT, 2,
                                             TINYGLTF_TARGET_ARRAY_BUFFER);
    p.indices = addAccessor(idx.data(), idx.size(), TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, 1,
                            TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    p.material = material;
    p.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh m;
    m.primitives.push_back(p);
    model.meshes.push_back(m);
    return int(model.meshes.size()) - 1;
  }

  int addNode(int mesh, glm::vec3 t, glm::vec3 s, glm::vec4 r = {0, 0, 0, 1}) {
    tinygltf::Node n;
    n.mesh = mesh;
    n.translation = {t.x, t.y, t.z};
    n.scale = {s.x, s.y, s.z};
    if (r != glm::vec4(0, 0, 0, 1)) n.rotation = {r.x, r.y, r.z, r.w};
    return pushNode(n);
  }

  int pushNode(const tinygltf::Node& n) {
    model.nodes.push_back(n);
    const int index = int(model.nodes.size()) - 1;
    model.scenes[0].nodes.push_back(index);
    return index;
  }

  // Node placed at `eye` looking at `target` (glTF nodes look down −Z).
  int addLookAtNode(glm::vec3 eye, glm::vec3 forward) {
    tinygltf::Node n;
    forward = glm::normalize(forward);
    const glm::vec3 from(0.0f, 0.0f, -1.0f);
    glm::dquat q;
    const float d = glm::dot(from, forward);
    if (d < -0.999999f) {
      q = glm::dquat(0.0, 0.0, 1.0, 0.0);  // 180° about Y
    } else {
      const glm::vec3 axis = glm::cross(from, forward);
      q = glm::normalize(glm::dquat(1.0 + d, axis.x, axis.y, axis.z));
    }
    n.translation = {eye.x, eye.y, eye.z};
    n.rotation = {q.x, q.y, q.z, q.w};
    return pushNode(n);
  }
};

GltfBuilder::GltfBuilder() : impl_(std::make_unique<Impl>()) {
  impl_->model.asset.version = "2.0";
  impl_->model.asset.generator = "manylight scene builder";
  impl_->model.scenes.emplace_back();
  impl_->model.defaultScene = 0;
}
GltfBuilder::~GltfBuilder() = default;

int GltfBuilder::addMaterial(const BuilderMaterial& m) {
  tinygltf::Material mat;
  mat.pbrMetallicRoughness.baseColorFactor = {m.baseColor.r, m.baseColor.g, m.baseColor.b,
                                              m.baseColor.a};
  mat.pbrMetallicRoughness.metallicFactor = m.metallic;
  mat.pbrMetallicRoughness.roughnessFactor = m.roughness;
  mat.emissiveFactor = {m.emissive.r, m.emissive.g, m.emissive.b};
  mat.doubleSided = m.doubleSided;
  mat.alphaMode = m.alphaMode;
  mat.alphaCutoff = m.alphaCutoff;
  BuilderTexture base;
  base.width = m.textureWidth, base.height = m.textureHeight, base.rgba = m.textureRgba;
  base.nearest = m.textureNearest;
  auto info = [&](const BuilderTexture& t, auto& out) {
    if (t.rgba.empty()) return;
    out.index = impl_->addTexture(t);
    out.texCoord = t.texCoord;
    if (t.transform) {
      tinygltf::Value::Object x;
      x["offset"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(double(t.offset.x)),
                                                           tinygltf::Value(double(t.offset.y))});
      x["scale"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(double(t.scale.x)),
                                                          tinygltf::Value(double(t.scale.y))});
      x["rotation"] = tinygltf::Value(double(t.rotation));
      out.extensions["KHR_texture_transform"] = tinygltf::Value(x);
      impl_->use("KHR_texture_transform");
    }
  };
  info(base, mat.pbrMetallicRoughness.baseColorTexture);
  info(m.metallicRoughness, mat.pbrMetallicRoughness.metallicRoughnessTexture);
  info(m.normal, mat.normalTexture);
  mat.normalTexture.scale = m.normalScale;
  info(m.occlusion, mat.occlusionTexture);
  mat.occlusionTexture.strength = m.occlusionStrength;
  info(m.emissiveTexture, mat.emissiveTexture);
  if (m.emissiveStrength != 1.0f) {
    tinygltf::Value::Object x;
    x["emissiveStrength"] = tinygltf::Value(double(m.emissiveStrength));
    mat.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(x);
    impl_->use("KHR_materials_emissive_strength");
  }
  if (m.unlit) {
    mat.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object{});
    impl_->use("KHR_materials_unlit");
  }
  if (m.specularGlossiness)
    mat.extensions["KHR_materials_pbrSpecularGlossiness"] = impl_->specularGlossiness(m);
  impl_->model.materials.push_back(mat);
  return int(impl_->model.materials.size()) - 1;
}

int GltfBuilder::addBox(glm::vec3 centre, glm::vec3 size, int material, glm::vec4 rotation) {
  std::vector<glm::vec3> pos, nrm;
  std::vector<glm::vec2> uv;
  std::vector<std::uint32_t> idx;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign = -1; sign <= 1; sign += 2) {
      glm::vec3 n(0.0f);
      n[axis] = float(sign);
      const glm::vec3 u = glm::vec3(n.y, n.z, n.x) * 1.0f;  // a tangent
      const glm::vec3 v = glm::cross(n, u);
      const auto base = std::uint32_t(pos.size());
      const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const glm::vec2& c : corners) {
        pos.push_back(0.5f * (n + c.x * u + c.y * v));
        nrm.push_back(n);
        uv.push_back(0.5f * (c + 1.0f));
      }
      idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  }
  // Each shape gets its own mesh, so each primitive keeps its own material.
  const int mesh = impl_->addMesh(pos, nrm, uv, idx, material);
  return impl_->addNode(mesh, centre, size, rotation);
}

int GltfBuilder::addSphere(glm::vec3 centre, float diameter, int material, int segments) {
  std::vector<glm::vec3> pos, nrm;
  std::vector<glm::vec2> uv;
  std::vector<std::uint32_t> idx;
  const int rings = segments / 2;
  for (int r = 0; r <= rings; ++r) {
    const float theta = float(M_PI) * r / rings;
    for (int s = 0; s <= segments; ++s) {
      const float phi = 2.0f * float(M_PI) * s / segments;
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
      pos.push_back(0.5f * n);
      nrm.push_back(n);
      uv.push_back({float(s) / segments, float(r) / rings});
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const auto a = std::uint32_t(r * (segments + 1) + s), b = a + segments + 1;
      if (r != 0) idx.insert(idx.end(), {a, a + 1, b});
      if (r != rings - 1) idx.insert(idx.end(), {a + 1, b + 1, b});
    }
  }
  const int mesh = impl_->addMesh(pos, nrm, uv, idx, material);
  return impl_->addNode(mesh, centre, glm::vec3(diameter));
}

int GltfBuilder::addPlane(glm::vec3 centre, glm::vec2 size, int material) {
  const std::vector<glm::vec3> pos = {
      {-0.5f, 0, 0.5f}, {0.5f, 0, 0.5f}, {0.5f, 0, -0.5f}, {-0.5f, 0, -0.5f}};
  const std::vector<glm::vec3> nrm(4, glm::vec3(0, 1, 0));
  const std::vector<glm::vec2> uv = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 2, 3};
  const int mesh = impl_->addMesh(pos, nrm, uv, idx, material);
  return impl_->addNode(mesh, centre, glm::vec3(size.x, 1.0f, size.y));
}

int GltfBuilder::addPlaneWithSecondUvs(glm::vec3 centre, glm::vec2 size, int material) {
  const std::vector<glm::vec3> pos = {
      {-0.5f, 0, 0.5f}, {0.5f, 0, 0.5f}, {0.5f, 0, -0.5f}, {-0.5f, 0, -0.5f}};
  const std::vector<glm::vec3> nrm(4, glm::vec3(0, 1, 0));
  const std::vector<glm::vec2> uv = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  const std::vector<glm::vec2> uv1 = {{1, 1}, {0, 1}, {0, 0}, {1, 0}};
  const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 2, 3};
  const int mesh = impl_->addMesh(pos, nrm, uv, idx, material, uv1);
  return impl_->addNode(mesh, centre, glm::vec3(size.x, 1.0f, size.y));
}

void GltfBuilder::addLight(const Light& light) {
  tinygltf::Light l;
  l.type = light.type == LightType::Point  ? "point"
           : light.type == LightType::Spot ? "spot"
                                           : "directional";
  l.color = {light.colour.r, light.colour.g, light.colour.b};
  l.intensity = light.intensity;
  l.range = light.type == LightType::Directional ? 0.0 : light.range;
  if (light.type == LightType::Spot) {
    l.spot.innerConeAngle = light.innerConeAngle;
    l.spot.outerConeAngle = light.outerConeAngle;
  }
  auto& m = impl_->model;
  m.lights.push_back(l);
  const int node = impl_->addLookAtNode(light.position, light.direction);
  tinygltf::Value::Object ext;
  ext["light"] = tinygltf::Value(int(m.lights.size()) - 1);
  m.nodes[node].extensions["KHR_lights_punctual"] = tinygltf::Value(ext);
  if (m.extensionsUsed.empty()) m.extensionsUsed.push_back("KHR_lights_punctual");
}

void GltfBuilder::addPerspectiveCamera(glm::vec3 eye, glm::vec3 target, float yfov) {
  tinygltf::Camera c;
  c.type = "perspective";
  c.perspective.yfov = yfov;
  c.perspective.znear = 0.05;
  c.perspective.zfar = 100.0;
  c.perspective.aspectRatio = 0.0;
  impl_->model.cameras.push_back(c);
  const int node = impl_->addLookAtNode(eye, target - eye);
  impl_->model.nodes[node].camera = int(impl_->model.cameras.size()) - 1;
}

void GltfBuilder::addOrthographicCamera(glm::vec3 eye, glm::vec3 target, float xmag, float ymag) {
  tinygltf::Camera c;
  c.type = "orthographic";
  c.orthographic.xmag = xmag;
  c.orthographic.ymag = ymag;
  c.orthographic.znear = 0.05;
  c.orthographic.zfar = 100.0;
  impl_->model.cameras.push_back(c);
  const int node = impl_->addLookAtNode(eye, target - eye);
  impl_->model.nodes[node].camera = int(impl_->model.cameras.size()) - 1;
}

void GltfBuilder::write(const std::string& path) const {
  tinygltf::Model model = impl_->model;
  tinygltf::Buffer buffer;
  buffer.data = impl_->bytes;
  model.buffers.push_back(buffer);
  const bool binary = std::filesystem::path(path).extension() == ".glb";
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&model, path, true, true, true, binary)) {
    throw SceneError(path + ": cannot write glTF");
  }
}

}  // namespace manylight
