#include "render/rsm.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numeric>
#include <thread>

#include "bake/parallel.h"
#include "gl/context.h"
#include "scene/shading_model.h"

namespace manylight {

namespace {

struct Sample {
  glm::dvec3 p, n;
};

// Up to `samples` covered pixels on a regular grid.
std::vector<Sample> samplePixels(const std::vector<float>& position,
                                 const std::vector<float>& normal, std::size_t samples) {
  const std::size_t pixels = normal.size() / 4;
  std::size_t covered = 0;
  for (std::size_t i = 0; i < pixels; ++i) covered += normal[4 * i + 3] != 0.0f;
  const std::size_t step = std::max<std::size_t>(1, covered / samples);
  std::vector<Sample> out;
  for (std::size_t i = 0, k = 0; i < pixels; ++i) {
    if (normal[4 * i + 3] == 0.0f) continue;
    if (k++ % step != 0) continue;
    out.push_back(
        {glm::dvec3(position[4 * i], position[4 * i + 1], position[4 * i + 2]),
         glm::normalize(glm::dvec3(normal[4 * i], normal[4 * i + 1], normal[4 * i + 2]))});
  }
  return out;
}

double luminance(glm::dvec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

}  // namespace

RsmChoice chooseRsmLights(const std::vector<Light>& lights, const std::vector<float>& position,
                          const std::vector<float>& normal, int count) {
  const double budget = kRsmChoiceEvaluations / double(std::max<std::size_t>(lights.size(), 1));
  const std::size_t sampleCount =
      std::size_t(std::clamp(budget, double(kRsmChoiceMinSamples), double(kRsmChoiceSamples)));
  const std::vector<Sample> samples = samplePixels(position, normal, sampleCount);
  std::vector<double> flux(lights.size(), 0.0);
  const int threads =
      std::max(1, std::min(int(std::thread::hardware_concurrency()), int(lights.size() / 256) + 1));
  runOnThreads(threads, [&](int t) {
    for (std::size_t i = std::size_t(t); i < lights.size(); i += std::size_t(threads)) {
      glm::dvec3 l;
      for (const Sample& s : samples)
        flux[i] += luminance(shading::irradiance(lights[i], s.p, s.n, l));
    }
  });
  RsmChoice choice;
  std::vector<int> candidates;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    if (lights[i].type != LightType::Point) candidates.push_back(int(i));
  }
  choice.candidates = int(candidates.size());
  const std::size_t k = std::min(candidates.size(), std::size_t(std::max(count, 0)));
  std::partial_sort(candidates.begin(), candidates.begin() + std::ptrdiff_t(k), candidates.end(),
                    [&](int a, int b) {
                      return flux[std::size_t(a)] > flux[std::size_t(b)] ||
                             (flux[std::size_t(a)] == flux[std::size_t(b)] && a < b);
                    });
  choice.lights.assign(candidates.begin(), candidates.begin() + std::ptrdiff_t(k));
  const double total = std::accumulate(flux.begin(), flux.end(), 0.0);
  double chosen = 0.0;
  for (int i : choice.lights) chosen += flux[std::size_t(i)];
  choice.fluxShare = total > 0.0 ? chosen / total : 1.0;
  return choice;
}

RsmView rsmView(const Light& light, const Bounds& bounds, int size) {
  const glm::vec3 centre = bounds.empty ? glm::vec3(0.0f) : 0.5f * (bounds.min + bounds.max);
  const float radius =
      bounds.empty ? 1.0f : std::max(0.5f * glm::length(bounds.max - bounds.min), 1e-6f);
  const glm::vec3 axis = glm::normalize(light.direction);
  const glm::vec3 up = std::abs(axis.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  RsmView r;
  r.view.forward = axis;
  if (light.type == LightType::Directional) {
    r.view.eye = centre - axis * (2.0f * radius);
    r.view.view = glm::lookAt(r.view.eye, centre, up);
    r.view.projection = glm::ortho(-radius, radius, -radius, radius, 0.0f, 4.0f * radius);
    r.view.orthographic = true;
    const float texel = 2.0f * radius / float(size);
    r.texelScale = texel * texel;
    return r;
  }
  const float half = std::clamp(light.outerConeAngle, 1e-3f, kMaxRsmHalfAngle);
  const float farSide = glm::length(centre - light.position) + radius;
  const float far = light.range > 0.0f ? std::min(light.range, farSide) : farSide;
  r.view.eye = light.position;
  r.view.view = glm::lookAt(light.position, light.position + axis, up);
  r.view.projection = glm::perspective(2.0f * half, 1.0f, 1e-3f * far, far);
  const float texel = 2.0f * std::tan(half) / float(size);
  r.texelScale = texel * texel;
  return r;
}

using namespace gl::api;

int drawRsmRowPasses(const gl::Program& program, const GBuffer& rsm, int firstUnit) {
  const GBuffer::Target targets[] = {GBuffer::kPosition, GBuffer::kNormal, GBuffer::kRadiance};
  const char* names[] = {"uRsmPosition", "uRsmNormal", "uRsmFlux"};
  for (int i = 0; i < 3; ++i) {
    glActiveTexture(GLenum(GL_TEXTURE0 + firstUnit + i));
    glBindTexture(GL_TEXTURE_2D, rsm.target(targets[i]).id());
    glUniform1i(program.uniform(names[i]), firstUnit + i);
  }
  glUniform1i(program.uniform("uRsmSize"), rsm.width());
  const int rows = std::max(1, 65000 / std::max(rsm.width(), 1) - 1);
  int passes = 0;
  for (int first = 0; first < rsm.height(); first += rows, ++passes) {
    glUniform1i(program.uniform("uFirstRow"), first);
    glUniform1i(program.uniform("uRows"), std::min(rows, rsm.height() - first));
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glActiveTexture(GL_TEXTURE0);
  return passes;
}

}  // namespace manylight
