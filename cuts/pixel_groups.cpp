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

// The lobes of `pixels` (SpecularLobes); off unless some pixel is specular and the albedo is
// given.
SpecularLobes specularLobes(const GBufferPixels& px, const std::vector<int>& pixels) {
  SpecularLobes s;
  if (!px.albedo) return s;
  glm::vec3 albedo(0.0f), specular(0.0f), axis(0.0f);
  float lowest = std::numeric_limits<float>::max(), highest = 0.0f, sum = 0.0f;
  int count = 0;
  for (const int i : pixels) {
    const std::size_t k = std::size_t(i);
    albedo += glm::vec3(px.albedo[4 * k], px.albedo[4 * k + 1], px.albedo[4 * k + 2]);
    specular += glm::vec3(px.specular[4 * k], px.specular[4 * k + 1], px.specular[4 * k + 2]);
    if (!isSpecular(px, k)) continue;
    const float e = px.position[4 * k + 3];
    lowest = std::min(lowest, e);
    highest = std::max(highest, e);
    sum += e;
    ++count;
    axis += mirrorAt(px, k);
  }
  if (count == 0) return s;
  const float len = glm::length(axis);
  s.on = true;
  s.albedo = albedo / float(pixels.size());
  s.specular = specular / float(pixels.size());
  s.minExponent = lowest;
  s.maxExponent = highest;
  s.meanExponent = sum / float(count);
  s.cosSpread = -1.0f;  // mirror directions that sum to zero: no cone
  if (len > 0.0f) {
    s.axis = axis / len;
    float lowestCos = 1.0f;
    for (const int i : pixels) {
      if (isSpecular(px, std::size_t(i)))
        lowestCos = std::min(lowestCos, glm::dot(mirrorAt(px, std::size_t(i)), s.axis));
    }
    s.cosSpread = std::max(lowestCos - 1e-6f, -1.0f);  // round-off, as the normals' cone
  }
  s.sinSpread = std::sqrt(std::max(1.0f - s.cosSpread * s.cosSpread, 0.0f));
  return s;
}

}  // namespace

glm::vec3 mirrorAt(const GBufferPixels& px, std::size_t i) {
  const glm::vec3 p = positionAt(px, i);
  const glm::vec3 v = px.orthographic ? -px.forward : glm::normalize(px.eye - p);
  const float len = glm::length(normalAt(px, i));
  const glm::vec3 n = len > 0.0f ? normalAt(px, i) / len : glm::vec3(0.0f);
  const glm::vec3 m = 2.0f * glm::dot(n, v) * n - v;
  const float mLen = glm::length(m);
  return mLen > 0.0f ? m / mLen : v;
}

bool shadingRegion(const GBufferPixels& px, const std::vector<int>& pixels, ShadingRegion& g) {
  g = ShadingRegion{glm::vec3(std::numeric_limits<float>::max()),
                    glm::vec3(-std::numeric_limits<float>::max()),
                    glm::vec3(0.0f),
                    1.0f,
                    0.0f,
                    SpecularLobes{}};
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
  g.lobes = specularLobes(px, pixels);
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
