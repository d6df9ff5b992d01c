#pragma once
// The bound on a light cache's gather (glsl/cache_gather.frag): a map's texels in blocks of
// kRsmClusterEdge², each block one cluster with its total flux and area, its flux-weighted
// centre, its mean normal and the radius of a sphere about the centre holding its texels. A
// cache farther from a cluster than kRsmClusterDistance radii (and than the texels' near
// reach, so every texel of it gets the whole far weight) takes the cluster's light as that of
// one texel at its centre, with the flux-weighted mean normal; nearer, or where its texels do not
// share a facing within kRsmClusterFlat, it sums the cluster's texels. No GL here; the textures are
// the caller's.
#include <glm/glm.hpp>
#include <vector>

namespace manylight {

inline constexpr int kRsmClusterEdge = 4;
inline constexpr float kRsmClusterDistance = 8.0f;
inline constexpr float kRsmClusterFlat =
    0.95f;  // least cosine between a texel's and the mean normal

// Per cluster (row-major over the map's (size / kRsmClusterEdge)² blocks, rows bottom-up as
// the map's), three RGBA texels:
struct RsmClusters {
  int size = 0;  // clusters a side
  // centre.xyz, radius; radius < 0: no texel of the block reflects flux
  std::vector<glm::vec4> centre;
  // mean unit normal, 1 where every texel is within kRsmClusterFlat of it (else 0)
  std::vector<glm::vec4> normal;
  // Σ flux.rgb, and the mean area of its texels: the gather's softening is a texel's
  std::vector<glm::vec4> flux;
};

// The clusters of a `size` × `size` map read back as RGBA floats (position, normal, flux with
// the patch area in w); `size` a multiple of kRsmClusterEdge.
RsmClusters clusterRsm(const std::vector<float>& position, const std::vector<float>& normal,
                       const std::vector<float>& flux, int size);

}  // namespace manylight
