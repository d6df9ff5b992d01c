#include "render/rsm_choice.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "base/parallel.h"
#include "scene/shading_model.h"

namespace manylight {

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
                          int count, const std::vector<int>& previous, double leastShare) {
  RsmChoice choice;
  // With no least share every light passes, whatever the sum (a NaN in it too).
  const double least = leastShare > 0.0
                           ? leastShare * std::accumulate(flux.begin(), flux.end(), 0.0)
                           : -std::numeric_limits<double>::infinity();
  const auto enough = [&](int i) { return flux[std::size_t(i)] >= least; };
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
        flux[std::size_t(i)] >= kRsmChoiceKeep * std::max(weakest, least) &&
        std::find(choice.lights.begin(), choice.lights.end(), i) == choice.lights.end())
      choice.lights.push_back(i);
  }
  for (std::size_t j = 0; j < k && choice.lights.size() < k; ++j) {
    if (std::find(choice.lights.begin(), choice.lights.end(), candidates[j]) != choice.lights.end())
      continue;
    if (enough(candidates[j]))
      choice.lights.push_back(candidates[j]);
    else
      ++choice.belowShare;
  }
  return choice;
}

double fluxShare(const std::vector<int>& chosen, const std::vector<double>& flux) {
  const double total = std::accumulate(flux.begin(), flux.end(), 0.0);
  double sum = 0.0;
  for (int i : chosen) sum += flux[std::size_t(i)];
  return total > 0.0 ? sum / total : 1.0;
}

std::vector<char> RsmFluxHistory::due(const std::vector<Light>& lights) const {
  std::vector<char> out(lights.size(), 1);
  if (lights.size() != lights_.size()) return out;
  const std::size_t turn = std::size_t(frames_ % kRsmChoiceStride);
  for (std::size_t i = 0; i < lights.size(); ++i)
    out[i] = i % kRsmChoiceStride == turn || !sameLight(lights[i], lights_[i]);
  return out;
}

const std::vector<double>& RsmFluxHistory::add(const std::vector<Light>& lights,
                                               const std::vector<double>& flux,
                                               const std::vector<char>* measured) {
  if (lights.size() != lights_.size() || flux.size() != sum_.size()) {
    lights_ = lights;
    sum_.assign(flux.size(), 0.0);
    weight_.assign(flux.size(), 0.0);
    frames_ = 0;
  }
  ++frames_;
  mean_.resize(flux.size());
  const double memory =
      measured ? std::pow(kRsmChoiceMemory, double(kRsmChoiceStride)) : kRsmChoiceMemory;
  for (std::size_t i = 0; i < sum_.size(); ++i) {
    const bool same = sameLight(lights[i], lights_[i]);
    if (same && measured && !(*measured)[i]) continue;  // keeps its mean
    if (!same) lights_[i] = lights[i];
    const double keep = same ? memory : 0.0;
    sum_[i] = keep * sum_[i] + flux[i];
    weight_[i] = keep * weight_[i] + 1.0;
    mean_[i] = sum_[i] / weight_[i];
  }
  return mean_;
}

namespace {

// The samples binned in a grid over their bounds, about one a cell: each point or spot light of
// a range reads only the cells its range's box overlaps.
class SampleGrid {
 public:
  explicit SampleGrid(const RsmSamples& samples) {
    const std::size_t count = samples.position.size();
    lo_ = hi_ = glm::dvec3(count > 0 ? samples.position[0] : glm::vec3(0.0f));
    for (const glm::vec3& p : samples.position) {
      lo_ = glm::min(lo_, glm::dvec3(p));
      hi_ = glm::max(hi_, glm::dvec3(p));
    }
    const int side = std::max(1, int(std::cbrt(double(count))));
    cells_ = glm::ivec3(side);
    cell_ = glm::max((hi_ - lo_) / double(side), glm::dvec3(1e-9));
    std::vector<int> cellOf(count);
    first_.assign(std::size_t(side * side * side) + 1, 0);
    for (std::size_t s = 0; s < count; ++s) {
      cellOf[s] = index(cellAt(glm::dvec3(samples.position[s])));
      ++first_[std::size_t(cellOf[s]) + 1];
    }
    std::partial_sum(first_.begin(), first_.end(), first_.begin());
    order_.resize(count);
    std::vector<int> next(first_.begin(), first_.end() - 1);
    for (std::size_t s = 0; s < count; ++s)
      order_[std::size_t(next[std::size_t(cellOf[s])]++)] = int(s);
  }
  // The samples in the cells that the box [lo, hi] overlaps.
  std::size_t countIn(glm::dvec3 lo, glm::dvec3 hi) const {
    std::size_t count = 0;
    forEachCell(lo, hi, [&](int c) {
      count += std::size_t(first_[std::size_t(c) + 1] - first_[std::size_t(c)]);
    });
    return count;
  }
  // Calls visit(s) for every sample s in a cell that the box [lo, hi] overlaps.
  template <typename Visit>
  void forEachIn(glm::dvec3 lo, glm::dvec3 hi, const Visit& visit) const {
    forEachCell(lo, hi, [&](int c) {
      for (int j = first_[std::size_t(c)]; j < first_[std::size_t(c) + 1]; ++j)
        visit(std::size_t(order_[std::size_t(j)]));
    });
  }

