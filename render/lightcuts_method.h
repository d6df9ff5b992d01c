#pragma once
// Lightcuts: the light trees of bake/light_tree.h in a node texture, and a per-pixel cut
// through them in the fragment shader (glsl/lightcuts_walk.glsl documents the bounds
// and stopping rules).
#include <memory>
#include <string>
#include <vector>

#include "bake/light_tree.h"
#include "bake/light_tree_pack.h"
#include "cuts/cell_cuts.h"
#include "cuts/tile_cuts.h"
#include "gl/texture_buffer.h"
#include "render/gbuffer.h"
#include "render/gpu_scene.h"
#include "scene/camera.h"

namespace manylight {

enum class ErrorMode { Node, Total };

// Under the total rule, where the scene has at most this many lights, a pixel whose cut cannot
// meet the rule sums every light instead (glsl/lighting_lightcuts.frag, exactIfAtMax): a group
// whose shared cut would fill up gets an exact cut (cuts/tile_cuts.h, RegionCut::exact), a
// pixel whose shared cut fails its check sums them at once rather than walking a cut of its
// own, and a walk that reaches the maximum sums them after it where the loop budget still has
// room for every light (kIterationBudget: a walk of several passes of thousands of nodes near
// 32,768 lights may not, and stays counted at the maximum). So with shared cuts no pixel was
// left at the maximum in any case measured, and a frame costs at most about twice the
// reference's. Measured in the stability suite (docs/stability.md; 16,384 lights, 320×240,
// ε = 0.02, 0.005 clustered): pixels at the maximum far 36,379 → 0, on-surfaces 48,458 → 0,
// clustered 56,232 → 0; frames 7.98 → 1.1 s, 4.5 → 1.7 s, 4.3 → 1.1 s (the
// reference 0.82 s). At 640×480, ε = 0.02, 16,384 uniform lights: 4.0 s, every pixel at the
// maximum before; the reference 3.3 s. Above the limit such pixels keep the estimate of the
// cut they reached (--stats pixels_at_max_cut): an exact sum costs as much as the reference's
// pixel, which grows with the lights.
inline constexpr int kExactLimit = 32768;
// Where pixels may sum every light and a shared cut cannot hold every leaf (more than
// kSharedCutLimit lights), a shared cut holds at most this share of them: a cut
// that fills up takes its pixels more time than their exact sums would (about as long as
// N / kExactCutShare lights), and the CPU gives up on it sooner. Measured at 16,384 far
// lights (320×240, ε = 0.02): frame 4.0 s with cuts of up to 8,000 entries (the CPU's
// 3.1 s), 1.0 s with 4,096 (0.05 s); the reference 0.8 s.
inline constexpr int kExactCutShare = 4;
// A pixel sums its shared cut (an iteration per entry at most, and 6) and then every light
// (one each, 8 to spare) within the shader's loop budget.
static_assert(kExactLimit + kSharedCutLimit + 14 <= kIterationBudget,
              "exact sums must fit the shader's loops (glsl/lighting_lightcuts.frag)");

struct LightcutsSettings {
  float error = 0.02f;  // ε
  ErrorMode mode = ErrorMode::Node;
  int maxCut = 2000;  // nodes of a cut a pixel walks itself; at most kMaxCutLimit
  // Pixels share the cut of their tile of tileSize × tileSize pixels where it holds for
  // them (cuts/tile_cuts.h); 1: every pixel finds its own cut. Not for the distance
  // criterion.
  int tileSize = 16;
  // Playback: the shared cuts are per cell of the scene and kept from frame to frame
  // (cuts/cell_cuts.h) instead of per square of the screen, found again only where the
  // camera shows new places. For the frames of one scene whose lights and geometry stay put.
  bool keepCuts = false;
  // Under the total rule, pixels whose cuts cannot meet it sum every light instead where the
  // scene has at most this many lights (and kExactLimit); 0: never.
  int exactLimit = kExactLimit;
  TreeOptions trees;  // how the trees are built and packed (used when they are built)
};

// Whether a frame's pixels may sum every light (kExactLimit).
bool exactSums(const LightcutsSettings& settings, int lights);

// llvmpipe ends a shader invocation's loops after 65,535 iterations in all, and a pass
// over the trees takes up to 2 iterations per cut node: this limit leaves room for several
// passes (glsl/lightcuts_walk.glsl).
inline constexpr int kMaxCutLimit = 8000;

// Per-pixel cut statistics of a frame, over the covered pixels.
struct CutStats {
  long long pixels = 0;
  double averageCut = 0.0;
  int maxCut = 0;
  long long pixelsAtMaxCut = 0;
  long long pixelsSharedCut = 0;  // pixels that took their group's cut (cuts/tile_cuts.h)
  // Groups of pixels with a shared cut, groups left per pixel, and groups split into their
  // surfaces (cuts/tile_cuts.h).
  int sharedCuts = 0, perPixelGroups = 0, surfaceSplits = 0;
  int exactCuts = 0;  // of the shared cuts, exact ones (cuts/tile_cuts.h, RegionCut::exact)
  double lightEvaluations = 0.0;       // per pixel
  double nodeEvaluations = 0.0;        // per pixel (error bounds or distance tests), with the
                                       // tile cuts' bounds on the CPU spread over the pixels
  CutWorks work{};                     // the cuts found on the CPU by kind (cuts/tile_cuts.h)
  std::vector<std::uint8_t> atMaxCut;  // per pixel, rows top-down: 1 where the cut hit the maximum
};

class LightcutsMethod {
 public:
  // Uploads trees baked for `lights` (bakeLightTrees, or a baked file's): nothing is built
  // here. Needs a current context; throws gl::GlError when the driver cannot hold them.
  // `distance`: cut by the distance criterion (lightcuts-distance) instead of error bounds.
  LightcutsMethod(PackedTrees packed, const std::vector<Light>& lights, const GBuffer& gbuffer,
                  bool distance);

