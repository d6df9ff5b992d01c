#pragma once
// The CPU oracle: the exact radiance of each pixel in double precision. The pixel's ray
// (through its centre) is intersected with every triangle of the scene, and the nearest hit
// is shaded with scene/shading_model.h. No GL, no shortcuts: slow, and the ground truth the
// GPU's reference method is held to.
#include <vector>

#include "image/image.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace manylight::testing {

struct OracleImage {
  Image image;               // linear radiance, alpha = coverage
  std::vector<int> surface;  // per pixel: index of the (instance, primitive) hit, −1: none
  // True where the 3×3 neighbourhood sees one surface: rasterisation and ray casting agree
  // there on which surface a pixel shows (silhouettes are left out of comparisons).
  bool interior(int x, int y) const;
};

OracleImage renderOracle(const Scene& scene, const Camera& camera, const std::vector<Light>& lights,
                         int width, int height, glm::dvec3 ambient = glm::dvec3(0.0));

}  // namespace manylight::testing
