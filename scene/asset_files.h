#pragma once
// The only way the glTF loader reads files. A scene is untrusted input: its external URIs
// may name only regular files inside the scene's own folder. Absolute paths, `..` escapes
// (also through symbolic links) and URI schemes other than data: (which tinygltf decodes
// itself, without reading files) are refused, and all bytes read for one scene count
// against a limit before they are read.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace manylight {

// A file's bytes in memory, writable, with bytes readable past size() up to capacity()
// (zero as read; a resize leaves what was there): the file mapped copy-on-write (its pages shared
// with the page cache, neither zeroed nor copied; only pages written are copied), or a buffer of
// its own once it grows past its capacity.
class FileBytes {
 public:
  FileBytes() = default;
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  ~FileBytes() { release(); }

  unsigned char* data() { return data_; }
  const unsigned char* data() const { return data_; }
  std::size_t size() const { return size_; }
  std::size_t capacity() const { return capacity_; }
  // Up to capacity() in place; past it the bytes move to a buffer of their own.
  void resize(std::size_t size);
  void release();

 private:
  friend class AssetFiles;
  unsigned char* data_ = nullptr;
  std::size_t size_ = 0, capacity_ = 0;
  void* mapped_ = nullptr;  // the mapping (file and padding), when mapped
  std::size_t mappedBytes_ = 0;
  std::vector<unsigned char> owned_;  // else the bytes
};

class AssetFiles {
 public:
  // `scene`: the glTF/GLB file; `base`: the folder prefix tinygltf joins URIs to (its
  // GetBaseDir of `scene`); `maxBytes`: bytes this scene may read in all.
  AssetFiles(const std::string& scene, const std::string& base, std::uintmax_t maxBytes);

  // For tinygltf's FsCallbacks. `path` is the scene itself or base + "/" + URI. exists()
  // says yes to everything, so that read() gets to name the problem.
  bool exists(const std::string& path);
  bool read(std::vector<unsigned char>* out, std::string* err, const std::string& path);
  // read() into a mapping, leaving at least `padding` zero bytes readable past out->size()
  // (in its capacity), for parsers that read ahead (simdjson).
  bool read(FileBytes* out, std::string* err, const std::string& path, std::size_t padding);

  // The first refusal (outside the folder, not a regular file, over the byte limit) as a
  // one-line reason naming the URI; empty if none. Missing files are not refusals.
  const std::string& refusal() const { return refusal_; }
  // The first missing file ("URI 'x.png': no such file"); empty if none.
  const std::string& missing() const { return missing_; }

 private:
  // Why `path` may not be read, or "" (and its resolved location in *resolved).
  std::string check(const std::string& path, std::filesystem::path* resolved) const;
  // check() and the byte limit: the file's size, or false with *err set (and noted).
  bool admit(const std::string& path, std::string* err, std::filesystem::path* resolved,
             std::uintmax_t* size);

  std::string scene_, base_;
  std::filesystem::path root_;  // canonical scene folder
  std::uintmax_t bytesLeft_;
  std::uintmax_t maxBytes_;
  std::string refusal_, missing_;
};

}  // namespace manylight
