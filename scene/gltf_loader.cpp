#include "scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "base/error.h"
#include "scene/asset_files.h"
#include "scene/gltf_accessors.h"
#include "scene/gltf_animation.h"
#include "scene/gltf_bulk.h"
#include "scene/gltf_convert.h"
#include "scene/gltf_extensions.h"
#include "scene/gltf_parse.h"
#include "scene/image_decode.h"
#include "scene/scene_walker.h"

namespace manylight {
namespace {

std::string oneLine(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  for (char& c : s) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return s;
}

// What is wrong with bufferView `i`: it names no buffer or does not lie within it; "" if
// nothing.
std::string bufferViewProblem(const tinygltf::Model& model, int i) {
  const tinygltf::BufferView& view = model.bufferViews[std::size_t(i)];
  if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size())
    return "bufferView " + std::to_string(i) + ": buffer " + std::to_string(view.buffer) +
           " does not exist";
  const std::size_t size = model.buffers[std::size_t(view.buffer)].data.size();
  if (view.byteOffset > size || view.byteLength > size - view.byteOffset)
    return "bufferView " + std::to_string(i) + ": bytes " + std::to_string(view.byteOffset) + ".." +
           std::to_string(view.byteOffset + view.byteLength) + " lie beyond its buffer's " +
           std::to_string(size);
  return "";
}

// What the image callback needs: the limits, and the model being parsed, whose buffers and
// views are read before its images.
struct ImageLoading {
  const LoadOptions* options;
  const tinygltf::Model* model;
};

bool decodeImageForTinygltf(tinygltf::Image* image, const int index, std::string* err, std::string*,
                            int, int, const unsigned char* bytes, int size, void* user) {
  const ImageLoading& loading = *static_cast<const ImageLoading*>(user);
  const LoadOptions& options = *loading.options;
  try {
    // tinygltf hands over a view's bytes without checking that they lie in its buffer.
    if (image->bufferView >= 0) {
      const std::string problem = bufferViewProblem(*loading.model, image->bufferView);
      if (!problem.empty()) throw SceneError("image " + std::to_string(index) + ": " + problem);
    }
    DecodedImage d = decodeImage(bytes, size_t(std::max(size, 0)), "image " + std::to_string(index),
                                 options.maxTextureDimension, options.maxTexturePixels);
    image->width = d.width;
    image->height = d.height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image = std::move(d.rgba);
    return true;
  } catch (const SceneError& e) {
    if (err) *err += e.what();
    return false;
  }
}

// Throws when the meshes hold more triangles than `limit`, from the accessor counts alone.
void checkTriangleCount(const tinygltf::Model& model, std::int64_t limit) {
  std::int64_t triangles = 0;
  for (const tinygltf::Mesh& mesh : model.meshes) {
    for (const tinygltf::Primitive& p : mesh.primitives) {
      int accessor = p.indices;
      if (accessor < 0) {
        const auto it = p.attributes.find("POSITION");
        accessor = it == p.attributes.end() ? -1 : it->second;
      }
      if (accessor < 0 || accessor >= int(model.accessors.size())) continue;
      triangles +=
          gltf::triangleCount(gltf::primitiveMode(p), (long long)model.accessors[accessor].count);
    }
  }
  if (triangles > limit) {
    throw SceneError(std::to_string(triangles) + " triangles exceed the limit of " +
                     std::to_string(limit));
  }
}

// Whole-file checks, for the parts the walk may never reach: the node graph is a forest
// (no cycles, no node with two parents), every buffer view lies inside its buffer, and every
// light is valid. A file that breaks them is invalid glTF, used or not.
void checkStructure(const tinygltf::Model& model, const gltf::BulkArrays& bulk,
                    const gltf::Converter& convert) {
  const int nodes = int(bulk.nodes.size());
  std::vector<int> parent(std::size_t(nodes), -1);
  for (int n = 0; n < nodes; ++n) {
    const gltf::NodeRecord& node = bulk.nodes[std::size_t(n)];
    for (const std::int32_t* child = bulk.childrenBegin(node); child != bulk.childrenEnd(node);
         ++child) {
      const int c = *child;
      if (c < 0 || c >= nodes)
        throw SceneError("node " + std::to_string(n) + ": child " + std::to_string(c) +
                         " does not exist");
      if (parent[c] >= 0) {
        throw SceneError("node " + std::to_string(c) + " has two parents (nodes " +
                         std::to_string(parent[c]) + " and " + std::to_string(n) + ")");
      }
      parent[c] = n;
    }
  }
  // With one parent each, a node is in a cycle exactly when climbing never ends at a root.
  std::vector<char> state(std::size_t(nodes), 0);  // 0 unknown, 1 climbing, 2 reaches a root
  std::vector<int> climb;
  for (int n = 0; n < nodes; ++n) {
    climb.clear();
    int v = n;
    while (v >= 0 && state[v] == 0) {
      state[v] = 1;
      climb.push_back(v);
      v = parent[v];
    }
    if (v >= 0 && state[v] == 1)
      throw SceneError("node " + std::to_string(v) + " is part of a cycle");
    for (int c : climb) state[c] = 2;
  }
  for (std::size_t i = 0; i < model.bufferViews.size(); ++i) {
    const std::string problem = bufferViewProblem(model, int(i));
    if (!problem.empty()) throw SceneError(problem);
  }
  for (std::size_t i = 0; i < bulk.lights.size(); ++i) convert.light(int(i), glm::mat4(1.0f));
}

bool isBinaryGltf(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  char magic[4] = {};
  f.read(magic, 4);
  return f.gcount() == 4 && std::memcmp(magic, "glTF", 4) == 0;
}

}  // namespace

