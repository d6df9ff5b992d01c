#include "bake/baked_animation.h"

#include <cmath>
#include <limits>

#include "scene/camera_animation.h"

namespace manylight::baked {

void writeChain(Writer& w, const std::vector<AnimatedNode>& chain) {
  w.put(std::uint32_t(chain.size()));
  for (const AnimatedNode& n : chain) {
    w.put(std::uint8_t(n.hasMatrix));
    putFloats(w, n.matrix), putFloats(w, n.translation), putFloats(w, n.rotation),
        putFloats(w, n.scale);
    w.put(std::uint32_t(n.tracks.size()));
    for (const AnimationTrack& t : n.tracks) {
      w.put(std::uint8_t(t.path)), w.put(std::uint8_t(t.interpolation));
      w.array(t.times), w.array(t.values);
    }
  }
}

std::vector<AnimatedNode> readChain(Reader& r, float duration) {
  std::vector<AnimatedNode> chain(r.count(1024, "animated nodes"));
  for (AnimatedNode& n : chain) {
    n.hasMatrix = r.get<std::uint8_t>() != 0;
    n.matrix = getFinite<glm::mat4>(r, "a node matrix");
    n.translation = getFinite<glm::vec3>(r, "a node translation");
    n.rotation = getFinite<glm::vec4>(r, "a node rotation");
    n.scale = getFinite<glm::vec3>(r, "a node scale");
    n.tracks.resize(r.count(16, "animation tracks"));
    for (AnimationTrack& t : n.tracks) {
      const auto path = r.get<std::uint8_t>(), interpolation = r.get<std::uint8_t>();
      if (path > 2 || interpolation > 2) r.fail("unknown animation path or interpolation");
      t.path = AnimationTrack::Path(path);
      t.interpolation = AnimationTrack::Interpolation(interpolation);
      t.times = r.array<float>();
      t.values = r.array<float>();
      const std::string problem = checkTrack(t);
      if (!problem.empty()) r.fail("animation track: " + problem);
      if (t.times.back() > duration) r.fail("animation track: keys past the duration");
    }
  }
  return chain;
}

void writeLightAnimation(Writer& w, const LightAnimation& a) {
  w.put(std::uint32_t(a.lights.size()));
  for (const AnimatedLight& l : a.lights) {
    w.put(std::int32_t(l.light));
    writeChain(w, l.chain);
    w.put(std::uint32_t(l.properties.size()));
    for (const LightPropertyTrack& t : l.properties) {
      w.put(std::uint8_t(t.property)), w.put(std::uint8_t(t.interpolation));
      w.array(t.times), w.array(t.values);
    }
  }
}

LightAnimation readLightAnimation(Reader& r, std::size_t lights) {
  LightAnimation a;
  a.lights.resize(
      r.count(std::uint32_t(std::min<std::size_t>(lights, 1u << 26)), "animated lights"));
  int previous = -1;
  for (AnimatedLight& l : a.lights) {
    l.light = r.get<std::int32_t>();
    if (l.light <= previous || std::size_t(l.light) >= lights)
      r.fail("animated light " + std::to_string(l.light) + " is out of order or range");
    previous = l.light;
    l.chain = readChain(r, std::numeric_limits<float>::infinity());
    l.properties.resize(r.count(5, "light property tracks"));
    for (LightPropertyTrack& t : l.properties) {
      const auto property = r.get<std::uint8_t>(), interpolation = r.get<std::uint8_t>();
      if (property > 4 || interpolation > 2) r.fail("unknown light property or interpolation");
      t.property = LightPropertyTrack::Property(property);
      t.interpolation = AnimationTrack::Interpolation(interpolation);
      t.times = r.array<float>();
      t.values = r.array<float>();
      const std::string problem = checkLightTrack(t);
      if (!problem.empty()) r.fail("light animation track: " + problem);
    }
  }
  return a;
}

}  // namespace manylight::baked
