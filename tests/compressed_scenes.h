#pragma once
// Small glTF files with compressed geometry for the loader's tests, encoded here with
// libdraco's and libmeshoptimizer's encoders: the same mesh plain, as a Draco primitive
// (KHR_draco_mesh_compression) and with meshopt buffer views (EXT_meshopt_compression).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace manylight::testing {

// A wavy grid over [-1, 1]² with normals and texture coordinates; no degenerate triangles.
struct TestMesh {
  std::vector<float> positions, normals, texcoords;  // 3, 3 and 2 per vertex
  std::vector<std::uint32_t> indices;                // triangle list
  std::size_t vertices() const { return positions.size() / 3; }
};
TestMesh gridMesh(int quadsPerSide);

// A glTF file being written: its JSON, one mesh of one primitive on node 0, and the bytes
// of buffer 0.
struct GltfFile {
  nlohmann::json json;
  std::string bin;
  // Appends `bytes` to buffer 0 (4-byte aligned) and returns the new bufferView's index.
  int addView(const std::string& bytes, int byteStride = 0);
  // Returns the new accessor's index; `view` −1 for none.
  int addAccessor(int view, int componentType, std::size_t count, const std::string& type,
                  bool normalized = false);
  nlohmann::json& primitive() { return json["meshes"][0]["primitives"][0]; }
  void require(const std::string& extension);
};

// Writes `file` as a GLB, or as .gltf with buffer 0 in NAME.bin beside it, by `path`'s
// extension.
void writeGltf(const std::string& path, GltfFile file);

// The mesh with float attributes and 32-bit indices, uncompressed.
GltfFile plainMeshFile(const TestMesh& mesh);

// The mesh as a Draco primitive (edgebreaker or sequential; positions 14 bits, normals 10,
// texture coordinates 12), accessors without bufferViews counting the decoded mesh. The
// bitstream is bufferView 0.
GltfFile dracoMeshFile(const TestMesh& mesh, bool edgebreaker);

// The mesh with every bufferView meshopt-compressed into buffer 0 and decoded into
// placeholder buffer 1 (no uri). `filters`: normals as 8-bit OCTAHEDRAL (KHR_mesh_quantization)
// and texture coordinates EXPONENTIAL (15-bit mantissa), else all NONE; `sequence`: indices
// in INDICES mode, else TRIANGLES. Views: 0 positions, 1 normals, 2 texcoords, 3 indices.
GltfFile meshoptMeshFile(const TestMesh& mesh, bool filters, bool sequence);

}  // namespace manylight::testing
