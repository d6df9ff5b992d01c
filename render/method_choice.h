#pragma once
// `--method auto` (the default of render and play): per scene, the fastest method that meets
// the request, by a cost model calibrated on the sweep (docs/performance.md). The exact
// methods always meet it; lightcuts, approximate, is chosen only where neither exact method
// is fast, and keeps its documented error at --error.
//   1. The reference when a frame is at most kAutoReferenceEvaluations light evaluations
//      (lights × pixels): exact, with nothing to bake.
//   2. The octree when some lights are ranged, the global list (lights without a range) is
//      at most kAutoOctreeEntries, and its lists (built here, or a baked file's) average at
//      most kAutoOctreeEntries entries with it: exact, and about as fast as lightcuts from
//      there (a list entry costs about what a cut node does).
//   3. Otherwise lightcuts.
#include <memory>
#include <string>
#include <vector>

#include "bake/linkless_octree.h"
#include "render/renderer.h"

namespace manylight {

// About 0.7 s of reference at kReferenceEvaluationsPerSecond.
inline constexpr double kAutoReferenceEvaluations = 268435456.0;
// List entries per pixel up to which the octree is chosen: lightcuts' frames at 640×480
// take as long as this many light evaluations per pixel or more (docs/performance.md).
inline constexpr double kAutoOctreeEntries = 256.0;

struct MethodChoice {
  Method method = Method::Reference;
  std::string reason;  // one line, for --verbose and --stats
  // The octree built to decide (null when none was built): prepareRenderer's baked octree.
  std::shared_ptr<LinklessOctree> octree;
};

// Chooses for `lights` over `scene` at width × height. `baked`: a baked file's octree, used
// instead of building one.
MethodChoice chooseMethod(const Scene& scene, const std::vector<Light>& lights, int width,
                          int height, const OctreeOptions& options,
                          const LinklessOctree* baked = nullptr);

// The mean length of the octree's leaf lists, weighted by nothing: each leaf once.
double meanLeafList(const LinklessOctree& octree);

}  // namespace manylight
