#include "tests/compressed_scenes.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <meshoptimizer.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace manylight::testing {
namespace {

constexpr int kByte = 5120, kUnsignedInt = 5125, kFloat = 5126;

template <typename T>
std::string bytesOf(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

std::string word(std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); }

GltfFile emptyFile() {
  GltfFile f;
  f.json = {{"asset", {{"version", "2.0"}}},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", {{{"mesh", 0}}}},
            {"meshes", {{{"primitives", {nlohmann::json::object()}}}}},
            {"bufferViews", nlohmann::json::array()},
            {"accessors", nlohmann::json::array()},
            {"buffers", {nlohmann::json::object()}}};
  return f;
}

// Encodes `mesh` with draco::Encoder; the attributes' unique ids in `ids` (POSITION, NORMAL,
// TEXCOORD_0).
std::string encodeDraco(const TestMesh& mesh, bool edgebreaker, nlohmann::json* ids) {
  draco::Mesh m;
  const std::size_t n = mesh.vertices();
  m.set_num_points(std::uint32_t(n));
  auto add = [&](draco::GeometryAttribute::Type type, int components, const float* data,
                 const char* name) {
    draco::GeometryAttribute ga;
    ga.Init(type, nullptr, std::uint8_t(components), draco::DT_FLOAT32, false,
            std::int64_t(sizeof(float)) * components, 0);
    const int id = m.AddAttribute(ga, true, std::uint32_t(n));
    for (std::size_t i = 0; i < n; ++i)
      m.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(std::uint32_t(i)),
                                         data + i * components);
    (*ids)[name] = m.attribute(id)->unique_id();
  };
  add(draco::GeometryAttribute::POSITION, 3, mesh.positions.data(), "POSITION");
  add(draco::GeometryAttribute::NORMAL, 3, mesh.normals.data(), "NORMAL");
  add(draco::GeometryAttribute::TEX_COORD, 2, mesh.texcoords.data(), "TEXCOORD_0");
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    draco::Mesh::Face face;
    for (int k = 0; k < 3; ++k) face[k] = draco::PointIndex(mesh.indices[t + k]);
    m.AddFace(face);
  }
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
  encoder.SetEncodingMethod(edgebreaker ? draco::MESH_EDGEBREAKER_ENCODING
                                        : draco::MESH_SEQUENTIAL_ENCODING);
  draco::EncoderBuffer out;
  const draco::Status s = encoder.EncodeMeshToBuffer(m, &out);
  if (!s.ok()) throw std::runtime_error("draco encoding failed: " + s.error_msg_string());
  return std::string(out.data(), out.size());
}

// One meshopt-compressed view: its data encoded into buffer 0, decoded into buffer 1.
int addMeshoptView(GltfFile& f, std::size_t* placeholderBytes, const std::string& raw,
                   std::size_t count, std::size_t stride, const std::string& mode,
                   const std::string& filter) {
  std::vector<unsigned char> encoded;
  std::size_t size = 0;
  if (mode == "ATTRIBUTES") {
    encoded.resize(meshopt_encodeVertexBufferBound(count, stride));
    size = meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), raw.data(), count, stride);
  } else {
    std::vector<std::uint32_t> indices(count);
    std::memcpy(indices.data(), raw.data(), count * 4);
    const bool triangles = mode == "TRIANGLES";
    encoded.resize(triangles ? meshopt_encodeIndexBufferBound(count, count)
                             : meshopt_encodeIndexSequenceBound(count, count));
    size = triangles
               ? meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), indices.data(), count)
               : meshopt_encodeIndexSequence(encoded.data(), encoded.size(), indices.data(), count);
  }
  if (size == 0) throw std::runtime_error("meshopt encoding failed");
  const std::size_t offset = f.bin.size();
  f.bin.append(reinterpret_cast<const char*>(encoded.data()), size);
  f.bin.resize((f.bin.size() + 3) / 4 * 4, '\0');
  nlohmann::json ext = {{"buffer", 0},          {"byteOffset", offset}, {"byteLength", size},
                        {"byteStride", stride}, {"count", count},       {"mode", mode}};
  if (filter != "NONE") ext["filter"] = filter;
  nlohmann::json view = {{"buffer", 1},
                         {"byteOffset", *placeholderBytes},
                         {"byteLength", count * stride},
                         {"extensions", {{"EXT_meshopt_compression", ext}}}};
  if (mode == "ATTRIBUTES") view["byteStride"] = stride;
  *placeholderBytes += (count * stride + 3) / 4 * 4;
  f.json["bufferViews"].push_back(view);
  return int(f.json["bufferViews"].size()) - 1;
}

}  // namespace

