#include "scene/image_io.h"

#include <dlfcn.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "base/error.h"

namespace manylight {
namespace {

constexpr const char* kModuleName = "libmanylight_imageio.so";

struct Loaded {
  const ImageIoApi* api = nullptr;
  std::string error;
};

// Links the module's libraries (OpenImageIO's, about 260) one dlopen call each, deepest
// first, from the list the build wrote beside the module (cmake/ModuleLibraries.cmake).
// glibc holds one lock for the whole of a dlopen call, and every dlsym waits on it: among
// them those of LLVM's JIT, so llvmpipe, compiling shaders on another thread while a scene
// loads, would stall for the whole of the module's single dlopen. One library per call
// lets the two interleave, and each library's symbols are looked up in its own
// dependencies only, a shorter search. A library that will not open is left to the
// module's own dlopen, which names what is missing.
void preloadLibraries(const std::string& listPath) {
  std::ifstream list(listPath);
  std::vector<std::string> libraries;
  for (std::string line; std::getline(list, line);) {
    if (!line.empty()) libraries.push_back(line);
  }
  for (auto it = libraries.rbegin(); it != libraries.rend(); ++it) {
    dlopen(it->c_str(), RTLD_LAZY | RTLD_LOCAL);  // open for the life of the process
  }
}

Loaded load() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::string path =
      ec ? std::string(kModuleName) : (exe.parent_path() / kModuleName).string();
  preloadLibraries(path + ".libs");
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

void preloadImageIo() {
  try {
    imageIo();
  } catch (const Error&) {
  }
}

}  // namespace manylight
