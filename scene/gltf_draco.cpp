#include "scene/gltf_draco.h"

#include <draco/compression/decode.h>
#include <draco/compression/point_cloud/point_cloud_decoder.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/varint_decoding.h>
#include <draco/mesh/mesh.h>
#include <draco/metadata/geometry_metadata.h>
#include <draco/metadata/metadata_decoder.h>
#include <tiny_gltf.h>

#include <map>

#include "base/error.h"
#include "scene/gltf_accessors.h"

namespace manylight::gltf {
namespace {

const char* const kExtension = "KHR_draco_mesh_compression";

std::string str(std::uint64_t n) { return std::to_string(n); }

// The counts a Draco mesh's connectivity header declares, which the decoder allocates for
// before it reads anything else.
struct DeclaredCounts {
  bool edgebreaker = false;
  std::uint64_t faces = 0;
  std::uint64_t vertices = 0;      // sequential: points; edgebreaker: encoded vertices
  std::uint64_t splitSymbols = 0;  // edgebreaker only: each may add a vertex
};

// Reads DeclaredCounts with Draco's own header, metadata and varint decoders, following the
// layout of the Draco bitstream specification 2.2: header, optional metadata, then the
// connectivity header (sequential: faces, points; edgebreaker: traversal type, encoded
// vertices, faces, attribute data count, symbols, split symbols). Returns the problem, or "".
std::string readDeclaredCounts(const unsigned char* data, std::size_t size, DeclaredCounts* out) {
  draco::DecoderBuffer b;
  b.Init(reinterpret_cast<const char*>(data), size);
  draco::DracoHeader h;
  const draco::Status header = draco::PointCloudDecoder::DecodeHeader(&b, &h);
  if (!header.ok()) return "not a Draco bitstream (" + header.error_msg_string() + ")";
  if (h.encoder_type != draco::TRIANGULAR_MESH) return "the Draco data is not a triangle mesh";
  if (h.version_major != 2 || h.version_minor != 2) {
    return "Draco bitstream version " + str(h.version_major) + "." + str(h.version_minor) +
           " is not supported, expected 2.2";
  }
  b.set_bitstream_version(DRACO_BITSTREAM_VERSION(2, 2));
  if (h.flags & METADATA_FLAG_MASK) {
    draco::MetadataDecoder metadata;
    draco::GeometryMetadata ignored;
    if (!metadata.DecodeGeometryMetadata(&b, &ignored)) return "cannot decode the Draco metadata";
  }
  const std::string truncated = "the Draco connectivity header is truncated";
  std::uint32_t first = 0, second = 0;
  if (h.encoder_method == draco::MESH_SEQUENTIAL_ENCODING) {
    if (!draco::DecodeVarint(&first, &b) || !draco::DecodeVarint(&second, &b)) return truncated;
    *out = {false, first, second, 0};
    return "";
  }
  if (h.encoder_method != draco::MESH_EDGEBREAKER_ENCODING)
    return "unknown Draco encoder method " + str(h.encoder_method);
  std::uint8_t traversal = 0, attributeData = 0;
  std::uint32_t symbols = 0, splits = 0;
  if (!b.Decode(&traversal) || !draco::DecodeVarint(&first, &b) ||
      !draco::DecodeVarint(&second, &b) || !b.Decode(&attributeData) ||
      !draco::DecodeVarint(&symbols, &b) || !draco::DecodeVarint(&splits, &b)) {
    return truncated;
  }
  *out = {true, second, first, splits};
  return "";
}

int glTFComponentType(draco::DataType t) {
  switch (t) {
    case draco::DT_INT8:
      return TINYGLTF_COMPONENT_TYPE_BYTE;
    case draco::DT_UINT8:
      return TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    case draco::DT_INT16:
      return TINYGLTF_COMPONENT_TYPE_SHORT;
    case draco::DT_UINT16:
      return TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    case draco::DT_UINT32:
      return TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    case draco::DT_FLOAT32:
      return TINYGLTF_COMPONENT_TYPE_FLOAT;
    default:
      return -1;
  }
}

}  // namespace

struct DracoPrimitive::Decoded {
  const tinygltf::Model* model = nullptr;
  const tinygltf::Primitive* primitive = nullptr;
  std::string where;                       // "mesh M primitive P: KHR_draco_mesh_compression"
  int view = -1;                           // the bufferView holding the bitstream
  std::map<std::string, int> ids;          // glTF attribute name → Draco attribute unique id
  std::size_t positions = 0, indices = 0;  // the accessors' counts
  std::unique_ptr<draco::Mesh> mesh;

