// The tile and cell cuts tests' synthetic G-buffer (tile_cuts_test.cpp, cell_cuts_test.cpp),
// and the check of their shared cuts against the exact sum in double precision.
#pragma once

#include <cstring>
#include <vector>

#include "cuts/tile_cuts.h"
#include "scene/scene.h"

namespace manylight {

inline constexpr int kSize = 64;

// A G-buffer of a floor (y = 0, facing up) on the left, with a patch of ceiling showing
// through it, a wall (x = 3, facing −x) on the right, and a band of background at the top;
// rows bottom-up as GL reads them. `pan` moves the view along z (a camera moving sideways).
struct SyntheticGBuffer {
  std::vector<float> position, normal, specular;
  explicit SyntheticGBuffer(float pan = 0.0f)
      : position(kSize * kSize * 4), normal(kSize * kSize * 4), specular(kSize * kSize * 4) {
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const std::size_t i = (std::size_t(y) * kSize + x) * 4;
        if (y >= kSize - 6) continue;  // background
        const float u = float(x) / kSize, v = float(y) / kSize + pan / 6.0f;
        glm::vec3 p, n;
        if (x < kSize * 5 / 8 && y >= 40 && y < 48 && (x + y) % 3 == 0) {
          // A patch of the ceiling seen through gaps: squares whose normals spread 180°.
          p = {-3.0f + 9.6f * u, 2.5f, -3.0f + 6.0f * v};
          n = {0.0f, -1.0f, 0.0f};
        } else if (x < kSize * 5 / 8) {
          p = {-3.0f + 9.6f * u, 0.0f, -3.0f + 6.0f * v};
          n = {0.0f, 1.0f, 0.0f};
        } else {
          p = {3.0f, 6.0f * (u - 0.625f) * 2.0f, -3.0f + 6.0f * v};
          n = {-1.0f, 0.0f, 0.0f};
        }
        std::memcpy(&position[i], &p, 12);
        std::memcpy(&normal[i], &n, 12);
        normal[i + 3] = 1.0f;
      }
    }
  }
  GBufferPixels pixels() const {
    return {kSize, kSize, position.data(), normal.data(), specular.data()};
  }
};

struct Checked {
  int sharedPixels = 0, failing = 0;
  int perPixel = 0;             // covered pixels without a shared cut
  int mixedSurfaces = 0;        // shared pixels facing over 90° away from their cut's first pixel
  int farFieldPixels = 0;       // shared pixels whose cut has a far field
  double worstOverBound = 0.0;  // largest error / bound, bounds above 1e-6 of the pixel
};

// Evaluates every shared cut of `cuts` at each of its pixels of `g` in double precision
// against the exact sum of `lights`.
Checked checkCuts(const SyntheticGBuffer& g, const std::vector<Light>& lights,
                  const TileCuts& cuts);

}  // namespace manylight