  // Adds the lights' contribution to the radiance target of `gbuffer` and writes the cut
  // statistics target.
  void light(const GpuScene& scene, const GBuffer& gbuffer, const View& view,
             const LightcutsSettings& settings) const;

  // Reads back the statistics of the last light() call.
  CutStats cutStats() const;
  // Milliseconds the last light() call spent finding shared cuts on the CPU and uploading
  // them, after the G-buffer was read back (0 without shared cuts).
  double cutMs() const { return cutMs_; }
  // Of the last light() call's shared cuts: how many were found, and how many were kept from
  // earlier frames (LightcutsSettings::keepCuts).
  int cutsMade() const { return tileInfo_.made; }
  int cutsKept() const { return tileInfo_.kept; }

  // The node colour coding of the packed trees: its fit and the error it adds.
  const NodeColourCoder& nodeColour() const { return layout_.colour; }

 private:
  const gl::Program& program(const std::vector<std::string>& defines) const;

  // Finds the cuts of tileSize × tileSize squares on the CPU, from the G-buffer read back.
  void cutTiles(const GBuffer& gbuffer, const View& view, bool specular,
                const LightcutsSettings& settings, int tileSize, bool exact, int lights) const;

  PackedTrees layout_;  // bases, leaf counts, colour coding (no words: the tile cutter's)
  gl::TextureBuffer nodes_;
  gl::TextureBuffer spotCones_;  // TileCutter::spotConeTexels, for the walks' spot bounds
  std::unique_ptr<TileCutter> tileCutter_;   // null for the distance criterion
  mutable std::unique_ptr<CellCuts> cells_;  // made by the first frame with keepCuts
  mutable gl::TextureBuffer tileCuts_;       // this frame's (cuts/tile_cuts.h), storage kept
  gl::Texture cutOfPixel_;                   // this frame's cut per pixel (R32UI)
  mutable TileCuts tileInfo_;                // its counts (the texels are dropped)
  mutable std::vector<float> readback_;
  mutable double cutMs_ = 0.0;
  bool distance_;
  int width_, height_;
  gl::Texture statsTarget_;
  gl::Texture stencil_;          // with shared cuts: which pixels walk cuts of their own
  gl::Framebuffer framebuffer_;  // radiance + statistics (+ stencil)
};

}  // namespace manylight
