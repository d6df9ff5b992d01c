#include "bake/baked_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <string_view>

#include "bake/baked_sections.h"
#include "base/output_file.h"
#include "base/parallel.h"

namespace manylight {
namespace {

bool littleEndian() {
  const std::uint32_t one = 1;
  std::uint8_t first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

// A file mapped read-only: a large baked file is read straight from the page cache, without
// allocating and clearing a copy of it, which would cost a large share of the load.
class MappedFile {
 public:
  MappedFile(const std::string& path, std::uint64_t maxBytes) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) throw BakeError(path + ": cannot open: " + std::strerror(errno));
    struct stat st {};
    std::string problem;
    if (::fstat(fd, &st) != 0) {
      problem = std::string("cannot read: ") + std::strerror(errno);
    } else if (!S_ISREG(st.st_mode)) {
      problem = "not a regular file";
    } else if (std::uint64_t(st.st_size) > maxBytes) {
      problem = std::to_string(st.st_size) + " bytes exceed the limit of " +
                std::to_string(maxBytes) + " bytes";
    } else if (st.st_size > 0) {
      void* p = ::mmap(nullptr, std::size_t(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
      if (p == MAP_FAILED) {
        problem = std::string("cannot map: ") + std::strerror(errno);
      } else {
        data_ = static_cast<const char*>(p);
        size_ = std::size_t(st.st_size);
        ::madvise(p, size_, MADV_SEQUENTIAL);
      }
    }
    ::close(fd);
    if (!problem.empty()) throw BakeError(path + ": " + problem);
  }
  ~MappedFile() {
    if (data_) ::munmap(const_cast<char*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  std::string_view bytes() const { return {data_ ? data_ : "", size_}; }

 private:
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace

namespace {

// bakedChecksum over pieces given in turn: the same value as over their concatenation.
class Checksum {
 public:
  void add(std::string_view bytes) {
    while (!bytes.empty() && pending_ > 0) {  // complete the word begun by the last piece
      word_[pending_++] = bytes[0];
      bytes.remove_prefix(1);
      if (pending_ == 8) fold(word_), pending_ = 0;
    }
    const std::size_t words = bytes.size() / 8;
    for (std::size_t i = 0; i < words; ++i) fold(bytes.data() + 8 * i);
    for (std::size_t i = words * 8; i < bytes.size(); ++i) word_[pending_++] = bytes[i];
  }
  std::uint64_t value() const {
    std::uint64_t h = h_;
    for (std::size_t i = 0; i < pending_; ++i) h = (h ^ std::uint8_t(word_[i])) * kPrime;
    return h;
  }

 private:
  static constexpr std::uint64_t kPrime = 0x100000001b3ull;
  void fold(const char* p) {
    std::uint64_t w;
    std::memcpy(&w, p, 8);
    h_ = (h_ ^ w) * kPrime;
  }
  std::uint64_t h_ = 0xcbf29ce484222325ull;
  char word_[8] = {};
  std::size_t pending_ = 0;
};

}  // namespace

// FNV-1a, 64 bits, taken over 64-bit little-endian words (8× fewer multiplications than
// byte by byte), then the last size % 8 bytes one by one.
std::uint64_t bakedChecksum(std::string_view bytes) {
  Checksum sum;
  sum.add(bytes);
  return sum.value();
}

BakedScene bakeScene(Scene scene, const TreeOptions& trees, const OctreeOptions& octree) {
  BakedScene b;
  b.trees = trees;
  b.hasTrees = !scene.lights.empty();
  b.hasOctree = std::any_of(scene.lights.begin(), scene.lights.end(),
                            [](const Light& l) { return isRanged(l); });
  // The octree is built while the trees are: each leaves cores idle at times. A fault of
  // the trees is reported before one of the octree's, as if they were built in turn.
  std::future<LinklessOctree> built;
  if (b.hasOctree) {
    built = std::async(kThreadOrDeferred, [&] {
      return packLinklessOctree(buildLightOctree(scene.lights, scene, octree));
    });
  }
  if (b.hasTrees) b.packed = packLightTrees(buildLightTrees(scene.lights, trees), trees.nodeColour);
  if (b.hasOctree) b.octree = built.get();
  b.scene = std::move(scene);
  return b;
}

void writeBakedScene(const std::string& path, const BakedScene& baked) {
  if (!littleEndian())
    throw BakeError(path + ": baked files are little-endian; this machine is not");
  const auto sections = baked::writeSections(baked);
  // Header, section table (count; tag, reserved, offset, size each), then the sections.
  baked::Writer table;
  table.put(std::uint32_t(sections.size()));
  std::uint64_t offset = kBakedHeaderBytes + 4 + sections.size() * 24;
  for (const auto& [tag, body] : sections) {
    const std::uint64_t size = body.size();
    table.put(tag), table.put(std::uint32_t(0)), table.put(offset), table.put(size);
    offset += size;
  }
  // The sections are written run by run (their large arrays are views of `baked`'s), never
  // gathered into one buffer: at a million lights they are a few hundred megabytes.
  std::vector<std::string_view> runs = table.runs();
  for (const auto& section : sections) {
    for (const std::string_view r : section.second.runs()) runs.push_back(r);
  }
  Checksum sum;
  for (const std::string_view r : runs) sum.add(r);
  char header[kBakedHeaderBytes] = {};
  std::memcpy(header, kBakedMagic, 8);
  const std::uint32_t version = kBakedFormatVersion, flags = 0;
  const std::uint64_t size = offset, checksum = sum.value();
  std::memcpy(header + 8, &version, 4);
  std::memcpy(header + 12, &flags, 4);
  std::memcpy(header + 16, &size, 8);
  std::memcpy(header + 24, &checksum, 8);
  const std::filesystem::path tmp = prepareTemporaryFor(path);
  {
    std::ofstream out(tmp, std::ios::binary);
    out.write(header, kBakedHeaderBytes);
    for (const std::string_view r : runs) out.write(r.data(), std::streamsize(r.size()));
    out.close();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw Error(path + ": cannot write");
    }
  }
  commitTemporary(tmp, path);
}

bool isBakedFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;  // a FIFO would block the read
  std::ifstream f(path, std::ios::binary);
  char magic[8] = {};
  f.read(magic, 8);
  return f.gcount() == 8 && std::memcmp(magic, kBakedMagic, 8) == 0;
}

BakedScene readBakedScene(const std::string& path, std::uint64_t maxBytes) {
  const MappedFile file(path, maxBytes);
  const std::string_view bytes = file.bytes();
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kBakedMagic, 8) != 0) {
    throw BakeError(path + ": not a manylight baked file (no MLBAKE magic)");
  }
  if (bytes.size() < kBakedHeaderBytes)
    throw BakeError(path + ": truncated: " + std::to_string(bytes.size()) + " bytes");
  std::uint32_t version, flags;
  std::uint64_t size, sum;
  std::memcpy(&version, &bytes[8], 4);
  std::memcpy(&flags, &bytes[12], 4);
  std::memcpy(&size, &bytes[16], 8);
  std::memcpy(&sum, &bytes[24], 8);
  if (version != kBakedFormatVersion) {
    throw BakeError(path + ": baked format version " + std::to_string(version) + ", expected " +
                    std::to_string(kBakedFormatVersion) + "; bake the scene again");
  }
  if (!littleEndian())
    throw BakeError(path + ": baked files are little-endian; this machine is not");
  if (size != bytes.size()) {
    throw BakeError(path + ": truncated or extended: " + std::to_string(bytes.size()) +
                    " bytes, the header says " + std::to_string(size));
  }
  if (flags != 0) throw BakeError(path + ": unknown flags " + std::to_string(flags));
  if (bakedChecksum(bytes.substr(kBakedHeaderBytes)) != sum)
    throw BakeError(path + ": checksum mismatch: the file is damaged");

  baked::Reader table(bytes.substr(kBakedHeaderBytes), path + ": section table");
  const std::uint32_t count = table.count(64, "sections");
  std::map<std::uint32_t, std::string_view> sections;
  for (std::uint32_t i = 0; i < count; ++i) {
    const auto t = table.get<std::uint32_t>();
    table.get<std::uint32_t>();
    const auto offset = table.get<std::uint64_t>(), length = table.get<std::uint64_t>();
    if (offset < kBakedHeaderBytes || offset > bytes.size() || length > bytes.size() - offset) {
      table.fail("a section lies outside the file");
    }
    if (!sections.emplace(t, bytes.substr(offset, length)).second)
      table.fail("a section appears twice");
  }
  return baked::readSections(sections, path);
}

}  // namespace manylight
