#pragma once
// A scene uploaded to the GPU once: vertex and index buffers per primitive, textures, and
// the light texture sized to the scene's lights (never to the budget).
#include <vector>

#include "gl/objects.h"
#include "gl/texture_buffer.h"
#include "scene/scene.h"

namespace manylight {

class GpuScene {
 public:
  // Uploads `scene` with `lights` (the scene's own, or a default rig). Throws gl::GlError
  // when the driver cannot hold the lights.
  GpuScene(const Scene& scene, const std::vector<Light>& lights);

  // Uploads `lights` in place of the current ones (the geometry stays). Throws gl::GlError.
  void replaceLights(const std::vector<Light>& lights);

  struct Draw {
    const gl::VertexArray* vao;
    GLsizei indexCount;
    GLenum mode;  // GL_TRIANGLES, GL_LINES or GL_POINTS
    bool hasNormals, hasTexcoords, hasTexcoords1, hasTangents, hasColours;
    int material;  // −1: default material
    glm::mat4 model;
    glm::mat3 normalMatrix;  // inverse transpose of the model's upper 3×3
    bool mirrored;           // negative determinant
    bool blended;            // alphaMode BLEND: drawn after the opaque frame is lit
    glm::vec3 centre;        // world-space centre of the primitive's bounds (blend order)
  };
  const std::vector<Draw>& draws() const { return draws_; }
  const gl::Texture* texture(int index) const { return &textures_[index]; }
  const gl::Texture& lightTexture() const { return lightTexture_.texture; }
  int lightCount() const { return lightCount_; }
  // Where point and spot lights start in the light texture (see light_texture_layout.h).
  int pointStart() const { return pointStart_; }
  int spotStart() const { return spotStart_; }
  // Whether any drawn material has a Phong specular term (see scene/shading_model.h).
  bool hasSpecular() const { return hasSpecular_; }
  // Whether any draw is blended (alphaMode BLEND).
  bool hasBlended() const { return hasBlended_; }

 private:
  struct GpuPrimitive {
    gl::VertexArray vao;
    std::vector<gl::Buffer> buffers;
    GLsizei indexCount = 0;
    GLenum mode = GL_TRIANGLES;
    bool hasNormals = false, hasTexcoords = false, hasTexcoords1 = false, hasTangents = false,
         hasColours = false;
    int material = -1;
    glm::vec3 centre{0.0f};  // local-space centre of the bounds
  };
  std::vector<std::vector<GpuPrimitive>> meshes_;
  std::vector<gl::Texture> textures_;
  std::vector<Draw> draws_;
  gl::TextureBuffer lightTexture_;
  int lightCount_ = 0, pointStart_ = 0, spotStart_ = 0;
  bool hasSpecular_ = false, hasBlended_ = false;
};

}  // namespace manylight
