#pragma once
// The bounds render/tile_cuts.cpp puts on a light tree node's contribution over a region of
// shading points (a box of positions, a cone of normals), as glsl/lighting_lightcuts.frag's
// nodeBounds puts them at one point. Inline: the CPU cut evaluates them millions of times a
// frame.
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "render/cpu_clones.h"

namespace manylight::region_bounds {

// The range window clamp(1 − (d²/range²)², 0, 1)² (glsl/shading.glsl).
MANYLIGHT_INLINE inline float window(float d2, float invRange2) {
  const float x = d2 * invRange2;
  const float w = std::clamp(1.0f - x * x, 0.0f, 1.0f);
  return w * w;
}

// cos(max(θ − γ, 0)) for θ = acos(c), γ the spread (cos cg, sin sg): the largest cosine to
// any normal of the tile when c bounds the cosine to their mean direction.
MANYLIGHT_INLINE inline float widenUp(float c, float cg, float sg) {
  if (cg <= 0.0f) return 1.0f;  // γ ≥ π/2: some normal may face the light head on
  c = std::clamp(c, 0.0f, 1.0f);
  const float s = std::sqrt(1.0f - c * c);
  return s <= sg ? 1.0f : c * cg + s * sg;
}

// cos(min(θ + γ, π/2))⁺ for θ = acos(c): the smallest cosine to any normal of the tile.
MANYLIGHT_INLINE inline float widenDown(float c, float cg, float sg) {
  if (cg <= 0.0f) return 0.0f;
  c = std::clamp(c, 0.0f, 1.0f);
  return std::max(c * cg - std::sqrt(1.0f - c * c) * sg, 0.0f);
}

// The nearest and farthest squared lengths of the vectors in the box [dMin, dMax].
MANYLIGHT_INLINE inline glm::vec2 lengths2(glm::vec3 dMin, glm::vec3 dMax) {
  const glm::vec3 nearest = glm::clamp(glm::vec3(0.0f), dMin, dMax);
  const glm::vec3 farthest = glm::max(glm::abs(dMin), glm::abs(dMax));
  return {glm::dot(nearest, nearest), glm::dot(farthest, farthest)};
}

// The cosine bounds of nodeBounds in glsl/lighting_lightcuts.frag, over the box D of all
// vectors from a shading point of the region to a light of the node (directional trees:
// the node's directions): the largest and smallest cosine to `u` over the box (`dist`: the
// nearest or farthest distance), and over its bounding sphere (upper, lower).
MANYLIGHT_INLINE inline float cosineUpper(glm::vec3 u, glm::vec3 dMin, glm::vec3 dMax, float dist) {
  const glm::vec3 m = glm::max(u * dMin, u * dMax);
  const float num = m.x + m.y + m.z;
  if (num <= 0.0f) return 0.0f;
  return dist > 0.0f ? std::min(num / dist, 1.0f) : 1.0f;
}

MANYLIGHT_INLINE inline float cosineLower(glm::vec3 u, glm::vec3 dMin, glm::vec3 dMax, float dist) {
  const glm::vec3 m = glm::min(u * dMin, u * dMax);
  const float num = m.x + m.y + m.z;
  return num > 0.0f ? std::min(num / dist, 1.0f) : 0.0f;
}

MANYLIGHT_INLINE inline glm::vec2 sphereCosines(glm::vec3 u, glm::vec3 dMin, glm::vec3 dMax) {
  const glm::vec3 c = 0.5f * (dMin + dMax);
  const float r2 = 0.25f * glm::dot(dMax - dMin, dMax - dMin);
  const float d2 = glm::dot(c, c);
  if (d2 <= r2) return {1.0f, 0.0f};
  const float cosT = glm::dot(u, c) / std::sqrt(d2);
  const float sinT = std::sqrt(std::max(1.0f - cosT * cosT, 0.0f));
  const float sinA = std::sqrt(r2 / d2);
  const float cosA = std::sqrt(1.0f - sinA * sinA);
  const float upper = cosT >= cosA ? 1.0f : cosT * cosA + sinT * sinA;
  const float lower = std::max(cosT * cosA - sinT * sinA, 0.0f);
  return {upper, lower};
}

// Whether some light of a spot node may shine on some point of the region: as spotMayReach
// in the shader, with the region's bounding sphere added to the node's.
MANYLIGHT_INLINE inline bool spotMayReach(glm::vec3 boxMin, glm::vec3 boxMax, glm::vec3 axis,
                                          float cosT, float sinT, glm::vec3 pMin, glm::vec3 pMax) {
  const glm::vec3 c = 0.5f * (boxMin + boxMax);
  const float r = 0.5f * glm::length(boxMax - boxMin) + 0.5f * glm::length(pMax - pMin);
  const glm::vec3 toP = 0.5f * (pMin + pMax) - c;
  const float d = glm::length(toP);
  if (d <= r) return true;
  const float sinA = r / d;
  const float cosA = std::sqrt(std::max(1.0f - sinA * sinA, 0.0f));
  const float sinSum = sinT * cosA + cosT * sinA;
  if (sinSum < 0.0f) return true;
  const float cosSum = cosT * cosA - sinT * sinA;
  return glm::dot(axis, toP) / d >= cosSum;
}

// The lowest and highest cosine between `axis` and a direction from `position` to a point
// of the box [pMin, pMax] (its bounding sphere): cos(ψ + α) and cos(max(ψ − α, 0)), ψ the
// angle to the sphere's centre and α its angular radius; (−1, 1) when `position` is inside.
MANYLIGHT_INLINE inline glm::vec2 axisCosines(glm::vec3 axis, glm::vec3 position, glm::vec3 pMin,
                                              glm::vec3 pMax) {
  const glm::vec3 w = 0.5f * (pMin + pMax) - position;
  const float d = glm::length(w);
  const float r = 0.5f * glm::length(pMax - pMin);
  if (d <= r) return {-1.0f, 1.0f};
  const float cosW = glm::dot(axis, w) / d;
  const float sinW = std::sqrt(std::max(1.0f - cosW * cosW, 0.0f));
  const float sinA = r / d, cosA = std::sqrt(std::max(1.0f - sinA * sinA, 0.0f));
  const float low = sinW * cosA + cosW * sinA < 0.0f ? -1.0f : cosW * cosA - sinW * sinA;
  const float high = cosW >= cosA ? 1.0f : cosW * cosA + sinW * sinA;
  return {low, high};
}

}  // namespace manylight::region_bounds
