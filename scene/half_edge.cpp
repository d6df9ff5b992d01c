#include "scene/half_edge.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <unordered_map>

namespace manylight {
namespace {

struct PositionHash {
  std::size_t operator()(const glm::vec3& p) const {
    std::uint32_t b[3];
    std::memcpy(b, &p, sizeof b);
    return (std::size_t(b[0]) * 73856093u) ^ (std::size_t(b[1]) * 19349663u) ^
           (std::size_t(b[2]) * 83492791u);
  }
};

std::uint64_t edgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}

glm::dvec3 faceCross(const std::vector<glm::vec3>& positions, const std::uint32_t* t) {
  const glm::dvec3 a(positions[t[0]]), b(positions[t[1]]), c(positions[t[2]]);
  return glm::cross(b - a, c - a);
}

}  // namespace

HalfEdgeMesh buildHalfEdgeMesh(const std::vector<glm::vec3>& positions,
                               const std::vector<std::uint32_t>& indices) {
  HalfEdgeMesh m;
  // Weld by position (-0 and +0 are different bits; a mesh writer would not mix them).
  std::unordered_map<glm::vec3, int, PositionHash> byPosition;
  m.welded.resize(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    m.welded[i] = byPosition.emplace(positions[i], int(byPosition.size())).first->second;
  }
  m.vertexIncoming.assign(byPosition.size(), -1);
  // Keep the faces with three distinct vertices and a non-zero area.
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::uint32_t* tri = &indices[t];
    const int a = m.welded[tri[0]], b = m.welded[tri[1]], c = m.welded[tri[2]];
    const glm::dvec3 n = faceCross(positions, tri);
    if (a == b || b == c || a == c || !(glm::dot(n, n) > 0.0)) {
      ++m.degenerateTriangles;
      continue;
    }
    const int f = int(m.faceEdge.size());
    m.faceEdge.push_back(3 * f);
    m.triangles.insert(m.triangles.end(), tri, tri + 3);
    const int corners[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      m.halfEdges.push_back({corners[(k + 1) % 3], -1, f, 3 * f + (k + 1) % 3});
      m.vertexIncoming[corners[(k + 1) % 3]] = 3 * f + k;
    }
  }
  // Twins: an edge with exactly two half-edges running opposite ways.
  std::unordered_map<std::uint64_t, std::vector<int>> edges;
  for (int h = 0; h < int(m.halfEdges.size()); ++h)
    edges[edgeKey(m.origin(h), m.halfEdges[h].target)].push_back(h);
  for (const auto& [key, list] : edges) {
    if (list.size() == 1) {
      ++m.boundaryEdges;
    } else if (list.size() == 2 && m.origin(list[0]) == m.halfEdges[list[1]].target) {
      m.halfEdges[list[0]].twin = list[1];
      m.halfEdges[list[1]].twin = list[0];
    } else {
      ++m.nonManifoldEdges;
    }
  }
  return m;
}

CreasedNormals creasedNormals(const HalfEdgeMesh& m, const std::vector<glm::vec3>& positions,
                              float creaseRadians) {
  const int faces = int(m.faceEdge.size());
  std::vector<glm::dvec3> faceNormal(faces);
  for (int f = 0; f < faces; ++f)
    faceNormal[f] = glm::normalize(faceCross(positions, &m.triangles[3 * f]));
  const double cosCrease = std::cos(double(creaseRadians));
  auto smooth = [&](int h) {  // whether the edge of half-edge h joins its faces smoothly
    const int t = m.halfEdges[h].twin;
    return t >= 0 &&
           glm::dot(faceNormal[m.halfEdges[h].face], faceNormal[m.halfEdges[t].face]) >= cosCrease;
  };
  // The corner of face f at its vertex k: angle-weighted normal.
  auto cornerWeight = [&](int f, int k) {
    const glm::dvec3 p(positions[m.triangles[3 * f + k]]);
    const glm::dvec3 u =
        glm::normalize(glm::dvec3(positions[m.triangles[3 * f + (k + 1) % 3]]) - p);
    const glm::dvec3 v =
        glm::normalize(glm::dvec3(positions[m.triangles[3 * f + (k + 2) % 3]]) - p);
    return std::acos(std::clamp(glm::dot(u, v), -1.0, 1.0)) * faceNormal[f];
  };
  CreasedNormals out;
  out.indices.resize(m.triangles.size());
  // One output vertex per (input vertex, smooth fan); a fan is named by its smallest face.
  std::map<std::pair<std::uint32_t, int>, std::uint32_t> vertexOf;
  for (int f = 0; f < faces; ++f) {
    for (int k = 0; k < 3; ++k) {
      // Half-edge of f ending at corner k: 3f + (k + 2) % 3 (3f + j ends at corner j + 1).
      const int start = 3 * f + (k + 2) % 3;
      glm::dvec3 sum(0.0);
      int smallest = f;
      // Turn one way: across the edge leaving the vertex, h → twin(next(h)).
      int h = start;
      bool closed = false;
      do {
        const int face = m.halfEdges[h].face;
        const int corner = (h - 3 * face + 1) % 3;
        sum += cornerWeight(face, corner);
        smallest = std::min(smallest, face);
        const int leaving = m.halfEdges[h].next;
        if (!smooth(leaving)) break;
        h = m.halfEdges[leaving].twin;
        closed = h == start;
      } while (!closed);
      // And the other way, across the edge arriving, unless the fan closed: h → prev(twin(h)).
      if (!closed) {
        h = start;
        while (smooth(h)) {
          h = m.prev(m.halfEdges[h].twin);
          if (h == start) break;
          const int face = m.halfEdges[h].face;
          sum += cornerWeight(face, (h - 3 * face + 1) % 3);
          smallest = std::min(smallest, face);
        }
      }
      const std::uint32_t input = m.triangles[3 * f + k];
      const auto [it, added] =
          vertexOf.emplace(std::make_pair(input, smallest), std::uint32_t(out.source.size()));
      if (added) {
        out.source.push_back(input);
        out.normals.push_back(glm::vec3(glm::normalize(sum)));
      }
      out.indices[3 * f + k] = it->second;
    }
  }
  return out;
}

}  // namespace manylight
