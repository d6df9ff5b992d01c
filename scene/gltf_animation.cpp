#include "scene/gltf_animation.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <map>
#include <string_view>

#include "base/error.h"
#include "scene/camera_animation.h"
#include "scene/gltf_accessors.h"
#include "scene/gltf_bulk.h"

namespace manylight::gltf {
namespace {

std::string str(std::size_t i) { return std::to_string(i); }

std::string channelWhere(std::size_t a, std::size_t c) {
  return "animation " + str(a) + ": channel " + str(c);
}

AnimatedNode restNode(const BulkArrays& bulk, const NodeRecord& node) {
  AnimatedNode an;
  an.hasMatrix = node.matrix >= 0;
  an.matrix = localTransform(bulk, node);
  if (node.trs & NodeRecord::kTranslation)
    an.translation =
        glm::vec3(glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
  if (node.trs & NodeRecord::kRotation)
    an.rotation = glm::vec4(
        glm::dvec4(node.rotation[0], node.rotation[1], node.rotation[2], node.rotation[3]));
  if (node.trs & NodeRecord::kScale)
    an.scale = glm::vec3(glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  return an;
}

// A channel's sampler, read and checked: `components` floats a key (×3 for cubic splines).
struct Keys {
  AnimationTrack::Interpolation interpolation = AnimationTrack::Linear;
  std::vector<float> times, values;
};
Keys readKeys(const tinygltf::Model& model, const tinygltf::Animation& anim,
              const tinygltf::AnimationChannel& ch, int components, const std::string& where) {
  if (ch.sampler < 0 || std::size_t(ch.sampler) >= anim.samplers.size())
    throw SceneError(where + ": sampler " + std::to_string(ch.sampler) + " does not exist");
  const tinygltf::AnimationSampler& sampler = anim.samplers[std::size_t(ch.sampler)];
  Keys k;
  if (sampler.interpolation == "STEP") {
    k.interpolation = AnimationTrack::Step;
  } else if (sampler.interpolation == "CUBICSPLINE") {
    k.interpolation = AnimationTrack::CubicSpline;
  } else if (!sampler.interpolation.empty() && sampler.interpolation != "LINEAR") {
    throw SceneError(where + ": unknown interpolation '" + sampler.interpolation + "'");
  }
  k.times = readFloats(model, sampler.input, 1, where + " input");
  k.values = readFloats(model, sampler.output, components, where + " output");
  const std::string problem = checkKeys(k.interpolation, k.times, k.values, components);
  if (!problem.empty()) throw SceneError(where + ": " + problem);
  return k;
}

AnimationTrack nodeTrack(const tinygltf::Model& model, const tinygltf::Animation& anim,
                         const tinygltf::AnimationChannel& ch, AnimationTrack::Path path,
                         const std::string& where) {
  Keys k = readKeys(model, anim, ch, path == AnimationTrack::Rotation ? 4 : 3, where);
  AnimationTrack t;
  t.path = path;
  t.interpolation = k.interpolation;
  t.times = std::move(k.times);
  t.values = std::move(k.values);
  return t;
}

// The node path a channel names ("translation", "rotation", "scale"); false for others.
bool nodePath(std::string_view name, AnimationTrack::Path& path) {
  if (name == "translation") path = AnimationTrack::Translation;
  if (name == "rotation") path = AnimationTrack::Rotation;
  if (name == "scale") path = AnimationTrack::Scale;
  return name == "translation" || name == "rotation" || name == "scale";
}

void throwIfMatrix(const AnimatedNode& an, int node, const std::string& where) {
  if (an.hasMatrix)
    throw SceneError(where + ": node " + std::to_string(node) +
                     " has a matrix and cannot be animated");
}

constexpr std::string_view kLightPrefix = "/extensions/KHR_lights_punctual/lights/";

// What a channel animates: a node's translation, rotation or scale, a light's property, or
// nothing lights depend on.
struct Target {
  enum Kind : std::uint8_t { None, Node, Light } kind = None;
  int index = -1;  // the node or the glTF light
  int what = 0;    // AnimationTrack::Path or LightPropertyTrack::Property
};

// The decimal index that starts `s`, taken off it; −1 when there is none.
int takeIndex(std::string_view& s) {
  std::size_t n = 0;
  long long v = 0;
  while (n < s.size() && n < 9 && s[n] >= '0' && s[n] <= '9') v = v * 10 + (s[n++] - '0');
  if (n == 0 || (n < s.size() && s[n] >= '0' && s[n] <= '9')) return -1;
  s.remove_prefix(n);
  return int(v);
}

Target lightTarget(const BulkArrays& bulk, std::string_view pointer, const std::string& where) {
  const std::string at = where + ": pointer '" + std::string(pointer) + "': ";
  std::string_view rest = pointer.substr(kLightPrefix.size());
  const int light = takeIndex(rest);
  if (light < 0) throw SceneError(at + "no light index");
  if (std::size_t(light) >= bulk.lights.size())
    throw SceneError(at + "light " + str(std::size_t(light)) + " does not exist");
  static const std::pair<std::string_view, LightPropertyTrack::Property> kProperties[] = {
      {"/color", LightPropertyTrack::Colour},
      {"/intensity", LightPropertyTrack::Intensity},
      {"/range", LightPropertyTrack::Range},
      {"/spot/innerConeAngle", LightPropertyTrack::InnerConeAngle},
      {"/spot/outerConeAngle", LightPropertyTrack::OuterConeAngle}};
  for (const auto& [name, property] : kProperties) {
    if (rest != name) continue;
    if (property >= LightPropertyTrack::InnerConeAngle &&
        bulk.lights[std::size_t(light)].type != PunctualType::Spot)
      throw SceneError(at + "light " + str(std::size_t(light)) + " is not a spot light");
    return {Target::Light, light, property};
  }
  throw SceneError(at + "light " + str(std::size_t(light)) +
                   " has no animatable property there (color, intensity, range, "
                   "spot/innerConeAngle, spot/outerConeAngle)");
}

Target channelTarget(const BulkArrays& bulk, const tinygltf::AnimationChannel& ch,
                     const std::string& where) {
  AnimationTrack::Path path;
  if (ch.target_path != "pointer") {
    if (ch.target_node < 0 || !nodePath(ch.target_path, path)) return {};
    return {Target::Node, ch.target_node, path};
  }
  const auto ext = ch.target_extensions.find("KHR_animation_pointer");
  if (ext == ch.target_extensions.end() || !ext->second.Get("pointer").IsString()) return {};
  const std::string& text = ext->second.Get("pointer").Get<std::string>();
  std::string_view pointer = text;
  if (pointer.substr(0, kLightPrefix.size()) == kLightPrefix)
    return lightTarget(bulk, pointer, where);
  if (pointer.substr(0, 7) != "/nodes/") return {};
  pointer.remove_prefix(7);
  const int node = takeIndex(pointer);
  if (node < 0 || pointer.empty() || pointer[0] != '/' || !nodePath(pointer.substr(1), path))
    return {};
  return {Target::Node, node, path};
}

// Reads the light animations: channels indexed by the node or light they target, each
// track read once.
class LightReader {
 public:
  LightReader(const tinygltf::Model& model, const BulkArrays& bulk)
      : model_(model),
        bulk_(bulk),
        parent_(bulk.nodes.size(), -1),
        nodeRefs_(bulk.nodes.size()),
        lightRefs_(bulk.lights.size()) {
    for (std::size_t n = 0; n < bulk.nodes.size(); ++n) {
      const NodeRecord& node = bulk.nodes[n];
      for (const std::int32_t* c = bulk.childrenBegin(node); c != bulk.childrenEnd(node); ++c)
        parent_[std::size_t(*c)] = int(n);
    }
    for (std::size_t a = 0; a < model.animations.size(); ++a) {
      for (std::size_t c = 0; c < model.animations[a].channels.size(); ++c) {
        const Target t = channelTarget(bulk, model.animations[a].channels[c], channelWhere(a, c));
        const Ref ref{a, c, t.what};
        if (t.kind == Target::Node && std::size_t(t.index) < nodeRefs_.size())
          nodeRefs_[std::size_t(t.index)].push_back(ref);
        if (t.kind == Target::Light) lightRefs_[std::size_t(t.index)].push_back(ref);
      }
    }
  }

  // Scene::lights[index], from `source`; light −1 when nothing animates it.
  AnimatedLight read(int index, const LightSource& source) {
    AnimatedLight out;
    out.light = index;
    std::vector<int> chain;
    bool moves = false;
    for (int n = source.node; n >= 0 && chain.size() <= parent_.size(); n = parent_[n]) {
      chain.push_back(n);
      moves = moves || !nodeRefs_[std::size_t(n)].empty();
    }
    for (const Ref& r : lightRefs_[std::size_t(source.light)])
      out.properties.push_back(property(r));
    if (!moves && out.properties.empty()) out.light = -1;
    if (!moves) return out;
    for (auto n = chain.rbegin(); n != chain.rend(); ++n) {
      out.chain.push_back(restNode(bulk_, bulk_.nodes[std::size_t(*n)]));
      for (const Ref& r : nodeRefs_[std::size_t(*n)]) {
        throwIfMatrix(out.chain.back(), *n, channelWhere(r.anim, r.channel));
        out.chain.back().tracks.push_back(track(r));
      }
    }
    return out;
  }

 private:
  struct Ref {
    std::size_t anim, channel;
    int what;
  };

  const AnimationTrack& track(const Ref& r) {
    auto [it, fresh] = tracks_.try_emplace({r.anim, r.channel});
    if (fresh) {
      const tinygltf::Animation& anim = model_.animations[r.anim];
      it->second = nodeTrack(model_, anim, anim.channels[r.channel], AnimationTrack::Path(r.what),
                             channelWhere(r.anim, r.channel));
    }
    return it->second;
  }

  const LightPropertyTrack& property(const Ref& r) {
    auto [it, fresh] = properties_.try_emplace({r.anim, r.channel});
    if (!fresh) return it->second;
    const tinygltf::Animation& anim = model_.animations[r.anim];
    const std::string where = channelWhere(r.anim, r.channel);
    const auto p = LightPropertyTrack::Property(r.what);
    Keys k = readKeys(model_, anim, anim.channels[r.channel],
                      p == LightPropertyTrack::Colour ? 3 : 1, where);
    LightPropertyTrack& t = it->second;
    t = {p, k.interpolation, std::move(k.times), std::move(k.values)};
    const std::string problem = checkLightTrack(t);
    if (!problem.empty()) throw SceneError(where + ": " + problem);
    return t;
  }

  const tinygltf::Model& model_;
  const BulkArrays& bulk_;
  std::vector<int> parent_;
  std::vector<std::vector<Ref>> nodeRefs_, lightRefs_;
  std::map<std::pair<std::size_t, std::size_t>, AnimationTrack> tracks_;
  std::map<std::pair<std::size_t, std::size_t>, LightPropertyTrack> properties_;
};

}  // namespace

glm::mat4 localTransform(const BulkArrays& bulk, const NodeRecord& node) {
  if (node.matrix >= 0) {
    glm::dmat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = bulk.matrices[std::size_t(node.matrix)][i];
    return glm::mat4(m);
  }
  glm::dmat4 m(1.0);
  if (node.trs & NodeRecord::kTranslation) {
    m = glm::translate(m,
                       glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
  }
  if (node.trs & NodeRecord::kRotation) {
    const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    m *= glm::mat4_cast(glm::normalize(q));
  }
  if (node.trs & NodeRecord::kScale) {
    m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  }
  return glm::mat4(m);
}

CameraAnimation cameraAnimation(const tinygltf::Model& model, const BulkArrays& bulk,
                                const std::vector<int>& parent, int index) {
  std::vector<int> chain;
  for (int n = index; n >= 0 && chain.size() <= bulk.nodes.size(); n = parent[n])
    chain.push_back(n);
  std::reverse(chain.begin(), chain.end());
  for (std::size_t a = 0; a < model.animations.size(); ++a) {
    const tinygltf::Animation& anim = model.animations[a];
    CameraAnimation out;
    for (int n : chain) {
      AnimatedNode an = restNode(bulk, bulk.nodes[std::size_t(n)]);
      for (std::size_t c = 0; c < anim.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = anim.channels[c];
        AnimationTrack::Path path;
        // Morph target weights and KHR_animation_pointer channels do not move a camera.
        if (ch.target_node != n || !nodePath(ch.target_path, path)) continue;
        throwIfMatrix(an, n, channelWhere(a, c));
        an.tracks.push_back(nodeTrack(model, anim, ch, path, channelWhere(a, c)));
        out.duration = std::max(out.duration, an.tracks.back().times.back());
      }
      out.chain.push_back(std::move(an));
    }
    for (const AnimatedNode& an : out.chain) {
      if (!an.tracks.empty()) return out;
    }
  }
  return {};
}

LightAnimation lightAnimation(const tinygltf::Model& model, const BulkArrays& bulk,
                              const std::vector<LightSource>& sources) {
  LightAnimation out;
  if (model.animations.empty()) return out;
  LightReader reader(model, bulk);
  for (std::size_t i = 0; i < sources.size(); ++i) {
    AnimatedLight a = reader.read(int(i), sources[i]);
    if (a.light >= 0) out.lights.push_back(std::move(a));
  }
  return out;
}

}  // namespace manylight::gltf
