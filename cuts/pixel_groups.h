#pragma once
// The shading points a shared cut must hold for (cuts/tile_cuts.h): a group of a square's
// pixels, seen as the box of their positions and a cone around the mean of their normals;
// and the split of a group whose normals spread wide into one group per surface. Where a
// square straddles an edge or a silhouette (a cube's edge, a sphere against the wall behind
// it), one cone holds normals 90° and more apart, its cosine bounds are loose, and the
// square's cut fills up; the pixels of each surface alone have a narrow cone and share a
// cut of the usual size. No GL here.
#include <glm/glm.hpp>
#include <vector>

namespace manylight {

// The G-buffer as read back, rows bottom-up (GL's order), RGBA floats per pixel.
struct GBufferPixels {
  int width = 0, height = 0;
  const float* position = nullptr;  // xyz; w: Phong exponent
  const float* normal = nullptr;    // xyz; w: 0 on background pixels
  const float* specular = nullptr;  // rgb: Phong specular colour
};

// Pixel i's position and normal (as stored: not always of unit length).
inline glm::vec3 positionAt(const GBufferPixels& px, std::size_t i) {
  return {px.position[4 * i], px.position[4 * i + 1], px.position[4 * i + 2]};
}
inline glm::vec3 normalAt(const GBufferPixels& px, std::size_t i) {
  return {px.normal[4 * i], px.normal[4 * i + 1], px.normal[4 * i + 2]};
}

// Whether pixel i may take a shared cut: covered, and Lambert only (a specular pixel's
// bounds are not per unit albedo, so it cuts for itself).
inline bool sharesCuts(const GBufferPixels& px, std::size_t i) {
  const float* ks = px.specular + 4 * i;
  return px.normal[4 * i + 3] != 0.0f && ks[0] == 0.0f && ks[1] == 0.0f && ks[2] == 0.0f;
}

// The shading points of a group: their box, and a cone around `axis` holding their normals.
struct ShadingRegion {
  glm::vec3 pMin, pMax, axis;
  float cosSpread, sinSpread;
};

// The region of `pixels` (indices y · width + x of covered pixels, at least one). False when
// their normals sum to zero: no axis, no cone.
bool shadingRegion(const GBufferPixels& px, const std::vector<int>& pixels, ShadingRegion& g);

// Splits `pixels` in two by their normals: two-means on the sphere, seeded with the normal
// farthest from `g`'s axis and the normal farthest from that one. False, leaving `a` and `b`
// unspecified, when all face the same way.
bool splitByNormal(const GBufferPixels& px, const std::vector<int>& pixels, const ShadingRegion& g,
                   std::vector<int>& a, std::vector<int>& b);

}  // namespace manylight
