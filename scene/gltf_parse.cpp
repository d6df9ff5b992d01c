#include "scene/gltf_parse.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string_view>

#include "scene/asset_files.h"
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

std::string wordBytes(std::uint32_t v) { return std::string(reinterpret_cast<char*>(&v), 4); }

// The GLB `glb` with its JSON chunk amended; empty when nothing changes, or when the header
// is not one to rewrite (tinygltf then reports the original's faults).
std::vector<unsigned char> amendedGlb(const std::vector<unsigned char>& glb, Amendments* out) {
  constexpr std::size_t kHeader = 20;  // magic, version, length; chunk length, chunk type
  if (glb.size() < kHeader || std::memcmp(glb.data() + 16, "JSON", 4) != 0) return {};
  const std::size_t jsonLength = word(glb.data() + 12);
  if (jsonLength > glb.size() - kHeader) return {};
  const char* json = reinterpret_cast<const char*>(glb.data() + kHeader);
  std::string amended = amendedJson({json, jsonLength}, true, out);
  if (amended.empty()) return {};
  amended.resize((amended.size() + 3) / 4 * 4, ' ');
  const std::size_t rest = glb.size() - kHeader - jsonLength;
  const std::string header = std::string(reinterpret_cast<const char*>(glb.data()), 8) +
                             wordBytes(std::uint32_t(kHeader + amended.size() + rest)) +
                             wordBytes(std::uint32_t(amended.size())) + "JSON";
  std::vector<unsigned char> bytes(header.begin(), header.end());
  bytes.insert(bytes.end(), amended.begin(), amended.end());
  bytes.insert(bytes.end(), glb.begin() + std::ptrdiff_t(kHeader + jsonLength), glb.end());
  return bytes;
}

}  // namespace

bool parseGltfFile(tinygltf::TinyGLTF& parser, tinygltf::Model* model, std::string* err,
                   std::string* warn, const std::string& path, const std::string& base, bool binary,
                   AssetFiles& files, std::uintmax_t maxDecodedBytes) {
  std::vector<unsigned char> bytes;
  std::string readError;
  if (!files.read(&bytes, &readError, path)) {
    *err = "Failed to read file: " + path + ": " + readError;
    return false;
  }
  Amendments amendments;
  bool ok = false;
  if (binary) {
    std::vector<unsigned char> amended = amendedGlb(bytes, &amendments);
    if (!amended.empty()) bytes = std::move(amended);
    ok = parser.LoadBinaryFromMemory(model, err, warn, bytes.data(),
                                     static_cast<unsigned int>(bytes.size()), base);
  } else if (bytes.empty()) {
    *err = "Empty file.";
  } else {
    std::string json(bytes.begin(), bytes.end());
    std::string amended = amendedJson(json, false, &amendments);
    if (!amended.empty()) json = std::move(amended);
    ok = parser.LoadASCIIFromString(model, err, warn, json.data(),
                                    static_cast<unsigned int>(json.size()), base);
  }
  if (!ok) return false;
  for (const Amendments::HeldIndices& h : amendments.held) {
    if (h.mesh < model->meshes.size() && h.primitive < model->meshes[h.mesh].primitives.size())
      model->meshes[h.mesh].primitives[h.primitive].indices = h.accessor;
  }
  decodeMeshoptViews(*model, amendments.placeholders, maxDecodedBytes);
  return true;
}

}  // namespace manylight::gltf
