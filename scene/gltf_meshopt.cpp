#include "scene/gltf_meshopt.h"

#include <meshoptimizer.h>
#include <tiny_gltf.h>

#include <algorithm>

#include "base/error.h"

namespace manylight::gltf {
namespace {

const char* const kExtension = "EXT_meshopt_compression";

std::string str(std::uint64_t n) { return std::to_string(n); }

// One view's extension object, read and checked.
struct CompressedView {
  int buffer = -1;
  std::size_t byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
  std::string mode, filter = "NONE";
};

// A required or optional non-negative integer of `ext`; throws naming `key`.
std::size_t field(const tinygltf::Value& ext, const char* key, bool required,
                  const std::string& where) {
  if (!ext.Has(key)) {
    if (required) throw SceneError(where + ": " + key + " is missing");
    return 0;
  }
  const tinygltf::Value& v = ext.Get(key);
  if (!v.IsInt() || v.Get<int>() < 0)
    throw SceneError(where + ": " + key + " is not a non-negative integer");
  return std::size_t(v.Get<int>());
}

std::string text(const tinygltf::Value& ext, const char* key, const std::string& fallback,
                 const std::string& where) {
  if (!ext.Has(key)) {
    if (fallback.empty()) throw SceneError(where + ": " + key + " is missing");
    return fallback;
  }
  if (!ext.Get(key).IsString()) throw SceneError(where + ": " + key + " is not a string");
  return ext.Get(key).Get<std::string>();
}

// The rules of the extension's specification, in its words where it has them.
void checkLayout(const CompressedView& c, const tinygltf::BufferView& view,
                 const std::string& where) {
  const std::string& m = c.mode;
  const std::string& f = c.filter;
  if (m != "ATTRIBUTES" && m != "TRIANGLES" && m != "INDICES")
    throw SceneError(where + ": unknown mode '" + m + "'");
  if (f != "NONE" && f != "OCTAHEDRAL" && f != "QUATERNION" && f != "EXPONENTIAL")
    throw SceneError(where + ": unknown filter '" + f + "'");
  const std::size_t s = c.byteStride;
  const bool attributes = m == "ATTRIBUTES";
  std::string problem;
  if (view.byteStride != 0 && view.byteStride != s)
    problem = "byteStride " + str(s) + " differs from the bufferView's " + str(view.byteStride);
  else if (s == 0 || view.byteLength / s != c.count || view.byteLength % s != 0)
    problem = "count " + str(c.count) + " times byteStride " + str(s) +
              " is not the bufferView's byteLength " + str(view.byteLength);
  else if (attributes && (s % 4 != 0 || s > 256))
    problem = "ATTRIBUTES byteStride " + str(s) + " is not a multiple of 4 up to 256";
  else if (m == "TRIANGLES" && c.count % 3 != 0)
    problem = "TRIANGLES count " + str(c.count) + " is not a multiple of 3";
  else if (!attributes && s != 2 && s != 4)
    problem = m + " byteStride " + str(s) + " is not 2 or 4";
  else if (!attributes && f != "NONE")
    problem = m + " takes no filter, got " + f;
  else if ((f == "OCTAHEDRAL" && s != 4 && s != 8) || (f == "QUATERNION" && s != 8))
    problem = f + " byteStride " + str(s) + " is not " + (f == "QUATERNION" ? "8" : "4 or 8");
  if (!problem.empty()) throw SceneError(where + ": " + problem);
}

CompressedView readView(const tinygltf::Model& model, const tinygltf::BufferView& view,
                        const std::vector<int>& placeholders, const std::string& where) {
  const tinygltf::Value& ext = view.extensions.at(kExtension);
  if (!ext.IsObject()) throw SceneError(where + ": the extension is not an object");
  CompressedView c;
  c.buffer = int(field(ext, "buffer", true, where));
  c.byteOffset = field(ext, "byteOffset", false, where);
  c.byteLength = field(ext, "byteLength", true, where);
  c.byteStride = field(ext, "byteStride", true, where);
  c.count = field(ext, "count", true, where);
  c.mode = text(ext, "mode", "", where);
  c.filter = text(ext, "filter", "NONE", where);
  if (std::size_t(c.buffer) >= model.buffers.size())
    throw SceneError(where + ": buffer " + str(c.buffer) + " does not exist");
  if (std::find(placeholders.begin(), placeholders.end(), c.buffer) != placeholders.end())
    throw SceneError(where + ": buffer " + str(c.buffer) + " is a placeholder without data");
  const std::size_t size = model.buffers[std::size_t(c.buffer)].data.size();
  if (c.byteOffset > size || c.byteLength > size - c.byteOffset) {
    throw SceneError(where + ": bytes " + str(c.byteOffset) + ".." +
                     str(c.byteOffset + c.byteLength) + " lie beyond buffer " + str(c.buffer) +
                     "'s " + str(size));
  }
  checkLayout(c, view, where);
  return c;
}

// Decodes `c` into `out` (count·byteStride bytes). Returns meshoptimizer's error code.
int decode(const CompressedView& c, const unsigned char* in, unsigned char* out) {
  if (c.mode == "TRIANGLES")
    return meshopt_decodeIndexBuffer(out, c.count, c.byteStride, in, c.byteLength);
  if (c.mode == "INDICES")
    return meshopt_decodeIndexSequence(out, c.count, c.byteStride, in, c.byteLength);
  const int rc = meshopt_decodeVertexBuffer(out, c.count, c.byteStride, in, c.byteLength);
  if (rc != 0) return rc;
  if (c.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out, c.count, c.byteStride);
  if (c.filter == "QUATERNION") meshopt_decodeFilterQuat(out, c.count, c.byteStride);
  if (c.filter == "EXPONENTIAL") meshopt_decodeFilterExp(out, c.count, c.byteStride);
  return 0;
}

}  // namespace

void decodeMeshoptViews(tinygltf::Model& model, const std::vector<int>& placeholders,
                        std::uintmax_t maxBytes) {
  std::vector<std::pair<std::size_t, CompressedView>> views;
  std::uintmax_t total = 0;
  for (std::size_t i = 0; i < model.bufferViews.size(); ++i) {
    const tinygltf::BufferView& view = model.bufferViews[i];
    if (!view.extensions.count(kExtension)) continue;
    const std::string where = "bufferView " + str(i) + ": " + kExtension;
    views.emplace_back(i, readView(model, view, placeholders, where));
    total += (view.byteLength + 15) / 16 * 16;  // each view starts 16-byte aligned
    if (total > maxBytes) {
      throw SceneError(where + ": the decoded views exceed the limit of " + str(maxBytes) +
                       " bytes (--max-file-bytes)");
    }
  }
  if (!views.empty()) {
    tinygltf::Buffer decoded;
    decoded.data.resize(std::size_t(total));
    std::size_t offset = 0;
    const int index = int(model.buffers.size());
    for (const auto& [i, c] : views) {
      const unsigned char* in = model.buffers[std::size_t(c.buffer)].data.data() + c.byteOffset;
      const int rc = decode(c, in, decoded.data.data() + offset);
      if (rc != 0) {
        throw SceneError("bufferView " + str(i) + ": " + kExtension + ": the " + c.mode +
                         " data cannot be decoded (meshoptimizer error " + std::to_string(rc) +
                         ")");
      }
      tinygltf::BufferView& view = model.bufferViews[i];
      view.buffer = index;
      view.byteOffset = offset;
      offset += (view.byteLength + 15) / 16 * 16;
    }
    model.buffers.push_back(std::move(decoded));
  }
  for (std::size_t i = 0; i < model.bufferViews.size(); ++i) {
    const int b = model.bufferViews[i].buffer;
    if (std::find(placeholders.begin(), placeholders.end(), b) != placeholders.end()) {
      throw SceneError("bufferView " + str(i) + ": buffer " + str(b) +
                       " is a placeholder without data (" + kExtension +
                       "), and the view is not compressed");
    }
  }
  for (int b : placeholders) model.buffers[std::size_t(b)].data.clear();
}

}  // namespace manylight::gltf
