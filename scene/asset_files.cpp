#include "scene/asset_files.h"

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

bool AssetFiles::read(std::vector<unsigned char>* out, std::string* err, const std::string& path) {
  return read(out, err, path, 0);
}

bool AssetFiles::read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                      std::size_t padding) {
  fs::path resolved;
  std::string reason = check(path, &resolved);
  std::error_code ec;
  bool missing = false;
  if (reason.empty()) {
    const std::string what =
        path == scene_ ? std::string("scene")
                       : "URI '" + path.substr(base_.empty() ? 0 : base_.size() + 1) + "'";
    if (!fs::exists(resolved, ec)) {
      reason = what + ": no such file";
      missing = true;
    } else if (!fs::is_regular_file(resolved, ec)) {
      reason = what + ": not a regular file";
    }
  }
  std::uintmax_t size = 0;
  if (reason.empty()) {
    size = fs::file_size(resolved, ec);
    if (ec) reason = resolved.string() + ": " + ec.message();
  }
  if (reason.empty() && size > bytesLeft_) {
    reason = "the scene's files exceed the limit of " + std::to_string(maxBytes_) + " bytes";
  }
  if (!reason.empty()) {
    // A missing file is the caller's to judge (tinygltf: an error for a buffer, a warning
    // for an image); anything refused is an error whatever asked for it.
    std::string& first = missing ? missing_ : refusal_;
    if (first.empty()) first = reason;
    *err = reason;
    return false;
  }
  std::ifstream f(resolved, std::ios::binary);
  out->clear();
  out->resize(size + padding);
  if (size > 0 && !f.read(reinterpret_cast<char*>(out->data()), std::streamsize(size))) {
    *err = "cannot read";
    return false;
  }
  out->resize(size);  // keeps the capacity, and the zero padding in it
  bytesLeft_ -= size;
  return true;
}

}  // namespace manylight