namespace {

// Throws SceneError when `path` is not a regular file that can be opened: opening a FIFO (or
// a device) would block until someone writes to it.
void checkOpenable(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (!ec && std::filesystem::exists(st) && !std::filesystem::is_regular_file(st)) {
    throw SceneError("not a regular file");
  }
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw SceneError(std::string("cannot open: ") + std::strerror(errno));
}

}  // namespace

Scene loadGltf(const std::string& path, const LoadOptions& options) {
  Scene scene;
  scene.name = path;
  try {
    checkOpenable(path);
    const bool binary = isBinaryGltf(path);
    tinygltf::TinyGLTF parser;
    tinygltf::Model model;
    gltf::BulkArrays bulk;
    ImageLoading loading{&options, &model};
    parser.SetImageLoader(decodeImageForTinygltf, &loading);
    // Every file read goes through AssetFiles; no shell expansion of paths (tinygltf's
    // default ExpandFilePath runs wordexp), no writing.
    const std::string base = path.find_last_of("/\\") == std::string::npos
                                 ? ""
                                 : path.substr(0, path.find_last_of("/\\"));
    AssetFiles files(path, base, options.maxFileBytes);
    tinygltf::FsCallbacks callbacks;
    callbacks.FileExists = [](const std::string& p, void* user) {
      return static_cast<AssetFiles*>(user)->exists(p);
    };
    callbacks.ExpandFilePath = [](const std::string& p, void*) { return p; };
    callbacks.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err,
                                 const std::string& p, void* user) {
      return static_cast<AssetFiles*>(user)->read(out, err, p);
    };
    callbacks.WriteWholeFile = [](std::string*, const std::string&,
                                  const std::vector<unsigned char>&, void*) { return false; };
    callbacks.user_data = &files;
    parser.SetFsCallbacks(callbacks);
    std::string err, warn;
    std::string failure;
    try {
      const bool ok = gltf::parseGltfFile(parser, &model, &bulk, &err, &warn, path, base, binary,
                                          files, options.maxFileBytes);
      if (!ok) {
        failure = !files.refusal().empty()   ? files.refusal()
                  : !files.missing().empty() ? files.missing()
                                             : oneLine(err.empty() ? "not a valid glTF file" : err);
      }
    } catch (const std::bad_alloc&) {
      failure = "out of memory while parsing: a size in the file is too large";
    } catch (const std::exception& e) {
      failure = oneLine(e.what());
    }
    // tinygltf treats an unreadable image as a warning; a refused URI is an error all the same.
    if (failure.empty() && !files.refusal().empty()) failure = files.refusal();
    if (!failure.empty()) {
      if (!binary)
        gltf::checkRequirementsInJson(path);  // throws when the real reason is a requirement
      throw SceneError(failure);
    }
    // A missing image leaves its textures out; say so.
    if (!files.missing().empty())
      scene.warnings.push_back(files.missing() + "; its textures are left out");
    gltf::checkVersion(model.asset.version, model.asset.minVersion, model.extensionsRequired);
    scene.ignoredExtensions = gltf::ignoredExtensions(model.extensionsUsed);
    checkTriangleCount(model, options.maxTriangles);
    gltf::Converter convert(model, bulk, scene, glm::radians(options.creaseAngleDegrees));
    checkStructure(model, bulk, convert);
    gltf::SceneWalker walker(model, bulk, scene, convert, options);
    walker.walk();
    scene.lightAnimation = gltf::lightAnimation(model, bulk, walker.lightSources());
  } catch (const SceneError& e) {
    throw SceneError(path + ": " + e.what());
  }
  if (scene.topology.degenerateTriangles > 0) {
    scene.warnings.push_back(std::to_string(scene.topology.degenerateTriangles) +
                             " degenerate triangles (repeated vertices or zero area) dropped");
  }
  return scene;
}

}  // namespace manylight
