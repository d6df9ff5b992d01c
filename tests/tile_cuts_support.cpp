#include "tests/tile_cuts_support.h"

#include <gtest/gtest.h>

#include <array>
#include <map>

#include "bake/light_tree_layout.h"
#include "cuts/far_field.h"
#include "scene/shading_model.h"
#include "tests/far_field_support.h"

namespace manylight {

using layout::floatOf;

Checked checkCuts(const SyntheticGBuffer& g, const std::vector<Light>& lights,
                  const TileCuts& cuts) {
  std::map<std::array<float, 3>, std::size_t> spotAt;  // positions are distinct
  for (std::size_t i = 0; i < lights.size(); ++i) {
    if (lights[i].type == LightType::Spot)
      spotAt[{lights[i].position.x, lights[i].position.y, lights[i].position.z}] = i;
  }
  EXPECT_EQ(cuts.cutOfPixel.size(), std::size_t(kSize * kSize));
  const std::vector<std::uint32_t> texels = cuts.texels.flat();
  Checked c;
  std::map<std::uint32_t, glm::dvec3> normalOfCut;  // its first pixel's
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const std::size_t i = (std::size_t(y) * kSize + x) * 4;
      if (g.normal[i + 3] == 0.0f) continue;
      const std::uint32_t cut = cuts.cutOfPixel[std::size_t(y) * kSize + x];
      if (cut == kNoSharedCut) {
        ++c.perPixel;
        continue;
      }
      EXPECT_LT(cut, std::uint32_t(cuts.sharedCuts));
      const std::uint32_t* head = texels.data() + std::size_t(cut) * 8;
      const glm::dvec3 p(g.position[i], g.position[i + 1], g.position[i + 2]);
      const glm::dvec3 n(g.normal[i], g.normal[i + 1], g.normal[i + 2]);
      if (glm::dot(normalOfCut.emplace(cut, n).first->second, n) < 0.0) ++c.mixedSurfaces;
      glm::dvec3 exact(0.0), estimate(0.0);
      for (const Light& l : lights)
        exact += unitRadiance(l, p, n) * glm::dvec3(l.colour) * double(l.intensity);
      const std::uint32_t* e = texels.data() + std::size_t(head[0]) * 4;
      if ((head[7] & 0x7fffu) > 0) {  // far field entries (cuts/tile_cuts.h: the word's bits)
        estimate += farFieldIrradiance(e, p, n) / shading::kPi;
        e += 4 * kFarFieldTexels;
        ++c.farFieldPixels;
      }
      for (int tree = 0; tree < 3; ++tree) {
        for (std::uint32_t k = 0; k < head[1 + tree]; ++k) {
          // The representative: direction or position and 1/range²; a spot's axis and cone
          // (smoothstep of cos · scale + offset); then the node's intensity.
          Light rep;
          const glm::vec3 a(floatOf(e[0]), floatOf(e[1]), floatOf(e[2]));
          rep.type = tree == 0   ? LightType::Directional
                     : tree == 1 ? LightType::Point
                                 : LightType::Spot;
          rep.position = a;
          rep.direction = -a;
          if (floatOf(e[3]) > 0.0f) rep.range = 1.0f / std::sqrt(floatOf(e[3]));
          e += 4;
          if (tree == 2) {  // the scene's spot at that position, its cone as given
            rep = lights[spotAt.at({a.x, a.y, a.z})];
            e += 4;
          }
          estimate +=
              unitRadiance(rep, p, n) * glm::dvec3(floatOf(e[0]), floatOf(e[1]), floatOf(e[2]));
          e += 4;
        }
      }
      const glm::dvec3 bound(floatOf(head[4]), floatOf(head[5]), floatOf(head[6]));
      ++c.sharedPixels;
      for (int ch = 0; ch < 3; ++ch) {
        const double error = std::abs(estimate[ch] - exact[ch]);
        // Float bounds and decoding against double sums: 1e-4 of the pixel, and a floor.
        const double allowed = bound[ch] + 1e-4 * exact[ch] + 1e-9;
        if (error > allowed) ++c.failing;
        // Bounds below 1e-6 of the pixel are within the float rounding of its sums.
        if (bound[ch] > 1e-6 * exact[ch])
          c.worstOverBound = std::max(c.worstOverBound, error / bound[ch]);
      }
    }
  }
  return c;
}

}  // namespace manylight
