#include "render/indirect_light.h"

#include <chrono>
#include <glm/gtc/type_ptr.hpp>
#include <utility>

#include "bake/light_pack.h"
#include "base/error.h"
#include "gl/context.h"
#include "render/lighting_inputs.h"
#include "render/rsm.h"

namespace manylight {

using namespace gl::api;

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// Writes the map's flux over its radiance target (glsl/rsm_flux.frag).
void renderFlux(const GBuffer& rsm, const Light& light, const RsmView& view) {
  const gl::Program& p = gl::cachedProgram("fullscreen.vert", "rsm_flux.frag", {}, {"oRadiance"});
  p.use();
  glBindFramebuffer(GL_FRAMEBUFFER, rsm.lightingFramebuffer().id());
  glViewport(0, 0, rsm.width(), rsm.height());
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  bindSampler(p, "uPosition", GL_TEXTURE_2D, rsm.target(GBuffer::kPosition).id(), 0);
  bindSampler(p, "uNormal", GL_TEXTURE_2D, rsm.target(GBuffer::kNormal).id(), 1);
  bindSampler(p, "uAlbedo", GL_TEXTURE_2D, rsm.target(GBuffer::kAlbedo).id(), 2);
  // The light texture's sampler is not read, but may not share a unit with the others.
  glUniform1i(p.uniform("uLights"), 3);
  const auto t = packLightTexels({light}, {0});
  glUniform4fv(p.uniform("uLight0"), 1, &t[0]);
  glUniform4fv(p.uniform("uLight1"), 1, &t[4]);
  glUniform4fv(p.uniform("uLight2"), 1, &t[8]);
  glUniform1i(p.uniform("uDirectional"), light.type == LightType::Directional ? 1 : 0);
  glUniform3fv(p.uniform("uAxis"), 1, glm::value_ptr(view.view.forward));
  glUniform1f(p.uniform("uTexelScale"), view.texelScale);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

// Adds the map's texels' light to the camera's radiance target; returns the passes.
int gather(const GBuffer& camera, const GBuffer& rsm) {
  const gl::Program& p =
      gl::cachedProgram("fullscreen.vert", "indirect_exact.frag", {}, {"oRadiance"});
  p.use();
  bindIndirectInputs(p, camera);
  const int passes = drawRsmRowPasses(p, rsm, 3);
  glDisable(GL_BLEND);
  return passes;
}

// Map texels that reflect flux (flux.w, the patch area, is non-zero).
long long reflectingTexels(const std::vector<float>& flux) {
  long long n = 0;
  for (std::size_t i = 3; i < flux.size(); i += 4) n += flux[i] != 0.0f;
  return n;
}

}  // namespace

Indirect parseIndirect(const std::string& name) {
  if (name == "none") return Indirect::None;
  if (name == "exact") return Indirect::Exact;
  if (name == "caches") return Indirect::Caches;
  throw Error("unknown indirect light '" + name + "' (choose none, exact or caches)");
}

const char* indirectName(Indirect i) {
  return i == Indirect::Exact ? "exact" : i == Indirect::Caches ? "caches" : "none";
}

CacheGrid frameCacheGrid(const IndirectSettings& settings, const Bounds& bounds, glm::vec3 eye) {
  const float diagonal = bounds.empty ? 1.0f : glm::length(bounds.max - bounds.min);
  const float cell = std::max(
      settings.cacheCell > 0.0f ? settings.cacheCell : diagonal / kCacheCellsPerScene, 1e-6f);
  return cacheGrid(eye, cell, cascadesToCover(eye, cell, bounds));
}

IndirectLight::IndirectLight(int rsmSize) : rsmSize_(rsmSize) {}

bool IndirectLight::sameMaps(const std::vector<Light>& lights, const RsmChoice& choice) const {
  if (mapGeneration_ == 0 || choice.lights != mapLights_) return false;
  for (std::size_t i = 0; i < maps_.size(); ++i)
    if (!sameLight(maps_[i].light, lights[std::size_t(mapLights_[i])])) return false;
  return true;
}

void IndirectLight::renderMaps(const Scene& scene, const GpuScene& gpu,
                               const GeometryPass& geometry, const std::vector<Light>& lights,
                               const RsmChoice& choice) {
  const Bounds bounds = scene.bounds();
  maps_.resize(choice.lights.size());
  mapLights_ = choice.lights;
  ++mapGeneration_;
  near_.clear();
  for (std::size_t i = 0; i < maps_.size(); ++i) {
    Map& m = maps_[i];
    m.light = lights[std::size_t(choice.lights[i])];
    if (!m.rsm) m.rsm = std::make_unique<GBuffer>(rsmSize_, rsmSize_);
    const RsmView rsmCamera = rsmView(m.light, bounds, rsmSize_);
    geometry.draw(scene, gpu, *m.rsm, rsmCamera.view, glm::vec3(0.0f));
    glBindVertexArray(emptyVao_.id());
    renderFlux(*m.rsm, m.light, rsmCamera);
    const std::vector<float> flux = m.rsm->read(GBuffer::kRadiance);
    const std::vector<float> position = m.rsm->read(GBuffer::kPosition);
    const std::vector<float> normal = m.rsm->read(GBuffer::kNormal);
    m.texels = reflectingTexels(flux);
    m.nearRadius = nearRadius(flux);
    const RsmClusters clusters = clusterRsm(position, normal, flux, rsmSize_);
    near_.add(position, normal, flux, clusters, m.nearRadius);
    if (!m.clusters) m.clusters = std::make_unique<RsmClusterTextures>();
    m.clusters->upload(clusters, position, normal, flux);
  }
}

IndirectStats IndirectLight::light(const Scene& scene, const GpuScene& gpu,
                                   const GeometryPass& geometry, const GBuffer& camera,
                                   const View& view, const std::vector<Light>& lights,
                                   const IndirectSettings& settings) {
  IndirectStats stats;
  if (settings.mode == Indirect::None) return stats;
  glFinish();  // the direct light's passes are not the choice's time
  auto start = Clock::now();
  const std::vector<float> position = camera.read(GBuffer::kPosition);
  const std::vector<float> normal = camera.read(GBuffer::kNormal);
  glBindVertexArray(emptyVao_.id());
  const RsmSamples samples = sampleRsmChoice(position, normal, lights.size());
  const std::vector<double> flux = measureLightFlux(lights, samples);
  const RsmChoice choice =
      chooseRsmLights(lights, fluxHistory_.add(lights, flux), settings.rsmLights, mapLights_);
  stats.candidates = choice.candidates;
  stats.fluxShare = fluxShare(choice.lights, flux);  // of this frame's flux, not the history's
  stats.chooseMs = msSince(start);
  start = Clock::now();
  stats.mapsKept = sameMaps(lights, choice);
  if (!stats.mapsKept) renderMaps(scene, gpu, geometry, lights, choice);
  glFinish();
  stats.rsmMs = msSince(start);
  stats.rsmLights = int(maps_.size());
  for (const Map& m : maps_) stats.rsmTexels += m.texels;
  const bool caches = settings.mode == Indirect::Caches;
  if (caches) {
    start = Clock::now();
    const CacheGrid grid = frameCacheGrid(settings, scene.bounds(), view.eye);
    if (!caches_) caches_ = std::make_unique<LightCaches>();
    // Kept only from caches gathered from these very maps (an `exact` frame between may have
    // made others).
    CacheAllocation allocation = allocateCaches(grid, position, normal);
    stats.cachesRefused = allocation.refused;
    caches_->upload(grid, std::move(allocation), settings.shL2,
                    stats.mapsKept && cachesGeneration_ == mapGeneration_);
    cachesGeneration_ = mapGeneration_;
    stats.caches = caches_->count();
    stats.cachesKept = caches_->kept();
    stats.cascades = grid.cascades;
    stats.cacheCell = grid.cell[0];
    stats.allocateMs = msSince(start);
  }
  start = Clock::now();
  glBindVertexArray(emptyVao_.id());
  for (const Map& m : maps_)
    stats.passes +=
        caches ? caches_->gather(*m.rsm, *m.clusters, m.nearRadius) : gather(camera, *m.rsm);
  glFinish();
  stats.gatherMs = msSince(start);
  if (caches) {
    start = Clock::now();
    near_.upload(caches_->grid());
    stats.nearPasses = near_.draw(camera);
    stats.nearClusters = near_.clusters();
    glFinish();
    stats.nearMs = msSince(start);
    start = Clock::now();
    caches_->interpolate(camera);
    glFinish();
    stats.interpolateMs = msSince(start);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindVertexArray(0);
  return stats;
}

}  // namespace manylight
