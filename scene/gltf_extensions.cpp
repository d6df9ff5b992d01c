#include "scene/gltf_extensions.h"

#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "base/error.h"

namespace manylight::gltf {
namespace {

// Extensions whose absence would change what we render; we implement these fully.
const std::set<std::string> kSupportedRequired = {
    "KHR_lights_punctual",     "KHR_mesh_quantization",
    "KHR_texture_transform",   "KHR_materials_emissive_strength",
    "KHR_materials_unlit",     "KHR_draco_mesh_compression",
    "EXT_meshopt_compression", "KHR_materials_pbrSpecularGlossiness"};
// Optional extensions used in part, so not listed as ignored: KHR_animation_pointer's
// channels on lights and on nodes move and change lights (scene/light_animation.h); its other
// pointers (materials, cameras, morph weights) are ignored. Required, it is refused.
const std::set<std::string> kUsedInPart = {"KHR_animation_pointer"};
// Required extensions refused with a reason of their own.
const std::map<std::string, std::string> kRefusedRequired = {
    {"KHR_texture_basisu", "Basis Universal (KTX2) textures have no decoder here"}};

}  // namespace

void checkVersion(const std::string& version, const std::string& minVersion,
                  const std::vector<std::string>& required) {
  auto major = [](const std::string& v) { return std::atoi(v.c_str()); };
  auto minor = [](const std::string& v) {
    const auto dot = v.find('.');
    return dot == std::string::npos ? 0 : std::atoi(v.c_str() + dot + 1);
  };
  if (major(version) != 2) {
    throw SceneError("asset.version '" + version + "' is not supported, expected 2.x");
  }
  if (!minVersion.empty() && (major(minVersion) != 2 || minor(minVersion) > 0)) {
    throw SceneError("asset.minVersion " + minVersion + " is not supported, expected 2.0");
  }
  for (const std::string& ext : required) {
    const auto refused = kRefusedRequired.find(ext);
    if (refused != kRefusedRequired.end())
      throw SceneError("required extension " + ext + " is not supported: " + refused->second);
    if (!kSupportedRequired.count(ext)) {
      throw SceneError("required extension " + ext + " is not supported");
    }
  }
}

// Called when tinygltf fails on a .gltf: refuses a file for an extension or version we lack
// (from the JSON's asset and extensionsRequired) rather than for the parse error it causes.
void checkRequirementsInJson(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  const nlohmann::json j = nlohmann::json::parse(f, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return;  // tinygltf reports the syntax error
  auto str = [](const nlohmann::json& o, const char* key) {
    const auto it = o.find(key);
    return it != o.end() && it->is_string() ? it->get<std::string>() : std::string();
  };
  const auto asset = j.find("asset");
  if (asset == j.end() || !asset->is_object()) return;
  std::vector<std::string> required;
  const auto req = j.find("extensionsRequired");
  if (req != j.end() && req->is_array()) {
    for (const auto& e : *req) {
      if (e.is_string()) required.push_back(e.get<std::string>());
    }
  }
  checkVersion(str(*asset, "version"), str(*asset, "minVersion"), required);
}

std::vector<std::string> ignoredExtensions(const std::vector<std::string>& used) {
  std::vector<std::string> out;
  for (const std::string& ext : used) {
    if (!kSupportedRequired.count(ext) && !kUsedInPart.count(ext)) out.push_back(ext);
  }
  return out;
}

}  // namespace manylight::gltf
