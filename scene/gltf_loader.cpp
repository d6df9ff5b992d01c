#include "scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtc/type_ptr.hpp>
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

// Walks the node hierarchy of the default scene, placing meshes, lights and cameras.
class SceneWalker {
 public:
  SceneWalker(const tinygltf::Model& model, const gltf::BulkArrays& bulk, Scene& scene,
              gltf::Converter& convert, const LoadOptions& options)
      : model_(model), bulk_(bulk), scene_(scene), convert_(convert), options_(options) {}

  void walk() {
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
      int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (std::size_t(s) >= model_.scenes.size()) {
        throw SceneError("scene " + std::to_string(s) + " does not exist");
      }
      // splitJson read the roots (and emptied them in what tinygltf read). It reads keys as
      // written: a `scenes` key written with escapes is one it did not see.
      if (std::size_t(s) >= bulk_.sceneNodes.size())
        throw SceneError("scenes: written with escapes in its key, which is not supported");
      roots.assign(bulk_.sceneNodes[std::size_t(s)].begin(),
                   bulk_.sceneNodes[std::size_t(s)].end());
    } else {
      // No scenes: show every node that is nobody's child.
      std::vector<bool> isChild(bulk_.nodes.size(), false);
      for (std::int32_t c : bulk_.children) {
        if (c >= 0 && std::size_t(c) < isChild.size()) isChild[std::size_t(c)] = true;
      }
      for (std::size_t i = 0; i < isChild.size(); ++i) {
        if (!isChild[i]) roots.push_back(int(i));
      }
    }
    parent_.assign(bulk_.nodes.size(), -1);
    for (std::size_t n = 0; n < bulk_.nodes.size(); ++n) {
      const gltf::NodeRecord& node = bulk_.nodes[n];
      for (const std::int32_t* c = bulk_.childrenBegin(node); c != bulk_.childrenEnd(node); ++c) {
        if (*c >= 0 && std::size_t(*c) < parent_.size()) parent_[std::size_t(*c)] = int(n);
      }
    }
    // At most one light a node, within the budget: stored without regrowing.
    std::size_t lightNodes = 0;
    for (const gltf::NodeRecord& n : bulk_.nodes) lightNodes += n.light >= 0 ? 1 : 0;
    lightNodes = std::min(lightNodes, options_.lightBudget);
    scene_.lights.reserve(scene_.lights.size() + lightNodes);
    lightSources_.reserve(lightNodes);
    cameraPlaced_.assign(model_.cameras.size(), false);
    scene_.cameras.assign(model_.cameras.size(), Camera{});
    for (std::size_t i = 0; i < model_.cameras.size(); ++i) {
      scene_.cameras[i] = convert_.camera(int(i));
    }
    // Iterative depth-first walk. checkStructure has ruled out cycles and second parents, so
    // a node met twice is listed twice among the roots, or is both a root and a child.
    std::vector<bool> visited(bulk_.nodes.size(), false);
    std::vector<Item> stack;
    // Root by root (a scene of a million lights may list each as a root), each depth first.
    for (const int root : roots) {
      stack.push_back({root, glm::mat4(1.0f)});
      walkFrom(stack, visited);
    }
    if (lightsSeen_ > options_.lightBudget) {
      throw SceneError(std::to_string(lightsSeen_) + " lights exceed the light budget of " +
                       std::to_string(options_.lightBudget) + " (--light-budget)");
    }
    for (std::size_t i = 0; i < cameraPlaced_.size(); ++i) {
      if (!cameraPlaced_[i]) {
        scene_.warnings.push_back("camera " + std::to_string(i) +
                                  " is used by no node of the scene; placed at the origin");
      }
    }
  }

  // Where each of Scene::lights comes from, in order.
  const std::vector<gltf::LightSource>& lightSources() const { return lightSources_; }

 private:
  struct Item {
    int node;
    glm::mat4 parent;
  };

  // Places the nodes below the one on `stack` (its only item), depth first.
  void walkFrom(std::vector<Item>& stack, std::vector<bool>& visited) {
    while (!stack.empty()) {
      const Item item = stack.back();
      stack.pop_back();
      if (item.node < 0 || std::size_t(item.node) >= bulk_.nodes.size()) {
        throw SceneError("node " + std::to_string(item.node) + " does not exist");
      }
      if (visited[item.node]) {
        throw SceneError("node " + std::to_string(item.node) +
                         " is reached twice (a scene root listed twice, or also a child)");
      }
      visited[item.node] = true;
      const gltf::NodeRecord& node = bulk_.nodes[std::size_t(item.node)];
      const glm::mat4 world = item.parent * gltf::localTransform(bulk_, node);
      place(item.node, node, world);
      for (const std::int32_t* c = bulk_.childrenEnd(node); c != bulk_.childrenBegin(node);) {
        stack.push_back({*--c, world});
      }
    }
  }

  void place(int index, const gltf::NodeRecord& node, const glm::mat4& world) {
    const auto where = [index] { return "node " + std::to_string(index); };
    for (int i = 0; i < 16; ++i) {
      if (!std::isfinite(glm::value_ptr(world)[i])) {
        throw SceneError(where() + ": transform is not finite");
      }
    }
    if (node.mesh >= 0) {
      scene_.instances.push_back({convert_.mesh(node.mesh), world});
    } else if (node.mesh < -1) {
      throw SceneError(where() + ": mesh " + std::to_string(node.mesh) + " does not exist");
    }
    if (node.camera >= 0) {
      if (std::size_t(node.camera) >= model_.cameras.size()) {
        throw SceneError(where() + ": camera " + std::to_string(node.camera) + " does not exist");
      }
      if (!cameraPlaced_[node.camera]) {
        cameraPlaced_[node.camera] = true;
        scene_.cameras[node.camera].world = gltf::withoutScale(world);
        scene_.cameras[node.camera].animation =
            gltf::cameraAnimation(model_, bulk_, parent_, index);
      }
    }
    const int light = node.light;
    if (light >= 0) {
      // Past the budget, lights are only counted (nothing more is stored), for the message.
      if (++lightsSeen_ <= options_.lightBudget) {
        scene_.lights.push_back(convert_.light(light, world));
        lightSources_.push_back({index, light});
      }
    } else if (light < -1) {
      throw SceneError(where() + ": light " + std::to_string(light) + " does not exist");
    }
  }

  const tinygltf::Model& model_;
  const gltf::BulkArrays& bulk_;
  Scene& scene_;
  gltf::Converter& convert_;
  const LoadOptions& options_;
  std::vector<bool> cameraPlaced_;
  std::vector<int> parent_;
  std::size_t lightsSeen_ = 0;
  std::vector<gltf::LightSource> lightSources_;
};

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
    SceneWalker walker(model, bulk, scene, convert, options);
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
