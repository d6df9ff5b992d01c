#include "scene/tangents.h"

#include <cmath>

namespace manylight {
namespace {

glm::vec3 anyOrthogonal(glm::vec3 n) {
  const glm::vec3 axis = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 t = glm::cross(n, axis);
  const float len = glm::length(t);
  return len > 0.0f ? t / len : glm::vec3(1, 0, 0);
}

}  // namespace

std::vector<glm::vec4> uvTangents(const std::vector<glm::vec3>& positions,
                                  const std::vector<glm::vec3>& normals,
                                  const std::vector<glm::vec2>& uvs,
                                  const std::vector<std::uint32_t>& indices) {
  std::vector<glm::dvec3> tan(positions.size(), glm::dvec3(0.0));
  std::vector<glm::dvec3> bitan(positions.size(), glm::dvec3(0.0));
  for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
    const std::uint32_t a = indices[i], b = indices[i + 1], c = indices[i + 2];
    const glm::dvec3 e1 = glm::dvec3(positions[b]) - glm::dvec3(positions[a]);
    const glm::dvec3 e2 = glm::dvec3(positions[c]) - glm::dvec3(positions[a]);
    const glm::dvec2 d1 = glm::dvec2(uvs[b]) - glm::dvec2(uvs[a]);
    const glm::dvec2 d2 = glm::dvec2(uvs[c]) - glm::dvec2(uvs[a]);
    const double det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(det) > 1e-20)) continue;
    // Unnormalised by |det| so each face weighs by its area in space; the sign of det keeps
    // its UV orientation.
    const double s = det > 0.0 ? 1.0 : -1.0;
    const glm::dvec3 t = s * (e1 * d2.y - e2 * d1.y);
    const glm::dvec3 bt = s * (e2 * d1.x - e1 * d2.x);
    for (std::uint32_t v : {a, b, c}) {
      tan[v] += t;
      bitan[v] += bt;
    }
  }
  std::vector<glm::vec4> out(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const glm::dvec3 n = glm::dvec3(normals[v]);
    glm::dvec3 t = tan[v] - n * glm::dot(n, tan[v]);
    const double len = glm::length(t);
    if (!(len > 1e-12) || !std::isfinite(len)) {
      out[v] = glm::vec4(anyOrthogonal(normals[v]), 1.0f);
      continue;
    }
    t /= len;
    // glTF's v runs down the image and a normal texture's +Y up it, so the bitangent
    // cross(n, t) · w points along −∂p/∂v.
    const double w = glm::dot(glm::cross(n, t), bitan[v]) > 0.0 ? -1.0 : 1.0;
    out[v] = glm::vec4(glm::vec3(t), float(w));
  }
  return out;
}

}  // namespace manylight
