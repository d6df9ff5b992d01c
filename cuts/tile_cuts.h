#pragma once
// manylight_cuts: the CPU side of lightcuts, no GL. Start here.
//
// In: the light trees packed by bake/ (PackedTrees) and a frame's G-buffer read back
// (GBufferPixels: positions and normals per pixel). Out: TileCuts, every pixel's shared cut
// and the cuts' entries as texels, which render/lightcuts_method.cpp uploads and
// glsl/lighting_lightcuts.frag sums. TileCutter (this file) finds them per square of the
// screen; CellCuts (cell_cuts.h) keeps them per cell of the scene across a playback's frames.
// Read next: pixel_groups.h (the groups of pixels a cut holds for), far_field.h (entries
// folded into one linear function), node_lanes.h (node bounds eight at a time), cut_heap.h.
//
// Cuts shared by the pixels of a screen tile.
//
// Per pixel, most of a lightcut's cost on a software rasteriser is finding the cut: error
// bounds for about twice as many nodes as the cut holds, in loops whose length differs
// from pixel to pixel. Neighbouring pixels mostly want the same cut. So, per square of
// tileSize × tileSize pixels, the CPU finds one cut with bounds that hold over all of its
// pixels — the nearest and farthest distances from the box of their shading points to a
// node's box, cosines widened by the spread of their normals around their mean — refining
// the node with the largest bound first, as the paper does, until the stopping rule holds
// against the estimate at the centre with a margin (kMargin in the .cpp). A group whose cut
// would exceed the maximum is split: into its surfaces where its normals spread wide (an
// edge, a silhouette: cuts/pixel_groups.h), else into quarters, down to kFinestTile. A group
// of tileSize or less holding metal-like pixels and others is split in two before its cut is
// found (cut_frame.cpp's materials: each pixel checks the cut with its own colours).
// Nodes that cannot reach any point of the group are left out. Each pixel then only sums
// its group's cut (the same loop for every pixel of the group; the entries that light all
// of it from in front folded into one linear far field, far_field.h, with their
// linearisation error added to their bounds) and checks the rule for itself with the
// group's bounds, which hold at every one of its pixels:
//   node rule:  max(albedo ∘ U + ks ∘ Uₛ) ≤ ε · max(estimate), U the channel-wise largest
//               upper bound over the cut's internal nodes per unit albedo, Uₛ the same per
//               unit specular colour (groups with specular pixels only);
//   total rule: max(b) ≤ ε · max(estimate − b) or ≤ the absolute floor, b = albedo ∘ B +
//               ks ∘ Bₛ, B and Bₛ the sums of (upper − lower) over the cut.
// The bounds hold at every pixel of the group, so the check is exactly the per-pixel rule
// with bounds at least the pixel's own: the total rule's guarantee is kept. Specular pixels'
// bounds are on their Phong lobes over the group's mirror directions and exponents
// (SpecularLobes, cut_region_cut.h's addLobe); the far field takes the folded entries' lobes
// as a constant, within their summed spread. A pixel whose check fails, and every pixel of
// a group left to per-pixel cuts (a cut over the maximum even at the finest size), walks its
// own cut, in a second pass over
// just those pixels (the stencil marks them; glsl/lighting_lightcuts.frag).
//
// Seeds. Most of a cut's cost is the nodes above its entries, and neighbouring squares
// refine much the same ones. So squares of tileSize · 2^kSeedLevels pixels find a cut first
// (by the same rule, over all their pixels) and hand it to their quarters as a seed
// (CutSeed): a quarter re-evaluates the seed's entries that were not folded over its own
// pixels, refines those still above its target, folds what it can into the seed's far field
// (moved to its own centre: the same linear function), and keeps the bound of the entries
// folded before, which holds over the larger square and so over the quarter. Where the
// quarter's cut fills up (a seed can only be refined, and a full seed, still a seed, is the
// cut found so far) the quarter starts over from the roots. A quarter
// whose seed holds starts from a cut close to its own and evaluates far fewer node bounds;
// the seeds that do not hold lie where cuts are large anyway (object edges, dim undersides).
#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "bake/light_pack.h"
#include "bake/light_tree_pack.h"
#include "cuts/cut_texels.h"
#include "cuts/far_field.h"
#include "cuts/node_lanes.h"
#include "cuts/pixel_groups.h"
#include "scene/scene.h"

