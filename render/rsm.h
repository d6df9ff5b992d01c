#pragma once
// Reflective shadow maps (Dachsbacher and Stamminger 2005) for `--indirect`
// (render/indirect_light.h): a spot or directional light's view of the scene, whose texels
// are patches of the surfaces it lights first, each reflecting a flux (glsl/rsm_flux.frag).
// Point lights get none (they would need six maps); neither do lights beyond the chosen few.
#include <vector>

#include "gl/objects.h"
#include "render/gbuffer.h"
#include "render/rsm_clusters.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace manylight {

// A map's camera and the scale of its texels' areas (glsl/rsm_flux.frag's uTexelScale).
struct RsmView {
  View view;
  float texelScale = 0.0f;
};

// The view of a `size` × `size` map of `light` over the scene `bounds`: for a spot, a
// perspective from its position along its direction whose field of view is twice the
// outer cone angle (at most kMaxRsmHalfAngle: a wider cone loses its rim), near at 10⁻³ of
// its reach, far at its range (or the scene's far side); for a directional light, an
// orthographic view along it covering the scene's bounding sphere.
RsmView rsmView(const Light& light, const Bounds& bounds, int size);
inline constexpr float kMaxRsmHalfAngle = 1.3089969f;  // 75°

// Draws `program` (in use, its target and other inputs bound) once per band of the map's
// rows: the map's position, normal and flux targets on units `firstUnit` … `firstUnit` + 2
// as uRsmPosition, uRsmNormal, uRsmFlux, its size as uRsmSize, and each band as uFirstRow
// and uRows. A band has as many rows (a multiple of `rowAlign`) as keep a loop of
// `iterationsPerTexel` per texel under llvmpipe's 65,535 iterations per invocation. Returns
// the passes.
int drawRsmRowPasses(const gl::Program& program, const GBuffer& rsm, int firstUnit,
                     int rowAlign = 1, double iterationsPerTexel = 1.0);

// A map's clusters (render/rsm_clusters.h) and its texels, as records of three RGBA32F
// textures (centre or position; normal; flux), for s clusters a side and n = kRsmClusterEdge²
// texels a cluster n · s wide and ⌈s / n⌉ + s high: cluster (bx, by) at texel
// (s · (by mod n) + bx, by / n), its texel j (glsl/cache_gather.frag's numbering) at
// (n · bx + j, ⌈s / n⌉ + by). So the gather reads a cluster and its texels from the same
// textures, in one loop, and they take about as much memory as the map.
struct RsmClusterTextures {
  gl::Texture centre, normal, flux;
  // `clusters` of a map read back as RGBA floats (`mapPosition`, `mapNormal`, `mapFlux`).
  // Throws gl::GlError.
  void upload(const RsmClusters& clusters, const std::vector<float>& mapPosition,
              const std::vector<float>& mapNormal, const std::vector<float>& mapFlux);
};

}  // namespace manylight
