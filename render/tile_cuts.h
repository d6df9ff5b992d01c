#pragma once
// Cuts shared by the pixels of a screen tile (no GL here; render/lightcuts_method.cpp uploads
// the result and glsl/lighting_lightcuts.frag uses it).
//
// Per pixel, most of a lightcut's cost on a software rasteriser is finding the cut: error
// bounds for about twice as many nodes as the cut holds, in loops whose length differs
// from pixel to pixel. Neighbouring pixels mostly want the same cut. So, per square of
// tileSize × tileSize pixels, the CPU finds one cut with bounds that hold over the whole
// square — the nearest and farthest distances from the box of its shading points to a
// node's box, cosines widened by the spread of its normals around their mean — refining
// the node with the largest bound first, as the paper does, until the stopping rule holds
// against the estimate at the square's centre with a margin (kMargin in the .cpp). A square
// whose cut would exceed the maximum is split into quarters, down to kFinestTile. Nodes
// that cannot reach any point of the square are left out. Each pixel then only sums the
// cut's representatives (the same loop for every pixel of the square; the entries that
// light the whole square from in front folded into one linear far field, far_field.h,
// with their linearisation error added to their bounds) and checks the rule
// for itself with the square's bounds, which hold at every one of its pixels:
//   node rule:  max(albedo ∘ U) ≤ ε · max(estimate), U the channel-wise largest upper
//               bound over the cut's internal nodes;
//   total rule: max(albedo ∘ B) ≤ ε · max(estimate − albedo ∘ B) or ≤ the absolute floor,
//               B the sum of (upper − lower) over the cut.
// U and B are per unit albedo (Lambert only), so the check is exactly the per-pixel rule
// with bounds at least the pixel's own: the total rule's guarantee is kept. A pixel whose
// check fails, and every pixel of a square left to per-pixel cuts (a specular material, a
// cut over the maximum even at the finest size), walks its own cut as before.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "bake/light_tree_pack.h"
#include "scene/scene.h"

namespace manylight {

// What the rule asks of a cut (see LightcutsSettings).
struct CutRule {
  float error = 0.02f;  // ε
  bool total = false;   // the total rule; else the node rule
  int maxCut = 1000;
};

// The G-buffer as read back, rows bottom-up (GL's order), RGBA floats per pixel.
struct GBufferPixels {
  int width = 0, height = 0;
  const float* position = nullptr;  // xyz; w: Phong exponent
  const float* normal = nullptr;    // xyz; w: 0 on background pixels
  const float* specular = nullptr;  // rgb: Phong specular colour
};

// The frame's tile cuts as texels of 4 words (GL_RGBA32UI), one texture buffer:
//   texel 2t      finest square t (row-major, bottom-up): first entry texel, then the
//                 number of entries of the directional, point and spot trees, in that order
//   texel 2t + 1  U (node rule) or B (total rule) per unit albedo, as float bits; flags
//                 (kTilePerPixel: the square's pixels cut for themselves) and, from bit
//                 kTileFoldedShift, how many entries the far field holds
//   from texel 2·tiles: each cut's far field (render/far_field.h: kFarFieldTexels texels,
//     when it holds any entry), then its entries, directional, point, spot, as float bits:
//     directional, point: 2 texels, the representative's direction towards it (or
//                         position) and 1/range² (0: none), then the node's intensity RGB, 0
//     spot:               3 texels: the representative's position and 1/range², its
//                         axis and cone scale, the node's intensity RGB and the cone
//                         offset (as the light texture holds them)
// Several squares may share one cut.
struct TileCuts {
  int tileSize = 0, tilesX = 0, tilesY = 0;
  std::vector<std::uint32_t> texels;  // 4 words each
  long long boundEvaluations = 0;     // on the CPU, all tiles together
  int sharedTiles = 0;                // squares with a shared cut
  int perPixelTiles = 0;              // covered squares left to per-pixel cuts
};

inline constexpr std::uint32_t kTilePerPixel = 1u;
inline constexpr int kTileFoldedShift = 8;
// A square whose cut would exceed the maximum is split into quarters, down to this size;
// the texels hold one header per square of this size (several may share a cut).
inline constexpr int kFinestTile = 4;

class TileCutter {
 public:
  // Decodes the nodes of `packed`, the trees of `lights`.
  TileCutter(const PackedTrees& packed, const std::vector<Light>& lights);

  // Cuts for every tile of the frame, on `threads` threads.
  TileCuts cut(const GBufferPixels& pixels, int tileSize, const CutRule& rule, int threads) const;

 private:
  // A node as glsl/light_tree.glsl's fetchNode reads it, decoded once.
  struct Node {
    glm::vec3 boxMin, boxMax, intensity, axis{0.0f};
    int representative;
    float invRange2, w2, sinTheta = 0.0f;
    bool leaf;
  };
  // A spot's cone as the light texture holds it: smoothstep(clamp(cos · scale + offset)),
  // cos to the axis (the way it shines).
  struct SpotCone {
    glm::vec3 axis;
    float scale, offset;
  };
  struct Region;
  struct Result;
  const Node& node(int tree, int i) const { return nodes_[tree][std::size_t(i)]; }
  static Node decode(const PackedTrees& packed, int tree, int i);
  Result cutTile(const Region& region, const CutRule& rule,
                 std::vector<std::uint32_t>& entries) const;
  static bool region(const GBufferPixels& px, int x0, int y0, int x1, int y1, Region& g,
                     bool& perPixel);

  std::vector<Node> nodes_[3];  // per tree
  int leaves_[3];
  NodeColourCoder colour_;
  std::vector<int> leafOfSlot_;  // light texture slot → its leaf node in its tree
  const SpotCone& spotCone(int slot) const { return spotCones_[std::size_t(slot - spotStart_)]; }
  std::vector<SpotCone> spotCones_;  // per spot slot, from spotStart_
  int spotStart_ = 0;
};

}  // namespace manylight
