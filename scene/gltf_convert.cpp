#include "scene/gltf_convert.h"

#include <tiny_gltf.h>

#include <cmath>
#include <type_traits>

#include "base/error.h"
#include "scene/gltf_attributes.h"
#include "scene/gltf_bulk.h"
#include "scene/half_edge.h"
#include "scene/tangents.h"

namespace manylight::gltf {
namespace {

constexpr double kHalfPi = 1.57079632679489661923;

std::string str(int i) { return std::to_string(i); }

template <typename T>
void checkIndex(int index, const std::vector<T>& v, const std::string& what) {
  if (index < 0 || std::size_t(index) >= v.size()) {
    throw SceneError(what + " " + str(index) + " does not exist");
  }
}

// The indices of a primitive mode as triangle, line-segment or point lists.
std::vector<std::uint32_t> assemble(int mode, std::vector<std::uint32_t> idx) {
  std::vector<std::uint32_t> out;
  switch (mode) {
    case TINYGLTF_MODE_TRIANGLES:
      idx.resize(idx.size() / 3 * 3);
      return idx;
    case TINYGLTF_MODE_TRIANGLE_STRIP:
      for (std::size_t i = 2; i < idx.size(); ++i) {
        const bool even = (i % 2) == 0;
        out.insert(out.end(), {idx[i - 2], even ? idx[i - 1] : idx[i], even ? idx[i] : idx[i - 1]});
      }
      return out;
    case TINYGLTF_MODE_TRIANGLE_FAN:
      for (std::size_t i = 2; i < idx.size(); ++i)
        out.insert(out.end(), {idx[i - 1], idx[i], idx[0]});
      return out;
    case TINYGLTF_MODE_LINE:
      idx.resize(idx.size() / 2 * 2);
      return idx;
    case TINYGLTF_MODE_LINE_STRIP:
    case TINYGLTF_MODE_LINE_LOOP:
      for (std::size_t i = 1; i < idx.size(); ++i) out.insert(out.end(), {idx[i - 1], idx[i]});
      if (mode == TINYGLTF_MODE_LINE_LOOP && idx.size() > 2)
        out.insert(out.end(), {idx.back(), idx[0]});
      return out;
    default:  // points
      return idx;
  }
}

PrimitiveMode modeOf(int mode) {
  if (mode == TINYGLTF_MODE_POINTS) return PrimitiveMode::Points;
  if (mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
      mode == TINYGLTF_MODE_LINE_STRIP)
    return PrimitiveMode::Lines;
  return PrimitiveMode::Triangles;
}

// Drops degenerate triangles, counts boundary and non-manifold edges into `topology`, and
// builds creased normals when the primitive has none (glTF prescribes flat ones; a crease
// angle gives those on sharp edges and smooth shading on curved surfaces).
void buildTopology(Primitive& p, float creaseRadians, MeshTopology& topology) {
  const HalfEdgeMesh m = buildHalfEdgeMesh(p.positions, p.indices);
  topology.degenerateTriangles += m.degenerateTriangles;
  topology.boundaryEdges += m.boundaryEdges;
  topology.nonManifoldEdges += m.nonManifoldEdges;
  if (!p.normals.empty()) {
    p.indices = m.triangles;
    return;
  }
  const CreasedNormals n = creasedNormals(m, p.positions, creaseRadians);
  Primitive out;
  out.material = p.material;
  out.indices = n.indices;
  out.normals = n.normals;
  for (std::uint32_t v : n.source) {
    out.positions.push_back(p.positions[v]);
    if (!p.texcoords.empty()) out.texcoords.push_back(p.texcoords[v]);
    if (!p.texcoords1.empty()) out.texcoords1.push_back(p.texcoords1[v]);
    if (!p.colours.empty()) out.colours.push_back(p.colours[v]);
  }
  // TANGENT is meaningless without the normals it was made for; they are made anew below.
  p = std::move(out);
}

template <typename V>
std::vector<V> toVectors(const std::vector<float>& f, int n, bool requireFinite,
                         const std::string& what) {
  std::vector<V> out(f.size() / n);
  for (std::size_t i = 0; i < out.size(); ++i) {
    for (int c = 0; c < n; ++c) {
      const float x = f[i * n + c];
      if (requireFinite && !std::isfinite(x)) {
        throw SceneError(what + ": element " + std::to_string(i) + " is not finite");
      }
      out[i][c] = x;
    }
  }
  return out;
}

}  // namespace

glm::mat4 withoutScale(const glm::mat4& world) {
  glm::mat4 m(1.0f);
  for (int c = 0; c < 3; ++c) {
    const glm::vec3 axis(world[c]);
    const float len = glm::length(axis);
    m[c] = glm::vec4(len > 0.0f ? axis / len : glm::vec3(0.0f), 0.0f);
  }
  m[3] = world[3];
  return m;
}

int primitiveMode(const tinygltf::Primitive& p) {
  return p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
}

long long triangleCount(int mode, long long count) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return count / 3;
  if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN)
    return std::max(count - 2, 0ll);
  return 0;
}

