#include "scene/gltf_accessors.h"

#include <tiny_gltf.h>

#include <cstring>

#include "base/error.h"

namespace manylight::gltf {
namespace {

int componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

float readComponent(const unsigned char* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, 4);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? p[0] / 255.0f : float(p[0]);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const auto v = static_cast<std::int8_t>(p[0]);
      return normalized ? std::max(v / 127.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return float(v);
    }
    default: {
      std::int32_t v;
      std::memcpy(&v, p, 4);
      return float(v);
    }
  }
}

std::uint32_t readIndex(const unsigned char* p, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    default: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

// A checked view of `count` elements of `elementSize` bytes starting at `byteOffset` within
// buffer view `viewIndex`, `stride` apart (0: tightly packed).
struct ElementView {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
};

ElementView checkedView(const tinygltf::Model& model, int viewIndex, std::size_t byteOffset,
                        std::size_t count, std::size_t elementSize, bool useViewStride,
                        const std::string& where) {
  if (viewIndex < 0 || std::size_t(viewIndex) >= model.bufferViews.size()) {
    throw SceneError(where + ": bufferView " + std::to_string(viewIndex) + " does not exist");
  }
  const tinygltf::BufferView& view = model.bufferViews[viewIndex];
  if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size()) {
    throw SceneError(where + ": bufferView " + std::to_string(viewIndex) + " names buffer " +
                     std::to_string(view.buffer) + ", which does not exist");
  }
  const std::vector<unsigned char>& buffer = model.buffers[view.buffer].data;
  const std::size_t stride = useViewStride && view.byteStride != 0 ? view.byteStride : elementSize;
  if (stride < elementSize) {
    throw SceneError(where + ": byteStride " + std::to_string(stride) +
                     " is smaller than the element size " + std::to_string(elementSize));
  }
  // Overflow-safe: offset + stride·(count−1) + elementSize ≤ byteLength ≤ buffer size.
  const std::size_t limit = std::min<std::size_t>(
      view.byteLength, buffer.size() > view.byteOffset ? buffer.size() - view.byteOffset : 0);
  bool fits = view.byteOffset <= buffer.size() && byteOffset <= limit;
  if (fits && count > 0) {
    const std::size_t room = limit - byteOffset;
    fits = elementSize <= room && (count - 1) <= (room - elementSize) / stride;
  }
  if (!fits) {
    throw SceneError(where + ": " + std::to_string(count) + " elements of " +
                     std::to_string(elementSize) + " bytes do not fit bufferView " +
                     std::to_string(viewIndex) + " (byteLength " + std::to_string(view.byteLength) +
                     ", buffer " + std::to_string(buffer.size()) + " bytes)");
  }
  return {buffer.data() + view.byteOffset + byteOffset, stride};
}

const tinygltf::Accessor& accessorAt(const tinygltf::Model& model, int index,
                                     const std::string& what) {
  if (index < 0 || std::size_t(index) >= model.accessors.size()) {
    throw SceneError(what + ": accessor " + std::to_string(index) + " does not exist");
  }
  return model.accessors[index];
}

}  // namespace

std::vector<float> readFloats(const tinygltf::Model& model, int index, int components,
                              const std::string& what) {
  const tinygltf::Accessor& acc = accessorAt(model, index, what);
  const std::string where = "accessor " + std::to_string(index) + " (" + what + ")";
  const int got = tinygltf::GetNumComponentsInType(acc.type);
  const int size = componentSize(acc.componentType);
  if (got != components || size == 0) {
    throw SceneError(where + ": expected " + std::to_string(components) +
                     " components per element, got " + std::to_string(got));
  }
  const std::size_t elementSize = std::size_t(size) * components;
  std::vector<float> out;
  if (acc.count > (std::size_t(1) << 31) / std::size_t(components)) {
    throw SceneError(where + ": count " + std::to_string(acc.count) + " is too large");
  }
  out.assign(acc.count * components, 0.0f);  // an accessor without a view is all zeros
  if (acc.bufferView >= 0) {
    const ElementView v =
        checkedView(model, acc.bufferView, acc.byteOffset, acc.count, elementSize, true, where);
    for (std::size_t i = 0; i < acc.count; ++i) {
      const unsigned char* e = v.data + i * v.stride;
      for (int c = 0; c < components; ++c) {
        out[i * components + c] = readComponent(e + c * size, acc.componentType, acc.normalized);
      }
    }
  }
  if (acc.sparse.isSparse) {
    const std::size_t n = std::size_t(acc.sparse.count);
    if (acc.sparse.count < 0 || n > acc.count) {
      throw SceneError(where + ": sparse count " + std::to_string(acc.sparse.count) +
                       " exceeds the accessor count " + std::to_string(acc.count));
    }
    const int indexSize = componentSize(acc.sparse.indices.componentType);
    if (indexSize == 0 || acc.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
        acc.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT) {
      throw SceneError(where + ": sparse indices must be unsigned integers");
    }
    const ElementView iv = checkedView(model, acc.sparse.indices.bufferView,
                                       acc.sparse.indices.byteOffset, n, indexSize, false, where);
    const ElementView vv = checkedView(model, acc.sparse.values.bufferView,
                                       acc.sparse.values.byteOffset, n, elementSize, false, where);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t target =
          readIndex(iv.data + i * indexSize, acc.sparse.indices.componentType);
      if (target >= acc.count) {
        throw SceneError(where + ": sparse index " + std::to_string(target) +
                         " is out of range (count " + std::to_string(acc.count) + ")");
      }
      for (int c = 0; c < components; ++c) {
        out[target * components + c] =
            readComponent(vv.data + i * elementSize + c * size, acc.componentType, acc.normalized);
      }
    }
  }
  return out;
}

std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& acc = accessorAt(model, index, "indices");
  const std::string where = "accessor " + std::to_string(index) + " (indices)";
  const int type = acc.componentType;
  if (acc.type != TINYGLTF_TYPE_SCALAR || (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                           type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                                           type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
    throw SceneError(where + ": expected unsigned integer scalars");
  }
  if (acc.sparse.isSparse || acc.bufferView < 0) {
    // Rare for indices; go through the general path and convert.
    const std::vector<float> f = readFloats(model, index, 1, "indices");
    return std::vector<std::uint32_t>(f.begin(), f.end());
  }
  const int size = componentSize(type);
  const ElementView v =
      checkedView(model, acc.bufferView, acc.byteOffset, acc.count, size, true, where);
  std::vector<std::uint32_t> out(acc.count);
  for (std::size_t i = 0; i < acc.count; ++i) out[i] = readIndex(v.data + i * v.stride, type);
  return out;
}

float componentAsFloat(const unsigned char* p, int componentType, bool normalized) {
  return readComponent(p, componentType, normalized);
}

ViewBytes bufferViewBytes(const tinygltf::Model& model, int index, const std::string& what) {
  const std::size_t size = index >= 0 && std::size_t(index) < model.bufferViews.size()
                               ? model.bufferViews[index].byteLength
                               : 0;
  return {checkedView(model, index, 0, size, 1, false, what).data, size};
}

}  // namespace manylight::gltf
