#include "scene/scene_walker.h"

#include <tiny_gltf.h>

#include <cmath>
#include <glm/gtc/type_ptr.hpp>
#include <string>

#include "base/error.h"
#include "base/parallel.h"

namespace manylight::gltf {

std::vector<int> SceneWalker::roots() const {
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
    roots.assign(bulk_.sceneNodes[std::size_t(s)].begin(), bulk_.sceneNodes[std::size_t(s)].end());
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
  return roots;
}

// Shares walk apart only when no node can be reached from two of them: the roots exist, are
// distinct and nobody's children (the hierarchy is a forest). Otherwise one walk finds the
// node reached twice and names it.
int SceneWalker::sharesFor(const std::vector<int>& roots) const {
  if (roots.size() < kParallelRoots) return 1;
  std::vector<char> seen(parent_.size(), 0);
  for (const int r : roots) {
    if (r < 0 || std::size_t(r) >= parent_.size() || parent_[std::size_t(r)] >= 0 ||
        seen[std::size_t(r)])
      return 1;
    seen[std::size_t(r)] = 1;
  }
  return sharesOf(roots.size(), kParallelRoots / 2);
}

void SceneWalker::walk() {
  const std::vector<int> roots = this->roots();
  parent_.assign(bulk_.nodes.size(), -1);
  for (std::size_t n = 0; n < bulk_.nodes.size(); ++n) {
    const NodeRecord& node = bulk_.nodes[n];
    for (const std::int32_t* c = bulk_.childrenBegin(node); c != bulk_.childrenEnd(node); ++c) {
      if (*c >= 0 && std::size_t(*c) < parent_.size()) parent_[std::size_t(*c)] = int(n);
    }
  }
  cameraPlaced_.assign(model_.cameras.size(), false);
  scene_.cameras.assign(model_.cameras.size(), Camera{});
  for (std::size_t i = 0; i < model_.cameras.size(); ++i) {
    scene_.cameras[i] = convert_.camera(int(i));
  }
  // At most one light a node. Past the budget one walk only counts lights, and throws for
  // them after it; shares would convert lights that walk only counts, and might meet an
  // error in one of them first: such a scene is walked in one share.
  std::size_t lightNodes = 0;
  for (const NodeRecord& n : bulk_.nodes) lightNodes += n.light >= 0 ? 1 : 0;
  std::vector<Share> shares(std::size_t(lightNodes > options_.lightBudget ? 1 : sharesFor(roots)));
  // The first share's vectors, which the Scene takes, hold every light without regrowing.
  lightNodes = std::min(lightNodes, options_.lightBudget);
  shares[0].lights.reserve(lightNodes);
  shares[0].sources.reserve(lightNodes);
  std::vector<char> visited(bulk_.nodes.size(), 0);  // bytes: shares write them at once
  runOnShares(int(shares.size()), roots.size(), [&](int k, std::size_t from, std::size_t to) {
    walkShare(roots.data() + from, roots.data() + to, shares[std::size_t(k)], visited);
  });
  for (Share& share : shares) merge(share);
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

// Walks the roots [first, last), each depth first, into `out`; the first error ends it.
void SceneWalker::walkShare(const int* first, const int* last, Share& out,
                            std::vector<char>& visited) const {
  try {
    std::vector<Item> stack;
    for (const int* root = first; root != last; ++root) {
      stack.push_back({*root, glm::mat4(1.0f)});
      while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        if (item.node < 0 || std::size_t(item.node) >= bulk_.nodes.size()) {
          throw SceneError("node " + std::to_string(item.node) + " does not exist");
        }
        if (visited[std::size_t(item.node)]) {
          throw SceneError("node " + std::to_string(item.node) +
                           " is reached twice (a scene root listed twice, or also a child)");
        }
        visited[std::size_t(item.node)] = 1;
        const NodeRecord& node = bulk_.nodes[std::size_t(item.node)];
        const glm::mat4 world = item.parent * localTransform(bulk_, node);
        place(item.node, node, world, out);
        for (const std::int32_t* c = bulk_.childrenEnd(node); c != bulk_.childrenBegin(node);) {
          stack.push_back({*--c, world});
        }
      }
    }
  } catch (...) {
    out.error = std::current_exception();
  }
}

void SceneWalker::place(int index, const NodeRecord& node, const glm::mat4& world,
                        Share& out) const {
  const auto where = [index] { return "node " + std::to_string(index); };
  for (int i = 0; i < 16; ++i) {
    if (!std::isfinite(glm::value_ptr(world)[i])) {
      throw SceneError(where() + ": transform is not finite");
    }
  }
  if (node.mesh >= 0) {
    out.uses.push_back({false, index, node.mesh, world});
  } else if (node.mesh < -1) {
    throw SceneError(where() + ": mesh " + std::to_string(node.mesh) + " does not exist");
  }
  if (node.camera >= 0) {
    if (std::size_t(node.camera) >= model_.cameras.size()) {
      throw SceneError(where() + ": camera " + std::to_string(node.camera) + " does not exist");
    }
    out.uses.push_back({true, index, node.camera, world});
  }
  const int light = node.light;
  if (light >= 0) {
    // Past the budget, lights are only counted (nothing more is stored), for the message.
    if (++out.lightsSeen <= options_.lightBudget) {
      out.lights.push_back(convert_.light(light, world));
      out.sources.push_back({index, light});
    }
  } else if (light < -1) {
    throw SceneError(where() + ": light " + std::to_string(light) + " does not exist");
  }
}

// Appends a share's meshes, cameras and lights, in order, then throws the error that ended
// its walk: the shares before it ended without one, so it is the first in walk order.
void SceneWalker::merge(Share& share) {
  for (const Use& use : share.uses) {
    if (!use.camera) {
      scene_.instances.push_back({convert_.mesh(use.index), use.world});
    } else if (!cameraPlaced_[std::size_t(use.index)]) {
      cameraPlaced_[std::size_t(use.index)] = true;
      Camera& camera = scene_.cameras[std::size_t(use.index)];
      camera.world = withoutScale(use.world);
      camera.animation = cameraAnimation(model_, bulk_, parent_, use.node);
    }
  }
  // A scene past the budget is walked in one share, whose lights (at most the budget) the
  // Scene takes; several shares hold every light between them.
  lightsSeen_ += share.lightsSeen;
  if (scene_.lights.empty()) {
    scene_.lights = std::move(share.lights);
    lightSources_ = std::move(share.sources);
  } else {
    scene_.lights.insert(scene_.lights.end(), share.lights.begin(), share.lights.end());
    lightSources_.insert(lightSources_.end(), share.sources.begin(), share.sources.end());
  }
  const std::exception_ptr error = share.error;
  share = Share{};  // its copies are in the Scene now
  if (error) std::rethrow_exception(error);
}

}  // namespace manylight::gltf