namespace manylight {

// The most entries a shared cut holds, whatever the most nodes a pixel walks itself
// (LightcutsSettings::maxCut, `--max-cut`). A pixel sums its group's entries in one loop of
// one iteration per spot entry and per two others, within the shader's budget of 65,000
// iterations (glsl/lighting_lightcuts.frag), and the far field counts its entries in 15 bits
// (below). Held to the walk's default of 2,000, groups at ε = 0.005 split until a 640×480
// frame of 65,536 mixed lights took 5,337 cuts, whose finding took 1.4 s of its 1.6 s; at
// 8,000 it takes 1,093 cuts and 0.7–0.9 s (docs/performance.md).
inline constexpr int kSharedCutLimit = 8000;
// llvmpipe ends every loop of a shader invocation once all its loops together have run 65,535
// iterations (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS), silently: glsl/lightcuts_walk.glsl
// counts its iterations against this budget.
inline constexpr int kIterationBudget = 65000;
static_assert(kSharedCutLimit < (1 << 15),
              "the far field's and the left-out entries' counts have 15 bits each (TileCuts)");

// The most texels a frame's shared cuts take (1 GiB), shared among the squares of
// TileCutter::cut in proportion to their pixels (CutRule::texelsPerPixel; the renderer also
// holds it to what the driver's texture buffers hold). Past its share, a square's cuts that
// cost the most texels per pixel they serve are dropped, full ones (RegionCut::full) first,
// and their pixels walk cuts of their own. Unbounded, the total rule's full cuts shared by
// groups of 4×4 pixels asked for 134 and 204 million texels at 16,384 uniform lights and
// ε = 0.05 and 0.1 (640×480), past llvmpipe's texture buffers (2^27 texels), and the frame
// failed. Measured on 65,536 mixed lights at 640×480: the node rule's cuts take 1.1
// (ε = 0.02) and 4.5 (ε = 0.005) texels a pixel, the total rule's full cuts 32 (ε = 0.02),
// of which 2 groups are dropped at 128 or 192 texels a pixel (this budget gives 218) and 68
// at 64, whose walks made the frame 3.5 s instead of 3.0 s. At 1920×1080 the share is 32
// texels a pixel.
inline constexpr std::size_t kCutTexelBudget = std::size_t(1) << 26;

// What the rule asks of a cut (see LightcutsSettings).
struct CutRule {
  float error = 0.02f;           // ε
  bool total = false;            // the total rule; else the node rule
  int maxCut = kSharedCutLimit;  // the most entries of a shared cut
  // Under the total rule, a full cut that smaller groups would not bring within the rule is
  // shared all the same (RegionCut::full), unless a pixel's own cut of at most ownCut nodes
  // (--max-cut) meets it. Playback's cells split instead (cuts/cell_cuts.h), and fall back to
  // the frame's squares.
  bool shareFull = true;
  int ownCut = 2000;
  // Bounds as a pixel's own walk puts them (RegionTerms::walkBounds): set on the cuts that
  // ask whether a group's pixels may walk (cut_frame.cpp's ownCutsFit), never on a shared cut.
  bool walkBounds = false;
  // Under the total rule, such a full cut is replaced by an exact one (RegionCut::exact):
  // no entries, and its pixels sum every light. Set by the renderer where the scene has at
  // most LightcutsSettings::exactLimit lights, which the shader sums within its loop budget.
  bool exactFull = false;
  // Under the node rule, how many times splitCut entries a group that can still be split may
  // take: kNearFinestSplit for groups one level above the finest and for lobe-dominated ones
  // (cut_frame.cpp's cutSquare), else 1.
  int splitScale = 1;
  // TileCutter::cut: the most entry texels a square's cuts take per pixel that shares them
  // (kCutTexelBudget over the frame's pixels, set by the renderer; unbounded here).
  std::size_t texelsPerPixel = std::size_t(1) << 32;
  // TileCutter::cut: each thread's entries go into chunks of about this many words (16 MiB),
  // reserved whole and never copied to grow (cuts/cut_texels.h says why); a chunk is closed
  // after the square that fills it, so that a square's cuts lie in one chunk.
  std::size_t chunkWords = std::size_t(1) << 22;
};

// The CPU's cuts of a frame by kind, and the node bounds each took (--stats cut_work): squares
// finding the seeds their quarters start from, groups starting from their seed, groups
// starting over from the roots after their seed's cut filled up, groups without a seed, the
// one-pixel probes of whether a group's pixels walk their own cuts, and playback's cells.
enum class CutKind { Seed, FromSeed, Retry, FromRoots, Probe, Cell };
inline constexpr int kCutKinds = 6;
inline constexpr const char* kCutKindNames[kCutKinds] = {"seeds",      "from_seeds", "retries",
                                                         "from_roots", "probes",     "cells"};
struct CutWork {
  int cuts = 0;
  int full = 0;  // of them, those that filled up before the rule held (perPixel or full)
  long long bounds = 0;
  void add(long long b, bool filled) { ++cuts, full += filled, bounds += b; }
  void add(const CutWork& o) { cuts += o.cuts, full += o.full, bounds += o.bounds; }
};
using CutWorks = std::array<CutWork, kCutKinds>;
inline void addWorks(CutWorks& to, const CutWorks& from) {
  for (int k = 0; k < kCutKinds; ++k) to[std::size_t(k)].add(from[std::size_t(k)]);
}

// The frame's shared cuts. Each pixel names its cut (cutOfPixel, one word per pixel, rows
// bottom-up as GL's; kNoSharedCut where it cuts for itself), and the cuts are texels of 4
// words (GL_RGBA32UI), one texture buffer:
//   texel 2c      cut c: its first entry texel, then the number of entries of the
//                 directional, point and spot trees, in that order
//   texel 2c + 1  U (node rule) or B (total rule) per unit albedo, as float bits; how many
//                 entries the far field holds (low 15 bits), whether the group has specular
//                 lobes (bit 15, kLobesBit), how many entries were left out because they
//                 give nothing at any pixel of the group (bits 16–30: a spot whose cone
//                 turns away from all of it, a light behind every normal or out of range of
//                 the nearest pixel), and whether the cut is full (bit 31, kFullCutBit); a
//                 full cut without entries is exact (RegionCut::exact)
//   from texel 2·cuts: a cut with lobes first has two texels, its U or B per unit specular
//     colour (the Phong lobe's bounds, below) and its far field's specular radiance per unit
//     specular colour S (constant over the group); then its far field (cuts/far_field.h:
//     kFarFieldTexels texels, when it holds any entry), then its entries, directional,
//     point, spot, as float bits:
//     directional, point: 2 texels, the representative's direction towards it (or
//                         position) and 1/range² (0: none), then the node's intensity RGB, 0
//                         (a spot whose cone lets all its light through to the whole group
//                         is written as a point)
//     spot:               3 texels: the representative's position and 1/range², its
//                         axis and cone scale, the node's intensity RGB and the cone
//                         offset (as the light texture holds them)
// A cut belongs to a group of pixels: a square, or the pixels of one surface in a square
// (cuts/pixel_groups.h), or in playback a cell of the scene (cuts/cell_cuts.h).
struct TileCuts {
  std::vector<std::uint32_t> cutOfPixel;  // per pixel
  CutTexels texels;                       // 4 words each, in pieces
  CutWorks work{};                        // the CPU's cuts by kind, and their node bounds
  int sharedCuts = 0;                     // groups with a shared cut
  int exactCuts = 0;                      // of them, exact ones (RegionCut::exact)
  int perPixelGroups = 0;                 // covered groups left to per-pixel cuts
  int surfaceSplits = 0;                  // groups split in two by their normals
  // Cuts found on the CPU for this frame (shared, or left to per-pixel cuts), and cuts kept
  // from earlier frames (cuts/cell_cuts.h).
  int made = 0, kept = 0;
  // Node bounds evaluated on the CPU, all groups together.
  long long boundEvaluations() const {
    long long n = 0;
    for (const CutWork& w : work) n += w.bounds;
    return n;
  }
};

inline constexpr std::uint32_t kNoSharedCut = 0xffffffffu;
inline constexpr std::uint32_t kLobesBit = 0x8000u;
// A full cut (RegionCut::full): a pixel whose check fails takes it all the same, and counts
// as at the maximum, instead of walking a cut of its own.
inline constexpr std::uint32_t kFullCutBit = 0x80000000u;
// Both rules hold on a pixel whose bound is at most this (near-black pixels), on the CPU and
// in glsl/lightcuts_walk.glsl.
inline constexpr float kAbsoluteFloor = 1e-6f;

// One group's cut, as TileCutter::cutRegion finds it; its entries are written apart.
struct RegionCut {
  int counts[3] = {0, 0, 0};    // entries per tree, besides the far field
  int folded = 0;               // entries in the far field
  int zeros = 0;                // entries left out: nothing at any pixel of the group
  glm::vec3 check{0.0f};        // U (node rule) or B (total rule) per unit albedo
  bool lobes = false;           // the group has specular pixels (ShadingRegion::lobes)
  glm::vec3 lobeCheck{0.0f};    // U or B per unit specular colour
  glm::vec3 farSpecular{0.0f};  // the far field's specular radiance per unit specular colour
  bool perPixel = false;        // full: the group's pixels cut for themselves
  // Full, under the total rule, where smaller groups would not meet the rule either
  // (TileCutter::Cut::sharedFull): shared all the same, unless a pixel of five of the group
  // comes close to meeting the rule with a cut of its own (cuts/cut_frame.cpp probes them;
  // their pixels then walk their own). Its pixels that fail their check take it and count as
  // at the maximum: their own walks, of at most --max-cut (≤ kSharedCutLimit) nodes, would
  // reach theirs too. On a seed's cut where it may not be made exact (below): its entries are
  // written instead of the seed, and a square without a seed whose probes cannot walk shares
  // it whole (cut_frame.cpp, cutSquare), rather than each quarter finding a full cut of its
  // own.
  bool full = false;
  // A full cut made exact (CutRule::exactFull): written as a full cut without entries, whose
  // pixels sum every light instead (glsl/lighting_lightcuts.frag, exactIfAtMax). On a seed's
  // cut (not written): it was as far off as a shared full cut, so a square without a seed
  // whose probes cannot walk is made exact (cut_frame.cpp, cutSquare).
  bool exact = false;
  long long bounds = 0;    // node bounds evaluated
  float shortfall = 0.0f;  // a full cut: how far its measure was above the rule's target

