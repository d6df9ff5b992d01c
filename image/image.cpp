#include "image/image.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "base/output_file.h"
#include "image/image_errors.h"
#include "scene/image_io.h"

namespace manylight {

namespace fs = std::filesystem;

void checkOutputPath(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  if (ext != ".png" && ext != ".PNG" && ext != ".exr" && ext != ".EXR") {
    throw ImageError(path + ": unsupported output format, expected .png or .exr");
  }
}

std::vector<std::uint8_t> displayCodes(const Image& image, const Display& display) {
  const double scale = std::exp2(double(display.exposure));
  const std::size_t n = std::size_t(image.width) * image.height;
  std::vector<std::uint8_t> codes(n * 4);
  auto code = [](float v) { return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  for (std::size_t i = 0; i < n; ++i) {
    const float* p = &image.rgba[i * 4];
    std::uint8_t* c = &codes[i * 4];
    // Alpha is coverage, not a colour: linear, not encoded.
    c[3] = code(p[3]);
    if (image.values == ImageValues::Data) {
      for (int ch = 0; ch < 3; ++ch) c[ch] = code(p[ch]);
      continue;
    }
    // Images hold colour premultiplied by coverage (as EXR does); PNG's is straight, so
    // partly covered pixels are divided by it.
    const double straight = p[3] > 0.0f && p[3] < 1.0f ? 1.0 / p[3] : 1.0;
    if (display.toneMap == ToneMap::None) {
      for (int ch = 0; ch < 3; ++ch) c[ch] = encodeSrgb8(p[ch] * scale * straight);
      continue;
    }
    const glm::vec3 linear = glm::vec3(glm::dvec3(p[0], p[1], p[2]) * (scale * straight));
    const glm::vec3 shown = toneMap(display.toneMap, linear);
    for (int ch = 0; ch < 3; ++ch) c[ch] = encodeSrgb8(shown[ch]);
  }
  return codes;
}

void writeImage(const Image& image, const std::string& path, const Display& display) {
  const float exposure = display.exposure;
  const fs::path target(path);
  const std::string ext = target.extension().string();
  checkOutputPath(path);
  const bool png = ext == ".png" || ext == ".PNG";
  const fs::path tmp = prepareTemporaryFor(target);
  const double scale = std::exp2(double(exposure));
  const std::size_t n = std::size_t(image.width) * image.height;
  bool ok = false;
  std::string reason;
  if (png) {
    const RawImage<std::uint8_t> codes{image.width, image.height, 4, displayCodes(image, display)};
    ok = imageIo().writeSrgb8(tmp.c_str(), codes, &reason);
  } else {
    RawImage<float> scaled{image.width, image.height, 4, image.rgba};
    for (std::size_t i = 0; i < n * 4; ++i) {
      if (i % 4 != 3) scaled.pixels[i] = float(scaled.pixels[i] * scale);
    }
    ok = imageIo().writeLinearFloat(tmp.c_str(), scaled, &reason);
  }
  if (ok) return commitTemporary(tmp, target);
  std::error_code ec;
  fs::remove(tmp, ec);
  throw ImageError(path + ": cannot write image: " + (reason.empty() ? "unknown error" : reason));
}

Image readImage(const std::string& path, int* channels) {
  RawImage<float> raw;
  std::string reason;
  if (!imageIo().readFloat(path.c_str(), &raw, &reason)) {
    throw ImageError(path + ": cannot read image: " + reason);
  }
  if (channels) *channels = raw.channels;
  Image img;
  img.width = raw.width;
  img.height = raw.height;
  img.rgba.assign(std::size_t(img.width) * img.height * 4, 1.0f);
  for (std::size_t i = 0, n = std::size_t(img.width) * img.height; i < n; ++i) {
    for (int c = 0; c < std::min(raw.channels, 4); ++c)
      img.rgba[i * 4 + c] = raw.pixels[i * raw.channels + c];
  }
  return img;
}

namespace {

// compareImageFiles' relative test: each file read once, its shape as OpenImageIO's
// comparison would give it.
CompareOutcome compareRelative(const std::string& a, const std::string& b,
                               const CompareThresholds& t, const std::string& diffPath) {
  CompareOutcome out;
  ImageComparison& v = out.values;
  const Image image = readImage(a, &v.channels[0]), reference = readImage(b, &v.channels[1]);
  v.width[0] = image.width, v.height[0] = image.height;
  v.width[1] = reference.width, v.height[1] = reference.height;
  v.sameShape = image.width == reference.width && image.height == reference.height &&
                v.channels[0] == v.channels[1];
  if (!v.sameShape) return out;
  const RelativeErrors e = relativeErrors(image, reference);
  out.relative = true;
  out.errors = {percentileOf(e.sorted, t.percentile), e.sorted.empty() ? 0.0 : e.sorted.back(),
                e.maxX, e.maxY, static_cast<long long>(e.sorted.size())};
  out.passed = out.errors.atPercentile <= t.maxRelative;
  if (out.passed || diffPath.empty()) return out;
  if (fs::path(diffPath).extension() != ".png")
    throw ImageError(diffPath + ": the difference image must be a .png");
  Image diff;
  diff.width = reference.width;
  diff.height = reference.height;
  diff.values = ImageValues::Data;
  diff.rgba.assign(reference.rgba.size(), 1.0f);
  for (int y = 0; y < reference.height; ++y) {
    for (int x = 0; x < reference.width; ++x) {
      const double r = reference.pixel(x, y)[3] > 0.0f
                           ? relativeError(image.pixel(x, y), reference.pixel(x, y))
                           : 0.0;
      const double grey = t.maxRelative > 0.0 ? r / (2.0 * t.maxRelative) : (r > 0.0 ? 1.0 : 0.0);
      for (int c = 0; c < 3; ++c) diff.pixel(x, y)[c] = float(std::min(grey, 1.0));
    }
  }
  writeImage(diff, diffPath);
  out.diffWritten = true;
  return out;
}

}  // namespace

CompareOutcome compareImageFiles(const std::string& a, const std::string& b,
                                 const CompareThresholds& thresholds, const std::string& diffPath) {
  for (const std::string& path : {a, b}) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (!ec && fs::exists(st) && !fs::is_regular_file(st)) {
      throw ImageError(path + ": not a regular file");  // a FIFO would block the reader
    }
  }
  if (thresholds.maxRelative >= 0.0) return compareRelative(a, b, thresholds, diffPath);
  CompareOutcome out;
  std::string reason;
  if (!imageIo().compareFiles(a.c_str(), b.c_str(), thresholds.maxAbs, nullptr, 0.0, &out.values,
                              &reason)) {
    throw ImageError(reason);
  }
  const ImageComparison& v = out.values;
  out.passed = v.sameShape && double(v.failing) <= thresholds.maxFraction * double(v.values);
  if (out.passed || !v.sameShape || diffPath.empty()) return out;
  if (fs::path(diffPath).extension() != ".png")
    throw ImageError(diffPath + ": the difference image must be a .png");
  const fs::path tmp = prepareTemporaryFor(diffPath);
  const double scale = thresholds.maxAbs > 0.0 ? 0.5 / thresholds.maxAbs : 127.5;
  ImageComparison again;
  if (!imageIo().compareFiles(a.c_str(), b.c_str(), thresholds.maxAbs, tmp.c_str(), scale, &again,
                              &reason)) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw ImageError(diffPath + ": cannot write the difference image: " + reason);
  }
  commitTemporary(tmp, diffPath);
  out.diffWritten = true;
  return out;
}

}  // namespace manylight
