#include "render/indirect_light.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <glm/gtc/type_ptr.hpp>
#include <utility>

#include "bake/light_pack.h"
#include "base/error.h"
#include "base/parallel.h"
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

void IndirectLight::renderMap(const Scene& scene, const GpuScene& gpu, const GeometryPass& geometry,
                              Map& m) {
  m.id = ++mapsRendered_;
  if (!m.rsm) m.rsm = std::make_unique<GBuffer>(rsmSize_, rsmSize_);
  const RsmView rsmCamera = rsmView(m.light, scene.bounds(), rsmSize_);
  geometry.draw(scene, gpu, *m.rsm, rsmCamera.view, glm::vec3(0.0f));
  glBindVertexArray(emptyVao_.id());
  renderFlux(*m.rsm, m.light, rsmCamera);
  m.flux = m.rsm->read(GBuffer::kRadiance);
  m.position = m.rsm->read(GBuffer::kPosition);
  m.normal = m.rsm->read(GBuffer::kNormal);
  m.texels = reflectingTexels(m.flux);
  m.nearRadius = nearRadius(m.flux);
  m.groups = clusterRsm(m.position, m.normal, m.flux, rsmSize_);
  if (!m.clusters) m.clusters = std::make_unique<RsmClusterTextures>();
  m.clusters->upload(m.groups, m.position, m.normal, m.flux);
}

bool IndirectLight::updateMaps(const Scene& scene, const GpuScene& gpu,
                               const GeometryPass& geometry, const std::vector<Light>& lights,
                               const RsmChoice& choice) {
  std::vector<Map> maps(choice.lights.size());
  std::vector<int> layerMaps(std::size_t(kMaxCacheLayers), 0);  // maps a layer holds
  std::vector<bool> placed(maps.size(), false);
  for (std::size_t i = 0; i < maps.size(); ++i) {
    const int index = choice.lights[i];
    for (Map& old : maps_) {
      if (old.index != index || !old.rsm || !sameLight(old.light, lights[std::size_t(index)]))
        continue;
      maps[i] = std::move(old);
      ++layerMaps[std::size_t(maps[i].layer)];
      placed[i] = true;
      break;
    }
  }
  // Maps that shared a layer while there were more than kMaxCacheLayers take one of their own
  // again once there are no more (their layers then gather anew, once).
  if (maps.size() <= std::size_t(kMaxCacheLayers))
    for (std::size_t i = 0; i < maps.size(); ++i) {
      if (!placed[i] || layerMaps[std::size_t(maps[i].layer)] < 2) continue;
      --layerMaps[std::size_t(maps[i].layer)];
      maps[i].layer = int(std::find(layerMaps.begin(), layerMaps.end(), 0) - layerMaps.begin());
      ++layerMaps[std::size_t(maps[i].layer)];
    }
  // The maps not kept lend their GBuffers to the new ones.
  std::vector<Map*> spare;
  for (Map& old : maps_)
    if (old.rsm) spare.push_back(&old);
  bool rendered = false;
  for (std::size_t i = 0; i < maps.size(); ++i) {
    if (placed[i]) continue;
    Map& m = maps[i];
    if (!spare.empty()) {
      m.rsm = std::move(spare.back()->rsm);
      m.clusters = std::move(spare.back()->clusters);
      spare.pop_back();
    }
    m.index = choice.lights[i];
    m.light = lights[std::size_t(m.index)];
    // The layer holding the fewest maps (a free one while there is one), the first of those.
    m.layer = int(std::min_element(layerMaps.begin(), layerMaps.end()) - layerMaps.begin());
    ++layerMaps[std::size_t(m.layer)];
    renderMap(scene, gpu, geometry, m);
    rendered = true;
  }
  const bool changed = rendered || maps.size() != maps_.size();
  maps_ = std::move(maps);
  if (changed) {
    near_.clear();
    for (const Map& m : maps_) near_.add(m.position, m.normal, m.flux, m.groups, m.nearRadius);
  }
  return changed;
}

int IndirectLight::gatherLayers(std::vector<int>& layers) {
  int passes = 0;
  for (int layer = 0; layer < kMaxCacheLayers; ++layer) {
    std::vector<long long> ids;
    for (const Map& m : maps_)
      if (m.layer == layer) ids.push_back(m.id);
    if (ids.empty()) continue;
    caches_->startLayer(layer, std::move(ids));
    for (const Map& m : maps_)
      if (m.layer == layer) passes += caches_->gather(layer, *m.rsm, *m.clusters, m.nearRadius);
    layers.push_back(layer);
  }
  return passes;
}

