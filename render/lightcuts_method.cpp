#include "render/lightcuts_method.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "gl/context.h"
#include "gl/texture_buffer.h"
#include "glsl/variants.h"
#include "render/lighting_inputs.h"

namespace manylight {

using namespace gl::api;

LightcutsMethod::LightcutsMethod(PackedTrees packed, const std::vector<Light>& lights,
                                 const GBuffer& gbuffer, bool distance)
    : distance_(distance), width_(gbuffer.width()), height_(gbuffer.height()) {
  auto& words = packed.words;
  const std::size_t nodeWords = words.size();
  if (words.empty()) words.assign(4, 0u);  // no lights: keep the sampler complete
  nodes_ = gl::uploadTextureBuffer(words.data(), words.size() / 4, GL_RGBA32UI,
                                   "light trees of " + std::to_string(nodeWords) + " words");
  std::copy(packed.base, packed.base + 3, layout_.base);
  std::copy(packed.leaves, packed.leaves + 3, layout_.leaves);
  layout_.colour = packed.colour;
  // The tile cutter keeps the words, to decode the nodes its cuts reach.
  if (!distance) tileCutter_ = std::make_unique<TileCutter>(std::move(packed), lights);
  std::vector<float> cones = tileCutter_ ? tileCutter_->spotConeTexels() : std::vector<float>{};
  if (cones.empty()) cones.assign(4, 0.0f);  // no spots: keep the sampler complete
  spotCones_ = gl::uploadTextureBuffer(cones.data(), cones.size() / 4, GL_RGBA32F,
                                       "spot cones of " + std::to_string(cones.size()) + " floats");

  if (tileCutter_) {  // sized once; each frame's cut numbers replace the last
    glBindTexture(GL_TEXTURE_2D, cutOfPixel_.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32UI, width_, height_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                 nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  if (tileCutter_) {  // the stencil of the two lighting passes
    glBindTexture(GL_TEXTURE_2D, stencil_.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH24_STENCIL8, width_, height_, 0, GL_DEPTH_STENCIL,
                 GL_UNSIGNED_INT_24_8, nullptr);
  }
  glBindTexture(GL_TEXTURE_2D, statsTarget_.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width_, height_, 0, GL_RGBA, GL_FLOAT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                         gbuffer.target(GBuffer::kRadiance).id(), 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, statsTarget_.id(), 0);
  if (tileCutter_) {
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D,
                           stencil_.id(), 0);
  }
  const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(2, buffers);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw gl::GlError("lightcuts framebuffer is incomplete");
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

bool exactSums(const LightcutsSettings& settings, int lights) {
  return settings.mode == ErrorMode::Total && lights <= std::min(settings.exactLimit, kExactLimit);
}

const gl::Program& LightcutsMethod::program(const std::vector<std::string>& defines) const {
  return gl::cachedProgram("fullscreen.vert", "lighting_lightcuts.frag", defines,
                           {"oRadiance", "oCutStats"});
}

void LightcutsMethod::light(const GpuScene& scene, const GBuffer& gbuffer, const View& view,
                            const LightcutsSettings& settings) const {
  const int maxCut = std::clamp(settings.maxCut, 1, kMaxCutLimit);
  const NodeColourCoder& colour = layout_.colour;
  const unsigned flags =
      (distance_ ? glsl::kLightcutsDistance : 0u) |
      (scene.hasSpecular() ? glsl::kLightcutsHasSpecular : 0u) |
      (colour.coding() == NodeColourCoding::Fitted ? glsl::kLightcutsFittedColour : 0u);
  const int tileSize = distance_ ? 1 : std::max(settings.tileSize, 1);
  const bool exact = exactSums(settings, scene.lightCount());
  if (tileSize > 1) {
    cutTiles(gbuffer, view, scene.hasSpecular(), settings, tileSize, exact, scene.lightCount());
  } else {
    tileInfo_ = {};
    cutMs_ = 0.0;
  }

  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  const float zero[4] = {0, 0, 0, 0};
  glClearBufferfv(GL_COLOR, 1, zero);
  // One lighting pass with `extra` flags; `tileCuts`: it reads the shared cuts.
  auto pass = [&](unsigned extra, bool tileCuts) {
    const gl::Program& shader = program(glsl::lightcutsDefines(flags | extra));
    shader.use();
    bindLightingInputs(shader, gbuffer, scene, view);
    glActiveTexture(GL_TEXTURE5);
    glBindTexture(GL_TEXTURE_BUFFER, nodes_.texture.id());
    glUniform1i(shader.uniform("uNodes"), 5);
    glActiveTexture(GL_TEXTURE8);
    glBindTexture(GL_TEXTURE_BUFFER, spotCones_.texture.id());
    glUniform1i(shader.uniform("uSpotCones"), 8);
    glUniform3i(shader.uniform("uTreeBase"), layout_.base[0], layout_.base[1], layout_.base[2]);
    glUniform3i(shader.uniform("uTreeLeaves"), layout_.leaves[0], layout_.leaves[1],
                layout_.leaves[2]);
    if (colour.coding() == NodeColourCoding::Rgb9e5) {
      glUniform1f(shader.uniform("uColourScale"), colour.scale());
    } else {
      glUniform2f(shader.uniform("uColourFit"), float(colour.fit().a), float(colour.fit().gamma));
    }
    glUniform2f(shader.uniform("uColourSlack"), float(colour.slack), float(colour.slackFloor));
    glUniform1f(shader.uniform("uError"), settings.error);
    glUniform1i(shader.uniform("uErrorMode"), settings.mode == ErrorMode::Total ? 1 : 0);
    glUniform1i(shader.uniform("uMaxCut"), maxCut);
    glUniform1i(shader.uniform("uLightCount"), scene.lightCount());
    glUniform1i(shader.uniform("uExactSums"), exact ? 1 : 0);
    glUniform1f(shader.uniform("uInfluence"), 1.0f / std::sqrt(std::max(settings.error, 1e-6f)));
    if (tileCuts) {
      glActiveTexture(GL_TEXTURE6);
      glBindTexture(GL_TEXTURE_BUFFER, tileCuts_.texture.id());
      glUniform1i(shader.uniform("uTileCuts"), 6);
      glActiveTexture(GL_TEXTURE7);
      glBindTexture(GL_TEXTURE_2D, cutOfPixel_.id());
      glUniform1i(shader.uniform("uCutOfPixel"), 7);
    }
    glDrawArrays(GL_TRIANGLES, 0, 3);
  };
  if (tileSize > 1) {
    // The pixels that take their group's cut set the stencil to 0; the rest (1) then walk
    // cuts of their own (glsl/lighting_lightcuts.frag says why in two passes).
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 1);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    pass(glsl::kLightcutsTileCuts | glsl::kLightcutsSharedPass, true);
    glStencilFunc(GL_EQUAL, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    pass(glsl::kLightcutsOwnPass, false);
    glDisable(GL_STENCIL_TEST);
  } else {
    pass(0u, false);
  }
  glDisable(GL_BLEND);
  glActiveTexture(GL_TEXTURE0);
}

void LightcutsMethod::cutTiles(const GBuffer& gbuffer, const View& view, bool specular,
                               const LightcutsSettings& settings, int tileSize, bool exact,
                               int lights) const {
  const std::size_t plane = std::size_t(width_) * height_ * 4;
  // With specular materials the albedo too: specular pixels share cuts bounded over their
  // lobes, weighed by it (cuts/pixel_groups.h).
  const int planes = specular ? 4 : 3;
  readback_.resize(std::size_t(planes) * plane);
  glBindFramebuffer(GL_FRAMEBUFFER, gbuffer.geometryFramebuffer().id());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  const GBuffer::Target targets[4] = {GBuffer::kPosition, GBuffer::kNormal, GBuffer::kSpecular,
                                      GBuffer::kAlbedo};
  for (int i = 0; i < planes; ++i) {
    glReadBuffer(GL_COLOR_ATTACHMENT0 + targets[i]);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, readback_.data() + i * plane);
  }
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  const auto start = std::chrono::steady_clock::now();  // the G-buffer is here
  GBufferPixels pixels{width_, height_, readback_.data(), readback_.data() + plane,
                       readback_.data() + 2 * plane};
  if (specular) {
    pixels.albedo = readback_.data() + 3 * plane;
    pixels.eye = view.eye;
    pixels.forward = view.forward;
    pixels.orthographic = view.orthographic;
  }
  // Shared cuts are not held to settings.maxCut, the most nodes a pixel walks itself
  // (kSharedCutLimit says why).
  CutRule rule{settings.error, settings.mode == ErrorMode::Total, kSharedCutLimit};
  rule.ownCut = settings.maxCut;
  rule.exactFull = exact;
  if (exact && lights > kSharedCutLimit)
    rule.maxCut = std::min(kSharedCutLimit, lights / kExactCutShare);
  // Every pixel may share a cut of its own (2 header texels) and its share of the entries.
  const std::size_t pixelCount = std::max<std::size_t>(std::size_t(width_) * height_, 1);
  const std::size_t perPixel = std::min(kCutTexelBudget, gl::maxTextureBufferTexels()) / pixelCount;
  rule.texelsPerPixel = perPixel > 2 ? perPixel - 2 : 0;
  const int threads = int(std::max(1u, std::thread::hardware_concurrency()));
  if (settings.keepCuts) {
    if (!cells_) cells_ = std::make_unique<CellCuts>(*tileCutter_);
    tileInfo_ = cells_->cut(pixels, rule, threads);
  } else {
    tileInfo_ = tileCutter_->cut(pixels, tileSize, rule, threads);
  }
  gl::fillTextureBuffer(
      tileCuts_, tileInfo_.texels.texels(), GL_RGBA32UI,
      [&](void* to) { tileInfo_.texels.writeTo(static_cast<std::uint32_t*>(to)); }, "tile cuts");
  tileInfo_.texels = {};
  glBindTexture(GL_TEXTURE_2D, cutOfPixel_.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_, height_, GL_RED_INTEGER, GL_UNSIGNED_INT,
                  tileInfo_.cutOfPixel.data());
  glBindTexture(GL_TEXTURE_2D, 0);
  tileInfo_.cutOfPixel = {};
  cutMs_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

CutStats LightcutsMethod::cutStats() const {
  std::vector<float> texels(std::size_t(width_) * height_ * 4);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glReadBuffer(GL_COLOR_ATTACHMENT1);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, texels.data());
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  CutStats stats;
  stats.sharedCuts = tileInfo_.sharedCuts;
  stats.exactCuts = tileInfo_.exactCuts;
  stats.perPixelGroups = tileInfo_.perPixelGroups;
  stats.surfaceSplits = tileInfo_.surfaceSplits;
  stats.work = tileInfo_.work;
  double cut = 0.0, lightEvals = 0.0, nodeEvals = 0.0;
  stats.atMaxCut.assign(std::size_t(width_) * height_, 0);
  for (std::size_t i = 0; i < texels.size(); i += 4) {
    if (texels[i + 3] == 0.0f) continue;  // background
    ++stats.pixels;
    cut += texels[i];
    lightEvals += texels[i + 1];
    nodeEvals += texels[i + 2];
    stats.maxCut = std::max(stats.maxCut, int(texels[i]));
    const int kind = int(texels[i + 3] + 0.5f);
    const bool shared = kind == glsl::kCutStatsSharedCut || kind == glsl::kCutStatsSharedCutAtMax;
    if (shared) ++stats.pixelsSharedCut;
    if (kind == glsl::kCutStatsOwnCutAtMax || kind == glsl::kCutStatsSharedCutAtMax) {
      ++stats.pixelsAtMaxCut;
      const std::size_t pixel = i / 4, x = pixel % width_, y = pixel / width_;
      stats.atMaxCut[(height_ - 1 - y) * width_ + x] = 1;  // GL rows run bottom-up
    }
  }
  if (stats.pixels > 0) {
    stats.averageCut = cut / stats.pixels;
    stats.lightEvaluations = lightEvals / stats.pixels;
    stats.nodeEvaluations = (nodeEvals + double(tileInfo_.boundEvaluations())) / stats.pixels;
  }
  return stats;
}

}  // namespace manylight