Converter::Converter(const tinygltf::Model& model, const BulkArrays& bulk, Scene& scene,
                     float creaseRadians)
    : model_(model),
      bulk_(bulk),
      scene_(scene),
      meshes_(model.meshes.size(), -1),
      materials_(model, scene),
      creaseRadians_(creaseRadians) {}

int Converter::mesh(int index) {
  checkIndex(index, model_.meshes, "mesh");
  if (meshes_[index] >= 0) return meshes_[index];
  Mesh mesh;
  for (std::size_t p = 0; p < model_.meshes[index].primitives.size(); ++p) {
    Primitive prim = primitive(index, int(p));
    if (!prim.indices.empty()) mesh.primitives.push_back(std::move(prim));
  }
  meshes_[index] = int(scene_.meshes.size());
  scene_.meshes.push_back(std::move(mesh));
  return meshes_[index];
}

Primitive Converter::primitive(int meshIndex, int primIndex) {
  const tinygltf::Primitive& src = model_.meshes[meshIndex].primitives[primIndex];
  const std::string where = "mesh " + str(meshIndex) + " primitive " + str(primIndex);
  Primitive p;
  const int mode = primitiveMode(src);
  if (mode < TINYGLTF_MODE_POINTS || mode > TINYGLTF_MODE_TRIANGLE_FAN) {
    scene_.warnings.push_back(where + ": unknown mode " + str(mode) + "; skipped");
    return p;
  }
  p.mode = modeOf(mode);
  // Every attribute and the indices are read through `source`: from the accessors, or from
  // the primitive's decoded KHR_draco_mesh_compression data.
  const AttributeSource source(model_, src, where);
  auto attr = [&](const std::string& name) { return source.accessor(name); };
  if (attr("POSITION") < 0) {
    scene_.warnings.push_back(where + ": no POSITION attribute; skipped");
    return p;
  }
  p.positions = toVectors<glm::vec3>(source.floats("POSITION", 3), 3, true, where + " POSITION");
  const std::size_t count = p.positions.size();
  auto sameCount = [&](std::size_t n, const std::string& what) {
    if (n != count) {
      throw SceneError(where + ": " + what + " has " + std::to_string(n) + " elements, POSITION " +
                       std::to_string(count));
    }
  };
  auto read = [&](const std::string& name, int n, bool requireFinite, auto& out) {
    using V = typename std::decay_t<decltype(out)>::value_type;
    if (attr(name) < 0) return;
    out = toVectors<V>(source.floats(name, n), n, requireFinite, where + " " + name);
    sameCount(out.size(), name);
  };
  read("NORMAL", 3, true, p.normals);
  p.material = src.material >= 0 ? materials_.material(src.material) : -1;
  const Material* m = p.material >= 0 ? &scene_.materials[p.material] : nullptr;
  read("TEXCOORD_0", 2, false, p.texcoords);
  if (m && m->readsTexCoord(1)) read("TEXCOORD_1", 2, false, p.texcoords1);
  const bool normalMapped =
      p.mode == PrimitiveMode::Triangles && m && m->normalTexture.texture >= 0;
  if (normalMapped && !p.normals.empty()) read("TANGENT", 4, true, p.tangents);
  if (attr("COLOR_0") >= 0) {
    const int acc = attr("COLOR_0");
    checkIndex(acc, model_.accessors, "accessor");
    const int n = model_.accessors[acc].type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
    const std::vector<float> f = source.floats("COLOR_0", n);
    p.colours.resize(f.size() / n);
    for (std::size_t i = 0; i < p.colours.size(); ++i) {
      p.colours[i] = glm::vec4(f[i * n], f[i * n + 1], f[i * n + 2], n == 4 ? f[i * n + 3] : 1.0f);
    }
    sameCount(p.colours.size(), "COLOR_0");
  }
  std::vector<std::uint32_t> idx;
  if (source.hasIndices()) {
    idx = source.indices();
    for (std::uint32_t i : idx) {
      if (i >= count) {
        throw SceneError(where + ": index " + std::to_string(i) + " is out of range (" +
                         std::to_string(count) + " vertices)");
      }
    }
  } else {
    idx.resize(count);
    for (std::size_t i = 0; i < count; ++i) idx[i] = std::uint32_t(i);
  }
  p.indices = assemble(mode, std::move(idx));
  if (p.mode != PrimitiveMode::Triangles) return p;
  buildTopology(p, creaseRadians_, scene_.topology);
  if (normalMapped && p.tangents.empty()) {
    const std::vector<glm::vec2>& uvs = m->normalTexture.texCoord == 1 ? p.texcoords1 : p.texcoords;
    if (!uvs.empty()) p.tangents = uvTangents(p.positions, p.normals, uvs, p.indices);
  }
  return p;
}

