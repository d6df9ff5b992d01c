#include "scene/image_io.h"

#include <dlfcn.h>

#include <filesystem>

#include "scene/error.h"

namespace manylight {
namespace {

constexpr const char* kModuleName = "libmanylight_imageio.so";

struct Loaded {
  const ImageIoApi* api = nullptr;
  std::string error;
};

Loaded load() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::string path =
      ec ? std::string(kModuleName) : (exe.parent_path() / kModuleName).string();
  // RTLD_LOCAL: OpenImageIO's libraries stay out of the global symbol scope. RTLD_LAZY: of
  // their thousands of functions, bind only those called.
  void* handle = dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
  if (!handle) return {nullptr, "cannot load the image I/O module: " + std::string(dlerror())};
  using Entry = const ImageIoApi* (*)();
  auto entry = reinterpret_cast<Entry>(dlsym(handle, "manylight_imageio_api"));
  const ImageIoApi* api = entry ? entry() : nullptr;
  if (!api || api->version != ImageIoApi::kVersion) {
    return {nullptr, path + ": not an image I/O module of this manylight build"};
  }
  return {api, {}};  // the handle stays open for the life of the process
}

}  // namespace

const ImageIoApi& imageIo() {
  static const Loaded loaded = load();  // thread-safe initialisation
  if (!loaded.api) throw Error(loaded.error);
  return *loaded.api;
}

}  // namespace manylight
