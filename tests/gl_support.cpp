#include "tests/gl_support.h"

#include <memory>

namespace manylight::testing {

gl::Context& context() {
  static std::unique_ptr<gl::Context> ctx = gl::createContext(gl::Backend::Auto);
  return *ctx;
}

}  // namespace manylight::testing
