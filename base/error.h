#pragma once
// One base exception for everything manylight reports to a user, one subtype per module.
// Messages say what, where, expected and got, e.g.
//   "model.gltf: accessor 3: expected VEC3 float normals, got VEC2".
#include <stdexcept>
#include <string>

namespace manylight {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Thrown by scene/: a glTF file that cannot be read or is not valid for rendering.
class SceneError : public Error {
 public:
  using Error::Error;
};

}  // namespace manylight
