#pragma once
// Exact radiance and far field texels in double precision, for the tests of shared tile cuts
// (tests/tile_cuts_test.cpp) and of the far field (tests/far_field_test.cpp).
#include <cstdint>
#include <glm/glm.hpp>

#include "bake/light_tree_layout.h"
#include "scene/scene.h"
#include "scene/shading_model.h"

namespace manylight {

// A far field's irradiance at (p, n) from its texels at `e`, as the shader takes it: per
// channel n · (F + J (x − c)).
inline glm::dvec3 farFieldIrradiance(const std::uint32_t* e, glm::dvec3 p, glm::dvec3 n) {
  auto texel = [&](int k) {
    return glm::dvec3(layout::floatOf(e[4 * k]), layout::floatOf(e[4 * k + 1]),
                      layout::floatOf(e[4 * k + 2]));
  };
  const glm::dvec3 d = p - texel(0);
  glm::dvec3 out;
  for (int ch = 0; ch < 3; ++ch) {
    const glm::dmat3 j(texel(4 + 3 * ch), texel(5 + 3 * ch), texel(6 + 3 * ch));
    out[ch] = glm::dot(n, texel(1 + ch) + j * d);
  }
  return out;
}

// Per unit albedo: the exact radiance of all lights at (p, n), and of a light per unit
// colour · intensity.
inline glm::dvec3 unitRadiance(Light light, glm::dvec3 p, glm::dvec3 n) {
  light.colour = glm::vec3(1.0f);
  light.intensity = 1.0f;
  glm::dvec3 l;
  return shading::irradiance(light, p, n, l) / shading::kPi;
}

}  // namespace manylight
