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
// caches holds it, and a pixel gets the same r as the caches it interpolates.
//
// The near texels come in entries: a map's cluster of kRsmClusterEdge² texels
// (render/rsm_clusters.h) where its radius is at most kNearClusterSpread · r, else each of its
// texels alone. A pixel farther from a flat cluster than kRsmClusterDistance radii takes its
// light as that of one texel at its flux-weighted centre, as the caches' gather does, and sums
// its texels nearer: so a map of texels much smaller than r (a narrow spot, a near wall) costs
// a pixel its clusters, not its texels. The pixels find their entries through a world-space
// grid per cascade, of cells as wide as the entries' reach (2r and an entry's radius) or half
// that (kNearEntriesPerCell), built on the CPU from the maps read back (render/near_grid.h):
// each pixel reads the cells its own cell lists, those whose entries' texels lie within 2r
// of its cell (r the cascade's largest), and leaves out those wholly behind its surface, and
// of each cell the entries on the plane most of its texels share where it is in or behind
// that plane; its cell lists last the cells wholly on one plane, which such a pixel skips at
// once.
#include <cmath>
#include <glm/glm.hpp>
#include <vector>

#include "gl/objects.h"
#include "render/cache_layout.h"
#include "render/gbuffer.h"
#include "render/light_caches.h"
#include "render/pixel_classes.h"
#include "render/rsm_clusters.h"

namespace manylight {

// A map's near radius: kNearTexelEdges × the median edge (√area) of its reflecting texels; 0
// for a map that reflects nothing.
float nearRadius(const std::vector<float>& flux);
inline constexpr float kNearTexelEdges = 1.5f;
// Grid cells a side at most; where the texels' bounds would need more, the cells grow.
inline constexpr int kNearGridCells = 64;
// Entries a cell holds on average at most: where cells as wide as the reach would hold more
// (denser maps, or several over the same surfaces) they are half as wide, at most 5 a side.
inline constexpr std::size_t kNearEntriesPerCell = 16;
// A cluster stays one entry while its radius is at most this × its texels' r in the cascade,
// so that the cells' reach (2r and the entries' largest radius) grows little.
inline constexpr float kNearClusterSpread = 0.25f;
// Loop iterations one pass takes at most per pixel and cascade (an entry's, and its texels'
// where it is summed texel by texel; NearField::cascadePasses): two cascades' worth stays under
// llvmpipe's 65,535 loop iterations per invocation.
inline constexpr int kNearTexelsPerPass = 30000;
// A cell's plane (NearField::cellPlanes) is sought among those of its first this many
// entries.
inline constexpr std::size_t kPlaneCandidates = 4;

class NearField {
 public:
  NearField() = default;
  // Forgets the texels added so far.
  void clear();
  // Adds a map's reflecting texels (read back as RGBA floats: position, normal, flux with the
  // patch area in w), `clusters` its clusterRsm, each texel of near radius `radius`.
  void add(const std::vector<float>& position, const std::vector<float>& normal,
           const std::vector<float>& flux, const RsmClusters& clusters, float radius);
  long long texels() const { return (long long)texels_.size(); }
  // Clusters kept as one entry in the grids uploaded, summed over the cascades.
  long long clusters() const { return clusterEntries_; }
  // Bins the entries in a grid per cascade of `grid` and uploads them, unless they were binned
  // for cascades of the same cells since the last clear. Throws gl::GlError.
  void upload(const CacheGrid& grid);
  // Adds the near light of the pixels `classes` sends to it (covered, within the cascades) to
  // `camera`'s radiance target; returns the passes.
  int draw(const GBuffer& camera, const PixelClasses& classes);

 private:
  struct Texel {
    glm::vec4 position, normalArea, flux;
  };
  // A cluster, or a texel alone: its texels are texels_[first, first + count).
  struct Entry {
    glm::vec4 centreRadius;  // the flux-weighted centre, radius (0 for a texel alone)
    glm::vec4 normalArea;    // mean unit normal, mean texel area
    // Σ flux, the map's nearRadius: negative where its texels do not share the mean's facing
    // within kRsmClusterFlat
    glm::vec4 fluxRadius;
    int first = 0, count = 0;
    int cluster = 0;  // its cluster's place in clusters_
    float mapRadius() const { return std::abs(fluxRadius.w); }
  };
  std::vector<Texel> texels_;    // by cluster
  std::vector<Entry> clusters_;  // of every map added
  std::vector<float> binned_;    // the cascades' cells of the bins uploaded; empty: none
  long long clusterEntries_ = 0;
  CacheGrid cascades_;
  glm::vec3 origin_{0.0f};
  std::vector<float> cell_;        // per cascade, the grid's cell edge
  std::vector<float> reach_;       // per cascade, the farthest a pixel reads an entry from
  std::vector<float> spread_;      // per cascade, the largest entry's radius
  std::vector<glm::ivec3> cells_;  // per cascade, its cells per axis
  std::vector<int> firstZ_;        // per cascade, its first slice in grid_
  // Per pass, per cascade: its first entry and the count (in the cascade's cells' order).
  std::vector<std::vector<int>> passFirst_, passCount_;
  // Per cascade, its entries ordered by the cascade's grid cell (the entry textures); per
  // cell, its neighbour list's range (grid_); the lists' items, each a listed cell's
  // coordinates, range of entries and count before its plane's, and its plane (cellPlanes).
  gl::Texture centres_, normals_, fluxes_, grid_, neighbours_, neighbourPlanes_;
  std::vector<Entry> cascadeEntries(float cell) const;
  static void cascadePasses(const std::vector<Entry>& entries, const std::vector<int>& list,
                            const std::vector<glm::vec2>& ranges, glm::ivec3 cells, int m,
                            std::vector<int>& first, std::vector<int>& count);
  // Per cell of `ranges` (its entries in `list`), the plane (n, n·p) that the most of its
  // texels lie on (within `tolerance`), or 0 where none does; the entries whose texels all
  // lie on it are moved to the end of the cell's part of `list`, and `before` gets per cell
  // the count of those before them. A pixel in or behind the plane reads those alone: the
  // others send it no light (each texel lights the side its normal faces).
  std::vector<glm::vec4> cellPlanes(const std::vector<Entry>& entries, std::vector<int>& list,
                                    const std::vector<glm::vec2>& ranges, float tolerance,
                                    std::vector<float>& before) const;
  void uploadGrids(glm::ivec3 size, const std::vector<std::vector<glm::vec3>>& lists);
  void uploadEntries(const std::vector<Entry>& ordered);
};

}  // namespace manylight
