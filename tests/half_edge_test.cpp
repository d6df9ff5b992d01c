// The half-edge structure (scene/half_edge.h) on hand-made meshes.
#include "scene/half_edge.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/constants.hpp>

namespace manylight {
namespace {

struct TestMesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
};

// A unit cube with 24 vertices (4 per face, as exporters write it) and 12 triangles.
TestMesh cube() {
  TestMesh m;
  const glm::vec3 n[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const glm::vec3& normal : n) {
    const glm::vec3 u = std::abs(normal.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 v = glm::cross(normal, u);
    const std::uint32_t base = std::uint32_t(m.positions.size());
    for (int k = 0; k < 4; ++k) {
      const float a = (k == 1 || k == 2) ? 1.0f : -1.0f, b = k >= 2 ? 1.0f : -1.0f;
      m.positions.push_back(0.5f * (normal + a * u + b * v));
    }
    // Counter-clockwise seen from outside: u × v = normal.
    for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
  }
  return m;
}

// An n×n grid of quads in the plane z = 0.
TestMesh grid(int n) {
  TestMesh m;
  for (int y = 0; y <= n; ++y) {
    for (int x = 0; x <= n; ++x) m.positions.push_back({float(x), float(y), 0.0f});
  }
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const std::uint32_t a = std::uint32_t(y * (n + 1) + x), b = a + 1, c = a + n + 2,
                          d = a + n + 1;
      for (std::uint32_t i : {a, b, c, a, c, d}) m.indices.push_back(i);
    }
  }
  return m;
}

TEST(HalfEdge, CubeIsClosedWithTwelveFacesAndFaceNormals) {
  const TestMesh c = cube();
  const HalfEdgeMesh m = buildHalfEdgeMesh(c.positions, c.indices);
  EXPECT_EQ(m.faceEdge.size(), 12u);
  EXPECT_EQ(m.halfEdges.size(), 36u);
  EXPECT_EQ(m.boundaryEdges, 0);
  EXPECT_EQ(m.nonManifoldEdges, 0);
  EXPECT_EQ(m.degenerateTriangles, 0);
  int welded = 0;
  for (int v : m.welded) welded = std::max(welded, v + 1);
  EXPECT_EQ(welded, 8);
  for (const auto& h : m.halfEdges) {
    ASSERT_GE(h.twin, 0);
    EXPECT_EQ(m.halfEdges[h.twin].twin, &h - m.halfEdges.data());
    EXPECT_EQ(m.halfEdges[h.next].face, h.face);
  }
  for (std::size_t v = 0; v < m.vertexIncoming.size(); ++v)
    EXPECT_EQ(m.halfEdges[m.vertexIncoming[v]].target, int(v));
  // 90° edges are creases at the default 60°: every corner gets its face's normal.
  const CreasedNormals n = creasedNormals(m, c.positions, glm::radians(60.0f));
  ASSERT_EQ(n.indices.size(), 36u);
  for (std::size_t f = 0; f < 12; ++f) {
    const glm::vec3 a = c.positions[c.indices[3 * f]], b = c.positions[c.indices[3 * f + 1]],
                    d = c.positions[c.indices[3 * f + 2]];
    const glm::vec3 face = glm::normalize(glm::cross(b - a, d - a));
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(glm::dot(n.normals[n.indices[3 * f + k]], face), 1.0f, 1e-6f);
  }
  EXPECT_EQ(n.source.size(), 24u);  // the 24 input vertices, one normal each
}

TEST(HalfEdge, OpenGridHasItsPerimeterAsBoundary) {
  const TestMesh g = grid(3);
  const HalfEdgeMesh m = buildHalfEdgeMesh(g.positions, g.indices);
  EXPECT_EQ(m.faceEdge.size(), 18u);
  EXPECT_EQ(m.boundaryEdges, 12);
  EXPECT_EQ(m.nonManifoldEdges, 0);
  const CreasedNormals n = creasedNormals(m, g.positions, glm::radians(60.0f));
  for (const glm::vec3& v : n.normals) EXPECT_NEAR(v.z, 1.0f, 1e-6f);
  EXPECT_EQ(n.source.size(), 16u);  // flat: one smooth fan per vertex
}

TEST(HalfEdge, BowTieEdgeSharedByThreeFacesIsNonManifold) {
  // Three triangles on the edge (0,0,0)–(1,0,0), fanned around it.
  const std::vector<glm::vec3> p = {
      {0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, -1, 0}, {0.5f, 0, 1}};
  const std::vector<std::uint32_t> idx = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  const HalfEdgeMesh m = buildHalfEdgeMesh(p, idx);
  EXPECT_EQ(m.nonManifoldEdges, 1);
  EXPECT_EQ(m.boundaryEdges, 6);
  // No smoothing across a non-manifold edge: each face keeps its own normal.
  const CreasedNormals n = creasedNormals(m, p, glm::radians(179.0f));
  EXPECT_EQ(n.source.size(), 9u);
}

TEST(HalfEdge, DegenerateTrianglesAreDropped) {
  TestMesh g = grid(1);
  g.positions.push_back(g.positions[0]);  // a duplicate of vertex 0: welded to it
  const std::uint32_t dup = std::uint32_t(g.positions.size() - 1);
  for (std::uint32_t i : {0u, 0u, 1u, 0u, dup, 2u, 0u, 1u, 1u})
    g.indices.push_back(i);  // repeated indices
  g.positions.push_back({2, 0, 0});
  for (std::uint32_t i : {0u, 1u, std::uint32_t(g.positions.size() - 1)})
    g.indices.push_back(i);  // collinear
  const HalfEdgeMesh m = buildHalfEdgeMesh(g.positions, g.indices);
  EXPECT_EQ(m.degenerateTriangles, 4);
  EXPECT_EQ(m.faceEdge.size(), 2u);
  EXPECT_EQ(m.triangles.size(), 6u);
}

TEST(HalfEdge, SphereNormalsAreSmooth) {
  // A UV sphere with duplicated seam vertices: welding joins the seam, so normals are radial.
  TestMesh s;
  const int rings = 16, segments = 32;
  for (int r = 0; r <= rings; ++r) {
    for (int k = 0; k <= segments; ++k) {
      const float theta = glm::pi<float>() * r / rings,
                  phi = 2.0f * glm::pi<float>() * (k % segments) / segments;
      glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta),
                  std::sin(theta) * std::sin(phi));
      if (r == 0 || r == rings) p = {0.0f, r == 0 ? 1.0f : -1.0f, 0.0f};  // exact poles
      s.positions.push_back(p);  // the seam (k = segments) repeats k = 0 bit for bit
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int k = 0; k < segments; ++k) {
      const std::uint32_t a = r * (segments + 1) + k, b = a + 1, c = a + segments + 2,
                          d = a + segments + 1;
      for (std::uint32_t i : {a, b, c, a, c, d}) s.indices.push_back(i);
    }
  }
  const HalfEdgeMesh m = buildHalfEdgeMesh(s.positions, s.indices);
  EXPECT_EQ(m.boundaryEdges, 0);
  EXPECT_EQ(m.degenerateTriangles, 2 * segments);  // the pole rows collapse to triangles
  const CreasedNormals n = creasedNormals(m, s.positions, glm::radians(60.0f));
  for (std::size_t i = 0; i < n.source.size(); ++i) {
    const glm::vec3 radial = glm::normalize(s.positions[n.source[i]]);
    EXPECT_GT(glm::dot(n.normals[i], radial), 0.995f) << "vertex " << n.source[i];
  }
}

}  // namespace
}  // namespace manylight
