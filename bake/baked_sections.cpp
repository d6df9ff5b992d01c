#include "bake/baked_sections.h"

#include <cmath>

#include "bake/baked_animation.h"
#include "bake/baked_octree.h"
#include "bake/light_tree_layout.h"
#include "scene/camera_animation.h"

namespace manylight::baked {
namespace {

void writeTrees(Writer& w, const BakedScene& b) {
  const PackedTrees& p = b.packed;
  for (int t = 0; t < 3; ++t) w.put(std::int32_t(p.base[t]));
  for (int t = 0; t < 3; ++t) w.put(std::int32_t(p.leaves[t]));
  const NodeColourCoder& c = p.colour;
  w.put(std::uint8_t(c.coding() == NodeColourCoding::Fitted ? 1 : 0));
  const PowerFit& f = c.fit();
  w.put(f.gamma), w.put(f.a), w.put(f.log10A), w.put(f.r2), w.put(f.worstRelative),
      w.put(std::uint64_t(f.pairs));
  w.put(std::uint8_t(c.fittedToSrgb()));
  w.put(c.scale());
  for (int k = 0; k < 3; ++k) w.put(c.maxError[k]);
  for (int k = 0; k < 3; ++k) w.put(c.p99Error[k]);
  w.put(c.slack), w.put(c.slackFloor);
  w.array(p.words);
}

Writer section(std::uint32_t which, const BakedScene& b) {
  const Scene& s = b.scene;
  Writer w;
  if (which == kScene) {
    w.string(s.name);
    w.put(std::int64_t(s.topology.degenerateTriangles));
    w.put(std::int64_t(s.topology.boundaryEdges));
    w.put(std::int64_t(s.topology.nonManifoldEdges));
    w.put(std::uint8_t(b.trees.split == Split::Metric ? 0 : 1));
    w.put(b.trees.coneWeight);
    w.put(b.trees.seed);
    w.put(std::uint8_t(b.trees.nodeColour == NodeColourCoding::Fitted ? 1 : 0));
    w.put(std::uint8_t(b.hasTrees));
  } else if (which == kMaterials) {
    w.put(std::uint32_t(s.materials.size()));
    for (const Material& m : s.materials) {
      putFloats(w, m.baseColorFactor);
      w.put(m.metallic), w.put(m.roughness);
      putFloats(w, m.emissive);
      w.put(m.normalScale), w.put(m.occlusionStrength), w.put(m.alphaCutoff);
      w.put(std::uint8_t(m.alphaMode)), w.put(std::uint8_t(m.doubleSided)),
          w.put(std::uint8_t(m.unlit)), w.put(std::uint8_t(m.specularGlossiness));
      putFloats(w, m.specularFactor);
      w.put(m.glossiness);
      for (int k = 0; k < Material::kTextureSlots; ++k) {
        const TextureRef& t = m.slot(k);
        w.put(std::int32_t(t.texture)), w.put(std::uint8_t(t.texCoord));
        putFloats(w, t.transform);
      }
    }
  } else if (which == kTextures) {
    w.put(std::uint32_t(s.textures.size()));
    for (const Texture& t : s.textures) {
      w.put(std::int32_t(t.width)), w.put(std::int32_t(t.height));
      const bool flags[8] = {t.repeatS,   t.repeatT,   t.mirrorS, t.mirrorT,
                             t.linearMag, t.linearMin, t.mipmaps, t.srgb};
      for (bool f : flags) w.put(std::uint8_t(f));
      w.array(t.rgba);
    }
  } else if (which == kMeshes) {
    w.put(std::uint32_t(s.meshes.size()));
    for (const Mesh& m : s.meshes) {
      w.put(std::uint32_t(m.primitives.size()));
      for (const Primitive& p : m.primitives) {
        w.put(std::int32_t(p.material)), w.put(std::uint8_t(p.mode));
        w.array(p.positions), w.array(p.normals), w.array(p.texcoords), w.array(p.texcoords1),
            w.array(p.tangents), w.array(p.colours), w.array(p.indices);
      }
    }
  } else if (which == kInstances) {
    w.put(std::uint32_t(s.instances.size()));
    for (const MeshInstance& i : s.instances) {
      w.put(std::int32_t(i.mesh));
      putFloats(w, i.world);
    }
  } else if (which == kLights) {
    w.put(std::uint32_t(s.lights.size()));
    for (const Light& l : s.lights) {
      w.put(std::uint8_t(l.type));
      putFloats(w, l.position), putFloats(w, l.direction), putFloats(w, l.colour);
      w.put(l.intensity), w.put(l.range), w.put(l.innerConeAngle), w.put(l.outerConeAngle);
    }
  } else if (which == kCameras) {
    w.put(std::uint32_t(s.cameras.size()));
    for (const Camera& c : s.cameras) {
      w.put(std::uint8_t(c.orthographic));
      w.put(c.yfov), w.put(c.xmag), w.put(c.ymag), w.put(c.znear), w.put(c.zfar);
      putFloats(w, c.world);
      w.put(c.animation.duration);
      writeChain(w, c.animation.chain);
    }
  } else if (which == kTrees) {
    writeTrees(w, b);
  } else if (which == kOctree) {
    writeOctree(w, b.octree);
  } else if (which == kLightAnimation) {
    writeLightAnimation(w, s.lightAnimation);
  }
  return w;
}

bool finite(const float* v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

void readScene(Reader& r, BakedScene& b) {
  b.scene.name = r.string();
  b.scene.topology.degenerateTriangles = r.get<std::int64_t>();
  b.scene.topology.boundaryEdges = r.get<std::int64_t>();
  b.scene.topology.nonManifoldEdges = r.get<std::int64_t>();
  const auto split = r.get<std::uint8_t>();
  if (split > 1) r.fail("unknown tree split " + std::to_string(split));
  b.trees.split = split == 0 ? Split::Metric : Split::LongestAxis;
  b.trees.coneWeight = r.get<double>();
  b.trees.seed = r.get<std::uint64_t>();
  const auto coding = r.get<std::uint8_t>();
  if (coding > 1) r.fail("unknown node colour coding " + std::to_string(coding));
  b.trees.nodeColour = coding == 1 ? NodeColourCoding::Fitted : NodeColourCoding::Rgb9e5;
  b.hasTrees = r.get<std::uint8_t>() != 0;
}

void readMaterials(Reader& r, Scene& s, std::size_t textures) {
  s.materials.resize(r.count(1u << 20, "materials"));
  for (Material& m : s.materials) {
    m.baseColorFactor = getFinite<glm::vec4>(r, "a base colour");
    m.metallic = getFinite<float>(r, "metallic");
    m.roughness = getFinite<float>(r, "roughness");
    m.emissive = getFinite<glm::vec3>(r, "emissive");
    m.normalScale = getFinite<float>(r, "a normal scale");
    m.occlusionStrength = getFinite<float>(r, "an occlusion strength");
    m.alphaCutoff = getFinite<float>(r, "an alpha cutoff");
    const auto alphaMode = r.get<std::uint8_t>();
    if (alphaMode > std::uint8_t(AlphaMode::Blend)) r.fail("unknown alpha mode");
    m.alphaMode = AlphaMode(alphaMode);
    m.doubleSided = r.get<std::uint8_t>() != 0;
    m.unlit = r.get<std::uint8_t>() != 0;
    m.specularGlossiness = r.get<std::uint8_t>() != 0;
    m.specularFactor = getFinite<glm::vec3>(r, "a specular factor");
    m.glossiness = getFinite<float>(r, "a glossiness");
    for (int k = 0; k < Material::kTextureSlots; ++k) {
      TextureRef& t = m.slot(k);
      t.texture = r.get<std::int32_t>();
      if (t.texture < -1 || t.texture >= std::int64_t(textures))
        r.fail("texture index out of range");
      t.texCoord = r.get<std::uint8_t>();
      if (t.texCoord > 1) r.fail("texture coordinate set out of range");
      t.transform = getFinite<glm::mat3>(r, "a texture transform");
    }
  }
}

void readTextures(Reader& r, Scene& s) {
  s.textures.resize(r.count(1u << 16, "textures"));
  for (Texture& t : s.textures) {
    t.width = r.get<std::int32_t>();
    t.height = r.get<std::int32_t>();
    if (t.width < 1 || t.height < 1 || t.width > 16384 || t.height > 16384)
      r.fail("texture size out of range");
    bool* flags[8] = {&t.repeatS,   &t.repeatT,   &t.mirrorS, &t.mirrorT,
                      &t.linearMag, &t.linearMin, &t.mipmaps, &t.srgb};
    for (bool* f : flags) *f = r.get<std::uint8_t>() != 0;
    t.rgba = r.array<std::uint8_t>();
    if (t.rgba.size() != std::size_t(t.width) * t.height * 4)
      r.fail("texture pixels do not match its size");
  }
}

void readMeshes(Reader& r, Scene& s) {
  s.meshes.resize(r.count(1u << 24, "meshes"));
  for (Mesh& m : s.meshes) {
    m.primitives.resize(r.count(1u << 16, "primitives"));
    for (Primitive& p : m.primitives) {
      p.material = r.get<std::int32_t>();
      if (p.material < -1 || p.material >= std::int64_t(s.materials.size()))
        r.fail("material index out of range");
      const auto mode = r.get<std::uint8_t>();
      if (mode > std::uint8_t(PrimitiveMode::Points)) r.fail("unknown primitive mode");
      p.mode = PrimitiveMode(mode);
      p.positions = r.array<glm::vec3>();
      p.normals = r.array<glm::vec3>();
      p.texcoords = r.array<glm::vec2>();
      p.texcoords1 = r.array<glm::vec2>();
      p.tangents = r.array<glm::vec4>();
      p.colours = r.array<glm::vec4>();
      p.indices = r.array<std::uint32_t>();
      const std::size_t n = p.positions.size();
      auto noneOrAll = [n](std::size_t k) { return k == 0 || k == n; };
      const bool triangles = p.mode == PrimitiveMode::Triangles;
      if ((triangles ? p.normals.size() != n : !noneOrAll(p.normals.size())) ||
          !noneOrAll(p.texcoords.size()) || !noneOrAll(p.texcoords1.size()) ||
          !noneOrAll(p.tangents.size()) || !noneOrAll(p.colours.size())) {
        r.fail("vertex attribute counts differ");
      }
      const std::size_t per = triangles ? 3 : p.mode == PrimitiveMode::Lines ? 2 : 1;
      if (p.indices.size() % per != 0) r.fail("index count does not fit the primitive mode");
      for (std::uint32_t i : p.indices) {
        if (i >= n) r.fail("vertex index out of range");
      }
      auto floats = [](const auto& v) { return reinterpret_cast<const float*>(v.data()); };
      if (!finite(floats(p.positions), n * 3) || !finite(floats(p.normals), p.normals.size() * 3) ||
          !finite(floats(p.tangents), p.tangents.size() * 4)) {
        r.fail("vertex positions, normals or tangents are not finite");
      }
    }
  }
}

void readInstances(Reader& r, Scene& s) {
  s.instances.resize(r.count(1u << 24, "instances"));
  for (MeshInstance& i : s.instances) {
    i.mesh = r.get<std::int32_t>();
    if (i.mesh < 0 || i.mesh >= std::int64_t(s.meshes.size())) r.fail("mesh index out of range");
    i.world = getFinite<glm::mat4>(r, "an instance transform");
  }
}

void readLights(Reader& r, Scene& s) {
  s.lights.resize(r.count(1u << 26, "lights"));
  for (Light& l : s.lights) {
    const auto type = r.get<std::uint8_t>();
    if (type > 2) r.fail("unknown light type " + std::to_string(type));
    l.type = LightType(type);
    l.position = getFinite<glm::vec3>(r, "a light position");
    l.direction = getFinite<glm::vec3>(r, "a light direction");
    l.colour = getFinite<glm::vec3>(r, "a light colour");
    l.intensity = getFinite<float>(r, "a light intensity");
    l.range = getFinite<float>(r, "a light range");
    l.innerConeAngle = getFinite<float>(r, "a cone angle");
    l.outerConeAngle = getFinite<float>(r, "a cone angle");
  }
}

void readCameras(Reader& r, Scene& s) {
  s.cameras.resize(r.count(1u << 16, "cameras"));
  for (Camera& c : s.cameras) {
    c.orthographic = r.get<std::uint8_t>() != 0;
    c.yfov = getFinite<float>(r, "yfov");
    c.xmag = getFinite<float>(r, "xmag");
    c.ymag = getFinite<float>(r, "ymag");
    c.znear = getFinite<float>(r, "znear");
    c.zfar = getFinite<float>(r, "zfar");
    c.world = getFinite<glm::mat4>(r, "a camera transform");
    c.animation.duration = getFinite<float>(r, "an animation duration");
    c.animation.chain = readChain(r, c.animation.duration);
  }
}

void readTrees(Reader& r, BakedScene& b) {
  PackedTrees& p = b.packed;
  for (int t = 0; t < 3; ++t) p.base[t] = r.get<std::int32_t>();
  for (int t = 0; t < 3; ++t) p.leaves[t] = r.get<std::int32_t>();
  const bool fitted = r.get<std::uint8_t>() != 0;
  PowerFit f;
  f.gamma = r.get<double>(), f.a = r.get<double>(), f.log10A = r.get<double>(),
  f.r2 = r.get<double>();
  f.worstRelative = r.get<double>();
  f.pairs = std::size_t(r.get<std::uint64_t>());
  const bool toSrgb = r.get<std::uint8_t>() != 0;
  const float scale = r.get<float>();
  if (!(f.gamma > 0.0) || !(f.a > 0.0) || !std::isfinite(f.gamma) || !std::isfinite(f.a) ||
      !(scale > 0.0f) || !std::isfinite(scale)) {
    r.fail("node colour constants out of range");
  }
  p.colour = NodeColourCoder(fitted ? NodeColourCoding::Fitted : NodeColourCoding::Rgb9e5, f,
                             toSrgb, scale);
  for (int k = 0; k < 3; ++k) p.colour.maxError[k] = r.get<double>();
  for (int k = 0; k < 3; ++k) p.colour.p99Error[k] = r.get<double>();
  p.colour.slack = r.get<double>();
  p.colour.slackFloor = r.get<double>();
  if (!(p.colour.slack >= 0.0 && p.colour.slack < 1e3) || !(p.colour.slackFloor >= 0.0))
    r.fail("slack out of range");
  p.words = r.array<std::uint32_t, Uninitialised<std::uint32_t>>();
  if (p.words.size() % 4 != 0) r.fail("tree words are not whole texels");
  // The trees must be the layout's, for lights the file holds: each complete, in place, every
  // representative a light of its type, and no light in two leaves (the tile cutter maps each
  // light to its one leaf).
  int typeCount[3] = {0, 0, 0};
  for (const Light& l : b.scene.lights)
    ++typeCount[l.type == LightType::Directional ? 0 : l.type == LightType::Point ? 1 : 2];
  int start[3] = {0, 0, 0};
  for (int t = 1; t < 3; ++t) start[t] = start[t - 1] + typeCount[t - 1];
  std::uint64_t expected = 0;
  std::vector<std::int32_t> leafOf(b.scene.lights.size(), -1);  // leaves < 2^28
  for (int t = 0; t < 3; ++t) {
    const std::int64_t leaves = p.leaves[t];
    if (leaves < 0 || (leaves & (leaves - 1)) != 0 || leaves < typeCount[t] ||
        (typeCount[t] == 0) != (leaves == 0) || leaves > (std::int64_t(1) << 27)) {
      r.fail("tree " + std::to_string(t) + " has " + std::to_string(leaves) + " leaves for " +
             std::to_string(typeCount[t]) + " lights");
    }
    if (leaves == 0) continue;
    const std::uint64_t stride = t == 2 ? layout::kSpotNodeWords : layout::kNodeWords;
    if (std::uint64_t(p.base[t]) != expected)
      r.fail("tree " + std::to_string(t) + " is not where the layout puts it");
    const std::uint64_t nodes = 2 * std::uint64_t(leaves) - 1;
    if (expected + nodes * stride > p.words.size())
      r.fail("tree " + std::to_string(t) + " runs past its words");
    for (std::uint64_t i = 0; i < nodes; ++i) {
      const auto rep = std::int32_t(p.words[expected + i * stride + 3]);
      if (rep != -1 && (rep < start[t] || rep >= start[t] + typeCount[t])) {
        r.fail("tree " + std::to_string(t) + ": node " + std::to_string(i) + " names light " +
               std::to_string(rep) + ", not one of its type");
      }
      if (rep == -1 || i + 1 < std::uint64_t(leaves)) continue;  // internal nodes share reps
      std::int32_t& leaf = leafOf[std::size_t(rep)];
      if (leaf >= 0) {
        r.fail("tree " + std::to_string(t) + ": leaves " + std::to_string(leaf) + " and " +
               std::to_string(i) + " both hold light " + std::to_string(rep));
      }
      leaf = std::int32_t(i);
    }
    expected += nodes * stride;
  }
  if ((expected + 3) / 4 * 4 != p.words.size()) r.fail("tree words do not add up");
}

}  // namespace

std::vector<std::pair<std::uint32_t, Writer>> writeSections(const BakedScene& baked) {
  std::vector<std::uint32_t> tags = {kScene,     kMaterials, kTextures, kMeshes,
                                     kInstances, kLights,    kCameras};
  if (baked.hasTrees) tags.push_back(kTrees);
  if (baked.hasOctree) tags.push_back(kOctree);
  if (baked.scene.lightAnimation.animated()) tags.push_back(kLightAnimation);
  std::vector<std::pair<std::uint32_t, Writer>> out;
  for (std::uint32_t t : tags) out.emplace_back(t, section(t, baked));
  return out;
}

BakedScene readSections(const std::map<std::uint32_t, std::string_view>& sections,
                        const std::string& path) {
  BakedScene b;
  Scene& scene = b.scene;
  auto read = [&](std::uint32_t t, const char* name, const auto& body) {
    const auto it = sections.find(t);
    if (it == sections.end()) throw BakeError(path + ": no " + name + " section");
    Reader r(it->second, path + ": " + name);
    body(r);
    r.end();
  };
  read(kScene, "scene", [&](Reader& r) { readScene(r, b); });
  read(kTextures, "textures", [&](Reader& r) { readTextures(r, scene); });
  read(kMaterials, "materials", [&](Reader& r) { readMaterials(r, scene, scene.textures.size()); });
  read(kMeshes, "meshes", [&](Reader& r) { readMeshes(r, scene); });
  read(kInstances, "instances", [&](Reader& r) { readInstances(r, scene); });
  read(kLights, "lights", [&](Reader& r) { readLights(r, scene); });
  read(kCameras, "cameras", [&](Reader& r) { readCameras(r, scene); });
  if (b.hasTrees != (sections.count(kTrees) > 0) || b.hasTrees != !b.scene.lights.empty()) {
    throw BakeError(path + ": the light trees and the lights do not agree");
  }
  if (b.hasTrees) read(kTrees, "light trees", [&](Reader& r) { readTrees(r, b); });
  if (sections.count(kLightAnimation)) {
    read(kLightAnimation, "light animation",
         [&](Reader& r) { scene.lightAnimation = readLightAnimation(r, scene.lights.size()); });
  }
  b.hasOctree = sections.count(kOctree) > 0;
  if (b.hasOctree) {
    read(kOctree, "light octree",
         [&](Reader& r) { b.octree = readOctree(r, scene.lights.size()); });
  }
  return b;
}

}  // namespace manylight::baked
