#pragma once
// Mesh topology: a half-edge structure over a triangle list, after welding vertices by
// position. Per half-edge: target vertex, twin, face, next; per face one half-edge; per
// vertex one incoming half-edge. Used to drop degenerate triangles, count boundary and
// non-manifold edges, and build normals where a primitive has none.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace manylight {

struct HalfEdgeMesh {
  struct HalfEdge {
    int target;  // welded vertex this half-edge points to
    int twin;    // the opposite half-edge; −1 on a boundary or non-manifold edge
    int face;
    int next;  // within the face
  };
  std::vector<HalfEdge> halfEdges;       // 3 per kept face: face f owns 3f, 3f+1, 3f+2
  std::vector<int> faceEdge;             // one half-edge per face (3f)
  std::vector<int> vertexIncoming;       // per welded vertex: one half-edge ending there, or −1
  std::vector<int> welded;               // per input vertex: its welded vertex
  std::vector<std::uint32_t> triangles;  // kept faces, 3 input vertex indices each
  int degenerateTriangles = 0;           // dropped: a repeated (welded) vertex or zero area
  int boundaryEdges = 0;                 // edges with one face
  int nonManifoldEdges = 0;  // edges with more than two faces, or two facing the same way

  int origin(int h) const { return halfEdges[prev(h)].target; }
  int prev(int h) const { return halfEdges[halfEdges[h].next].next; }
};

// Builds the structure for triangles `indices` (3 per face) over `positions`; vertices at
// bit-identical positions are welded.
HalfEdgeMesh buildHalfEdgeMesh(const std::vector<glm::vec3>& positions,
                               const std::vector<std::uint32_t>& indices);

// Normals for the kept faces of `mesh`: around each vertex, faces joined by edges whose
// dihedral angle is below `creaseRadians` share one normal (the angle-weighted mean of
// their face normals); sharper, boundary and non-manifold edges split it, so an isolated
// triangle gets its face normal. Output vertex k copies input vertex source[k].
struct CreasedNormals {
  std::vector<std::uint32_t> source;
  std::vector<glm::vec3> normals;
  std::vector<std::uint32_t> indices;  // 3 per kept face, into the output vertices
};
CreasedNormals creasedNormals(const HalfEdgeMesh& mesh, const std::vector<glm::vec3>& positions,
                              float creaseRadians);

}  // namespace manylight
