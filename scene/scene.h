#pragma once
// The scene as the renderer sees it: world-space lights and cameras, meshes with their
// instances, materials and decoded textures. Plain data; no GL.
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <utility>
#include <vector>

#include "scene/animation_track.h"
#include "scene/light_animation.h"

namespace manylight {

enum class LightType : std::uint8_t { Point, Spot, Directional };

// A KHR_lights_punctual light placed in the world. Spec defaults apply to absent fields.
struct Light {
  LightType type = LightType::Point;
  glm::vec3 position{0.0f};                   // world space; unused for directional lights
  glm::vec3 direction{0.0f, 0.0f, -1.0f};     // unit, the way the light travels (spot, directional)
  glm::vec3 colour{1.0f};                     // linear RGB
  float intensity = 1.0f;                     // candela (point, spot) or lux (directional)
  float range = 0.0f;                         // 0: infinite
  float innerConeAngle = 0.0f;                // radians, spot only
  float outerConeAngle = 0.785398163397448f;  // π/4
};

// Whether the light has a range (a point or spot light with range > 0): its contribution is
// zero from that distance on (scene/shading_model.h's window).
inline bool isRanged(const Light& l) { return l.type != LightType::Directional && l.range > 0.0f; }

// Whether two lights are the same in every value that lights a scene.
inline bool sameLight(const Light& a, const Light& b) {
  return a.type == b.type && a.position == b.position && a.direction == b.direction &&
         a.colour == b.colour && a.intensity == b.intensity && a.range == b.range &&
         a.innerConeAngle == b.innerConeAngle && a.outerConeAngle == b.outerConeAngle;
}

struct Texture {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // RGBA8, row 0 at the top (glTF UV v = 0)
  bool srgb = true;  // colour (base colour, emissive): sRGB-encoded; data (normals, …): linear
  bool repeatS = true, repeatT = true;
  bool mirrorS = false, mirrorT = false;
  bool linearMag = true;
  bool linearMin = true;
  bool mipmaps = true;
};

// A material's use of a texture (glTF textureInfo): which texture, which UV set, and the
// KHR_texture_transform of its UVs.
struct TextureRef {
  int texture = -1;  // index into Scene::textures; −1: none
  int texCoord = 0;  // 0: TEXCOORD_0, 1: TEXCOORD_1
  // uv' = (transform · (uv, 1)).xy: translation · rotation · scale, identity when absent.
  glm::mat3 transform{1.0f};
  bool operator==(const TextureRef& o) const {
    return texture == o.texture && texCoord == o.texCoord && transform == o.transform;
  }
};

enum class AlphaMode : std::uint8_t { Opaque, Mask, Blend };

// glTF 2.0 metallic-roughness, with its textures and the extensions that change a picture
// (scene/shading_model.h says how it is shaded).
struct Material {
  glm::vec4 baseColorFactor{1.0f};
  TextureRef baseColorTexture;  // sRGB
  float metallic = 1.0f;
  float roughness = 1.0f;
  TextureRef metallicRoughnessTexture;  // linear: B metalness, G roughness, times the factors
  TextureRef normalTexture;             // linear, tangent space
  float normalScale = 1.0f;
  TextureRef occlusionTexture;  // linear: R, on the ambient term only
  float occlusionStrength = 1.0f;
  glm::vec3 emissive{0.0f};    // emissiveFactor × KHR_materials_emissive_strength
  TextureRef emissiveTexture;  // sRGB
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;  // AlphaMode::Mask
  bool doubleSided = false;
  bool unlit = false;  // KHR_materials_unlit: base colour out, no lighting
  // KHR_materials_pbrSpecularGlossiness: baseColorFactor and baseColorTexture hold the
  // diffuse factor and texture, metallicRoughnessTexture the specular-glossiness texture
  // (sRGB specular colour, linear glossiness in A); metallic and roughness are unused.
  bool specularGlossiness = false;
  glm::vec3 specularFactor{1.0f};
  float glossiness = 1.0f;