 private:
  template <typename Visit>
  void forEachCell(glm::dvec3 lo, glm::dvec3 hi, const Visit& visit) const {
    if (glm::any(glm::lessThan(hi, lo_)) || glm::any(glm::greaterThan(lo, hi_))) return;
    const glm::ivec3 a = cellAt(lo), b = cellAt(hi);
    for (int z = a.z; z <= b.z; ++z)
      for (int y = a.y; y <= b.y; ++y)
        for (int x = a.x; x <= b.x; ++x) visit(index(glm::ivec3(x, y, z)));
  }
  // Clamped in double before the conversion: a light of a huge range reaches far past the
  // int's range of cells.
  glm::ivec3 cellAt(glm::dvec3 p) const {
    return glm::ivec3(
        glm::clamp(glm::floor((p - lo_) / cell_), glm::dvec3(0.0), glm::dvec3(cells_ - 1)));
  }
  int index(glm::ivec3 c) const { return (c.z * cells_.y + c.y) * cells_.x + c.x; }
  glm::dvec3 lo_, hi_, cell_;
  glm::ivec3 cells_;
  std::vector<int> first_, order_;  // per cell its first place in order_, then one past the last
};

// The samples as arrays of floats: the loops over every sample run four at a time.
struct SampleArrays {
  explicit SampleArrays(const RsmSamples& samples) {
    for (std::size_t s = 0; s < samples.position.size(); ++s) {
      for (int c = 0; c < 3; ++c) {
        p[c].push_back(samples.position[s][c]);
        n[c].push_back(samples.normal[s][c]);
      }
    }
  }
  std::size_t size() const { return p[0].size(); }
  std::vector<float> p[3], n[3];
};

// A light's irradiance per unit luminance at the samples (glsl/light_texture.glsl's, in float).
class UnitLight {
 public:
  explicit UnitLight(const Light& light)
      : position_(light.position),
        direction_(glm::normalize(light.direction)),
        inverseRange2_(light.range > 0.0f && !std::isinf(light.range)
                           ? 1.0f / (light.range * light.range)
                           : 0.0f) {
    const double outer = std::cos(double(light.outerConeAngle));
    const double scale =
        1.0 / std::max(std::cos(double(light.innerConeAngle)) - outer, shading::kMinConeWidth);
    coneScale_ = float(scale);
    coneOffset_ = float(-outer * scale);
  }
  bool ranged() const { return inverseRange2_ > 0.0f; }
  // Per sample into `out`: max(n·l, 0).
  void directional(const SampleArrays& a, float* __restrict out) const {
    const float* __restrict nx = a.n[0].data();
    const float* __restrict ny = a.n[1].data();
    const float* __restrict nz = a.n[2].data();
    const glm::vec3 d = direction_;
    for (std::size_t s = 0; s < a.size(); ++s) {
      const float c = -(nx[s] * d.x + ny[s] * d.y + nz[s] * d.z);
      out[s] = c > 0.0f ? c : 0.0f;
    }
  }
  // Per sample s in [from, to) into out[s]: cos θ · window / d², times the cone's smoothstep
  // for a spot. Every input is a local, so that the compiler vectorizes the loop.
  template <bool kSpot>
  __attribute__((noinline)) void point(const SampleArrays& a, std::size_t from, std::size_t to,
                                       float* __restrict out) const {
    const float* __restrict px = a.p[0].data();
    const float* __restrict py = a.p[1].data();
    const float* __restrict pz = a.p[2].data();
    const float* __restrict nx = a.n[0].data();
    const float* __restrict ny = a.n[1].data();
    const float* __restrict nz = a.n[2].data();
    const glm::vec3 p = position_, d = direction_;
    const float inverseRange2 = inverseRange2_, scale = coneScale_, offset = coneOffset_;
    const float least = float(shading::kMinDistanceSquared);
    for (std::size_t s = from; s < to; ++s) {
      const float dx = p.x - px[s], dy = p.y - py[s], dz = p.z - pz[s];
      // d² + the least instead of the larger of the two: a max before the sqrt would keep the
      // compiler from vectorizing the loop, and they differ by under 10⁻¹² of d².
      const float d2 = dx * dx + dy * dy + dz * dz + least;
      const float inverse = 1.0f / std::sqrt(d2);
      float cosine = (nx[s] * dx + ny[s] * dy + nz[s] * dz) * inverse;
      cosine = cosine > 0.0f ? cosine : 0.0f;
      const float x = d2 * inverseRange2;
      float window = 1.0f - x * x;
      window = window > 0.0f ? window : 0.0f;  // at most 1 as x ≥ 0
      float e = cosine * window * (inverse * inverse);
      if (kSpot) {
        float t = -(dx * d.x + dy * d.y + dz * d.z) * inverse * scale + offset;
        // clamp(t, 0, 1) without a branch, which the compiler would split the loop on.
        t = 0.5f * (std::abs(t) - std::abs(t - 1.0f) + 1.0f);
        e *= t * t * (3.0f - 2.0f * t);
      }
      out[s] = e;
    }
  }

