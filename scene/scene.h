#pragma once
// The scene as the renderer sees it: world-space lights and cameras, meshes with their
// instances, materials and decoded textures. Plain data; no GL.
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

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

struct Texture {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // sRGB-encoded RGBA8, row 0 at the top (glTF UV v = 0)
  bool repeatS = true, repeatT = true;
  bool mirrorS = false, mirrorT = false;
  bool linearMag = true;
  bool linearMin = true;
  bool mipmaps = true;
};

struct Material {
  glm::vec4 baseColorFactor{1.0f};
  int baseColorTexture = -1;  // index into Scene::textures
  float metallic = 1.0f;
  float roughness = 1.0f;
  glm::vec3 emissive{0.0f};
  bool doubleSided = false;
};

// One triangle list. Attributes are in the mesh's local space.
struct Primitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;      // same count as positions
  std::vector<glm::vec2> texcoords;    // empty or same count
  std::vector<glm::vec4> colours;      // empty or same count (linear RGBA)
  std::vector<std::uint32_t> indices;  // triangles, 3 per face
  int material = -1;                   // index into Scene::materials; -1 for the default material
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
// tracks that move it.
struct AnimationTrack {
  enum Path : std::uint8_t { Translation, Rotation, Scale } path = Translation;
  enum Interpolation : std::uint8_t { Linear, Step, CubicSpline } interpolation = Linear;
  std::vector<float> times;   // seconds, increasing
  std::vector<float> values;  // 3 (4 for rotation, xyzw) floats per key; ×3 for cubic spline
};
struct AnimatedNode {
  glm::mat4 matrix{1.0f};  // used when the node gives a matrix (such nodes are not animated)
  bool hasMatrix = false;
  glm::vec3 translation{0.0f};
  glm::vec4 rotation{0.0f, 0.0f, 0.0f, 1.0f};  // quaternion xyzw
  glm::vec3 scale{1.0f};
  std::vector<AnimationTrack> tracks;
};
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
  std::vector<Camera> cameras;  // one per glTF camera, placed by the first node using it
  std::vector<std::string> warnings;
  MeshTopology topology;

  // World-space bounds of all instanced geometry.
  Bounds bounds() const;
};

// The material used by primitives without one: white, non-metallic, fully rough (pure
// Lambert), as the design documents prescribe.
Material defaultMaterial();

}  // namespace manylight
