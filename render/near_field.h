#pragma once
// The near field of `--indirect caches` (render/light_caches.h). A map texel's light varies
// fastest close to it, on the scale of the texel itself, where a cache a cell away cannot
// stand in for the pixel: along the edges where walls meet, the texels beside a pixel give
// most of its indirect light. So each texel's light is split by distance d from where it
// arrives, with r the texel's near radius in the receiver's cascade (glsl/near_weight.glsl):
//   far part  w(d) = smoothstep(r, 2r, d), gathered at the caches and interpolated;
//   near part 1 − w(d), gathered per pixel, exactly as `--indirect exact` does
//                       (glsl/cache_near.frag).
// r is the larger of the map's radius (nearRadius) and kNearCells cells of the cascade: the
// far part is smooth on the scale of r, so trilinear interpolation between that cascade's
// caches holds it, and a pixel gets the same r as the caches it interpolates. The pixels find
// their near texels through a world-space grid per cascade, of cells 2 · r (the largest r) or
// r (kNearTexelsPerCell), built on the CPU from the maps read back: each pixel reads the cells
// within 2 · r of it, and leaves out those wholly behind its surface, those whose texels all
// lie in one plane that it is in or behind, and those beyond that reach.
#include <glm/glm.hpp>
#include <vector>

#include "gl/objects.h"
#include "render/cache_layout.h"
#include "render/gbuffer.h"
#include "render/light_caches.h"

namespace manylight {

// A map's near radius: kNearTexelEdges × the median edge (√area) of its reflecting texels; 0
// for a map that reflects nothing.
float nearRadius(const std::vector<float>& flux);
inline constexpr float kNearTexelEdges = 1.5f;
// Grid cells a side at most; where the texels' bounds would need more, the cells grow.
inline constexpr int kNearGridCells = 64;
// A cascade's grid cells are as wide as its texels' reach (twice the largest near radius), so
// a pixel reads at most 3 a side; where they would hold more texels than this on average
// (denser maps, or several over the same surfaces), they are half as wide, at most 5 a side:
// more cells to read, of which the distance and facing tests leave out more texels.
inline constexpr std::size_t kNearTexelsPerCell = 16;
// Near texels one pass reads at most per pixel and cascade: two cascades' worth stays under
// llvmpipe's 65,535 loop iterations per invocation.
inline constexpr int kNearTexelsPerPass = 30000;

class NearField {
 public:
  NearField() = default;
  // Forgets the texels added so far.
  void clear();
  // Adds a map's reflecting texels (read back as RGBA floats: position, normal, flux with the
  // patch area in w), each of near radius `radius`.
  void add(const std::vector<float>& position, const std::vector<float>& normal,
           const std::vector<float>& flux, float radius);
  long long texels() const { return (long long)texels_.size(); }
  // Bins the texels in a grid per cascade of `grid` and uploads them, unless they were binned
  // for cascades of the same cells since the last clear. Throws gl::GlError.
  void upload(const CacheGrid& grid);
  // Adds every covered pixel's near light to `camera`'s radiance target; returns the passes.
  int draw(const GBuffer& camera);

 private:
  struct Texel {
    glm::vec4 positionRadius, normalArea, flux;  // radius: the map's nearRadius
  };
  std::vector<Texel> texels_;
  int uploaded_ = 0;           // texels
  std::vector<float> binned_;  // the cascades' cells of the bins uploaded; empty: none
  CacheGrid cascades_;
  glm::vec3 origin_{0.0f};
  std::vector<float> cell_;        // per cascade, the grid's cell edge
  std::vector<float> reach_;       // per cascade, twice the largest near radius
  std::vector<glm::ivec3> cells_;  // per cascade, its cells per axis
  std::vector<int> firstZ_;        // per cascade, its first slice in grid_
  // Per cascade, every texel, ordered by the cascade's grid cell; per cell, its range and plane.
  gl::Texture positions_, normals_, fluxes_, grid_, planes_;
  static std::vector<glm::vec2> binCascade(const std::vector<Texel>& texels, glm::vec3 lo,
                                           glm::vec3 hi, float reach, std::vector<float>& lists,
                                           float& cell, glm::ivec3& cells);
  static std::vector<glm::vec2> binTexels(const std::vector<Texel>& texels, glm::vec3 lo,
                                          float cell, glm::ivec3 cells, std::vector<float>& lists);
  void uploadGrids(glm::ivec3 size, const std::vector<std::vector<glm::vec2>>& ranges,
                   const std::vector<std::vector<glm::vec4>>& planes);
  static std::vector<glm::vec4> cellPlanes(const std::vector<Texel>& texels,
                                           const std::vector<float>& lists,
                                           const std::vector<glm::vec2>& ranges, float tolerance);
};

}  // namespace manylight
