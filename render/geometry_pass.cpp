#include "render/geometry_pass.h"

#include <glm/gtc/type_ptr.hpp>

#include "gl/context.h"
#include "glsl/variants.h"

namespace manylight {

using namespace gl::api;

namespace {

// The G-buffer program's texture slots, in Material::slot order; slot k samples unit k.
constexpr const char* kSlotNames[Material::kTextureSlots] = {
    "uBaseColourSlot", "uMetalRoughSlot", "uNormalSlot", "uOcclusionSlot", "uEmissiveSlot"};
constexpr const char* kSamplerNames[Material::kTextureSlots] = {
    "uBaseColourTexture", "uMetalRoughTexture", "uNormalTexture", "uOcclusionTexture",
    "uEmissiveTexture"};

// Points are drawn this many pixels wide (glTF gives points no size; one pixel is what the
// Khronos glTF Sample Viewer draws).
constexpr float kPointSize = 1.0f;

}  // namespace

GeometryPass::GeometryPass(Aov aov)
    : aov_(aov),
      program_(gl::cachedProgram("gbuffer.vert", "gbuffer.frag", glsl::gbufferDefines(aov),
                                 {"gPosition", "gNormal", "gAlbedo", "gSpecular", "gRadiance"})) {
  const gl::Program& p = program_;
  viewProjection_ = p.uniform("uViewProjection");
  ambient_ = p.uniform("uAmbient");
  model_ = p.uniform("uModel");
  normalMatrix_ = p.uniform("uNormalMatrix");
  baseColorFactor_ = p.uniform("uBaseColorFactor");
  metallic_ = p.uniform("uMetallic");
  roughness_ = p.uniform("uRoughness");
  emissive_ = p.uniform("uEmissive");
  normalScale_ = p.uniform("uNormalScale");
  occlusionStrength_ = p.uniform("uOcclusionStrength");
  alphaCutoff_ = p.uniform("uAlphaCutoff");
  unlit_ = p.uniform("uUnlit");
  opaque_ = p.uniform("uOpaque");  // -1 (ignored) in the lit program, which reads no alpha
  doubleSided_ = p.uniform("uDoubleSided");
  mirrored_ = p.uniform("uMirrored");
  pointSize_ = p.uniform("uPointSize");
  specularGlossiness_ = p.uniform("uSpecularGlossiness");
  specularFactor_ = p.uniform("uSpecularFactor");
  glossiness_ = p.uniform("uGlossiness");
  p.use();
  for (int k = 0; k < Material::kTextureSlots; ++k) {
    const std::string slot = kSlotNames[k];
    slots_[k] = {p.uniform((slot + ".bound").c_str()), p.uniform((slot + ".secondSet").c_str()),
                 p.uniform((slot + ".transform").c_str())};
    glUniform1i(p.uniform(kSamplerNames[k]), k);
  }
}

void GeometryPass::setMaterial(const Material& m, const GpuScene& gpu,
                               const GpuScene::Draw& d) const {
  glUniform4fv(baseColorFactor_, 1, glm::value_ptr(m.baseColorFactor));
  glUniform1f(metallic_, m.metallic);
  glUniform1f(roughness_, m.roughness);
  glUniform3fv(emissive_, 1, glm::value_ptr(m.emissive));
  glUniform1f(normalScale_, m.normalScale);
  glUniform1f(occlusionStrength_, m.occlusionStrength);
  glUniform1f(alphaCutoff_, m.alphaMode == AlphaMode::Mask ? m.alphaCutoff : -1.0f);
  // Points and lines without normals show their base colour, as glTF says.
  glUniform1i(unlit_, m.unlit || !d.hasNormals ? 1 : 0);
  glUniform1i(opaque_, m.alphaMode == AlphaMode::Opaque ? 1 : 0);
  glUniform1i(doubleSided_, m.doubleSided ? 1 : 0);
  glUniform1i(specularGlossiness_, m.specularGlossiness ? 1 : 0);
  glUniform3fv(specularFactor_, 1, glm::value_ptr(m.specularFactor));
  glUniform1f(glossiness_, m.glossiness);
  for (int k = 0; k < Material::kTextureSlots; ++k) {
    const TextureRef& t = m.slot(k);
    const bool hasUvs = t.texCoord == 1 ? d.hasTexcoords1 : d.hasTexcoords;
    const bool bound = t.texture >= 0 && hasUvs;
    glUniform1i(slots_[k].bound, bound ? 1 : 0);
    if (!bound) continue;
    glUniform1i(slots_[k].secondSet, t.texCoord == 1 ? 1 : 0);
    glUniformMatrix3fv(slots_[k].transform, 1, GL_FALSE, glm::value_ptr(t.transform));
    glActiveTexture(GL_TEXTURE0 + k);
    glBindTexture(GL_TEXTURE_2D, gpu.texture(t.texture)->id());
  }
  glActiveTexture(GL_TEXTURE0);
}

void GeometryPass::draw(const Scene& scene, const GpuScene& gpu, const GBuffer& gbuffer,
                        const View& view, glm::vec3 ambient, int only) const {
  glBindFramebuffer(GL_FRAMEBUFFER, gbuffer.geometryFramebuffer().id());
  glViewport(0, 0, gbuffer.width(), gbuffer.height());
  const float zero[4] = {0, 0, 0, 0};
  for (int i = 0; i < GBuffer::kTargetCount; ++i) glClearBufferfv(GL_COLOR, i, zero);
  glDepthMask(GL_TRUE);
  if (only < 0) glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glCullFace(GL_BACK);
  glEnable(GL_PROGRAM_POINT_SIZE);

  program_.use();
  const glm::mat4 viewProjection = view.projection * view.view;
  glUniformMatrix4fv(viewProjection_, 1, GL_FALSE, glm::value_ptr(viewProjection));
  glUniform3fv(ambient_, 1, glm::value_ptr(ambient));
  glUniform1f(pointSize_, kPointSize);
  const Material fallback = defaultMaterial();
  for (std::size_t i = 0; i < gpu.draws().size(); ++i) {
    const GpuScene::Draw& d = gpu.draws()[i];
    const bool skip = only == kOpaque ? d.blended : only == kAll ? false : int(i) != only;
    if (skip) continue;
    const Material& m = d.material >= 0 ? scene.materials[d.material] : fallback;
    glUniformMatrix4fv(model_, 1, GL_FALSE, glm::value_ptr(d.model));
    glUniformMatrix3fv(normalMatrix_, 1, GL_FALSE, glm::value_ptr(d.normalMatrix));
    glUniform1i(mirrored_, d.mirrored ? 1 : 0);
    setMaterial(m, gpu, d);
    if (m.doubleSided || d.mode != GL_TRIANGLES) {
      glDisable(GL_CULL_FACE);
    } else {
      glEnable(GL_CULL_FACE);
    }
    glFrontFace(d.mirrored ? GL_CW : GL_CCW);
    // Absent attributes read these constants.
    if (!d.hasNormals) glVertexAttrib4f(1, 0.0f, 0.0f, 1.0f, 0.0f);
    if (!d.hasTexcoords) glVertexAttrib4f(2, 0.0f, 0.0f, 0.0f, 1.0f);
    if (!d.hasColours) glVertexAttrib4f(3, 1.0f, 1.0f, 1.0f, 1.0f);
    if (!d.hasTexcoords1) glVertexAttrib4f(4, 0.0f, 0.0f, 0.0f, 1.0f);
    if (!d.hasTangents) glVertexAttrib4f(5, 0.0f, 0.0f, 0.0f, 0.0f);
    glBindVertexArray(d.vao->id());
    glDrawElements(d.mode, d.indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glFrontFace(GL_CCW);
  glDisable(GL_CULL_FACE);
  glDisable(GL_PROGRAM_POINT_SIZE);
}

}  // namespace manylight
