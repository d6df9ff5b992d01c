#include "render/rsm_choice.h"

#include <algorithm>
#include <numeric>

#include "bake/light_pack.h"
#include "gl/context.h"
#include "render/cache_layout.h"
#include "render/lighting_inputs.h"

namespace manylight {

using namespace gl::api;

RsmSamples sampleRsmChoice(const std::vector<float>& position, const std::vector<float>& normal,
                           std::size_t lights) {
  const double budget = kRsmChoiceEvaluations / double(std::max<std::size_t>(lights, 1));
  const std::size_t wanted =
      std::size_t(std::clamp(budget, double(kRsmChoiceMinSamples), double(kRsmChoiceSamples)));
  const std::size_t pixels = normal.size() / 4;
  std::size_t covered = 0;
  for (std::size_t i = 0; i < pixels; ++i) covered += normal[4 * i + 3] != 0.0f;
  const std::size_t step = std::max<std::size_t>(1, covered / wanted);
  RsmSamples out;
  for (std::size_t i = 0, k = 0; i < pixels; ++i) {
    if (normal[4 * i + 3] == 0.0f) continue;
    if (k++ % step != 0) continue;
    out.position.push_back(glm::vec3(position[4 * i], position[4 * i + 1], position[4 * i + 2]));
    out.normal.push_back(
        glm::normalize(glm::vec3(normal[4 * i], normal[4 * i + 1], normal[4 * i + 2])));
  }
  return out;
}

RsmChoice chooseRsmLights(const std::vector<Light>& lights, const std::vector<double>& flux,
                          int count, const std::vector<int>& previous) {
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
  const double weakest = k > 0 ? flux[std::size_t(candidates[k - 1])] : 0.0;
  for (int i : previous) {
    const bool candidate =
        i >= 0 && std::size_t(i) < lights.size() && lights[std::size_t(i)].type != LightType::Point;
    if (candidate && choice.lights.size() < k && flux[std::size_t(i)] > 0.0 &&
        flux[std::size_t(i)] >= kRsmChoiceKeep * weakest &&
        std::find(choice.lights.begin(), choice.lights.end(), i) == choice.lights.end())
      choice.lights.push_back(i);
  }
  for (std::size_t j = 0; j < k && choice.lights.size() < k; ++j) {
    if (std::find(choice.lights.begin(), choice.lights.end(), candidates[j]) == choice.lights.end())
      choice.lights.push_back(candidates[j]);
  }
  return choice;
}

double fluxShare(const std::vector<int>& chosen, const std::vector<double>& flux) {
  const double total = std::accumulate(flux.begin(), flux.end(), 0.0);
  double sum = 0.0;
  for (int i : chosen) sum += flux[std::size_t(i)];
  return total > 0.0 ? sum / total : 1.0;
}

const std::vector<double>& RsmFluxHistory::add(const std::vector<Light>& lights,
                                               const std::vector<double>& flux) {
  if (lights.size() != lights_.size() || flux.size() != sum_.size()) {
    lights_ = lights;
    sum_.assign(flux.size(), 0.0);
    weight_.assign(flux.size(), 0.0);
  }
  mean_.resize(flux.size());
  for (std::size_t i = 0; i < sum_.size(); ++i) {
    const bool same = sameLight(lights[i], lights_[i]);
    if (!same) lights_[i] = lights[i];
    const double keep = same ? kRsmChoiceMemory : 0.0;
    sum_[i] = keep * sum_[i] + flux[i];
    weight_[i] = keep * weight_[i] + 1.0;
    mean_[i] = sum_[i] / weight_[i];
  }
  return mean_;
}

std::vector<double> LightFlux::measure(const GpuScene& gpu, const std::vector<Light>& lights,
                                       const RsmSamples& samples) {
  std::vector<double> flux(lights.size(), 0.0);
  const int count = int(samples.position.size());
  if (lights.empty() || count == 0) return flux;
  std::vector<glm::vec4> texels(2 * std::size_t(count));
  for (std::size_t s = 0; s < std::size_t(count); ++s) {
    texels[s] = glm::vec4(samples.position[s], 1.0f);
    texels[std::size_t(count) + s] = glm::vec4(samples.normal[s], 0.0f);
  }
  glBindTexture(GL_TEXTURE_2D, samples_.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, count, 2, 0, GL_RGBA, GL_FLOAT, texels.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  const int height = int((lights.size() + kRsmChoiceWidth - 1) / kRsmChoiceWidth);
  if (height > height_) {
    glBindTexture(GL_TEXTURE_2D, flux_.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, kRsmChoiceWidth, height, 0, GL_RED, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, flux_.id(), 0);
    height_ = height;
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  const gl::Program& p = gl::cachedProgram("fullscreen.vert", "rsm_choice.frag", {}, {"oFlux"});
  p.use();
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, kRsmChoiceWidth, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  bindSampler(p, "uSamples", GL_TEXTURE_2D, samples_.id(), 0);
  bindSampler(p, "uLights", GL_TEXTURE_BUFFER, gpu.lightTexture().id(), 1);
  glUniform1i(p.uniform("uPointStart"), gpu.pointStart());
  glUniform1i(p.uniform("uSpotStart"), gpu.spotStart());
  glUniform1i(p.uniform("uSampleCount"), count);
  glUniform1i(p.uniform("uLightCount"), int(lights.size()));
  glDrawArrays(GL_TRIANGLES, 0, 3);
  std::vector<float> out(std::size_t(kRsmChoiceWidth) * std::size_t(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, kRsmChoiceWidth, height, GL_RED, GL_FLOAT, out.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glActiveTexture(GL_TEXTURE0);
  const LightOrder order = lightOrder(lights);
  for (std::size_t slot = 0; slot < order.scene.size(); ++slot)
    flux[std::size_t(order.scene[slot])] = double(out[slot]);
  return flux;
}

}  // namespace manylight
