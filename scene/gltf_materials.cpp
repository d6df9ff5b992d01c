#include "scene/gltf_materials.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "base/error.h"

namespace manylight::gltf {
namespace {

std::string str(int i) { return std::to_string(i); }

double number(const tinygltf::Value& v, const char* key, double fallback) {
  if (!v.IsObject() || !v.Has(key)) return fallback;
  const tinygltf::Value& x = v.Get(key);
  return x.IsNumber() ? x.GetNumberAsDouble() : fallback;
}

glm::vec2 pair(const tinygltf::Value& v, const char* key, glm::vec2 fallback) {
  if (!v.IsObject() || !v.Has(key)) return fallback;
  const tinygltf::Value& x = v.Get(key);
  if (!x.IsArray() || x.ArrayLen() != 2 || !x.Get(0).IsNumber() || !x.Get(1).IsNumber())
    return fallback;
  return {float(x.Get(0).GetNumberAsDouble()), float(x.Get(1).GetNumberAsDouble())};
}

// KHR_texture_transform's matrix, as its specification writes it: translation · rotation ·
// scale, applied to (u, v, 1).
glm::mat3 uvTransform(const tinygltf::Value& t) {
  const glm::vec2 offset = pair(t, "offset", glm::vec2(0.0f));
  const glm::vec2 scale = pair(t, "scale", glm::vec2(1.0f));
  const float r = float(number(t, "rotation", 0.0));
  const glm::mat3 translation(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
  const glm::mat3 rotation(std::cos(r), std::sin(r), 0, -std::sin(r), std::cos(r), 0, 0, 0, 1);
  const glm::mat3 scaling(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
  return translation * rotation * scaling;
}

// A textureInfo written inside an extension's JSON (tinygltf parses only the core ones).
tinygltf::TextureInfo textureInfoOf(const tinygltf::Value& v) {
  tinygltf::TextureInfo info;
  if (!v.IsObject()) return info;
  info.index = int(number(v, "index", -1.0));
  info.texCoord = int(number(v, "texCoord", 0.0));
  if (v.Has("extensions") && v.Get("extensions").IsObject()) {
    const tinygltf::Value& ext = v.Get("extensions");
    for (const std::string& key : ext.Keys()) info.extensions[key] = ext.Get(key);
  }
  return info;
}

glm::vec4 vec4Of(const tinygltf::Value& v, const char* key, glm::vec4 fallback) {
  if (!v.IsObject() || !v.Has(key)) return fallback;
  const tinygltf::Value& x = v.Get(key);
  if (!x.IsArray() || (x.ArrayLen() != 3 && x.ArrayLen() != 4)) return fallback;
  glm::vec4 out = fallback;
  for (int i = 0; i < int(x.ArrayLen()); ++i) {
    if (!x.Get(i).IsNumber()) return fallback;
    out[i] = float(x.Get(i).GetNumberAsDouble());
  }
  return out;
}

bool finite(glm::mat3 m) {
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) {
      if (!std::isfinite(m[c][r])) return false;
    }
  }
  return true;
}

}  // namespace

MaterialConverter::MaterialConverter(const tinygltf::Model& model, Scene& scene)
    : model_(model), scene_(scene), materials_(model.materials.size(), -1) {}

int MaterialConverter::material(int index) {
  if (index < 0 || std::size_t(index) >= model_.materials.size())
    throw SceneError("material " + str(index) + " does not exist");
  if (materials_[index] >= 0) return materials_[index];
  const tinygltf::Material& src = model_.materials[index];
  const auto& pbr = src.pbrMetallicRoughness;
  const std::string where = "material " + str(index);
  Material m;
  if (pbr.baseColorFactor.size() == 4) {
    m.baseColorFactor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1],
                                  pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
  }
  m.metallic = float(pbr.metallicFactor);
  m.roughness = float(pbr.roughnessFactor);
  if (src.emissiveFactor.size() == 3) {
    m.emissive = glm::vec3(src.emissiveFactor[0], src.emissiveFactor[1], src.emissiveFactor[2]);
  }
  const auto strength = src.extensions.find("KHR_materials_emissive_strength");
  if (strength != src.extensions.end()) {
    const double s = number(strength->second, "emissiveStrength", 1.0);
    if (!(s >= 0.0) || !std::isfinite(s))
      throw SceneError(where + ": emissiveStrength must be a finite number >= 0");
    m.emissive *= float(s);
  }
  m.unlit = src.extensions.count("KHR_materials_unlit") > 0;
  m.doubleSided = src.doubleSided;
  if (src.alphaMode == "MASK") {
    m.alphaMode = AlphaMode::Mask;
    m.alphaCutoff = float(src.alphaCutoff);
    if (!(m.alphaCutoff >= 0.0f) || !std::isfinite(m.alphaCutoff))
      throw SceneError(where + ": alphaCutoff must be a finite number >= 0");
  } else if (src.alphaMode == "BLEND") {
    m.alphaMode = AlphaMode::Blend;
  } else if (src.alphaMode != "OPAQUE" && !src.alphaMode.empty()) {
    throw SceneError(where + ": unknown alphaMode '" + src.alphaMode + "'");
  }
  const glm::vec4 base = m.baseColorFactor;
  const float factors[] = {m.metallic, m.roughness,  base.r,       base.g,      base.b,
                           base.a,     m.emissive.r, m.emissive.g, m.emissive.b};
  if (!std::all_of(std::begin(factors), std::end(factors),
                   [](float f) { return std::isfinite(f); })) {
    throw SceneError(where + ": factors must be finite");
  }
  const tinygltf::TextureInfo& baseInfo = pbr.baseColorTexture;
  m.baseColorTexture =
      textureRef(index, "base colour", baseInfo, baseInfo.index, baseInfo.texCoord, true);
  if (!m.unlit) {
    const tinygltf::TextureInfo& mr = pbr.metallicRoughnessTexture;
    m.metallicRoughnessTexture =
        textureRef(index, "metallic-roughness", mr, mr.index, mr.texCoord, false);
    const tinygltf::NormalTextureInfo& n = src.normalTexture;
    tinygltf::TextureInfo info;
    info.extensions = n.extensions;
    m.normalTexture = textureRef(index, "normal", info, n.index, n.texCoord, false);
    m.normalScale = float(n.scale);
    const tinygltf::OcclusionTextureInfo& o = src.occlusionTexture;
    info.extensions = o.extensions;
    m.occlusionTexture = textureRef(index, "occlusion", info, o.index, o.texCoord, false);
    m.occlusionStrength = float(o.strength);
    if (!std::isfinite(m.normalScale) || !std::isfinite(m.occlusionStrength))
      throw SceneError(where + ": normal scale and occlusion strength must be finite");
    const tinygltf::TextureInfo& e = src.emissiveTexture;
    m.emissiveTexture = textureRef(index, "emissive", e, e.index, e.texCoord, true);
  }
  const auto sg = src.extensions.find("KHR_materials_pbrSpecularGlossiness");
  if (sg != src.extensions.end() && !m.unlit) specularGlossiness(index, sg->second, m);
  materials_[index] = int(scene_.materials.size());
  scene_.materials.push_back(m);
  return materials_[index];
}

