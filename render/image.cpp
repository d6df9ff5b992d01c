#include "render/image.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <OpenImageIO/imageio.h>

#include "render/output_file.h"

namespace manylight {

namespace fs = std::filesystem;

std::uint8_t encodeSrgb8(double linear) {
  if (!(linear > 0.0)) return 0;  // also NaN
  if (linear >= 1.0) return 255;
  const double v = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return std::uint8_t(std::lround(v * 255.0));
}

double decodeSrgb8(std::uint8_t code) {
  const double v = code / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

void checkOutputPath(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  if (ext != ".png" && ext != ".PNG" && ext != ".exr" && ext != ".EXR") {
    throw ImageError(path + ": unsupported output format, expected .png or .exr");
  }
}

void writeImage(const Image& image, const std::string& path, float exposure) {
  const fs::path target(path);
  const std::string ext = target.extension().string();
  checkOutputPath(path);
  const bool png = ext == ".png" || ext == ".PNG";
  const bool exr = !png;
  const fs::path tmp = prepareTemporaryFor(target);
  const double scale = std::exp2(double(exposure));
  const std::size_t n = std::size_t(image.width) * image.height;
  bool ok = false;
  std::string reason;
  {
    auto out = OIIO::ImageOutput::create(tmp.string());
    if (out) {
      OIIO::ImageSpec spec(image.width, image.height, 4, png ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
      spec.attribute("oiio:ColorSpace", png ? "sRGB" : "Linear");
      if (exr) spec.attribute("compression", "zip");
      // No capture date: reruns must produce bit-identical files.
      spec.attribute("DateTime", "");
      if (out->open(tmp.string(), spec)) {
        if (png) {
          std::vector<std::uint8_t> codes(n * 4);
          for (std::size_t i = 0; i < n * 4; ++i) {
            // Alpha is coverage, not a colour: linear, not encoded.
            codes[i] = (i % 4 == 3) ? std::uint8_t(std::lround(std::clamp(image.rgba[i], 0.0f, 1.0f) * 255.0f))
                                    : encodeSrgb8(image.rgba[i] * scale);
          }
          ok = out->write_image(OIIO::TypeDesc::UINT8, codes.data());
        } else {
          std::vector<float> scaled(image.rgba);
          for (std::size_t i = 0; i < n * 4; ++i) {
            if (i % 4 != 3) scaled[i] = float(scaled[i] * scale);
          }
          ok = out->write_image(OIIO::TypeDesc::FLOAT, scaled.data());
        }
        ok = out->close() && ok;
      }
      if (!ok) reason = out->geterror();
    } else {
      reason = OIIO::geterror();
    }
  }
  if (ok) return commitTemporary(tmp, target);
  std::error_code ec;
  fs::remove(tmp, ec);
  throw ImageError(path + ": cannot write image: " + (reason.empty() ? "unknown error" : reason));
}

Image readImage(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw ImageError(path + ": cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  Image img;
  img.width = spec.width;
  img.height = spec.height;
  const int channels = spec.nchannels;
  std::vector<float> raw(std::size_t(spec.width) * spec.height * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, raw.data())) {
    throw ImageError(path + ": cannot read image: " + in->geterror());
  }
  img.rgba.assign(std::size_t(img.width) * img.height * 4, 1.0f);
  for (std::size_t i = 0, n = std::size_t(img.width) * img.height; i < n; ++i) {
    for (int c = 0; c < std::min(channels, 4); ++c) img.rgba[i * 4 + c] = raw[i * channels + c];
  }
  return img;
}

}  // namespace manylight
