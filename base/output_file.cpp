#include "base/output_file.h"

#include <unistd.h>

#include <fstream>

#include "base/error.h"

namespace manylight {

namespace fs = std::filesystem;

fs::path prepareTemporaryFor(const fs::path& target) {
  std::error_code ec;
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  if (ec) throw Error(target.string() + ": cannot create folder: " + ec.message());
  return target.parent_path() / ("." + target.filename().string() + ".tmp" +
                                 std::to_string(::getpid()) + target.extension().string());
}

void commitTemporary(const fs::path& tmp, const fs::path& target) {
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error(target.string() + ": cannot write: " + ec.message());
  }
}

void writeFileAtomic(const std::string& path, const std::string& text) {
  const fs::path tmp = prepareTemporaryFor(path);
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw Error(path + ": cannot write");
    }
  }
  commitTemporary(tmp, path);
}

}  // namespace manylight