TestMesh gridMesh(int quads) {
  TestMesh m;
  for (int j = 0; j <= quads; ++j) {
    for (int i = 0; i <= quads; ++i) {
      const float u = float(i) / quads, v = float(j) / quads;
      const float x = 2 * u - 1, z = 2 * v - 1;
      const float y = 0.2f * std::sin(3 * x) * std::cos(2 * z);
      const float dx = 0.6f * std::cos(3 * x) * std::cos(2 * z);
      const float dz = -0.4f * std::sin(3 * x) * std::sin(2 * z);
      const float len = std::sqrt(dx * dx + 1 + dz * dz);
      m.positions.insert(m.positions.end(), {x, y, z});
      m.normals.insert(m.normals.end(), {-dx / len, 1 / len, -dz / len});
      m.texcoords.insert(m.texcoords.end(), {u, v});
    }
  }
  const std::uint32_t row = std::uint32_t(quads + 1);
  for (std::uint32_t j = 0; j < std::uint32_t(quads); ++j) {
    for (std::uint32_t i = 0; i < std::uint32_t(quads); ++i) {
      const std::uint32_t a = j * row + i, b = a + 1, c = a + row, d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
  }
  return m;
}

int GltfFile::addView(const std::string& bytes, int byteStride) {
  nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}};
  if (byteStride) view["byteStride"] = byteStride;
  bin += bytes;
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  json["bufferViews"].push_back(view);
  return int(json["bufferViews"].size()) - 1;
}

int GltfFile::addAccessor(int view, int componentType, std::size_t count, const std::string& type,
                          bool normalized) {
  nlohmann::json a = {{"componentType", componentType}, {"count", count}, {"type", type}};
  if (view >= 0) a["bufferView"] = view;
  if (normalized) a["normalized"] = true;
  json["accessors"].push_back(a);
  return int(json["accessors"].size()) - 1;
}

void GltfFile::require(const std::string& extension) {
  json["extensionsUsed"].push_back(extension);
  json["extensionsRequired"].push_back(extension);
}

void writeGltf(const std::string& path, GltfFile f) {
  f.json["buffers"][0]["byteLength"] = f.bin.size();
  const bool glb = path.size() > 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  std::ofstream out(path, std::ios::binary);
  if (!glb) {
    const std::string name = path.substr(path.find_last_of('/') + 1);
    const std::string binName = name.substr(0, name.rfind('.')) + ".bin";
    f.json["buffers"][0]["uri"] = binName;
    out << f.json.dump();
    std::ofstream(path.substr(0, path.size() - name.size()) + binName, std::ios::binary) << f.bin;
    return;
  }
  std::string json = f.json.dump();
  json.resize((json.size() + 3) / 4 * 4, ' ');
  f.bin.resize((f.bin.size() + 3) / 4 * 4, '\0');
  out << "glTF" << word(2) << word(std::uint32_t(28 + json.size() + f.bin.size()))
      << word(std::uint32_t(json.size())) << "JSON" << json << word(std::uint32_t(f.bin.size()))
      << std::string("BIN\0", 4) << f.bin;
}

GltfFile plainMeshFile(const TestMesh& m) {
  GltfFile f = emptyFile();
  const std::size_t n = m.vertices();
  nlohmann::json& p = f.primitive();
  p["attributes"]["POSITION"] = f.addAccessor(f.addView(bytesOf(m.positions)), kFloat, n, "VEC3");
  p["attributes"]["NORMAL"] = f.addAccessor(f.addView(bytesOf(m.normals)), kFloat, n, "VEC3");
  p["attributes"]["TEXCOORD_0"] = f.addAccessor(f.addView(bytesOf(m.texcoords)), kFloat, n, "VEC2");
  p["indices"] =
      f.addAccessor(f.addView(bytesOf(m.indices)), kUnsignedInt, m.indices.size(), "SCALAR");
  return f;
}

