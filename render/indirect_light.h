#pragma once
// One bounce of diffuse indirect light (`--indirect`), added to the direct light of any
// method: reflective shadow maps (render/rsm.h) for the spot and directional lights that send
// the most flux into the view, whose texels light every pixel as small diffuse patches
// (glsl/indirect_exact.frag). No visibility between a texel and a pixel: indirect light
// passes through walls. Blended surfaces neither reflect nor receive it.
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "render/gbuffer.h"
#include "render/geometry_pass.h"
#include "render/gpu_scene.h"
#include "render/light_caches.h"
#include "render/near_field.h"
#include "render/pixel_classes.h"
#include "render/rsm.h"
#include "render/rsm_choice.h"
#include "scene/scene.h"

namespace manylight {

// none: direct light only; exact: every map texel at every pixel; caches: every map texel at
// every light cache (render/light_caches.h), interpolated per pixel.
enum class Indirect { None, Exact, Caches };

// "none", "exact", "caches" → Indirect; throws Error naming the choices for anything else.
Indirect parseIndirect(const std::string& name);
const char* indirectName(Indirect i);

struct IndirectSettings {
  Indirect mode = Indirect::None;
  int rsmLights = 4;       // lights given maps at most (docs/indirect.md)
  int rsmSize = 64;        // a map's width and height in texels
  bool shL2 = true;        // caches: SH L2 (9 coefficients) or SH L1 (4)
  float cacheCell = 0.0f;  // caches: the smallest cascade's cell edge; 0: kCacheCellsPerScene
  // The least share of the view's flux a light sends for a map (chooseRsmLights)
  double rsmLeastShare = kRsmLeastShare;
};
// The default smallest cell edge: the scene's bounding box diagonal over this.
inline constexpr float kCacheCellsPerScene = 128.0f;

// A frame's indirect light (`--stats`).
struct IndirectStats {
  int rsmLights = 0;        // maps used
  bool mapsKept = false;    // the maps were the last frame's (IndirectLight::light)
  int mapsRendered = 0;     // maps rendered anew: the others were the last frame's
  int candidates = 0;       // spot and directional lights
  int belowShare = 0;       // lights passed over for their small share (RsmChoice::belowShare)
  long long rsmTexels = 0;  // map texels that reflect flux, over all maps
  double fluxShare = 1.0;   // the chosen lights' share of the means' flux (fluxShare)
  int passes = 0;           // gather passes
  // Reading the G-buffer back, and choosing the lights (beside the direct light:
  // IndirectLight::begin)
  double chooseMs = 0.0;
  double rsmMs = 0.0;     // rendering the maps and their flux
  double gatherMs = 0.0;  // the gather passes (exact), or the caches' (caches)
  // --indirect caches:
  int caches = 0;      // allocated this frame
  int cachesKept = 0;  // of them, those that kept the last frame's light (LightCaches::kept)
  long long cachesGathered = 0;  // caches gathered, summed over the maps (LightCaches::gathered)
  long long cachesRefused = 0;   // CacheAllocation::refused
  int cascades = 0;
  float cacheCell = 0.0f;      // the smallest cascade's cell edge
  double allocateMs = 0.0;     // allocated on the CPU (beside the direct light) and uploaded
  int nearPasses = 0;          // near-field passes (render/near_field.h)
  long long nearClusters = 0;  // NearField::clusters
  double nearMs = 0.0;         // the near field binned, uploaded and gathered per pixel
  double interpolateMs = 0.0;  // the per-pixel interpolation pass
};

// The cascades of a frame seen from `eye`: the smallest cell `settings.cacheCell` (or the
// scene's diagonal / kCacheCellsPerScene), and as many cascades as hold the scene.
CacheGrid frameCacheGrid(const IndirectSettings& settings, const Bounds& bounds, glm::vec3 eye);

class IndirectLight {
 public:
  // Needs a current context; throws gl::GlError.
  explicit IndirectLight(int rsmSize);
  int rsmSize() const { return rsmSize_; }