 private:
  glm::vec3 position_, direction_;
  float inverseRange2_, coneScale_ = 0.0f, coneOffset_ = 0.0f;
};

// Partial sums a sum over the samples keeps: one chain of additions would wait on each.
constexpr std::size_t kLanes = 8;
std::size_t padded(std::size_t n) { return (n + kLanes - 1) / kLanes * kLanes; }

// Σ `v`, of padded(n) floats (zeros past the samples), in kLanes partial sums.
double laneSum(const std::vector<float>& v) {
  float lanes[kLanes] = {};
  for (std::size_t s = 0; s < v.size(); s += kLanes)
    for (std::size_t k = 0; k < kLanes; ++k) lanes[k] += v[s + k];
  return std::accumulate(lanes, lanes + kLanes, 0.0);
}

// Σ over the samples of `light`'s irradiance per unit luminance; `scratch` holds a float a
// sample.
double unitFlux(const Light& light, const SampleArrays& a, const SampleGrid& grid,
                std::vector<float>& scratch) {
  const UnitLight u(light);
  const bool spot = light.type == LightType::Spot;
  if (light.type != LightType::Directional && u.ranged()) {
    // The range window is 0 from the range on: where the range's box holds few samples, those
    // alone.
    const glm::dvec3 p(light.position), r(double(light.range));
    if (8 * grid.countIn(p - r, p + r) < a.size()) {
      double sum = 0.0;
      grid.forEachIn(p - r, p + r, [&](std::size_t s) {
        spot ? u.point<true>(a, s, s + 1, scratch.data())
             : u.point<false>(a, s, s + 1, scratch.data());
        sum += double(scratch[s]);
      });
      return sum;
    }
  }
  if (light.type == LightType::Directional)
    u.directional(a, scratch.data());
  else if (spot)
    u.point<true>(a, 0, a.size(), scratch.data());
  else
    u.point<false>(a, 0, a.size(), scratch.data());
  return laneSum(scratch);
}

}  // namespace

std::vector<double> measureLightFlux(const std::vector<Light>& lights, const RsmSamples& samples,
                                     const std::vector<char>* which) {
  std::vector<double> flux(lights.size(), 0.0);
  const SampleGrid grid(samples);
  const SampleArrays arrays(samples);
  runOnShares(
      sharesOf(lights.size(), 4096), lights.size(), [&](int, std::size_t from, std::size_t to) {
        std::vector<float> scratch(padded(arrays.size()), 0.0f);
        for (std::size_t i = from; i < to; ++i) {
          if (which && !(*which)[i]) continue;
          const glm::dvec3 radiant = glm::dvec3(lights[i].colour) * double(lights[i].intensity);
          flux[i] = shading::luminance(radiant) * unitFlux(lights[i], arrays, grid, scratch);
        }
      });
  return flux;
}

}  // namespace manylight
