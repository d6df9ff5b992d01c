#pragma once
// Per-vertex tangents for normal mapping where a primitive has no TANGENT attribute.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace manylight {

// Tangents of triangles `indices` from their UVs: each vertex sums the UV-space tangent and
// bitangent of its faces (area-weighted), then the tangent is made orthogonal to the normal
// (Gram-Schmidt) and w is the handedness, ±1. glTF asks for MikkTSpace; this is the classic
// per-vertex method (Lengyel), which agrees with it on meshes whose UV islands split their
// vertices and can differ where faces sharing a vertex have mirrored or sheared UVs. A vertex
// whose faces have degenerate UVs gets any unit vector orthogonal to its normal.
std::vector<glm::vec4> uvTangents(const std::vector<glm::vec3>& positions,
                                  const std::vector<glm::vec3>& normals,
                                  const std::vector<glm::vec2>& uvs,
                                  const std::vector<std::uint32_t>& indices);

}  // namespace manylight
