#pragma once
// Which glTF versions and extensions manylight accepts, refuses, or ignores. Internal to
// scene/.
#include <string>
#include <vector>

namespace manylight::gltf {

// Throws SceneError when asset.version is not 2.x, asset.minVersion is above 2.0, or an
// extension in `required` is not implemented (naming it, and why where there is a reason).
void checkVersion(const std::string& version, const std::string& minVersion,
                  const std::vector<std::string>& required);

// Called when tinygltf fails on a .gltf: refuses a file for an extension or version we lack
// (from the JSON's asset and extensionsRequired) rather than for the parse error it causes.
// Throws SceneError; returns when the requirements are met or cannot be read.
void checkRequirementsInJson(const std::string& path);

// The extensions of `used` that change nothing here: optional appearance extensions (sheen,
// transmission, …) that the glTF spec lets a renderer ignore, and vendors' own.
std::vector<std::string> ignoredExtensions(const std::vector<std::string>& used);

}  // namespace manylight::gltf
