#pragma once
// `--indirect caches`: the light caches of the second design document. Caches sit at the
// nodes of nested world-space grids around the camera, the cascades of a Cache Address
// Volume (CAV), which stores only each node's first cache; each cache holds the indirect
// light arriving at its position from the reflective shadow maps (render/rsm.h) in a
// spherical harmonics basis (glsl/sh_basis.glsl), and the exact irradiance for its normal
// bin's centre as a correction to it; each pixel interpolates its irradiance from the caches
// at its cell's eight nodes (glsl/cache_interpolate.frag).
//
// GL 3.3 has no compute shaders or image atomics, so caches are allocated on the CPU, from
// the G-buffer's positions read back: each covered pixel marks the eight nodes of its cell
// in the smallest cascade whose decision boundary holds it, and, in the band kBandCells
// cells wide inside that boundary, those of the next cascade too. The CAV ((resolution + 1)³
// nodes a cascade, 4 bytes each) is uploaded as one 3D texture; the caches' positions,
// normals, links and coefficients are texels of 2D textures sized from the frame's count.
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "gl/objects.h"
#include "render/cache_layout.h"
#include "render/gbuffer.h"
#include "render/pixel_classes.h"
#include "render/rsm.h"
#include "scene/scene.h"

namespace manylight {

// The cascades of one frame. Cascade k has cells of edge cell · 2^k, `resolution` cells a
// side, and is centred on the node nearest the camera (so a node's world position never
// depends on where the camera is within a cell); its decision boundary is the cube of half
// edge (resolution/2 − 2) cells centred on the camera itself, so it moves smoothly and its
// cells' nodes always lie in the cascade.
// Cells a side of every cascade.
inline constexpr int kCacheResolution = 128;

struct CacheGrid {
  int cascades = 4;
  int resolution = kCacheResolution;
  glm::vec3 centre{0.0f};
  std::vector<glm::vec3> origin;  // per cascade: the world position of node (0, 0, 0)
  std::vector<float> cell;        // per cascade: the cell edge
  std::vector<float> decision;    // per cascade: the decision boundary's half edge
  int nodesPerAxis() const { return resolution + 1; }
};
inline constexpr int kMaxCascades = 8;

// Cascades of cell edge `cell` (at the smallest) around `centre`.
CacheGrid cacheGrid(glm::vec3 centre, float cell, int cascades = 4,
                    int resolution = kCacheResolution);
// The fewest cascades (at most kMaxCascades) whose largest decision boundary around `centre`
// holds all of `bounds`.
int cascadesToCover(glm::vec3 centre, float cell, const Bounds& bounds,
                    int resolution = kCacheResolution);

// The cascade that holds `p` (cascades when none does), and where p lies in its transition
// band: 0 outside it, rising to 1 at the decision boundary.
int cascadeOf(const CacheGrid& grid, glm::vec3 p, float* band = nullptr);

// Sets glsl/cache_cascade.glsl's uniforms of `p`, in use.
void setCascadeUniforms(const gl::Program& p, const CacheGrid& grid);

struct CacheAllocation {
  // Per cascade, (resolution + 1)³ nodes, x fastest then y then z: the node's first cache, or
  // −1.
  std::vector<float> cav;
  std::vector<glm::vec4> positions;  // per cache, its node's world position and cell edge
  // per cache, the normal its correction is for (binNormal) and that bin: a node has a cache
  // per bin of the pixels marking it, so a pixel's caches do not depend on the view.
  std::vector<glm::vec4> normals;
  std::vector<int> next;           // per cache, the next cache of its node, or −1
  std::vector<std::size_t> nodes;  // the nodes of a cache, as indices into cav
  // caches not made as kMaxCaches were, counted once per run of pixels that share a cell and bin
  long long refused = 0;
  // per pixel, its PixelClass bits (render/pixel_classes.h): which per-pixel passes it takes
  std::vector<std::uint8_t> classes;
};
// Layers of coefficients the caches keep at most (LightCaches): a map has one of its own
// while there are at most this many maps; past that, maps share layers, and a layer gathers
// anew whenever one of its maps is rendered anew.
inline constexpr int kMaxCacheLayers = 4;
// Caches a frame holds at most (the per-process budget): their textures take 64 bytes a cache,
// and 128 a cache for each layer and two more (LightCaches): 218 MB at most.
// Past it, no pixel makes another: the pixels of a node without caches go without its light
// (the others of their cell are blended without it), or without their bin's correction.
inline constexpr std::size_t kMaxCaches = std::size_t(1) << 18;

// Normals in 6 · kNormalBinGrid² bins: the cube face of the normal's largest component (+x,
// −x, +y, −y, +z, −z), then a kNormalBinGrid² grid over the face (glsl/cache_interpolate.frag
// bins as this does); binNormal is a bin's central direction, the face's axis for the middle
// cell.
int normalBin(glm::vec3 n);
glm::vec3 binNormal(int bin);

// A normal whose cosine to its bin's centre is at least this counts as the centre
// (kPixelCentred): within 0.49 mrad of it, so a normal along an axis, a float's rounding
// short of unit length, counts. The correction's weight there is 1 within 2 × 10⁻¹⁰, and the
// exact irradiance for the centre stands for the pixel's within about 5 × 10⁻⁴ of it.
inline constexpr float kCentredCosine = 1.0f - 1.0f / 8388608.0f;  // 1 − 2⁻²³

// Which per-pixel passes of the caches a pixel takes (render/pixel_classes.h).
enum PixelClass : std::uint8_t {
  kPixelCached = 1,   // covered, and within the cascades
  kPixelCentred = 2,  // its normal at its bin's centre (kCentredCosine)
  kPixelBand = 4,     // in a transition band, blended with the next cascade
};

// The caches the covered pixels of a G-buffer read back as RGBA floats need (normal.w 0 off
// the geometry), in the order the pixels first mark them, and the pixels' classes.
CacheAllocation allocateCaches(const CacheGrid& grid, const std::vector<float>& position,
                               const std::vector<float>& normal);
// The same, into `a`, whose vectors keep their memory from one frame to the next: the CAV
// alone takes 17 MB at 128 cells a side and two cascades, and memory new to the process
// costs its pages' faults, a frame's worth each frame. `a` is empty or as the last call
// left it (LightCaches::upload rewrites only the entries of a.nodes): then only those are
// reset.
void allocateCaches(const CacheGrid& grid, const std::vector<float>& position,
                    const std::vector<float>& normal, CacheAllocation& a);

// The caches on the GPU: the CAV, the cache positions and their coefficients, kept per map in
// a layer of its own and summed for the interpolation. A cache's light from a map depends
// only on its node and the map, so while a map stays the same (a static scene, kiosk
// playback) a cache at a node the frame before also had keeps that map's coefficients, and
// only the frame's new caches gather it; a map rendered anew gathers every cache, and the
// others keep theirs.
class LightCaches {
 public:
  LightCaches() = default;
  // Uploads `a`: textures grow to hold its caches. With the same basis, the caches at nodes
  // and bins the last upload also had come first (kept()), and each map's layer gathered at
  // the last upload can keep their coefficients (gather). Rewrites a.cav's entries from
  // caches to their slots. Throws gl::GlError.
  void upload(const CacheGrid& grid, CacheAllocation& a, bool shL2);
  int count() const { return count_; }
  // Caches that kept their coefficients in every layer gathered since the upload: those at
  // nodes and bins the last upload also had, or 0 where a layer gathered every cache.
  int kept() const { return keptEverywhere_ ? kept_ : 0; }
  // Caches gathered since the upload, summed over the layers.
  long long gathered() const { return gathered_; }
  const CacheGrid& grid() const { return grid_; }
  // Starts layer `layer` (below kMaxCacheLayers) of this upload for the maps of ids `maps`
  // (an id names one rendering of one map): where the layer held the same maps at the last
  // upload, the kept caches keep their coefficients; otherwise every cache starts at 0.
  void startLayer(int layer, std::vector<long long> maps);
  // Adds one of the started layer's maps' far light to the layer (glsl/cache_gather.frag),
  // for texels of near radius `nearRadius` (render/near_field.h), through the map's
  // `clusters`: every cache's, or where the layer was kept, the caches not kept. Returns the
  // passes.
  int gather(int layer, const GBuffer& rsm, const RsmClusterTextures& clusters, float nearRadius);
  // Adds the light interpolated from the caches of `layers` (each gathered since the last
  // upload) to `camera`'s radiance target, at the pixels `classes` sends to it.
  void interpolate(const GBuffer& camera, const PixelClasses& classes,
                   const std::vector<int>& layers);

