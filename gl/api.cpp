#include "gl/api.h"

namespace manylight::gl::api {

#define MANYLIGHT_GL_DEFINE(type, name) type name = nullptr;
MANYLIGHT_GL_FUNCTIONS(MANYLIGHT_GL_DEFINE)
#undef MANYLIGHT_GL_DEFINE

}  // namespace manylight::gl::api

namespace manylight::gl {

const char* loadApi(ProcAddressFn getProcAddress) {
#define MANYLIGHT_GL_LOAD(type, name)                        \
  api::name = reinterpret_cast<type>(getProcAddress(#name)); \
  if (!api::name) return #name;
  MANYLIGHT_GL_FUNCTIONS(MANYLIGHT_GL_LOAD)
#undef MANYLIGHT_GL_LOAD
  return "";
}

}  // namespace manylight::gl
