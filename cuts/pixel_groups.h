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
  // rgb: albedo. Given, specular pixels share cuts too, bounded over their Phong lobes, and
  // the view below must be the frame's; absent, they cut for themselves.
  const float* albedo = nullptr;
  glm::vec3 eye{0.0f};                   // perspective: the eye
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  // orthographic: the viewing direction
  bool orthographic = false;
};

// Pixel i's position and normal (as stored: not always of unit length).
inline glm::vec3 positionAt(const GBufferPixels& px, std::size_t i) {
  return {px.position[4 * i], px.position[4 * i + 1], px.position[4 * i + 2]};
}
inline glm::vec3 normalAt(const GBufferPixels& px, std::size_t i) {
  return {px.normal[4 * i], px.normal[4 * i + 1], px.normal[4 * i + 2]};
}

inline bool isSpecular(const GBufferPixels& px, std::size_t i) {
  const float* ks = px.specular + 4 * i;
  return ks[0] != 0.0f || ks[1] != 0.0f || ks[2] != 0.0f;
}

// Whether pixel i may take a shared cut: covered, and Lambert unless the albedo (and with it
// the view) is given: a specular pixel's bounds need its lobe's, over the view directions.
inline bool sharesCuts(const GBufferPixels& px, std::size_t i) {
  return px.normal[4 * i + 3] != 0.0f && (px.albedo || !isSpecular(px, i));
}

// The unit mirror direction of the view at pixel i, reflect(−V, N): a light seen along l
// gives the Phong lobe max(l · m, 0)^n (R·V = l·m, scene/shading_model.h).
glm::vec3 mirrorAt(const GBufferPixels& px, std::size_t i);

// The Phong lobes of a group's specular pixels: a cone around `axis` holding their mirror
// directions, their exponents' range, and the means over all of the group's pixels of their
// albedo and specular colour (the CPU weighs a node's two bounds by these; each pixel checks
// with its own). `on` false: every pixel is Lambert, and the cut is per unit albedo.
struct SpecularLobes {
  bool on = false;
  glm::vec3 axis{0.0f};
  float cosSpread = 1.0f, sinSpread = 0.0f;
  float minExponent = 1.0f, maxExponent = 1.0f, meanExponent = 1.0f;
  glm::vec3 albedo{1.0f}, specular{0.0f};
};

// The shading points of a group: their box, and a cone around `axis` holding their normals.
struct ShadingRegion {
  glm::vec3 pMin, pMax, axis;
  float cosSpread, sinSpread;
  SpecularLobes lobes;
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