  [[noreturn]] void fail(const std::string& problem) const {
    throw SceneError(where + ": " + problem);
  }
  const tinygltf::Accessor& accessor(int index, const std::string& what) const {
    if (index < 0 || std::size_t(index) >= model->accessors.size())
      fail("accessor " + str(index) + " (" + what + ") does not exist");
    return model->accessors[std::size_t(index)];
  }
  int attributeAccessor(const std::string& name) const {
    const auto it = primitive->attributes.find(name);
    return it == primitive->attributes.end() ? -1 : it->second;
  }

  void readExtension();
  void checkAccessorCounts();
  void checkDeclared(const DeclaredCounts& c) const;
  void decode();
};

// The extension's bufferView and attribute ids; the primitive's mode and indices.
void DracoPrimitive::Decoded::readExtension() {
  const tinygltf::Value& ext = primitive->extensions.at(kExtension);
  if (!ext.IsObject()) fail("the extension is not an object");
  if (!ext.Has("bufferView") || !ext.Get("bufferView").IsInt())
    fail("bufferView is missing or not an index");
  view = ext.Get("bufferView").Get<int>();
  if (!ext.Has("attributes") || !ext.Get("attributes").IsObject())
    fail("attributes is missing or not an object");
  const tinygltf::Value& attributes = ext.Get("attributes");
  for (const std::string& name : attributes.Keys()) {
    const tinygltf::Value& id = attributes.Get(name);
    if (!id.IsInt() || id.Get<int>() < 0)
      fail("attribute " + name + ": the Draco id is not an integer");
    if (attributeAccessor(name) < 0)
      fail("attribute " + name + " is not among the primitive's attributes");
    ids[name] = id.Get<int>();
  }
  const int mode = primitive->mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive->mode;
  if (mode != TINYGLTF_MODE_TRIANGLES) fail("mode " + str(mode) + " is not TRIANGLES (4)");
  if (primitive->indices < 0) fail("the primitive has no indices accessor");
}

// Every count the decoded mesh will be held to, from the accessors: a vertex count above the
// index count would leave vertices no triangle uses, so it bounds what the decoder may make.
void DracoPrimitive::Decoded::checkAccessorCounts() {
  indices = accessor(primitive->indices, "indices").count;
  const int position = attributeAccessor("POSITION");
  if (position < 0) fail("the primitive has no POSITION attribute");
  positions = accessor(position, "POSITION").count;
  if (positions > indices) {
    fail("accessor " + str(position) + " (POSITION) has count " + str(positions) +
         ", more than the " + str(indices) + " indices");
  }
  for (const auto& [name, id] : ids) {
    const int index = attributeAccessor(name);
    const std::size_t count = accessor(index, name).count;
    if (count != positions) {
      fail("accessor " + str(index) + " (" + name + ") has count " + str(count) + ", POSITION " +
           str(positions));
    }
  }
}

void DracoPrimitive::Decoded::checkDeclared(const DeclaredCounts& c) const {
  if (c.faces * 3 != indices) {
    fail("the Draco data declares " + str(c.faces) + " triangles, accessor " +
         str(primitive->indices) + " (indices) has count " + str(indices));
  }
  const std::string position = "accessor " + str(attributeAccessor("POSITION")) + " (POSITION)";
  if (!c.edgebreaker && c.vertices != positions) {
    fail("the Draco data declares " + str(c.vertices) + " vertices, " + position + " has count " +
         str(positions));
  }
  if (c.edgebreaker && c.vertices > positions) {
    fail("the Draco data declares " + str(c.vertices) + " vertices, more than the count " +
         str(positions) + " of " + position);
  }
  if (c.edgebreaker && c.splitSymbols > c.faces) {
    fail("the Draco data declares " + str(c.splitSymbols) + " split symbols, more than its " +
         str(c.faces) + " triangles");
  }
}

void DracoPrimitive::Decoded::decode() {
  const ViewBytes bytes = bufferViewBytes(*model, view, where);
  DeclaredCounts declared;
  const std::string problem = readDeclaredCounts(bytes.data, bytes.size, &declared);
  if (!problem.empty()) fail(problem);
  checkDeclared(declared);
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes.data), bytes.size);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) fail("cannot decode: " + decoded.status().error_msg_string());
  mesh = std::move(decoded).value();
  if (std::uint64_t(mesh->num_faces()) * 3 != indices) {
    fail("decoded " + str(mesh->num_faces()) + " triangles, accessor " + str(primitive->indices) +
         " (indices) has count " + str(indices));
  }
  if (mesh->num_points() != positions) {
    fail("decoded " + str(mesh->num_points()) + " vertices, accessor " +
         str(attributeAccessor("POSITION")) + " (POSITION) has count " + str(positions));
  }
}