 private:
  // A cache's node in world units of its cascade's cell (cell edge, and the node's position
  // over it), the same in every frame whose cascades have the same cells, and its normal bin.
  using NodeKey = std::array<std::int64_t, 5>;
  struct Targets {
    std::vector<gl::Texture> sh;  // 7 coefficient targets (SH L1 fills 3), the exact
    gl::Framebuffer framebuffer;
    int height = 0;
  };
  struct Layer {
    Targets targets;
    std::vector<long long> maps;  // the maps gathered (sorted), and at which upload
    int upload = -1;
    bool keep = false;  // at this upload, the kept caches kept their coefficients
  };
  void allocateTargets(Targets& t, int height);
  void clearTargets(const Targets& t);
  void copyKept(const Targets& from, const Targets& to);
  void sum(const std::vector<int>& layers);
  CacheGrid grid_;
  bool shL2_ = false;
  int count_ = 0, kept_ = 0, width_ = 0, height_ = 0;
  int uploads_ = 0;
  bool keptEverywhere_ = true;
  long long gathered_ = 0;
  std::vector<NodeKey> keys_;  // per cache, its node
  // previous_: per kept cache, its slot the frame before
  // links_: CacheAllocation::next, and the bin (normals_.w) beside it
  gl::Texture cav_, positions_, normals_, links_, previous_;
  glm::ivec3 cavSize_{0};  // cav_'s texels a side, and in z for every cascade
  // Per cascade, the first and last z slices holding nodes at the last upload (last < first:
  // none)
  std::vector<glm::ivec2> cavSlices_;
  std::vector<Layer> layers_;
  Targets scratch_;  // a layer's kept caches are copied here, then the two trade places
  Targets sum_;      // Σ over the interpolated layers, where there is more than one
};

}  // namespace manylight
