#include "tests/gl_support.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "generators/scene_builder.h"
#include "scene/gltf_loader.h"

namespace manylight::testing {

gl::Context& context() {
  static std::unique_ptr<gl::Context> ctx = gl::createContext(gl::Backend::Auto);
  return *ctx;
}

double largestDifference(const Image& a, const Image& b) {
  double diff = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    diff = std::max(diff, std::abs(double(a.rgba[i]) - double(b.rgba[i])));
    peak = std::max({peak, double(a.rgba[i]), double(b.rgba[i])});
  }
  return diff / std::max(peak, 1e-30);
}

Scene cornellWith(int extraLights) {
  context();
  // Per process: ctest runs the tests side by side, each in its own.
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("manylight_cornell_" + std::to_string(extraLights) + "_" +
                             std::to_string(::getpid()) + ".glb"))
                               .string();
  CornellOptions options;
  options.extraLights = extraLights;
  writeCornellScene(path, options);
  Scene s = loadGltf(path);
  std::filesystem::remove(path);
  return s;
}

}  // namespace manylight::testing
