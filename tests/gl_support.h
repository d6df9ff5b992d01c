#pragma once
// What the GL tests share beyond tests/test_support.h: one GL context per process.
#include "gl/context.h"

namespace manylight::testing {

// The process's GL context (auto backend), created on first use.
gl::Context& context();

}  // namespace manylight::testing
