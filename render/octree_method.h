#pragma once
// The octree method: the linkless octree of bake/linkless_octree.h in texture buffers, and
// at each pixel the exact sum over the lights of its leaf and of the global list
// (glsl/lighting_octree.frag). Exact for every scene: a leaf lists every ranged light that
// reaches it, and every light without a range is in the global list.
#include <string>
#include <vector>

#include "bake/linkless_octree.h"
#include "gl/texture_buffer.h"
#include "render/gbuffer.h"
#include "render/gpu_scene.h"
#include "scene/camera.h"

namespace manylight {

// Per covered pixel of a frame, over the opaque G-buffer (`--stats`).
struct OctreeFrameStats {
  long long pixels = 0;
  double listEntries = 0.0;       // list entries per pixel: global list + leaf list
  double lightEvaluations = 0.0;  // of which evaluated in full (the rest fail the shader's
                                  // range test, at the cost of one texel read)
  double lightsReaching = 0.0;    // lights whose range window is non-zero there (of those
                                  // listed: a spot whose cone misses the cell may not be)
  double lightsLit = 0.0;         // of which a spot's outer cone holds the point too: the
                                  // lights that can light it (bake/light_octree.h)
  long long missed = 0;           // with bruteForce: lights reaching a pixel not in its lists
};

class OctreeMethod {
 public:
  // Uploads `octree`, packed for these lights. Needs a current context; throws gl::GlError
  // when the driver cannot hold it.
  OctreeMethod(LinklessOctree octree, const std::vector<Light>& lights);

  // Uploads `octree` for `lights` in place of the current one: the same octree with its
  // lights moved (bake/octree_update.h), or one built anew.
  void replace(const LinklessOctree& octree, const std::vector<Light>& lights);

  // Adds the lights' contribution to the radiance target of `gbuffer`, in passes of at most
  // `perPass` list entries a pixel (0 or more than kOctreeEntriesPerPass: that). Returns the
  // passes.
  int light(const GpuScene& scene, const GBuffer& gbuffer, const View& view, int perPass = 0) const;

  // The list lengths and the lights reaching each covered pixel of the last G-buffer, from
  // its positions read back (on the CPU, as the shader descends). `bruteForce` also tests
  // every light at every pixel for the lights the lists miss (tests).
  OctreeFrameStats frameStats(const GBuffer& gbuffer, bool bruteForce = false) const;

  const LinklessOctree& octree() const { return octree_; }

 private:
  // Uploads octree_ and its order of `lights`.
  void uploadAll(const std::vector<Light>& lights);

  LinklessOctree octree_;      // kept for the statistics
  std::vector<Light> lights_;  // in light texture order
  gl::TextureBuffer lightTexture_, nodes_, offsets_, indices_;
};

}  // namespace manylight
