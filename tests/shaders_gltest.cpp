#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "gl/context.h"
#include "gl/objects.h"
#include "glsl/variants.h"
#include "tests/gl_support.h"

namespace manylight::testing {
namespace {

TEST(Shaders, EveryVariantUsedCompilesAndLinks) {
  context();
  for (const glsl::ProgramVariants& p : glsl::programs()) {
    for (const std::vector<std::string>& defines : p.variants) {
      std::string name = p.fragment;
      for (const std::string& d : defines) name += " " + d;
      EXPECT_NO_THROW(gl::Program(p.vertex, p.fragment, defines, p.outputs)) << name;
    }
  }
}

TEST(Shaders, TheContextCompilesEachProgramOnce) {
  context();
  const gl::Program& a = gl::cachedProgram("gbuffer.vert", "gbuffer.frag", {}, {"gPosition"});
  const gl::Program& b = gl::cachedProgram("gbuffer.vert", "gbuffer.frag", {}, {"gPosition"});
  const gl::Program& c =
      gl::cachedProgram("gbuffer.vert", "gbuffer.frag", {}, {"gPosition", "gNormal"});
  EXPECT_EQ(&a, &b);
  EXPECT_EQ(a.id(), b.id());
  EXPECT_NE(a.id(), c.id());
}

}  // namespace
}  // namespace manylight::testing
