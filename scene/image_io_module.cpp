// libmanylight_imageio.so: image files through OpenImageIO (see image_io_module.h).
#include "scene/image_io_module.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <mutex>

namespace manylight {
namespace {

// libpng writes "libpng error: ..." to stderr before OpenImageIO's PNG reader reports the
// same error (OpenImageIO's handler notes the message and returns, so libpng's default
// handler prints it and unwinds): a corrupt PNG gives one to three such lines before
// manylight's own one-line error. While OpenImageIO works, stderr (the process's file
// descriptor 2) goes to an anonymous file; when the last guard leaves, what was written
// there meanwhile goes on to stderr without libpng's lines (OpenImageIO's errors come back
// as text and are reported once). Other threads' lines are held back, not lost: a batch
// decodes the next scene's textures while it renders and reports the one before.
//
// Not under AddressSanitizer: its report of a fault inside a decoder would land in the held
// file and be lost with the process (CI's sanitizer and fuzzing runs read that report).
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kHoldStderr = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kHoldStderr = false;
#else
constexpr bool kHoldStderr = true;
#endif
#else
constexpr bool kHoldStderr = true;
#endif

class QuietLibpng {
 public:
  QuietLibpng() {
    if (!kHoldStderr) return;
    const std::lock_guard<std::mutex> lock(state().mutex);
    State& s = state();
    if (s.depth++ > 0) return;
    std::fflush(stderr);
    s.held = ::memfd_create("manylight-stderr", MFD_CLOEXEC);
    s.saved = s.held >= 0 ? ::dup(STDERR_FILENO) : -1;
    if (s.saved >= 0) ::dup2(s.held, STDERR_FILENO);
  }
  ~QuietLibpng() {
    if (!kHoldStderr) return;
    const std::lock_guard<std::mutex> lock(state().mutex);
    State& s = state();
    if (--s.depth > 0) return;
    std::fflush(stderr);
    if (s.saved >= 0) {
      ::dup2(s.saved, STDERR_FILENO);
      ::close(s.saved);
      std::string text;
      char buffer[4096];
      for (ssize_t n; (n = ::pread(s.held, buffer, sizeof buffer, off_t(text.size()))) > 0;)
        text.append(buffer, std::size_t(n));
      for (std::size_t at = 0; at < text.size();) {
        const std::size_t end = std::min(text.find('\n', at), text.size() - 1) + 1;
        if (text.compare(at, 7, "libpng ") != 0) writeAll(text.data() + at, end - at);
        at = end;
      }
    }
    if (s.held >= 0) ::close(s.held);
    s.held = s.saved = -1;
  }
  QuietLibpng(const QuietLibpng&) = delete;
  QuietLibpng& operator=(const QuietLibpng&) = delete;

