#pragma once
// Where a ranged light can contribute (its support, bake/light_octree.h) and the box tests
// the light octree is built and updated with. Conservative by `margin`: a test never says a
// support misses a box it meets. Internal to bake/.
#include "scene/scene.h"

namespace manylight::octree {

struct Support {
  glm::vec3 position{0.0f};
  float range = 0.0f;      // 0: not a ranged light
  glm::vec3 centre{0.0f};  // bounding sphere of the support
  float radius = 0.0f;
  bool spot = false;
  glm::vec3 axis{0.0f};
  float cosOuter = 0.0f, sinOuter = 1.0f;
};

struct Box {
  glm::vec3 lo, hi;
};

// The support of a point or spot light with a range.
Support supportOf(const Light& light);
// Whether the spot's cone may meet the ball of radius `rho` around `c`.
bool withinCone(const Support& s, glm::vec3 c, float rho);
// Whether the spot's cone may meet the box grown by `margin`: the ball around the box
// against the cone, then, where that cannot tell, the box's halves `depth` times over.
bool coneMeetsBox(const Support& s, const Box& b, float margin, int depth = 1);
// Whether the support may overlap the box grown by `margin`; a spot's cone tested with
// coneMeetsBox at `coneDepth`.
bool overlaps(const Support& s, const Box& b, float margin, int coneDepth = 1);
// Whether every point of the box is inside the support, `margin` from its boundary.
bool contains(const Support& s, const Box& b, float margin);
Box grow(const Box& b, float by);
// The bounding sphere's box.
Box sphereBox(const Support& s);

}  // namespace manylight::octree
