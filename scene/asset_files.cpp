#include "scene/asset_files.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <fstream>

namespace manylight {

namespace fs = std::filesystem;

AssetFiles::AssetFiles(const std::string& scene, const std::string& base, std::uintmax_t maxBytes)
    : scene_(scene), base_(base), bytesLeft_(maxBytes), maxBytes_(maxBytes) {
  std::error_code ec;
  root_ = fs::weakly_canonical(fs::absolute(fs::path(scene)).parent_path(), ec);
}

namespace {

// The scheme of a URI ("http" in "http://..."), or "" for a plain path.
std::string schemeOf(const std::string& uri) {
  if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return "";
  for (std::size_t i = 1; i < uri.size(); ++i) {
    const char c = uri[i];
    if (c == ':') return i > 1 ? uri.substr(0, i) : "";  // one letter: a drive, not a scheme
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return "";
  }
  return "";
}

}  // namespace

std::string AssetFiles::check(const std::string& path, fs::path* resolved) const {
  std::error_code ec;
  if (path == scene_) {
    *resolved = path;
    return "";
  }
  std::string uri = path;
  if (!base_.empty() && path.compare(0, base_.size(), base_) == 0) {
    uri = path.substr(base_.size());
    if (!uri.empty() && uri[0] == '/') uri.erase(0, 1);
  }
  const std::string quoted = "URI '" + uri + "'";
  const std::string scheme = schemeOf(uri);
  if (!scheme.empty())
    return quoted + ": scheme '" + scheme + "' is not allowed (only data: URIs and relative paths)";
  if (!uri.empty() && (uri[0] == '/' || uri[0] == '\\'))
    return quoted + ": absolute paths are not allowed";
  const fs::path relative = fs::path(uri).lexically_normal();
  if (relative.empty() || *relative.begin() == "..") return quoted + ": leaves the scene's folder";
  const fs::path target = fs::weakly_canonical(root_ / relative, ec);
  if (ec) return quoted + ": " + ec.message();
  const fs::path inside = target.lexically_relative(root_);
  if (inside.empty() || *inside.begin() == "..")
    return quoted + ": leads outside the scene's folder (through a link)";
  *resolved = target;
  return "";
}

bool AssetFiles::exists(const std::string& path) {
  // Every path "exists", so that tinygltf asks to read it and read() reports the reason
  // (refused, missing) in its own words.
  (void)path;
  return true;
}

bool AssetFiles::admit(const std::string& path, std::string* err, fs::path* resolved,
                       std::uintmax_t* size) {
  std::string reason = check(path, resolved);
  std::error_code ec;
  bool missing = false;
  if (reason.empty()) {
    const std::string what =
        path == scene_ ? std::string("scene")
                       : "URI '" + path.substr(base_.empty() ? 0 : base_.size() + 1) + "'";
    if (!fs::exists(*resolved, ec)) {
      reason = what + ": no such file";
      missing = true;
    } else if (!fs::is_regular_file(*resolved, ec)) {
      reason = what + ": not a regular file";
    }
  }
  if (reason.empty()) {
    *size = fs::file_size(*resolved, ec);
    if (ec) reason = resolved->string() + ": " + ec.message();
  }
  if (reason.empty() && *size > bytesLeft_) {
    reason = "the scene's files exceed the limit of " + std::to_string(maxBytes_) + " bytes";
  }
  if (reason.empty()) return true;
  // A missing file is the caller's to judge (tinygltf: an error for a buffer, a warning
  // for an image); anything refused is an error whatever asked for it.
  std::string& first = missing ? missing_ : refusal_;
  if (first.empty()) first = reason;
  *err = reason;
  return false;
}

bool AssetFiles::read(std::vector<unsigned char>* out, std::string* err, const std::string& path) {
  fs::path resolved;
  std::uintmax_t size = 0;
  if (!admit(path, err, &resolved, &size)) return false;
  std::ifstream f(resolved, std::ios::binary);
  out->assign(size, 0);
  if (size > 0 && !f.read(reinterpret_cast<char*>(out->data()), std::streamsize(size))) {
    *err = "cannot read";
    return false;
  }
  bytesLeft_ -= size;
  return true;
}

bool AssetFiles::read(FileBytes* out, std::string* err, const std::string& path,
                      std::size_t padding) {
  fs::path resolved;
  std::uintmax_t size = 0;
  if (!admit(path, err, &resolved, &size)) return false;
  out->release();
  // Anonymous zero pages first, the file's pages over their start: whatever the file's
  // size, the bytes past its end up to the padding are mapped and zero. Not populated: on a
  // writable private mapping that would copy every page, where reading faults map the page
  // cache's own (and only pages written are copied).
  const std::size_t page = std::size_t(sysconf(_SC_PAGESIZE));
  const std::size_t bytes = (std::size_t(size) + padding + page - 1) / page * page;
  void* base = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (base == MAP_FAILED) {
    *err = "cannot map " + std::to_string(bytes) + " bytes";
    return false;
  }
  out->mapped_ = base;
  out->mappedBytes_ = bytes;
  out->data_ = static_cast<unsigned char*>(base);
  out->capacity_ = bytes;
  if (size > 0) {
    const int fd = open(resolved.c_str(), O_RDONLY | O_CLOEXEC);
    void* file = fd < 0 ? MAP_FAILED
                        : mmap(base, std::size_t(size), PROT_READ | PROT_WRITE,
                               MAP_PRIVATE | MAP_FIXED, fd, 0);
    if (fd >= 0) close(fd);
    if (file == MAP_FAILED) {
      out->release();
      *err = "cannot read";
      return false;
    }
  }
  out->size_ = std::size_t(size);
  bytesLeft_ -= size;
  return true;
}

void FileBytes::resize(std::size_t size) {
  if (size > capacity_) {
    std::vector<unsigned char> grown(size);
    std::copy(data_, data_ + size_, grown.begin());
    release();
    owned_ = std::move(grown);
    data_ = owned_.data();
    capacity_ = owned_.size();
  }
  size_ = size;
}

void FileBytes::release() {
  if (mapped_) munmap(mapped_, mappedBytes_);
  mapped_ = nullptr;
  mappedBytes_ = 0;
  std::vector<unsigned char>().swap(owned_);
  data_ = nullptr;
  size_ = capacity_ = 0;
}

}  // namespace manylight
