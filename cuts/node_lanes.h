#pragma once
// The CPU cut's node bounds and far field linearisation bounds (cuts/cut_region.cpp) for up
// to kLanes nodes at once (cuts/node_lanes_kernel.h), written once over a lane type: one
// float or, on x86-64 CPUs with AVX2 (under GCC), eight in a register. Every lane takes every
// branch and the results are selected, so the two give the same results bit for bit: the same IEEE
// operations in the same order (no fused multiply-add, nothing reassociated; min and max
// keep std::min and std::max's operand order).
#include <glm/glm.hpp>

#include "cuts/pixel_groups.h"

// The lanes' helpers are inlined into each lane type's copy of the kernels.
#if defined(__GNUC__)
#define MANYLIGHT_INLINE __attribute__((always_inline))
#else
#define MANYLIGHT_INLINE
#endif

namespace manylight {

inline constexpr int kLanes = 8;

// Up to kLanes nodes, one lane each: kNodeRows rows of TileCutter::Node's fields, in the order
// its first kNodeRows floats hold them (gatherNodes), then the tree, and whether the
// representative's shading at the region's centre is known (its parent's, the same light).
struct NodeLanes {
  float boxMin[3][kLanes], boxMax[3][kLanes], intensity[3][kLanes], axis[3][kLanes];
  float invRange2[kLanes], w2[kLanes], sinTheta[kLanes];
  // repCos rides along with the rows; the bounds take the representative's cone terms below.
  float repPoint[3][kLanes], repAxis[3][kLanes], repInvRange2[kLanes], repCos[kLanes];
  float leaf[kLanes];  // 1 for a leaf
  // Spot nodes (TileCutter::SpotCone): the cosine of their axes' spread about `axis`, the
  // smoothstep terms (scale, offset) of the widest and of the narrowest cone, the smallest
  // range's 1/range², and the representative's cone terms.
  float spreadCos[kLanes], upScale[kLanes], upOffset[kLanes], lowScale[kLanes];
  float lowOffset[kLanes], lowInvRange2[kLanes], repConeScale[kLanes], repConeOffset[kLanes];
  float tree[kLanes];
  float knownUnit[kLanes], unit[kLanes];  // 1: `unit` holds it
};
inline constexpr int kNodeRows = 32;

// Rows [0, kNodeRows) of `out`'s lanes [0, count) from the first kNodeRows floats at each of
// `nodes` (32-byte aligned; 1 ≤ count ≤ kLanes); lanes past `count` take lane 0's. Eight at once, a
// transpose, where `wide` and the CPU has AVX2.
void gatherNodes(const float* const nodes[kLanes], int count, NodeLanes& out, bool wide = true);

// A spot node's cone factor bounds (cuts/lane_cones.h's spotConeLanes, and its one-point form
// in glsl/lightcuts_walk.glsl, spotConeFactor): within kSpotReachSlack times the bounding
// spheres' reach the angular radius is taken as 90°, and the cosines' bounds are widened by
// kSpotCosineMargin (lane_cones.h says why the two go together).
inline constexpr float kSpotReachSlack = 1.0001f;
inline constexpr float kSpotCosineMargin = 1e-5f;

// What the bounds need of the group of shading points and of the rule.
struct RegionTerms {
  ShadingRegion g;
  glm::vec3 centre;
  float halfDiagonal;           // 0.5 · |pMax − pMin|
  float h2;                     // its square, as 0.25 · |pMax − pMin|²
  float slackRate, slackFloor;  // node colours' decoding slack (NodeColourCoder)
  bool total;                   // the total rule: lower bounds too
  // Lobes' lower bounds 0: the bounds of glsl/lightcuts_walk.glsl's nodeBounds, which bounds
  // a Phong lobe from above only, for cuts that predict a pixel's own walk
  // (CutRule::walkBounds).
  bool walkBounds = false;
  // Where g.lobes.on: the cone of the group's mirror directions (g.lobes' axis and spread, as
  // a region's normals), about which BoundLanes::lobeTop and lobeBottom are taken.
  ShadingRegion mirror{};
};

// Per lane: the representative's shading at the centre per unit intensity, and the item's
// measure (−1: a leaf; +inf: unbounded), error (upper, or upper − lower), estimate and
// whether it is dark (TileCutter::cutRegion's Item).
// Where the region has specular lobes, also (leaves too): cos⁺ · window(d⁻)/d⁻² (0 where no
// light of the node reaches the region) and cos⁻ · window⁻(d⁺)/d⁺², a spot's times its cone
// factor's upper and lower bounds (spotConeLanes in cuts/lane_cones.h); with
// cosᵣ⁺ and cosᵣ⁻ the largest and smallest cosines between a mirror direction of the region
// and a direction from its box into the node's, clamped to [0, 1], an upper bound on
// cosᵣ⁺^e⁻ (0 where the first term is) and a lower bound on cosᵣ⁻^e⁺ (0 where the second is),
// e⁻ and e⁺ the lobes' smallest and largest exponents; and c^ē, c the cosine between the mirror
// axis and the direction from the centre to the representative (0 where c ≤ 0), ē the mean
// exponent. From these cuts/cut_region_cut.h bounds the node's Phong lobe and estimates it.
struct BoundLanes {
  float unit[kLanes], measure[kLanes], dark[kLanes];
  float error[3][kLanes], estimate[3][kLanes];
  float upperScale[kLanes], lowerScale[kLanes];
  float lobeTop[kLanes], lobeBottom[kLanes], lobeTowards[kLanes];
};

// Lanes [0, count) of `out` for the nodes in lanes [0, count) of `in` (count ≤ kLanes); all
// kLanes lanes of `in` must hold numbers. `wide`: eight lanes at once where the CPU has AVX2,
// else one at a time (the tests compare the two).
void nodeBounds(const RegionTerms& region, const NodeLanes& in, int count, BoundLanes& out,
                bool wide = true);
bool wideNodeBounds();  // whether `wide` takes eight lanes at once here

// x^e for kLanes values x in [0, 1] and an exponent e ≥ 1, as BoundLanes' lobe terms take
// it: an upper bound, a lower bound and an estimate (cuts/node_lanes_kernel.h's powLanes).
void lobePowers(const float x[kLanes], float e, float upper[kLanes], float lower[kLanes],
                float estimate[kLanes], bool wide = true);

// Up to kLanes entries of a cut (their representatives' lights), one lane each, and their far
// field linearisation bounds T (cuts/far_field.h) per unit albedo and intensity over the
// region, or where they do not fold −1, kZeroEntry (nothing at any point of the region), or
// kFullCone (a spot whose cone lets all its light through to the whole region).
inline constexpr float kZeroEntry = -2.0f, kFullCone = -3.0f;
struct FoldLanes {
  float tree[kLanes];
  float repPoint[3][kLanes], repAxis[3][kLanes], repInvRange2[kLanes];
  float repCos[kLanes];                         // a spot's outer cosine
  float coneScale[kLanes], coneOffset[kLanes];  // a spot's cone (SpotConeTerms)
};
void foldBounds(const RegionTerms& region, const FoldLanes& in, int count, float t[kLanes],
                bool wide = true);

// Up to kLanes point or spot entries folded into a far field (cuts/far_field.h), and the
// sums of their terms per channel and lane: f(c) and Df(c) (by columns) times the intensity.
struct FarLanes {
  float position[3][kLanes], invRange2[kLanes];
  float spot[kLanes];  // 1: a spot, whose cone follows
  float coneAxis[3][kLanes], coneScale[kLanes], coneOffset[kLanes];
  float intensity[3][kLanes];
};
struct FarSums {
  float f[3][3][kLanes];  // [channel][component][lane]
  float j[3][9][kLanes];  // [channel][3 · column + row][lane]
};
// Adds lanes [0, count) of `in` to `sums`, about `centre` (single precision; FarField::add
// takes the sums over the lanes in double).
void addFarField(glm::vec3 centre, const FarLanes& in, int count, FarSums& sums, bool wide = true);

}  // namespace manylight