  // Its entries' texels (far field included).
  std::size_t entryTexels() const;
  // Its two header texels (TileCuts), its entries starting at texel `firstEntryTexel`.
  void writeHeader(std::uint32_t firstEntryTexel, std::uint32_t* words) const;
  // Writes it as cut number `cut` of `texels` (laid out as TileCuts'): its header, and its
  // `count` entry texels from `words` at texel `next`, which moves past them.
  void writeTexels(std::size_t cut, const std::uint32_t* words, std::size_t count,
                   std::size_t& next, std::uint32_t* texels) const;
};
// Under the node rule, the far field's entries are binned by their direction from the
// group (towards a point or spot light's representative, a directional light's direction):
// a cube's face, then kFarSplit × kFarSplit over the face. The summed remainders T of a bin's
// entries are one node's bound: entries that lie the same way err the same way.
inline constexpr int kFarSplit = 6;
inline constexpr int kFarBins = 6 * kFarSplit * kFarSplit;
using FarRemainders = std::array<glm::vec3, kFarBins>;
inline int farBin(glm::vec3 v) {
  const glm::vec3 a = glm::abs(v);
  const int axis = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
  if (!(a[axis] > 0.0f)) return 0;
  const auto cell = [&](float c) {
    return std::clamp(int((c / a[axis] + 1.0f) * 0.5f * kFarSplit), 0, kFarSplit - 1);
  };
  return ((2 * axis + (v[axis] < 0.0f ? 1 : 0)) * kFarSplit + cell(v[(axis + 1) % 3])) * kFarSplit +
         cell(v[(axis + 2) % 3]);
}

// A cut found for a larger group of pixels, from which the cut of a smaller group inside it
// starts (TileCutter::cut): the entries it did not fold, and its far field with the bound
// of the entries folded into it (largest under the node rule, sum under the total rule).
// Bounds over the larger group hold over the smaller one.
struct CutSeed {
  struct NodeRef {
    int tree, index;
  };
  std::vector<NodeRef> nodes;
  FarField far{glm::vec3(0.0f)};
  glm::vec3 farCheck{0.0f};
  glm::vec3 farLobeCheck{0.0f};   // the same per unit specular colour
  glm::vec3 farLobeSpread{0.0f};  // node rule: the sum of its entries' lobe spreads
  FarRemainders farRemainders{};  // node rule: its entries' remainders T, summed by bin
};

// A group whose cut would exceed the maximum is split into its surfaces while its normals
// spread wider than this (cosine to their mean), else into quarters down to this size.
inline constexpr float kSurfaceSpread = 0.9f;
inline constexpr int kFinestTile = 4;
// Under the node rule a group that can still be split is split once its cut would exceed
// kSplitCut entries at ε = kSplitError, and proportionally more at a smaller ε (or the
// maximum, if lower): smaller groups' cuts are smaller, so cheaper per pixel, but each
// quarter cuts again over ground its parent covered, and a smaller ε asks for larger cuts
// everywhere. Measured on 65,536 mixed lights at 640×480 (docs/performance.md): a fixed
// 1,000 made ε = 0.01 cost 6× ε = 0.02; splitting only at the maximum made ε = 0.02 cost 10%
// (Lambert) to 25% (specular) more, its pixels summing more entries. Groups of the finest
// size take cuts up to the maximum (CutRule::maxCut), since their pixels would otherwise walk
// cuts of their own, each about as costly as a 4×4 group's shared cut.
inline constexpr int kSplitCut = 1000;
// Groups one level above the finest split at kNearFinestSplit times that: their quarters are
// of the finest size, whose cuts may reach the maximum, so that a split there costs four cuts
// that each refine most of what the parent's did. Measured at 65,536 lights (640×480, node
// rule), node bounds and summed entries a pixel, splitting at 1 and at 2 times kSplitCut:
// mixed ε = 0.02 14.8 and 829 against 12.0 and 834, clustered ε = 0.005 28.0 and 1,012
// against 26.1 and 1,048, uniform alike (19.9 and 19.5 bounds at ε = 0.005), the generated
// room with --specular 13.4 against 10.0 bounds (766 and 772 entries); 4 and 8 times gave about
// the same as 2. Twice kSplitCut one level higher as well left clustered lights dearer (32.0
// bounds, 1,167 entries at ε = 0.005). Groups of lobe-dominated pixels (a metal's) split so at
// every size: their lobes' bounds narrow little in quarters, and in the generated room with
// --specular at ε = 0.02, all 64 of their 16×16 cuts from a seed and 74 of 96 from the roots
// filled up at splitCut. There the frame's node bounds fall from 10.0 to 8.7 a pixel
// (784 entries against 772; 4 and 8 times gave 9.0 and 9.1), its errors alike.
inline constexpr int kNearFinestSplit = 2;
// Under the total rule, a square whose cut filled up with its summed bound this many times
// the rule's target or more would not meet the rule in quarters either (its bounds add up
// over the whole cut): it may take its full cut (TileCutter::Cut::sharedFull), and splits
// only where that one's nodes are too coarse.
inline constexpr float kSplitShortfall = 8.0f;
inline constexpr float kSplitError = 0.02f;
inline int splitCut(const CutRule& rule) {
  const float scale = std::max(1.0f, kSplitError / std::max(rule.error, 1e-6f));
  return int(std::min(float(rule.maxCut), float(kSplitCut) * scale * float(rule.splitScale)));
}
// Squares of tileSize · 2^kSeedLevels pixels find the cuts their quarters start from.
inline constexpr int kSeedLevels = 1;

// Scratch space for TileCutter::cutRegion, in the manner of an allocator passed in: its
// buffers keep their capacity from cut to cut, so that a cut allocates nothing once they
// have grown. cutRegion overwrites all of it; one per thread, made by the caller.
struct CutWorkspace {
  // A node of the cut being found.
  struct Item {
    float measure;  // what the rule refines by; +inf: unbounded; −1: a leaf (never refined)
    int tree, index;
    glm::vec3 error;     // upper (node rule) or upper − lower (total rule)
    glm::vec3 estimate;  // at the region's centre
    bool dark;           // no light of the node reaches any point of the region
    bool leaf;
    int representative;
    float unit;           // the representative's shading at the centre per unit intensity
    glm::vec3 intensity;  // decoded (internal nodes) or exact (leaves)
    // Groups with specular lobes (else 0, and `weighted` = `error`): the node's bound per
    // unit specular colour, upper (node rule) or upper − lower (total rule), a leaf's too
    // (folded, its lobe is estimated), the
    // representative's lobe at the centre per unit intensity and specular colour, and
    // `error` and `lobeError` weighed by the group's mean albedo and specular colour.
    glm::vec3 lobeError{0.0f};
    glm::vec3 lobeSpread{0.0f};  // upper − lower of the lobe: a folded entry's error bound
    float lobeUnit = 0.0f;
    glm::vec3 weighted{0.0f};
  };
  // An entry that may fold into the far field, with its T per channel, and the key entries
  // fold in the order of (TileCutter::foldEntries): the largest channel of T under the total
  // rule, of the lobe's spread under the node rule with lobes.
  struct Foldable {
    int item;
    glm::vec3 t;
    float key;
    bool operator<(const Foldable& o) const;  // smallest key first
  };
  std::vector<Item> items;
  std::vector<int> settled;  // items refined no further
  // The max-heap of the items still to refine: one word each, the measure's bits above the
  // item's index (positive floats and +inf order as their bits do).
  std::vector<std::uint64_t> heap;
  std::vector<Foldable> foldable;
  // Per item: kFolded once folded, else foldBounds' answer where it cannot fold
  // (kZeroEntry, kFullCone), else −1.
  std::vector<float> shape;
  std::vector<std::uint32_t> byTree[3];  // the entries' words, per tree
  NodeLanes lanes{};
  FoldLanes lights{};
  FarLanes toFold{};
};

class TileCutter {
 public:
  // The lights of the trees.
  int lights() const { return leaves_[0] + leaves_[1] + leaves_[2]; }
  // Keeps `packed`, the trees of `lights`, and decodes its nodes as cuts first reach them.
  TileCutter(PackedTrees packed, const std::vector<Light>& lights);