GltfFile dracoMeshFile(const TestMesh& m, bool edgebreaker) {
  GltfFile f = emptyFile();
  nlohmann::json ids;
  const std::string bitstream = encodeDraco(m, edgebreaker, &ids);
  draco::DecoderBuffer buffer;
  buffer.Init(bitstream.data(), bitstream.size());
  const auto decoded = draco::Decoder().DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) throw std::runtime_error("draco decoding failed");
  const std::size_t points = decoded.value()->num_points();
  const std::size_t faces = decoded.value()->num_faces();
  f.require("KHR_draco_mesh_compression");
  const int view = f.addView(bitstream);
  nlohmann::json& p = f.primitive();
  p["indices"] = f.addAccessor(-1, kUnsignedInt, faces * 3, "SCALAR");
  p["attributes"]["POSITION"] = f.addAccessor(-1, kFloat, points, "VEC3");
  p["attributes"]["NORMAL"] = f.addAccessor(-1, kFloat, points, "VEC3");
  p["attributes"]["TEXCOORD_0"] = f.addAccessor(-1, kFloat, points, "VEC2");
  p["extensions"]["KHR_draco_mesh_compression"] = {{"bufferView", view}, {"attributes", ids}};
  return f;
}

GltfFile meshoptMeshFile(const TestMesh& m, bool filters, bool sequence) {
  GltfFile f = emptyFile();
  f.require("EXT_meshopt_compression");
  const std::size_t n = m.vertices();
  std::size_t placeholder = 0;
  nlohmann::json& p = f.primitive();
  const int positions =
      addMeshoptView(f, &placeholder, bytesOf(m.positions), n, 12, "ATTRIBUTES", "NONE");
  p["attributes"]["POSITION"] = f.addAccessor(positions, kFloat, n, "VEC3");
  if (filters) {
    f.require("KHR_mesh_quantization");
    std::vector<float> normals4, uvs = m.texcoords;
    for (std::size_t i = 0; i < n; ++i)
      normals4.insert(normals4.end(),
                      {m.normals[3 * i], m.normals[3 * i + 1], m.normals[3 * i + 2], 0.0f});
    std::vector<std::int8_t> oct(n * 4);
    meshopt_encodeFilterOct(oct.data(), n, 4, 8, normals4.data());
    std::vector<std::uint32_t> exp(n * 2);
    meshopt_encodeFilterExp(exp.data(), n, 8, 15, uvs.data());
    const int nv = addMeshoptView(f, &placeholder, bytesOf(oct), n, 4, "ATTRIBUTES", "OCTAHEDRAL");
    p["attributes"]["NORMAL"] = f.addAccessor(nv, kByte, n, "VEC3", true);
    const int tv = addMeshoptView(f, &placeholder, bytesOf(exp), n, 8, "ATTRIBUTES", "EXPONENTIAL");
    p["attributes"]["TEXCOORD_0"] = f.addAccessor(tv, kFloat, n, "VEC2");
  } else {
    const int nv = addMeshoptView(f, &placeholder, bytesOf(m.normals), n, 12, "ATTRIBUTES", "NONE");
    p["attributes"]["NORMAL"] = f.addAccessor(nv, kFloat, n, "VEC3");
    const int tv =
        addMeshoptView(f, &placeholder, bytesOf(m.texcoords), n, 8, "ATTRIBUTES", "NONE");
    p["attributes"]["TEXCOORD_0"] = f.addAccessor(tv, kFloat, n, "VEC2");
  }
  const int iv = addMeshoptView(f, &placeholder, bytesOf(m.indices), m.indices.size(), 4,
                                sequence ? "INDICES" : "TRIANGLES", "NONE");
  p["indices"] = f.addAccessor(iv, kUnsignedInt, m.indices.size(), "SCALAR");
  f.json["buffers"].push_back(
      {{"byteLength", placeholder},
       {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
  return f;
}

}  // namespace manylight::testing