void MaterialConverter::specularGlossiness(int index, const tinygltf::Value& ext, Material& m) {
  m.specularGlossiness = true;
  m.baseColorFactor = vec4Of(ext, "diffuseFactor", glm::vec4(1.0f));
  m.specularFactor = glm::vec3(vec4Of(ext, "specularFactor", glm::vec4(1.0f)));
  m.glossiness = float(number(ext, "glossinessFactor", 1.0));
  const float factors[] = {m.baseColorFactor.r, m.baseColorFactor.g, m.baseColorFactor.b,
                           m.baseColorFactor.a, m.specularFactor.r,  m.specularFactor.g,
                           m.specularFactor.b,  m.glossiness};
  if (!std::all_of(std::begin(factors), std::end(factors),
                   [](float f) { return std::isfinite(f); }))
    throw SceneError("material " + str(index) +
                     ": KHR_materials_pbrSpecularGlossiness factors "
                     "must be finite");
  const tinygltf::TextureInfo diffuse = ext.Has("diffuseTexture")
                                            ? textureInfoOf(ext.Get("diffuseTexture"))
                                            : tinygltf::TextureInfo{};
  m.baseColorTexture = textureRef(index, "diffuse", diffuse, diffuse.index, diffuse.texCoord, true);
  const tinygltf::TextureInfo sgInfo = ext.Has("specularGlossinessTexture")
                                           ? textureInfoOf(ext.Get("specularGlossinessTexture"))
                                           : tinygltf::TextureInfo{};
  // sRGB specular colour; the sampler decodes RGB only, so A (glossiness) stays linear.
  m.metallicRoughnessTexture =
      textureRef(index, "specular-glossiness", sgInfo, sgInfo.index, sgInfo.texCoord, true);
}