 private:
  struct State {
    std::mutex mutex;
    int depth = 0;
    int held = -1;   // the anonymous file that stands in for stderr
    int saved = -1;  // stderr itself
  };
  static State& state() {
    static State s;
    return s;
  }
  static void writeAll(const char* p, std::size_t n) {
    while (n > 0) {
      const ssize_t w = ::write(STDERR_FILENO, p, n);
      if (w <= 0) return;
      p += w;
      n -= std::size_t(w);
    }
  }
};

bool fail(std::string* error, const std::string& reason) {
  *error = reason.empty() ? "unknown error" : reason;
  return false;
}

// Reads all channels of the opened image `in` as `type` into `out`.
template <typename T>
bool readPixels(OIIO::ImageInput& in, OIIO::TypeDesc type, RawImage<T>* out, std::string* error) {
  const OIIO::ImageSpec& spec = in.spec();
  out->width = spec.width;
  out->height = spec.height;
  out->channels = spec.nchannels;
  out->pixels.resize(std::size_t(spec.width) * spec.height * spec.nchannels);
  return in.read_image(0, 0, 0, spec.nchannels, type, out->pixels.data())
             ? true
             : fail(error, in.geterror());
}

bool decode8(const unsigned char* bytes, std::size_t size, const char* extension,
             std::int64_t maxDimension, std::int64_t maxPixels, RawImage<std::uint8_t>* out,
             std::string* error) {
  const QuietLibpng quiet;
  OIIO::Filesystem::IOMemReader reader(const_cast<unsigned char*>(bytes), size);
  // The reader of that format alone: given a file name, OpenImageIO tries every reader it
  // has on bytes that the named one rejects, and glTF images are PNG or JPEG, nothing else.
  auto in = OIIO::ImageInput::create(extension + 1);  // "png", "jpg": no probing
  if (!in) return fail(error, OIIO::geterror());
  OIIO::ImageSpec spec;
  if (!in->set_ioproxy(&reader) || !in->open(std::string("image") + extension, spec))
    return fail(error, in->geterror());
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth != 1) {
    return fail(error, "image has no pixels");
  }
  if (spec.width > maxDimension || spec.height > maxDimension) {
    return fail(error, std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                           " exceeds the texture dimension limit of " +
                           std::to_string(maxDimension));
  }
  if (std::int64_t(spec.width) * spec.height > maxPixels) {
    return fail(error, std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                           " exceeds the texture limit of " + std::to_string(maxPixels) +
                           " pixels");
  }
  return readPixels(*in, OIIO::TypeDesc::UINT8, out, error);
}

// Writes `image` to `path`, or into `proxy` when one is given (`path` then names the format).
template <typename T>
bool write(const char* path, const RawImage<T>& image, OIIO::TypeDesc type, const char* colourSpace,
           std::string* error, OIIO::Filesystem::IOProxy* proxy = nullptr) {
  const QuietLibpng quiet;
  auto out = OIIO::ImageOutput::create(path, proxy);
  if (!out) return fail(error, OIIO::geterror());
  OIIO::ImageSpec spec(image.width, image.height, image.channels, type);
  spec.attribute("oiio:ColorSpace", colourSpace);
  if (type == OIIO::TypeDesc::FLOAT) spec.attribute("compression", "zip");
  // No capture date: reruns must produce bit-identical files.
  spec.attribute("DateTime", "");
  bool ok = out->open(path, spec) && out->write_image(type, image.pixels.data());
  ok = out->close() && ok;
  return ok ? true : fail(error, out->geterror());
}

bool encodePng8(const RawImage<std::uint8_t>& image, std::vector<unsigned char>* png,
                std::string* error) {
  OIIO::Filesystem::IOVecOutput memory(*png);
  return write("memory.png", image, OIIO::TypeDesc::UINT8, "sRGB", error, &memory);
}

bool writeSrgb8(const char* path, const RawImage<std::uint8_t>& image, std::string* error) {
  return write(path, image, OIIO::TypeDesc::UINT8, "sRGB", error);
}

bool writeLinearFloat(const char* path, const RawImage<float>& image, std::string* error) {
  return write(path, image, OIIO::TypeDesc::FLOAT, "Linear", error);
}

bool readFloat(const char* path, RawImage<float>* out, std::string* error) {
  const QuietLibpng quiet;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return fail(error, OIIO::geterror());
  return readPixels(*in, OIIO::TypeDesc::FLOAT, out, error);
}

// Compares `a` and `b`, whose shapes are already in `out`, with ImageBufAlgo::compare.
bool compareBuffers(const OIIO::ImageBuf& a, const OIIO::ImageBuf& b, double threshold,
                    ImageComparison* out, std::string* error) {
  out->sameShape = out->width[0] == out->width[1] && out->height[0] == out->height[1] &&
                   out->channels[0] == out->channels[1];
  if (!out->sameShape) return true;
  const auto r = OIIO::ImageBufAlgo::compare(a, b, float(threshold), float(threshold));
  // r.error only says that some value failed; errors of the comparison itself land here.
  if (a.has_error() || b.has_error()) return fail(error, a.geterror() + b.geterror());
  out->maxError = r.maxerror;
  out->meanError = r.meanerror;
  out->rmsError = r.rms_error;
  out->psnr = r.PSNR;
  out->maxX = r.maxx;
  out->maxY = r.maxy;
  out->maxChannel = r.maxc;
  out->failing = static_cast<long long>(r.nfail);
  out->values = static_cast<long long>(out->width[0]) * out->height[0] * out->channels[0];
  return true;
}

bool compareFiles(const char* a, const char* b, double threshold, const char* diffPath,
                  double diffScale, ImageComparison* out, std::string* error) {
  const QuietLibpng quiet;
  OIIO::ImageBuf images[2] = {OIIO::ImageBuf(a), OIIO::ImageBuf(b)};
  for (int i = 0; i < 2; ++i) {
    if (!images[i].read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
      return fail(error, std::string(i ? b : a) + ": cannot read image: " + images[i].geterror());
    }
    const OIIO::ImageSpec& spec = images[i].spec();
    out->width[i] = spec.width;
    out->height[i] = spec.height;
    out->channels[i] = spec.nchannels;
  }
  if (!compareBuffers(images[0], images[1], threshold, out, error)) return false;
  if (!out->sameShape) return true;
  if (!diffPath) return true;
  OIIO::ImageBuf diff = OIIO::ImageBufAlgo::absdiff(images[0], images[1]);
  diff = OIIO::ImageBufAlgo::mul(diff, float(diffScale));
  diff = OIIO::ImageBufAlgo::channels(diff, std::min(3, out->channels[0]), {});
  diff = OIIO::ImageBufAlgo::clamp(diff, 0.0f, 1.0f);
  if (diff.has_error()) return fail(error, diff.geterror());
  diff.specmod().attribute("DateTime", "");
  return diff.write(diffPath, OIIO::TypeDesc::UINT8, "png")
             ? true
             : fail(error, diff.geterror() + OIIO::geterror());
}

bool compareImages(const RawImage<float>& a, const RawImage<float>& b, double threshold,
                   ImageComparison* out, std::string* error) {
  const RawImage<float>* images[2] = {&a, &b};
  OIIO::ImageBuf buffers[2];
  for (int i = 0; i < 2; ++i) {
    const RawImage<float>& image = *images[i];
    out->width[i] = image.width;
    out->height[i] = image.height;
    out->channels[i] = image.channels;
    if (std::size_t(image.width) * image.height * image.channels != image.pixels.size())
      return fail(error, "image size does not match its pixels");
    // Wraps the caller's pixels; compare only reads them.
    buffers[i].reset(
        OIIO::ImageSpec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT),
        const_cast<float*>(image.pixels.data()));
  }
  return compareBuffers(buffers[0], buffers[1], threshold, out, error);
}

const ImageIoApi kApi = {ImageIoApi::kVersion, decode8,   encodePng8,   writeSrgb8,
                         writeLinearFloat,     readFloat, compareFiles, compareImages};

}  // namespace
}  // namespace manylight

extern "C" __attribute__((visibility("default"))) const manylight::ImageIoApi*
manylight_imageio_api() {
  return &manylight::kApi;
}
