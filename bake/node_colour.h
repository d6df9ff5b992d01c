#pragma once
// Compact light tree node colours: one 32-bit word per node instead of three floats. Two
// codings, both with a shared exponent (node intensities span many orders of magnitude):
//
//   Fitted  8 bits per channel on a fitted power law plus an 8-bit exponent e:
//           C = 2^(e − 128) · A · c^γ for each channel's code c (0–255). A and γ are fitted
//           at bake time (bake/colour_fit.h), by least squares in log–log space, to the
//           colours of the nodes actually present: for each internal node, each non-zero
//           channel's chromaticity (channel / largest channel) against its exact 8-bit sRGB
//           code. A scene whose nodes give fewer than two different codes (all lights grey,
//           say) is fitted to the sRGB curve over codes 1–255 instead.
//   Rgb9e5  GL's RGB9_E5 (EXT_texture_shared_exponent: 9-bit mantissas, 5-bit exponent)
//           of the colour divided by a per-bake scale that puts the brightest node at the
//           top of its range. Nodes dimmer than the format's 2^40 range are stored as its
//           smallest non-zero value, so no light is ever lost, only over-estimated.
//
// Only internal nodes are decoded: leaves are evaluated exactly from the light texture.
// `slack` η and `slackFloor` ζ bound the coding error of every internal node, for every
// channel: |decoded − exact| ≤ η · largest decoded channel + ζ; the lightcuts shader widens
// its bounds by it, so the error guarantee holds with compact colours. ζ is one unit of
// RGB9_E5's smallest exponent (so nodes below its range do not inflate η), 0 for Fitted.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "bake/colour_fit.h"

namespace manylight {

enum class NodeColourCoding { Fitted, Rgb9e5 };

class NodeColourCoder {
 public:
  // Fits the coder to `colours` (linear RGB, ≥ 0: the internal nodes' intensities) and
  // measures what it does to them.
  NodeColourCoder(NodeColourCoding coding, const std::vector<glm::vec3>& colours);
  // Fits it only; measure() then takes the words its caller encodes anyway.
  struct Unmeasured {};
  NodeColourCoder(NodeColourCoding coding, const std::vector<glm::vec3>& colours, Unmeasured);
  // Sets the error figures below from `colours` and their words, words[i] = encode(colours[i]).
  void measure(const std::vector<glm::vec3>& colours, const std::vector<std::uint32_t>& words);
  NodeColourCoder() : NodeColourCoder(NodeColourCoding::Rgb9e5, {}) {}
  // A coder as baked before (bake/baked_file.h): its constants; the caller restores the
  // error figures.
  NodeColourCoder(NodeColourCoding coding, const PowerFit& fit, bool fittedToSrgb, float scale)
      : coding_(coding), fit_(fit), fittedToSrgb_(fittedToSrgb), scale_(scale) {}

  std::uint32_t encode(glm::vec3 colour) const;
  glm::vec3 decode(std::uint32_t word) const;

  NodeColourCoding coding() const { return coding_; }
  const PowerFit& fit() const { return fit_; }  // Fitted: A, γ
  bool fittedToSrgb() const { return fittedToSrgb_; }
  float scale() const { return scale_; }  // Rgb9e5: stored = colour / scale

  // Over the colours given to the constructor, per channel: |decoded − exact| / the largest
  // exact channel of that colour, the maximum and the 99th percentile.
  double maxError[3] = {0, 0, 0};
  double p99Error[3] = {0, 0, 0};
  double slack = 0.0;       // η, with margin for the shader's single-precision decode
  double slackFloor = 0.0;  // ζ

 private:
  NodeColourCoding coding_;
  PowerFit fit_;
  bool fittedToSrgb_ = false;
  float scale_ = 1.0f;
};

}  // namespace manylight
