#include "bake/light_support.h"

#include <algorithm>
#include <cmath>

namespace manylight::octree {

// Where a ranged light can contribute: a ball, cut by a cone for a spot; and the ball
// around that support used for the coarse tests.
Support supportOf(const Light& light) {
  Support s;
  s.position = light.position;
  s.range = light.range;
  s.centre = light.position;
  s.radius = light.range;
  if (light.type != LightType::Spot) return s;
  const double outer = std::clamp(double(light.outerConeAngle), 0.0, 1.5707963267948966);
  s.spot = true;
  s.axis = glm::normalize(light.direction);
  s.cosOuter = float(std::cos(outer));
  s.sinOuter = float(std::sin(outer));
  // The smallest ball around the cone's cap: through the apex and the rim for a narrow cone,
  // centred on the rim's plane for a wide one.
  if (outer <= 0.7853981633974483) {
    const double r = light.range / (2.0 * std::cos(outer));
    s.centre = light.position + s.axis * float(r);
    s.radius = float(r);
  } else {
    s.centre = light.position + s.axis * (light.range * s.cosOuter);
    s.radius = light.range * s.sinOuter;
  }
  return s;
}

namespace {

float squaredDistanceToBox(glm::vec3 p, const Box& b) {
  const glm::vec3 d = glm::max(glm::max(b.lo - p, p - b.hi), glm::vec3(0.0f));
  return glm::dot(d, d);
}

}  // namespace

// Whether the spot's cone may meet the ball of radius `rho` around `c`: in front of the
// apex, within range, and within the outer angle of the axis plus the ball (conservative:
// never false where they meet).
bool withinCone(const Support& s, glm::vec3 c, float rho) {
  const glm::vec3 v = c - s.position;
  const float along = glm::dot(v, s.axis);
  if (along < -rho || along > s.range + rho) return false;
  // cos · across ≤ rho + sin · along, squared where both sides are non-negative.
  const float right = rho + s.sinOuter * along;
  if (right < 0.0f) return false;
  const float across2 = std::max(glm::dot(v, v) - along * along, 0.0f);
  return s.cosOuter * s.cosOuter * across2 <= right * right;
}

namespace {

// Whether the ball of radius `rho` around `c` lies inside the cone, ignoring its range: its
// distance to the cone's side is at least rho.
bool insideCone(const Support& s, glm::vec3 c, float rho) {
  const glm::vec3 v = c - s.position;
  const float along = glm::dot(v, s.axis);
  const float across = std::sqrt(std::max(glm::dot(v, v) - along * along, 0.0f));
  return along > rho && s.sinOuter * along - s.cosOuter * across >= rho;
}

}  // namespace

bool coneMeetsBox(const Support& s, const Box& b, float margin, int depth) {
  const glm::vec3 size = b.hi - b.lo;
  const glm::vec3 c = 0.5f * (b.lo + b.hi);
  const float rho = 0.5f * glm::length(size) + margin;
  if (!withinCone(s, c, rho)) return false;
  if (depth == 0 || insideCone(s, c, rho)) return true;
  // Halves along the axes not much thinner than the longest, so a thin slab splits in its
  // plane only.
  const float longest = std::max({size.x, size.y, size.z});
  const glm::bvec3 split(size.x > 0.25f * longest, size.y > 0.25f * longest,
                         size.z > 0.25f * longest);
  const glm::vec3 half = glm::mix(size, 0.5f * size, split);
  for (int k = 0; k < 8; ++k) {
    const glm::ivec3 o(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    if ((o.x && !split.x) || (o.y && !split.y) || (o.z && !split.z)) continue;
    const glm::vec3 lo = b.lo + glm::vec3(o) * half;
    if (coneMeetsBox(s, {lo, lo + half}, margin, depth - 1)) return true;
  }
  return false;
}

// Whether the support may overlap the box grown by `margin` (conservative).
bool overlaps(const Support& s, const Box& b, float margin, int coneDepth) {
  const float reach = s.radius + margin;
  if (squaredDistanceToBox(s.centre, b) > reach * reach) return false;
  return !s.spot || coneMeetsBox(s, b, margin, coneDepth);
}

// Whether every point of the box is inside the support, `margin` from its boundary.
bool contains(const Support& s, const Box& b, float margin) {
  const float inner = s.range - margin;
  if (inner <= 0.0f) return false;
  // Two opposite corners are the box's diagonal apart, so a ball holds both only if its
  // diameter exceeds the diagonal.
  const glm::vec3 size = b.hi - b.lo;
  if (glm::dot(size, size) >= 4.0f * inner * inner) return false;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 c((corner & 1) ? b.hi.x : b.lo.x, (corner & 2) ? b.hi.y : b.lo.y,
                      (corner & 4) ? b.hi.z : b.lo.z);
    const glm::vec3 v = c - s.position;
    const float d2 = glm::dot(v, v);
    if (d2 >= inner * inner) return false;
    // Inside the cone with room to spare (the cone and the ball are convex, so the box is
    // inside both when its corners are).
    if (s.spot && glm::dot(v, s.axis) < s.cosOuter * std::sqrt(d2) + margin) return false;
  }
  return true;
}

Box grow(const Box& b, float by) { return {b.lo - glm::vec3(by), b.hi + glm::vec3(by)}; }

Box sphereBox(const Support& s) {
  return {s.centre - glm::vec3(s.radius), s.centre + glm::vec3(s.radius)};
}

}  // namespace manylight::octree