  // The spot tree's cones (SpotCone) for a pixel's own walk (glsl/lightcuts_walk.glsl's
  // spotConeFactor): per internal node (the first leaves − 1), (spread's cosine, upScale,
  // upOffset, lowScale), (lowOffset, lowInvRange2, 0, 0); empty without spots. 32 MiB at
  // 1,048,576 spots, against 112 MiB for the spot tree's nodes.
  std::vector<float> spotConeTexels() const;

  // Cuts for every tile of the frame, on `threads` threads; only for the pixels marked in
  // `only` (one byte per pixel) when it is given. Each square of the frame's seeds (of
  // tileSize << kSeedLevels pixels) keeps its cuts' entries within rule.texelsPerPixel texels
  // per pixel that shares them.
  TileCuts cut(const GBufferPixels& pixels, int tileSize, const CutRule& rule, int threads,
               const std::vector<std::uint8_t>* only = nullptr) const;

  // The cut of one group of shading points, `region`, its entries appended to `entries`.
  // `finest`: the group cannot be split further, so a full cut that meets the rule without
  // the margin is shared rather than left to per-pixel cuts.
  // `seed`: start from that cut (of a group holding this one) instead of the trees' roots.
  // `next`: the cut is wanted only as a seed for smaller groups: it is written there (a full
  // cut too) instead of to `entries`.
  // `work`: this thread's scratch space.
  RegionCut cutRegion(CutWorkspace& work, const ShadingRegion& region, const CutRule& rule,
                      bool finest, std::vector<std::uint32_t>& entries,
                      const CutSeed* seed = nullptr, CutSeed* next = nullptr) const;
  // The same with scratch space of its own, for a single cut.
  RegionCut cutRegion(const ShadingRegion& region, const CutRule& rule, bool finest,
                      std::vector<std::uint32_t>& entries, const CutSeed* seed = nullptr,
                      CutSeed* next = nullptr) const;

