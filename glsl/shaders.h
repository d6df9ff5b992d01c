#pragma once
// The shader stages of glsl/, validated by glslangValidator at build time for every variant
// glsl/variants.h lists and embedded into the binary (glsl/CMakeLists.txt), so nothing is
// looked up on disk at run time.
#include <string_view>

namespace manylight::glsl {

// The assembled text of a stage such as "gbuffer.vert"; empty if no stage has that name.
// Its first line is "#version 330 core"; callers insert #define lines after it.
std::string_view source(std::string_view name);

}  // namespace manylight::glsl