void IndirectLight::begin(const GBuffer& camera, const Bounds& bounds, const View& view,
                          const std::vector<Light>& lights, const IndirectSettings& settings) {
  if (pending_.valid()) pending_.wait();  // its thread reads position_ and normal_
  glFinish();                             // the geometry pass is not the choice's time
  const auto start = Clock::now();
  camera.read(GBuffer::kPosition, position_);
  camera.read(GBuffer::kNormal, normal_);
  const double readMs = msSince(start);
  const glm::vec3 eye = view.eye;
  pending_ = std::async(kThreadOrDeferred, [this, &lights, settings, bounds, eye, readMs] {
    Prepared p = prepare(lights, settings, bounds, eye);
    p.stats.chooseMs += readMs;
    return p;
  });
}

IndirectLight::Prepared IndirectLight::prepare(const std::vector<Light>& lights,
                                               const IndirectSettings& settings,
                                               const Bounds& bounds, glm::vec3 eye) {
  Prepared out;
  IndirectStats& stats = out.stats;
  auto start = Clock::now();
  const RsmSamples samples = sampleRsmChoice(position_, normal_, lights.size());
  const std::vector<char> due = fluxHistory_.due(lights);
  std::vector<double> flux = measureLightFlux(lights, samples, &due);
  // Per sample: a frame's sums and another's, whose samples differ in number, weigh alike.
  if (!samples.position.empty())
    for (double& f : flux) f /= double(samples.position.size());
  const std::vector<double>& means = fluxHistory_.add(lights, flux, &due);
  std::vector<int> previous;
  for (const Map& m : maps_) previous.push_back(m.index);
  out.choice = chooseRsmLights(lights, means, settings.rsmLights, previous, settings.rsmLeastShare);
  stats.candidates = out.choice.candidates;
  stats.belowShare = out.choice.belowShare;
  stats.fluxShare = fluxShare(out.choice.lights, means);
  stats.chooseMs = msSince(start);
  // No map, no caches (light() then adds nothing).
  if (settings.mode != Indirect::Caches || out.choice.lights.empty()) return out;
  start = Clock::now();
  out.grid = frameCacheGrid(settings, bounds, eye);
  allocateCaches(out.grid, position_, normal_, allocation_);
  stats.cachesRefused = allocation_.refused;
  stats.allocateMs = msSince(start);
  return out;
}

IndirectStats IndirectLight::light(const Scene& scene, const GpuScene& gpu,
                                   const GeometryPass& geometry, const GBuffer& camera,
                                   const View& view, const std::vector<Light>& lights,
                                   const IndirectSettings& settings) {
  if (settings.mode == Indirect::None) return {};
  if (!pending_.valid()) begin(camera, scene.bounds(), view, lights, settings);
  glFinish();  // the direct light's passes are not the maps' time
  Prepared prepared = pending_.get();
  IndirectStats stats = prepared.stats;
  const RsmChoice& choice = prepared.choice;
  auto start = Clock::now();
  const long long before = mapsRendered_;
  const bool changed = updateMaps(scene, gpu, geometry, lights, choice);
  stats.mapsKept = chosen_ && !changed;
  chosen_ = true;
  stats.mapsRendered = int(mapsRendered_ - before);
  glFinish();
  stats.rsmMs = msSince(start);
  stats.rsmLights = int(maps_.size());
  for (const Map& m : maps_) stats.rsmTexels += m.texels;
  if (maps_.empty()) {  // no light sends the least share: no indirect light
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    return stats;
  }
  const bool caches = settings.mode == Indirect::Caches;
  if (caches) {
    start = Clock::now();
    assert(!prepared.grid.cell.empty() && "begin() and light() were given the same settings");
    const CacheGrid& grid = prepared.grid;
    if (!caches_) caches_ = std::make_unique<LightCaches>();
    classes_.upload(camera, allocation_.classes);
    caches_->upload(grid, allocation_, settings.shL2);
    stats.caches = caches_->count();
    stats.cascades = grid.cascades;
    stats.cacheCell = grid.cell[0];
    stats.allocateMs += msSince(start);
  }
  start = Clock::now();
  glBindVertexArray(emptyVao_.id());
  std::vector<int> layers;
  if (caches) {
    stats.passes = gatherLayers(layers);
    stats.cachesKept = caches_->kept();  // once every layer has gathered
    stats.cachesGathered = caches_->gathered();
  } else {
    for (const Map& m : maps_) stats.passes += gather(camera, *m.rsm);
  }
  glFinish();
  stats.gatherMs = msSince(start);
  if (caches) {
    start = Clock::now();
    near_.upload(caches_->grid());
    stats.nearPasses = near_.draw(camera, classes_);
    stats.nearClusters = near_.clusters();
    glFinish();
    stats.nearMs = msSince(start);
    start = Clock::now();
    caches_->interpolate(camera, classes_, layers);
    glFinish();
    stats.interpolateMs = msSince(start);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindVertexArray(0);
  return stats;
}

}  // namespace manylight