 private:
  // A node as glsl/light_tree.glsl's fetchNode reads it, decoded once.
  // Its first kNodeRows floats are NodeLanes' rows in order (cuts/node_lanes.h), so that
  // eight nodes are gathered into lanes by transposing them.
  // Trivial, so that its arrays are allocated untouched and first written by the threads
  // that decode them; decode sets every field.
  struct alignas(32) Node {
    glm::vec3 boxMin, boxMax, intensity, axis;  // axis: spots only, else 0
    float invRange2, w2, sinTheta;
    // Its representative's light, as its leaf holds it: position (direction), 1/range²; a
    // spot's axis (the way it shines) and cos θ, and its cone as the light texture holds it,
    // smoothstep(clamp(cos · scale + offset)) of the cosine to the axis.
    glm::vec3 repPoint, repAxis;
    float repInvRange2, repCos;
    float leafRow;  // 1 for a leaf, else 0
    // A spot node's cones (SpotCone; other trees' nodes: SpotCone's defaults, unread), then
    // the representative's.
    float spreadCos, upScale, upOffset, lowScale, lowOffset, lowInvRange2;
    float repConeScale, repConeOffset;
    int representative;
    bool leaf() const { return leafRow != 0.0f; }
  };
  // What a spot node's bounds take of its lights' cones, found from the lights by the
  // constructor (the node texture holds only the cone Θ around the axis that holds them all):
  // the spread of their axes about the node's axis (cos), and the smoothstep terms of the widest
  // cone (the smallest cosines of the outer and inner angles: a cone factor at least each
  // light's at any angle) and of the narrowest (at most each light's), and the largest 1/range².
  struct SpotCone {
    float spreadCos = -1.0f;
    float upScale = 0.0f, upOffset = 1.0f, lowScale = 0.0f, lowOffset = 0.0f;
    float lowInvRange2 = 0.0f;
  };
  void findSpotCones();
  // Node i of `tree`, decoded with its block on first use (by whichever thread gets there
  // first; the others wait for it). A cut reaches a small share of a large forest's nodes,
  // so most are never decoded: their memory is never touched.
  const Node& node(int tree, int i) const {
    const std::size_t block = std::size_t(i) >> kBlockShift;
    if (state_[tree][block].load(std::memory_order_acquire) != kDecoded) decodeBlock(tree, block);
    return nodes_[tree][std::size_t(i)];
  }
  // One cut in the making (cut_region.cpp): the steps below share it.
  struct Cut;
  // Refines the cut from its start until the rule holds or it is full; false when it is full
  // and not wanted as a seed, so that nothing is left to do.
  bool refine(Cut& cut) const;
  // Folds the settled entries that may into the far field (bounds only).
  void fold(Cut& cut) const;
  // fold's second half: which of the entries that may fold do, by the rule's margins.
  void foldEntries(Cut& cut) const;
  // Writes the cut's entries, far field first, to `entries` or to `next`.
  void emit(Cut& cut, std::vector<std::uint32_t>& entries, CutSeed* next) const;
  Node decode(int tree, int i) const;
  void decodeBlock(int tree, std::size_t block) const;

  // Blocks of 2^kBlockShift nodes, a page of them, are decoded at once.
  static constexpr int kBlockShift = 5;
  enum : std::uint8_t { kRaw, kDecoding, kDecoded };
  PackedTrees packed_;                // what nodes are decoded from
  std::vector<int> leafOfSlot_;       // per light texture slot, its leaf (in its type's tree)
  std::vector<SpotConeTerms> cones_;  // per spot slot, from spotStart_
  std::vector<SpotCone> spotCones_;   // per node of the spot tree
  int spotStart_ = 0;
  mutable std::unique_ptr<Node[]> nodes_[3];  // per tree, 2 · leaves_ − 1 (none without leaves)
  mutable std::unique_ptr<std::atomic<std::uint8_t>[]> state_[3];  // per block of nodes_
  int leaves_[3];
  NodeColourCoder colour_;
};

}  // namespace manylight
