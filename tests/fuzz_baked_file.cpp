// libFuzzer target for the baked file reader (clang, -DMANYLIGHT_FUZZ=ON; run by
// ci/sanitize.sh). An input is the file after its header: the target writes a header that
// passes (magic, version, size, checksum), so the fuzzer spends its time in the section table
// and the sections rather than on checksum mismatches. A BakeError is the expected way to
// fail; anything else is a bug.
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "bake/baked_file.h"

namespace {

const std::filesystem::path& folder() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() /
             ("manylight-fuzz-baked-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string file(manylight::kBakedHeaderBytes, '\0');
  file.append(reinterpret_cast<const char*>(data), size);
  std::memcpy(&file[0], manylight::kBakedMagic, 8);
  const std::uint32_t version = manylight::kBakedFormatVersion;
  std::memcpy(&file[8], &version, 4);
  const std::uint64_t total = file.size();
  std::memcpy(&file[16], &total, 8);
  const std::uint64_t sum =
      manylight::bakedChecksum(std::string_view(file).substr(manylight::kBakedHeaderBytes));
  std::memcpy(&file[24], &sum, 8);
  const auto path = folder() / "input.mlbake";
  std::ofstream(path, std::ios::binary | std::ios::trunc) << file;
  try {
    manylight::readBakedScene(path.string(), 64u << 20);
  } catch (const manylight::BakeError&) {
  }
  return 0;
}
