#include "render/rsm_clusters.h"

#include <algorithm>
#include <cassert>

namespace manylight {

namespace {

double weightOf(const float* f) { return double(f[0]) + double(f[1]) + double(f[2]); }

}  // namespace

RsmClusters clusterRsm(const std::vector<float>& position, const std::vector<float>& normal,
                       const std::vector<float>& flux, int size) {
  assert(size % kRsmClusterEdge == 0 && "--rsm-size takes powers of two from 16");
  RsmClusters c;
  c.size = size / kRsmClusterEdge;
  const std::size_t n = std::size_t(c.size) * std::size_t(c.size);
  c.centre.assign(n, glm::vec4(0.0f, 0.0f, 0.0f, -1.0f));
  c.normal.assign(n, glm::vec4(0.0f));
  c.flux.assign(n, glm::vec4(0.0f));
  for (int by = 0; by < c.size; ++by) {
    for (int bx = 0; bx < c.size; ++bx) {
      std::vector<std::size_t> texels;
      for (int y = by * kRsmClusterEdge; y < (by + 1) * kRsmClusterEdge; ++y)
        for (int x = bx * kRsmClusterEdge; x < (bx + 1) * kRsmClusterEdge; ++x) {
          const std::size_t t = 4 * (std::size_t(y) * std::size_t(size) + std::size_t(x));
          if (flux[t + 3] != 0.0f) texels.push_back(t);
        }
      if (texels.empty()) continue;
      // Weighted by the flux (its channels' sum), or evenly where the block reflects none.
      double total = 0.0;
      for (std::size_t t : texels) total += weightOf(&flux[t]);
      glm::dvec3 centre(0.0), meanNormal(0.0);
      glm::vec4 sum(0.0f);
      for (std::size_t t : texels) {
        const double w = total > 0.0 ? weightOf(&flux[t]) / total : 1.0 / double(texels.size());
        centre += w * glm::dvec3(position[t], position[t + 1], position[t + 2]);
        meanNormal += w * glm::dvec3(normal[t], normal[t + 1], normal[t + 2]);
        sum += glm::vec4(flux[t], flux[t + 1], flux[t + 2], flux[t + 3]);
      }
      const double length = glm::length(meanNormal);
      const glm::dvec3 unit = length > 0.0 ? meanNormal / length : glm::dvec3(0.0, 0.0, 1.0);
      double radius = 0.0, leastCosine = 1.0;
      for (std::size_t t : texels) {
        radius = std::max(
            radius,
            glm::length(glm::dvec3(position[t], position[t + 1], position[t + 2]) - centre));
        leastCosine = std::min(leastCosine,
                               glm::dot(unit, glm::dvec3(normal[t], normal[t + 1], normal[t + 2])));
      }
      const std::size_t at = std::size_t(by) * std::size_t(c.size) + std::size_t(bx);
      c.centre[at] = glm::vec4(glm::vec3(centre), float(radius));
      c.normal[at] = glm::vec4(glm::vec3(unit), leastCosine >= kRsmClusterFlat ? 1.0f : 0.0f);
      c.flux[at] = glm::vec4(glm::vec3(sum), sum.w / float(texels.size()));
    }
  }
  return c;
}

}  // namespace manylight