  // Reads the camera's G-buffer back (its geometry pass drawn), then chooses the frame's lights
  // and, for caches, allocates them (the CPU's part of light()) on a thread of its own, while
  // the direct light renders; light() waits for it. `lights` stay as they are until then.
  // Throws gl::GlError.
  void begin(const GBuffer& camera, const Bounds& bounds, const View& view,
             const std::vector<Light>& lights, const IndirectSettings& settings);
  // Waits for begin()'s thread, if one runs: for a frame that ends early (the direct light
  // threw), before the lights it reads may change or go.
  void wait() const {
    if (pending_.valid()) pending_.wait();
  }
  // Adds one bounce from the maps of the chosen `lights` (the renderer's, by scene index) to
  // the radiance target of `camera`, whose G-buffer holds the frame (after begin(), with the
  // same arguments, or alone). A light the last frame chose too, with the same values, keeps
  // its map, and the caches at the nodes both frames have keep that map's light: the scene's
  // geometry does not change under a renderer.
  // Throws gl::GlError.
  IndirectStats light(const Scene& scene, const GpuScene& gpu, const GeometryPass& geometry,
                      const GBuffer& camera, const View& view, const std::vector<Light>& lights,
                      const IndirectSettings& settings);

 private:
  // A chosen light's map (its radiance target holds the flux), what it gives the caches, and
  // what was read back of it for the near field.
  struct Map {
    Light light;
    int index = -1;    // the light's, in the scene
    long long id = 0;  // which rendering (LightCaches::startLayer)
    int layer = 0;     // its layer of the caches, below kMaxCacheLayers
    std::unique_ptr<GBuffer> rsm;
    std::unique_ptr<RsmClusterTextures> clusters;
    std::vector<float> position, normal, flux;
    RsmClusters groups;
    float nearRadius = 0.0f;
    long long texels = 0;  // that reflect flux
  };
  // What begin() makes: the frame's lights, the choice's and the allocation's parts of the
  // stats, and for caches (where a light has a map) the cascades allocation_ holds (else none).
  struct Prepared {
    RsmChoice choice;
    IndirectStats stats;
    CacheGrid grid;
  };
  // Chooses the frame's lights (rsm_choice.h) from position_ and normal_, and allocates the
  // caches for them: no GL.
  Prepared prepare(const std::vector<Light>& lights, const IndirectSettings& settings,
                   const Bounds& bounds, glm::vec3 eye);
  // Makes maps_ those of `choice`, rendering those the last frame had not; returns whether the
  // maps changed.
  bool updateMaps(const Scene& scene, const GpuScene& gpu, const GeometryPass& geometry,
                  const std::vector<Light>& lights, const RsmChoice& choice);
  void renderMap(const Scene& scene, const GpuScene& gpu, const GeometryPass& geometry, Map& m);
  // Gathers each layer's maps into the caches; appends the layers used; returns the passes.
  int gatherLayers(std::vector<int>& layers);
  int rsmSize_;
  std::vector<Map> maps_;       // the last frame's, in the order of its choice
  long long mapsRendered_ = 0;  // maps rendered so far (their ids)
  bool chosen_ = false;         // a frame has chosen its lights
  gl::VertexArray emptyVao_;    // the full-screen triangle needs a bound VAO in core profile
  std::unique_ptr<LightCaches> caches_;  // made at the first frame with caches
  NearField near_;
  PixelClasses classes_;  // of the camera's pixels, for the caches' per-pixel passes
  // The frame's G-buffer read back, and its caches: kept from frame to frame for their memory
  // (allocateCaches).
  std::vector<float> position_, normal_;
  CacheAllocation allocation_;
  RsmFluxHistory fluxHistory_;
  // begin()'s work, declared last: destroyed first, it waits for the thread that uses the rest
  std::future<Prepared> pending_;
};

}  // namespace manylight