bool hasDraco(const tinygltf::Primitive& primitive) {
  return primitive.extensions.count(kExtension) > 0;
}

DracoPrimitive::DracoPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                               const std::string& where)
    : d_(std::make_unique<Decoded>()) {
  d_->model = &model;
  d_->primitive = &primitive;
  d_->where = where + ": " + kExtension;
  d_->readExtension();
  d_->checkAccessorCounts();
  d_->decode();
}

DracoPrimitive::~DracoPrimitive() = default;

bool DracoPrimitive::has(const std::string& name) const { return d_->ids.count(name) > 0; }

std::vector<float> DracoPrimitive::floats(const std::string& name, int components) const {
  const int index = d_->attributeAccessor(name);
  const tinygltf::Accessor& acc = d_->accessor(index, name);
  const std::string what = "attribute " + name + ": ";
  const int expected = tinygltf::GetNumComponentsInType(acc.type);
  if (expected != components) {
    d_->fail(what + "accessor " + str(index) + " has " + str(expected) +
             " components per element, expected " + str(components));
  }
  const int id = d_->ids.at(name);
  const draco::PointAttribute* attr = d_->mesh->GetAttributeByUniqueId(std::uint32_t(id));
  if (!attr) d_->fail(what + "Draco attribute " + str(id) + " does not exist");
  if (attr->num_components() != components) {
    d_->fail(what + "Draco attribute " + str(id) + " has " + str(attr->num_components()) +
             " components, accessor " + str(index) + " has " + str(components));
  }
  const int type = glTFComponentType(attr->data_type());
  if (type < 0) {
    d_->fail(what + "Draco data type " + str(attr->data_type()) + " is not a glTF component type");
  }
  const std::size_t size = draco::DataTypeLength(attr->data_type());
  const std::size_t points = d_->mesh->num_points();
  std::vector<float> out(points * std::size_t(components));
  for (std::size_t i = 0; i < points; ++i) {
    const draco::AttributeValueIndex v = attr->mapped_index(draco::PointIndex(std::uint32_t(i)));
    if (v.value() >= attr->size()) d_->fail(what + "vertex " + str(i) + " maps to no value");
    const unsigned char* p = attr->GetAddress(v);
    for (int c = 0; c < components; ++c)
      out[i * components + c] = componentAsFloat(p + c * size, type, acc.normalized);
  }
  return out;
}

std::vector<std::uint32_t> DracoPrimitive::indices() const {
  const draco::Mesh& mesh = *d_->mesh;
  std::vector<std::uint32_t> out;
  out.reserve(std::size_t(mesh.num_faces()) * 3);
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) out.push_back(mesh.face(f)[k].value());
  }
  return out;
}

}  // namespace manylight::gltf
