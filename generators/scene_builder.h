#pragma once
// Writes procedural glTF scenes: the bundled sample, and the generated scenes the tests and
// benchmarks render (so they go through the same loader as users' files).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace manylight {

// An optional texture of a material: RGBA8, row 0 at the top; sampled with LINEAR (or
// `nearest`) filtering, no mipmaps, REPEAT wrapping, from TEXCOORD_`texCoord`; `transform`
// writes a KHR_texture_transform (offset, rotation, scale).
struct BuilderTexture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // empty: no texture
  int texCoord = 0;
  bool nearest = false;
  bool transform = false;
  glm::vec2 offset{0.0f}, scale{1.0f};
  float rotation = 0.0f;
};

struct BuilderMaterial {
  glm::vec4 baseColor{1.0f};
  float metallic = 0.0f;
  float roughness = 1.0f;
  glm::vec3 emissive{0.0f};
  bool doubleSided = false;
  // Optional base-colour texture (sRGB).
  int textureWidth = 0, textureHeight = 0;
  std::vector<std::uint8_t> textureRgba;
  bool textureNearest = false;
  // The other core textures, and what only tests of the loader write.
  BuilderTexture metallicRoughness, normal, occlusion, emissiveTexture;
  float normalScale = 1.0f, occlusionStrength = 1.0f;
  std::string alphaMode = "OPAQUE";
  float alphaCutoff = 0.5f;
  float emissiveStrength = 1.0f;  // written as KHR_materials_emissive_strength when not 1
  bool unlit = false;             // KHR_materials_unlit
  // KHR_materials_pbrSpecularGlossiness when set: baseColor and the base-colour texture are
  // written as its diffuse factor and texture, `specularGlossinessTexture` beside them.
  bool specularGlossiness = false;
  glm::vec3 specularFactor{1.0f};
  float glossiness = 1.0f;
  BuilderTexture specularGlossinessTexture;
};

class GltfBuilder {
 public:
  GltfBuilder();
  ~GltfBuilder();
  GltfBuilder(const GltfBuilder&) = delete;
  GltfBuilder& operator=(const GltfBuilder&) = delete;

  int addMaterial(const BuilderMaterial& m);
  // Unit shapes placed by translation and scale: a box [-0.5, 0.5]³, a sphere of radius 0.5,
  // a plane [-0.5, 0.5]² in XZ facing +Y with UVs over [0, 1]². Return the node index.
  int addBox(glm::vec3 centre, glm::vec3 size, int material, glm::vec4 rotation = {0, 0, 0, 1});
  int addSphere(glm::vec3 centre, float diameter, int material, int segments = 24);
  int addPlane(glm::vec3 centre, glm::vec2 size, int material);
  // The plane above with a second UV set, TEXCOORD_1 = (1 − u, v) (a mirrored copy).
  int addPlaneWithSecondUvs(glm::vec3 centre, glm::vec2 size, int material);
  void addLight(const Light& light);
  void addPerspectiveCamera(glm::vec3 eye, glm::vec3 target, float yfovRadians);
  void addOrthographicCamera(glm::vec3 eye, glm::vec3 target, float xmag, float ymag);

  // Writes a .gltf with the buffer embedded as a data URI, or a .glb (by extension).
  // Throws SceneError when the file cannot be written.
  void write(const std::string& path) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The scene most tests and benchmarks render: a floor, a back wall, a box, a sphere and a
// textured panel, lit by `lightCount` lights from a fixed seed. `mix` chooses point, spot and
// directional in turn; otherwise all are point lights. `withRange` gives every other
// point/spot light a range.
struct RoomOptions {
  int lightCount = 8;
  std::uint32_t seed = 1;
  bool mix = true;
  bool withRange = true;
  bool textured = true;
  bool specular = false;
  // When not empty: these lights (generators/light_layouts.h), and none generated.
  std::vector<Light> lights;
};
void writeRoomScene(const std::string& path, const RoomOptions& options);

// The Cornell-like room of docs/indirect.md: the five inner faces of the box [−1, 1] × [0, 2]
// × [−1, 1] (open towards +Z), Lambert walls, white but for a red left (x = −1) and a green
// right (x = 1) wall, one spot light under the ceiling pointing down (cornellSpot), and a
// camera looking in from +Z. `extraLights` adds that many lights inside the room (point,
// spot and directional in turn, half of the point and spot ones ranged), their intensities
// summing to about half the spot's.
struct CornellOptions {
  int extraLights = 0;
  std::uint32_t seed = 1;
  // A white block standing on the floor, right of the spot, 0.5 × 0.8 × 0.5: the room is then
  // not convex, and shows what indirect light without visibility misses (the gallery).
  bool block = false;
};
void writeCornellScene(const std::string& path, const CornellOptions& options);
// A wall: the rectangle origin + s·u + t·v, s, t ∈ [0, 1], facing into the room along
// `normal`, of Lambert albedo `albedo` (its base colour).
struct CornellWall {
  glm::vec3 origin, u, v, normal, albedo;
};
std::vector<CornellWall> cornellWalls();
Light cornellSpot();

// `count` lights scattered uniformly in the box [0, extent] from seed `seed`: all point
// lights, or point, spot and directional in turn (`mixed`); random colours, intensities in
// [0.5, 1.5], three in four with a range, spot cones of 0.2–0.8 rad. For tests and
// benchmarks of light structures.
std::vector<Light> scatteredLights(int count, bool mixed, std::uint32_t seed, glm::vec3 extent);

}  // namespace manylight
