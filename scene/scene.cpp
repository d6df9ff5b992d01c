#include "scene/scene.h"

namespace manylight {

void Bounds::add(glm::vec3 p) {
  if (empty) {
    min = max = p;
    empty = false;
  } else {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const MeshInstance& inst : instances) {
    for (const Primitive& prim : meshes[inst.mesh].primitives) {
      for (const glm::vec3& p : prim.positions) b.add(glm::vec3(inst.world * glm::vec4(p, 1.0f)));
    }
  }
  return b;
}

Material defaultMaterial() {
  Material m;
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  return m;
}

}  // namespace manylight
