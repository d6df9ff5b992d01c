#include "scene/gltf_parse.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string_view>

#include "scene/asset_files.h"
#include "scene/gltf_bulk.h"
#include "scene/gltf_meshopt.h"

namespace manylight::gltf {
namespace {

const char* const kDraco = "KHR_draco_mesh_compression";
const char* const kMeshopt = "EXT_meshopt_compression";
const char* const kPointer = "KHR_animation_pointer";
// What a placeholder buffer gets instead of no data: tinygltf refuses an empty data: URI.
const char* const kPlaceholderUri = "data:application/octet-stream;base64,AA==";

// What the JSON was amended by, to be undone in the model.
struct Amendments {
  std::vector<int> placeholders;
  struct HeldIndices {
    std::size_t mesh, primitive;
    int accessor;
  };
  std::vector<HeldIndices> held;
  std::size_t pointerChannels = 0;  // given node −1, which tinygltf also gives a target without one
};

bool uses(const nlohmann::json& j, const char* extension) {
  const auto used = j.find("extensionsUsed");
  return used != j.end() && used->is_array() &&
         std::find(used->begin(), used->end(), extension) != used->end();
}

// Placeholder buffers: no uri; in a GLB, not buffer 0 (the binary chunk's).
void givePlaceholdersData(nlohmann::json& j, bool binary, Amendments* out) {
  const auto buffers = j.find("buffers");
  if (buffers == j.end() || !buffers->is_array()) return;
  for (std::size_t i = binary ? 1 : 0; i < buffers->size(); ++i) {
    nlohmann::json& b = (*buffers)[i];
    if (!b.is_object() || b.contains("uri")) continue;
    b["uri"] = kPlaceholderUri;
    b["byteLength"] = 1;
    out->placeholders.push_back(int(i));
  }
}

// Draco primitives whose indices accessor has no bufferView.
void holdDracoIndices(nlohmann::json& j, Amendments* out) {
  const auto meshes = j.find("meshes");
  const auto accessors = j.find("accessors");
  if (meshes == j.end() || !meshes->is_array() || accessors == j.end() || !accessors->is_array())
    return;
  for (std::size_t m = 0; m < meshes->size(); ++m) {
    nlohmann::json& mesh = (*meshes)[m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
      continue;
    nlohmann::json& primitives = mesh["primitives"];
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      nlohmann::json& prim = primitives[p];
      if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object() ||
          !prim["extensions"].contains(kDraco) || !prim.contains("indices") ||
          !prim["indices"].is_number_integer()) {
        continue;
      }
      const std::int64_t a = prim["indices"].get<std::int64_t>();
      if (a < 0 || std::size_t(a) >= accessors->size()) continue;  // tinygltf refuses it
      const nlohmann::json& accessor = (*accessors)[std::size_t(a)];
      if (!accessor.is_object() || accessor.contains("bufferView")) continue;
      out->held.push_back({m, p, int(a)});
      prim.erase("indices");
    }
  }
}

// Animation channels whose target has no node (KHR_animation_pointer's): tinygltf drops
// them, and with them the channel numbering; they get node −1.
void givePointerChannelsANode(nlohmann::json& j, Amendments* out) {
  const auto animations = j.find("animations");
  if (animations == j.end() || !animations->is_array()) return;
  for (nlohmann::json& animation : *animations) {
    if (!animation.is_object() || !animation.contains("channels") ||
        !animation["channels"].is_array())
      continue;
    for (nlohmann::json& channel : animation["channels"]) {
      if (!channel.is_object() || !channel.contains("target")) continue;
      nlohmann::json& target = channel["target"];
      if (!target.is_object() || target.contains("node")) continue;
      target["node"] = -1;
      ++out->pointerChannels;
    }
  }
}

// The JSON amended as the header says; "" when nothing changes (also for JSON that tinygltf
// will refuse for itself).
std::string amendedJson(std::string_view json, bool binary, Amendments* out) {
  if (json.find(kDraco) == std::string_view::npos &&
      json.find(kMeshopt) == std::string_view::npos &&
      json.find(kPointer) == std::string_view::npos)
    return "";
  nlohmann::json j = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  if (j.is_discarded() || !j.is_object()) return "";
  if (uses(j, kMeshopt)) givePlaceholdersData(j, binary, out);
  if (uses(j, kDraco)) holdDracoIndices(j, out);
  if (uses(j, kPointer)) givePointerChannelsANode(j, out);
  const bool same = out->placeholders.empty() && out->held.empty() && out->pointerChannels == 0;
  return same ? "" : j.dump();
}

std::uint32_t word(const unsigned char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

constexpr std::size_t kGlbHeader = 20;  // magic, version, length; chunk length, chunk type

// The JSON chunk of a GLB, or an empty view when the header is not one to read (tinygltf
// then reports the faults).
std::string_view glbJson(const FileBytes& glb) {
  if (glb.size() < kGlbHeader || std::memcmp(glb.data() + 16, "JSON", 4) != 0) return {};
  const std::size_t jsonLength = word(glb.data() + 12);
  if (jsonLength > glb.size() - kGlbHeader) return {};
  return {reinterpret_cast<const char*>(glb.data() + kGlbHeader), jsonLength};
}

// Replaces the JSON chunk of `glb` (as glbJson found it) by `json`, in place: no copy of the
// binary chunk beside the original when the new JSON is not longer.
void replaceGlbJson(FileBytes& glb, std::string json) {
  const std::size_t oldLength = word(glb.data() + 12);
  json.resize((json.size() + 3) / 4 * 4, ' ');
  const std::size_t rest = glb.size() - kGlbHeader - oldLength;
  const std::size_t newSize = kGlbHeader + json.size() + rest;
  if (json.size() > oldLength) glb.resize(newSize);
  unsigned char* chunk = glb.data() + kGlbHeader;
  std::memmove(chunk + json.size(), chunk + oldLength, rest);
  std::memcpy(chunk, json.data(), json.size());
  glb.resize(newSize);
  // The header's total length changes by as much as the chunk, so that a total that was
  // wrong stays wrong by as much, for tinygltf to refuse.
  const std::uint32_t total =
      word(glb.data() + 8) - std::uint32_t(oldLength) + std::uint32_t(json.size());
  const std::uint32_t length = std::uint32_t(json.size());
  std::memcpy(glb.data() + 8, &total, 4);
  std::memcpy(glb.data() + 12, &length, 4);
}

// Splits the nodes and lights out of the file's JSON (scene/gltf_bulk.h) into *bulk, and
// leaves the rest for tinygltf: in `bytes` for a GLB, in *json for a .gltf (`bytes` then
// freed). False when the JSON could not be read; tinygltf then gets the file as it is.
bool splitFile(FileBytes& bytes, bool binary, std::string* json, BulkArrays* bulk,
               std::string* syntaxError) {
  const std::string_view text =
      binary ? glbJson(bytes)
             : std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (text.empty()) return false;
  const std::size_t offset = std::size_t(text.data() - reinterpret_cast<const char*>(bytes.data()));
  SplitJson split = splitJson(text, bytes.capacity() - offset);
  if (!split.parsed) {
    *syntaxError = split.syntaxError;
    return false;
  }
  *bulk = std::move(split.bulk);
  if (binary) {
    replaceGlbJson(bytes, std::move(split.rest));
  } else {
    *json = std::move(split.rest);
    bytes.release();
  }
  return true;
}

}  // namespace

bool parseGltfFile(tinygltf::TinyGLTF& parser, tinygltf::Model* model, BulkArrays* bulk,
                   std::string* err, std::string* warn, const std::string& path,
                   const std::string& base, bool binary, AssetFiles& files,
                   std::uintmax_t maxDecodedBytes) {
  FileBytes bytes;
  std::string readError;
  if (!files.read(&bytes, &readError, path, kJsonPadding)) {
    *err = "Failed to read file: " + path + ": " + readError;
    return false;
  }
  if (!binary && bytes.size() == 0) {
    *err = "Empty file.";
    return false;
  }
  std::string json, syntaxError;
  const bool split = splitFile(bytes, binary, &json, bulk, &syntaxError);
  if (!binary && !split) json.assign(bytes.data(), bytes.data() + bytes.size());
  Amendments amendments;
  bool ok = false;
  if (binary) {
    const std::string_view chunk = glbJson(bytes);
    std::string amended = chunk.empty() ? "" : amendedJson(chunk, true, &amendments);
    if (!amended.empty()) replaceGlbJson(bytes, std::move(amended));
    ok = parser.LoadBinaryFromMemory(model, err, warn, bytes.data(),
                                     static_cast<unsigned int>(bytes.size()), base);
  } else {
    std::string amended = amendedJson(json, false, &amendments);
    if (!amended.empty()) json = std::move(amended);
    ok = parser.LoadASCIIFromString(model, err, warn, json.data(),
                                    static_cast<unsigned int>(json.size()), base);
  }
  if (!ok) return false;
  if (!split) {
    // tinygltf read what simdjson could not: one reader for nodes and lights, so refused.
    *err = "not a valid glTF file: " + (syntaxError.empty() ? "no JSON chunk" : syntaxError);
    return false;
  }
  for (const Amendments::HeldIndices& h : amendments.held) {
    if (h.mesh < model->meshes.size() && h.primitive < model->meshes[h.mesh].primitives.size())
      model->meshes[h.mesh].primitives[h.primitive].indices = h.accessor;
  }
  decodeMeshoptViews(*model, amendments.placeholders, maxDecodedBytes);
  return true;
}

}  // namespace manylight::gltf
