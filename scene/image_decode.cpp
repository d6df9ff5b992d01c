#include "scene/image_decode.h"

#include <cstring>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "scene/error.h"

namespace manylight {

DecodedImage decodeImage(const unsigned char* bytes, std::size_t size, const std::string& what) {
  namespace oiio = OIIO;
  // OpenImageIO picks the reader from the name; choose it from the magic number.
  std::string name = "image";
  if (size >= 8 && std::memcmp(bytes, "\x89PNG", 4) == 0) {
    name += ".png";
  } else if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) {
    name += ".jpg";
  } else {
    throw SceneError(what + ": not a PNG or JPEG image");
  }
  oiio::Filesystem::IOMemReader reader(const_cast<unsigned char*>(bytes), size);
  auto in = oiio::ImageInput::open(name, nullptr, &reader);
  if (!in) {
    throw SceneError(what + ": cannot decode image: " + oiio::geterror());
  }
  const oiio::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth != 1) {
    throw SceneError(what + ": image has no pixels");
  }
  const int channels = std::min(spec.nchannels, 4);
  std::vector<std::uint8_t> raw(std::size_t(spec.width) * spec.height * channels);
  if (!in->read_image(0, 0, 0, channels, oiio::TypeDesc::UINT8, raw.data())) {
    throw SceneError(what + ": cannot decode image: " + in->geterror());
  }
  DecodedImage img;
  img.width = spec.width;
  img.height = spec.height;
  img.rgba.resize(std::size_t(img.width) * img.height * 4);
  for (std::size_t i = 0, n = std::size_t(img.width) * img.height; i < n; ++i) {
    const std::uint8_t* s = &raw[i * channels];
    std::uint8_t* d = &img.rgba[i * 4];
    if (channels >= 3) {
      d[0] = s[0], d[1] = s[1], d[2] = s[2];
    } else {
      d[0] = d[1] = d[2] = s[0];  // grey or grey + alpha
    }
    d[3] = channels == 4 ? s[3] : channels == 2 ? s[1] : 255;
  }
  return img;
}

}  // namespace manylight