Camera Converter::camera(int index) const {
  const tinygltf::Camera& src = model_.cameras[index];
  Camera c;
  const std::string where = "camera " + str(index);
  if (src.type == "orthographic") {
    c.orthographic = true;
    c.xmag = float(src.orthographic.xmag);
    c.ymag = float(src.orthographic.ymag);
    c.znear = float(src.orthographic.znear);
    c.zfar = float(src.orthographic.zfar);
    if (!(c.xmag != 0.0f && c.ymag != 0.0f && c.zfar > c.znear && c.znear >= 0.0f)) {
      throw SceneError(where + ": orthographic xmag, ymag must be non-zero and zfar > znear >= 0");
    }
  } else if (src.type == "perspective") {
    c.yfov = float(src.perspective.yfov);
    c.znear = float(src.perspective.znear);
    c.zfar = float(src.perspective.zfar);
    if (!(c.yfov > 0.0f && c.yfov < 3.14159f && c.znear > 0.0f &&
          (c.zfar == 0.0f || c.zfar > c.znear))) {
      throw SceneError(where + ": perspective yfov must be in (0, π), znear > 0, zfar > znear");
    }
  } else {
    throw SceneError(where + ": unknown type '" + src.type + "'");
  }
  return c;
}

Light Converter::light(int index, const glm::mat4& world) const {
  checkIndex(index, bulk_.lights, "light");
  const LightRecord& src = bulk_.lights[std::size_t(index)];
  // Built only for a message: a million lights are converted twice each.
  const auto where = [index] { return "light " + str(index); };
  Light l;
  switch (src.type) {
    case PunctualType::Point:
      l.type = LightType::Point;
      break;
    case PunctualType::Spot:
      l.type = LightType::Spot;
      break;
    case PunctualType::Directional:
      l.type = LightType::Directional;
      break;
    default:
      throw SceneError(where() + ": unknown type '" + bulk_.otherTypes.at(std::size_t(index)) +
                       "'");
  }
  if (src.colorCount != 0 && src.colorCount != 3) {
    throw SceneError(where() + ": color must have 3 components, got " +
                     std::to_string(src.colorCount));
  }
  l.colour =
      src.colorCount == 3 ? glm::vec3(src.color[0], src.color[1], src.color[2]) : glm::vec3(1.0f);
  l.intensity = float(src.intensity);
  l.range = float(src.range);
  if (!std::isfinite(l.intensity) || l.intensity < 0.0f || !(l.colour == l.colour) ||
      glm::any(glm::lessThan(l.colour, glm::vec3(0.0f)))) {
    throw SceneError(where() + ": colour and intensity must be finite and not negative");
  }
  if (!(l.range >= 0.0f) || std::isinf(l.range)) {
    throw SceneError(where() + ": range must be a positive number");
  }
  if (l.type == LightType::Spot) {
    l.innerConeAngle = float(src.innerConeAngle);
    l.outerConeAngle = float(src.outerConeAngle);
    if (!(src.innerConeAngle >= 0.0 && src.innerConeAngle < src.outerConeAngle &&
          src.outerConeAngle <= kHalfPi)) {
      throw SceneError(where() + ": spot cone angles must satisfy 0 <= inner < outer <= pi/2");
    }
  }
  if (!placeLight(l, world)) {
    throw SceneError(where() + ": the node's transform collapses the light direction");
  }
  return l;
}

bool placeLight(Light& l, const glm::mat4& world) {
  const glm::vec3 dir = glm::vec3(world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
  const float len = glm::length(dir);
  if (!(len > 0.0f) || !std::isfinite(len)) return false;
  l.position = glm::vec3(world[3]);
  l.direction = dir / len;
  return true;
}

}  // namespace manylight::gltf