TextureRef MaterialConverter::textureRef(int materialIndex, const char* what,
                                         const tinygltf::TextureInfo& info, int index, int texCoord,
                                         bool srgb) {
  TextureRef ref;
  if (index < 0) return ref;
  const std::string where = "material " + str(materialIndex) + ": " + what + " texture";
  ref.texture = texture(index, srgb);
  if (ref.texture < 0) {
    scene_.warnings.push_back(where + " " + str(index) + " has no image; ignored");
    return ref;
  }
  ref.texCoord = texCoord;
  const auto transform = info.extensions.find("KHR_texture_transform");
  if (transform != info.extensions.end()) {
    ref.transform = uvTransform(transform->second);
    ref.texCoord = int(number(transform->second, "texCoord", texCoord));
    if (!finite(ref.transform)) throw SceneError(where + ": KHR_texture_transform is not finite");
  }
  if (ref.texCoord != 0 && ref.texCoord != 1) {
    scene_.warnings.push_back(where + " reads TEXCOORD_" + str(ref.texCoord) +
                              " (only 0 and 1 are read); ignored");
    return TextureRef{};
  }
  return ref;
}

int MaterialConverter::texture(int index, bool srgb) {
  if (index < 0 || std::size_t(index) >= model_.textures.size()) return -1;
  const auto known = textures_.find({index, srgb});
  if (known != textures_.end()) return known->second;
  const tinygltf::Texture& src = model_.textures[index];
  if (src.source < 0 && src.extensions.count("KHR_texture_basisu")) {
    scene_.warnings.push_back("texture " + str(index) +
                              ": KHR_texture_basisu (KTX2) has no decoder here and the texture "
                              "gives no PNG or JPEG fallback; ignored");
    return -1;
  }
  if (src.source < 0 || std::size_t(src.source) >= model_.images.size()) return -1;
  const tinygltf::Image& img = model_.images[src.source];
  if (img.image.empty() || img.width <= 0 || img.height <= 0 || img.component != 4 ||
      img.bits != 8) {
    return -1;
  }
  Texture t;
  t.width = img.width;
  t.height = img.height;
  t.rgba = img.image;
  t.srgb = srgb;
  if (src.sampler >= 0 && std::size_t(src.sampler) < model_.samplers.size()) {
    const tinygltf::Sampler& s = model_.samplers[src.sampler];
    t.repeatS = s.wrapS != TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    t.repeatT = s.wrapT != TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    t.mirrorS = s.wrapS == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
    t.mirrorT = s.wrapT == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
    t.linearMag = s.magFilter != TINYGLTF_TEXTURE_FILTER_NEAREST;
    t.linearMin = s.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST &&
                  s.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST &&
                  s.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR;
    t.mipmaps = s.minFilter < 0 || s.minFilter >= TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST;
  }
  const int out = int(scene_.textures.size());
  textures_[{index, srgb}] = out;
  scene_.textures.push_back(std::move(t));
  return out;
}

}  // namespace manylight::gltf
