#pragma once
// The sections of a baked file (docs/baked-format.md): byte writer and checked reader, each
// section written, all of them read. Internal to bake/: baked_file.cpp adds the header, the
// section table and the checksum around them.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "bake/baked_file.h"

namespace manylight::baked {

constexpr std::uint32_t tag(const char (&name)[5]) {
  return std::uint32_t(std::uint8_t(name[0])) | std::uint32_t(std::uint8_t(name[1])) << 8 |
         std::uint32_t(std::uint8_t(name[2])) << 16 | std::uint32_t(std::uint8_t(name[3])) << 24;
}
constexpr std::uint32_t kScene = tag("SCNE"), kMaterials = tag("MATL"), kTextures = tag("TEXR"),
                        kMeshes = tag("MESH"), kInstances = tag("INST"), kLights = tag("LGHT"),
                        kCameras = tag("CAMR"), kTrees = tag("TREE");

// Writes a section as a list of byte runs: its own, and views of the large arrays written
// (which must outlive it), so that a million lights' trees (hundreds of megabytes) go to
// the file without a copy.
class Writer {
 public:
  template <typename T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    tail().append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <typename T, typename Allocator>
  void array(const std::vector<T, Allocator>& v) {  // count, then the elements
    put(std::uint64_t(v.size()));
    if (v.empty()) return;
    const std::string_view bytes(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    if (bytes.size() >= kBorrowFrom) {
      runs_.push_back({std::string(), bytes});
    } else {
      tail().append(bytes);
    }
  }
  void string(const std::string& s) {
    put(std::uint64_t(s.size()));
    tail() += s;
  }
  // The runs, in order.
  std::vector<std::string_view> runs() const {
    std::vector<std::string_view> out;
    for (const Run& r : runs_) out.push_back(r.borrowed.data() ? r.borrowed : r.owned);
    return out;
  }
  std::size_t size() const {
    std::size_t n = 0;
    for (const Run& r : runs_) n += r.borrowed.data() ? r.borrowed.size() : r.owned.size();
    return n;
  }

 private:
  // Arrays of this many bytes or more are viewed, not copied.
  static constexpr std::size_t kBorrowFrom = std::size_t(1) << 16;
  struct Run {
    std::string owned;
    std::string_view borrowed;  // when set, the run
  };
  std::string& tail() {
    if (runs_.empty() || runs_.back().borrowed.data()) runs_.emplace_back();
    return runs_.back().owned;
  }
  std::vector<Run> runs_;
};

// Reads a section; every read is checked against what is left, before any allocation.
class Reader {
 public:
  Reader(std::string_view bytes, std::string where) : bytes_(bytes), where_(std::move(where)) {}

  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  template <typename T, typename Allocator = std::allocator<T>>
  std::vector<T, Allocator> array() {
    const std::uint64_t n = get<std::uint64_t>();
    if (n > (bytes_.size() - at_) / sizeof(T))
      fail("an array of " + std::to_string(n) + " runs past the section");
    std::vector<T, Allocator> v(n);
    if (n > 0)
      std::memcpy(v.data(), bytes_.data() + at_, n * sizeof(T));  // memcpy from/to null is UB
    at_ += n * sizeof(T);
    return v;
  }
  std::string string() {
    const std::vector<char> c = array<char>();
    return std::string(c.begin(), c.end());
  }
  std::uint32_t count(std::uint32_t most, const char* what) {
    const auto n = get<std::uint32_t>();
    if (n > most)
      fail(std::string(what) + ": " + std::to_string(n) + " is more than " + std::to_string(most));
    return n;
  }
  void end() {
    if (at_ != bytes_.size()) fail(std::to_string(bytes_.size() - at_) + " bytes left over");
  }
  [[noreturn]] void fail(const std::string& problem) const {
    throw BakeError(where_ + ": " + problem);
  }

 private:
  void need(std::size_t n) {
    if (n > bytes_.size() - at_) fail("ends early");
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
  std::string where_;
};

// glm vectors and matrices: tightly packed floats.
template <typename T>
void putFloats(Writer& w, const T& v) {
  w.put(v);
}

// A glm vector or matrix (or a float) whose every component must be finite.
template <typename T>
T getFinite(Reader& r, const char* what) {
  const T v = r.get<T>();
  float f[sizeof(T) / sizeof(float)];
  std::memcpy(f, &v, sizeof f);
  for (float x : f) {
    if (!std::isfinite(x)) r.fail(std::string(what) + " is not finite");
  }
  return v;
}

// The sections `baked` needs, in file order: (tag, bytes); they view `baked`'s arrays.
std::vector<std::pair<std::uint32_t, Writer>> writeSections(const BakedScene& baked);

// Reads the sections (tag → bytes) of the file at `path`. Throws BakeError
// "PATH: SECTION: problem".
BakedScene readSections(const std::map<std::uint32_t, std::string_view>& sections,
                        const std::string& path);

}  // namespace manylight::baked