  // The material's textures, in the order the G-buffer pass binds them.
  static constexpr int kTextureSlots = 5;
  const TextureRef& slot(int i) const {
    const TextureRef* slots[kTextureSlots] = {&baseColorTexture, &metallicRoughnessTexture,
                                              &normalTexture, &occlusionTexture, &emissiveTexture};
    return *slots[i];
  }
  TextureRef& slot(int i) { return const_cast<TextureRef&>(std::as_const(*this).slot(i)); }
  // Whether any texture reads UV set `set`.
  bool readsTexCoord(int set) const {
    for (int i = 0; i < kTextureSlots; ++i) {
      if (slot(i).texture >= 0 && slot(i).texCoord == set) return true;
    }
    return false;
  }
};

// What a primitive's indices list: triangles (3 each), line segments (2 each; strips and loops
// are expanded) or points (1 each).
enum class PrimitiveMode : std::uint8_t { Triangles, Lines, Points };

// One list of triangles, lines or points. Attributes are in the mesh's local space.
struct Primitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;      // same count as positions; empty for points and lines
  std::vector<glm::vec2> texcoords;    // TEXCOORD_0: empty or same count
  std::vector<glm::vec2> texcoords1;   // TEXCOORD_1, where a texture reads it: empty or same
  std::vector<glm::vec4> tangents;     // where a normal texture is used: empty or same (w ±1)
  std::vector<glm::vec4> colours;      // empty or same count (linear RGBA)
  std::vector<std::uint32_t> indices;  // by `mode`
  PrimitiveMode mode = PrimitiveMode::Triangles;
  int material = -1;  // index into Scene::materials; -1 for the default material
};

// What the half-edge pass (scene/half_edge.h) found over all primitives.
struct MeshTopology {
  long long degenerateTriangles = 0;  // dropped
  long long boundaryEdges = 0;
  long long nonManifoldEdges = 0;
};

struct Mesh {
  std::vector<Primitive> primitives;
};

struct MeshInstance {
  int mesh = 0;
  glm::mat4 world{1.0f};
};

// A glTF animation of a camera's node and its ancestors (scene/camera_animation.h evaluates
// it): the chain from the root to the camera's node, each node's rest transform and the
// tracks that move it (scene/animation_track.h).
struct CameraAnimation {
  std::vector<AnimatedNode> chain;  // root first, the camera's node last; empty: not animated
  float duration = 0.0f;            // seconds: the last key time of any track
};

struct Camera {
  bool orthographic = false;
  float yfov = 0.785398163397448f;  // radians, perspective
  float xmag = 1.0f, ymag = 1.0f;   // orthographic half extents
  float znear = 0.01f;
  float zfar = 0.0f;          // 0: infinite (perspective only)
  glm::mat4 world{1.0f};      // camera-to-world, unit scale; looks down −Z, +Y up
  CameraAnimation animation;  // the first glTF animation that moves it, if any
};

struct Bounds {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};
  bool empty = true;
  void add(glm::vec3 p);
};

struct Scene {
  std::string name;  // the file it came from, for messages
  std::vector<Mesh> meshes;
  std::vector<MeshInstance> instances;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Light> lights;
  // How glTF animations move and change `lights` (scene/light_animation.h).
  LightAnimation lightAnimation;
  std::vector<Camera> cameras;  // one per glTF camera, placed by the first node using it
  std::vector<std::string> warnings;
  // extensionsUsed that change nothing here (optional appearance extensions such as
  // KHR_materials_sheen, ignored as the glTF spec allows), for --verbose.
  std::vector<std::string> ignoredExtensions;
  MeshTopology topology;

  // World-space bounds of all instanced geometry.
  Bounds bounds() const;
};

// The material used by primitives without one: white, non-metallic, fully rough (pure
// Lambert), as the design documents prescribe.
Material defaultMaterial();

}  // namespace manylight
