#include "cuts/pixel_groups.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace manylight {

namespace {

// The normal of `pixels` with the smallest cosine to `u`.
glm::vec3 farthestNormal(const GBufferPixels& px, const std::vector<int>& pixels, glm::vec3 u) {
  glm::vec3 best = normalAt(px, pixels.front());
  float lowest = std::numeric_limits<float>::max();
  for (const int i : pixels) {
    const glm::vec3 n = normalAt(px, i);
    if (glm::dot(n, u) < lowest) {
      lowest = glm::dot(n, u);
      best = n;
    }
  }
  return best;
}

}  // namespace

bool shadingRegion(const GBufferPixels& px, const std::vector<int>& pixels, ShadingRegion& g) {
  g = ShadingRegion{glm::vec3(std::numeric_limits<float>::max()),
                    glm::vec3(-std::numeric_limits<float>::max()), glm::vec3(0.0f), 1.0f, 0.0f};
  for (const int i : pixels) {
    const glm::vec3 p = positionAt(px, i);
    g.pMin = glm::min(g.pMin, p);
    g.pMax = glm::max(g.pMax, p);
    g.axis += normalAt(px, i);
  }
  const float len = glm::length(g.axis);
  if (len == 0.0f) return false;
  g.axis /= len;
  for (const int i : pixels) {
    const glm::vec3 n = normalAt(px, i);
    g.cosSpread = std::min(g.cosSpread, glm::dot(n, g.axis) / std::max(glm::length(n), 1e-20f));
  }
  // Round-off: a flat group's normals differ in their last bits.
  g.cosSpread = std::max(g.cosSpread - 1e-6f, -1.0f);
  g.sinSpread = std::sqrt(std::max(1.0f - g.cosSpread * g.cosSpread, 0.0f));
  return true;
}

bool splitByNormal(const GBufferPixels& px, const std::vector<int>& pixels, const ShadingRegion& g,
                   std::vector<int>& a, std::vector<int>& b) {
  if (pixels.size() < 2) return false;
  glm::vec3 seedA = farthestNormal(px, pixels, g.axis);
  glm::vec3 seedB = farthestNormal(px, pixels, seedA);
  if (glm::dot(seedA, seedB) > 0.999f) return false;  // within 2.6°: one surface
  for (int round = 0; round < 3; ++round) {
    a.clear();
    b.clear();
    glm::vec3 sumA(0.0f), sumB(0.0f);
    for (const int i : pixels) {
      const glm::vec3 n = normalAt(px, i);
      if (glm::dot(n, seedA) >= glm::dot(n, seedB)) {
        a.push_back(i);
        sumA += n;
      } else {
        b.push_back(i);
        sumB += n;
      }
    }
    if (a.empty() || b.empty()) return false;
    if (glm::length(sumA) > 0.0f) seedA = glm::normalize(sumA);
    if (glm::length(sumB) > 0.0f) seedB = glm::normalize(sumB);
  }
  return true;
}

}  // namespace manylight
