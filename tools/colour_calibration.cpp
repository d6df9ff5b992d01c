#include "tools/colour_calibration.h"

#include <cmath>
#include <cstdlib>

#include "render/render_job.h"
#include "scene/srgb.h"

namespace manylight {

ColourCalibration calibrateColour(const Scene& scene, int firstCode, int lastCode, int width,
                                  int height) {
  if (firstCode < 1 || lastCode > 255 || firstCode >= lastCode) {
    throw Error("calibration codes must satisfy 1 <= first < last <= 255, got " +
                std::to_string(firstCode) + ".." + std::to_string(lastCode));
  }
  RenderRequest request;
  request.width = width;
  request.height = height;
  const Camera camera = resolveCamera(scene, request);
  Light probe = scene.lights.empty() ? defaultLightRig(camera).front() : scene.lights.front();
  Renderer renderer(scene, {probe}, width, height, Method::Reference);
  const View view = makeView(camera, width, height);
  ColourCalibration c;
  for (int code = firstCode; code <= lastCode; ++code) {
    probe.colour = glm::vec3(float(decodeSrgb8(std::uint8_t(code))));
    renderer.replaceLights({probe});
    const Image image = renderer.render(view, FrameSettings{});
    double sum = 0.0;
    long long covered = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
      if (image.rgba[i + 3] <= 0.0f) continue;
      sum += (double(image.rgba[i]) + image.rgba[i + 1] + image.rgba[i + 2]) / 3.0;
      ++covered;
    }
    const double mean = covered > 0 ? sum / double(covered) : 0.0;
    if (!(mean > 0.0)) {
      throw Error(scene.name + ": the calibration probe (light " +
                  (scene.lights.empty() ? "of the default rig" : "0") +
                  ") lights nothing the camera sees at code " + std::to_string(code));
    }
    c.pairs.push_back({double(code), mean});
  }
  c.fit = fitPowerLaw(c.pairs);
  const double top = c.fit(255.0);
  for (int code = 0; code < 256; ++code) {
    const int fitted = code == 0 ? 0 : encodeSrgb8(c.fit(double(code)) / top);
    const int difference = std::abs(fitted - code);
    if (difference > c.largestCodeDifference) {
      c.largestCodeDifference = difference;
      c.worstCode = code;
    }
  }
  return c;
}

}  // namespace manylight
