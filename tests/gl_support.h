#pragma once
// What the GL tests share beyond tests/test_support.h: one GL context per process.
#include "gl/context.h"
#include "image/image.h"

namespace manylight::testing {

// The process's GL context (auto backend), created on first use.
gl::Context& context();

// The largest channel difference between two frames of one size over the larger of their peaks.
double largestDifference(const Image& a, const Image& b);

}  // namespace manylight::testing
