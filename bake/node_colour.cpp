#include "bake/node_colour.h"

#include <algorithm>
#include <cmath>

#include "base/parallel.h"
#include "base/uninitialised.h"
#include "scene/srgb.h"

namespace manylight {
namespace {

// Fewer colours than this a thread are measured on one.
constexpr std::size_t kColoursPerThread = 65536;

float largest(glm::vec3 c) { return std::max(c.r, std::max(c.g, c.b)); }

// RGB9_E5 as EXT_texture_shared_exponent defines it.
constexpr int kMantissaBits = 9, kExponentBias = 15, kMaxExponent = 31;
constexpr double kRgb9e5Max =
    double((1 << kMantissaBits) - 1) / (1 << kMantissaBits) * (1 << (kMaxExponent - kExponentBias));

std::uint32_t encodeRgb9e5(glm::dvec3 v) {
  for (int c = 0; c < 3; ++c) v[c] = std::clamp(v[c], 0.0, kRgb9e5Max);
  const double m = std::max(v.x, std::max(v.y, v.z));
  if (m <= 0.0) return 0;
  int e = std::max(-kExponentBias - 1, int(std::floor(std::log2(m)))) + 1 + kExponentBias;
  if (std::floor(m / std::ldexp(1.0, e - kExponentBias - kMantissaBits) + 0.5) ==
      double(1 << kMantissaBits))
    ++e;
  const double unit = std::ldexp(1.0, e - kExponentBias - kMantissaBits);
  std::uint32_t word = std::uint32_t(e) << 27;
  std::uint32_t codes[3];
  for (int c = 0; c < 3; ++c) codes[c] = std::uint32_t(std::floor(v[c] / unit + 0.5));
  // Too dim for the format: the smallest non-zero value, so the light is not lost.
  if (codes[0] == 0 && codes[1] == 0 && codes[2] == 0) codes[v.x == m ? 0 : v.y == m ? 1 : 2] = 1;
  for (int c = 0; c < 3; ++c) word |= std::min(codes[c], 511u) << (9 * c);
  return word;
}

glm::dvec3 decodeRgb9e5(std::uint32_t w) {
  const double unit = std::ldexp(1.0, int(w >> 27) - kExponentBias - kMantissaBits);
  return glm::dvec3(w & 511u, (w >> 9) & 511u, (w >> 18) & 511u) * unit;
}

constexpr int kExponentOffset = 128;

glm::dvec3 decodeFitted(std::uint32_t w, const PowerFit& fit) {
  const double scale = std::exp2(int(w >> 24) - kExponentOffset) * fit.a;
  glm::dvec3 c;
  for (int k = 0; k < 3; ++k) {
    const double code = double((w >> (8 * k)) & 255u);
    c[k] = code == 0.0 ? 0.0 : scale * std::pow(code, fit.gamma);
  }
  return c;
}

std::uint32_t encodeFitted(glm::dvec3 v, const PowerFit& fit) {
  const double m = std::max(v.x, std::max(v.y, v.z));
  if (!(m > 0.0)) return 0;
  // The exponent that puts the largest channel in the top octave of the codes.
  const int k = std::clamp(int(std::ceil(std::log2(m / fit(255.0)))), -kExponentOffset,
                           255 - kExponentOffset);
  const double unit = std::exp2(k);
  std::uint32_t word = std::uint32_t(k + kExponentOffset) << 24;
  std::uint32_t codes[3];
  for (int c = 0; c < 3; ++c) {
    const double exact = std::pow(std::max(v[c], 0.0) / unit / fit.a, 1.0 / fit.gamma);
    const double lo = std::clamp(std::floor(exact), 0.0, 255.0),
                 hi = std::clamp(std::ceil(exact), 0.0, 255.0);
    auto value = [&](double code) { return code == 0.0 ? 0.0 : unit * fit(code); };
    codes[c] = std::uint32_t(std::abs(value(lo) - v[c]) <= std::abs(value(hi) - v[c]) ? lo : hi);
  }
  if (codes[0] == 0 && codes[1] == 0 && codes[2] == 0) codes[v.x == m ? 0 : v.y == m ? 1 : 2] = 1;
  return word | codes[0] | codes[1] << 8 | codes[2] << 16;
}

// The 99th percentile of `v` less its `skipped` values that lie below all the others.
double percentile99(UninitialisedVector<double>& v, std::size_t skipped) {
  const std::size_t n = v.size() - skipped;
  if (n == 0) return 0.0;
  const std::size_t k = std::min(n - 1, std::size_t(std::ceil(0.99 * double(n))) - 1);
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(skipped + k), v.end());
  return v[skipped + k];
}

}  // namespace

NodeColourCoder::NodeColourCoder(NodeColourCoding coding, const std::vector<glm::vec3>& colours)
    : NodeColourCoder(coding, colours, Unmeasured{}) {
  std::vector<std::uint32_t> words(colours.size());
  runOnShares(sharesOf(colours.size(), kColoursPerThread), colours.size(),
              [&](int, std::size_t from, std::size_t to) {
                for (std::size_t i = from; i < to; ++i) words[i] = encode(colours[i]);
              });
  measure(colours, words);
}

NodeColourCoder::NodeColourCoder(NodeColourCoding coding, const std::vector<glm::vec3>& colours,
                                 Unmeasured)
    : coding_(coding) {
  if (coding == NodeColourCoding::Fitted) {
    std::vector<FitPair> pairs;
    pairs.reserve(colours.size() * 3);
    bool twoCodes = false;
    for (const glm::vec3& c : colours) {
      const float m = largest(c);
      if (!(m > 0.0f)) continue;
      for (int k = 0; k < 3; ++k) {
        const double chromaticity = double(c[k]) / m;
        const int code = encodeSrgb8(chromaticity);
        if (code == 0) continue;  // decodes to 0; log 0 has no place in the fit
        twoCodes = twoCodes || (!pairs.empty() && pairs.front().in != code);
        pairs.push_back({double(code), chromaticity});
      }
    }
    if (!twoCodes) {
      fittedToSrgb_ = true;
      pairs.clear();
      for (int code = 1; code < 256; ++code)
        pairs.push_back({double(code), decodeSrgb8(std::uint8_t(code))});
    }
    fit_ = fitPowerLaw(pairs);
  } else {
    float brightest = 0.0f;
    for (const glm::vec3& c : colours) brightest = std::max(brightest, largest(c));
    scale_ = brightest > 0.0f ? float(brightest / kRgb9e5Max) : 1.0f;
    // The scale must itself round-trip: a float scale slightly below brightest / max would
    // clamp the brightest node.
    while (brightest / double(scale_) > kRgb9e5Max) scale_ = std::nextafter(scale_, HUGE_VALF);
  }
  if (coding == NodeColourCoding::Rgb9e5)
    slackFloor = std::exp2(-kExponentBias - kMantissaBits) * double(scale_);
}

void NodeColourCoder::measure(const std::vector<glm::vec3>& colours,
                              const std::vector<std::uint32_t>& words) {
  // Each colour's relative errors at its own index, −1 for a black colour (which counts in
  // no figure), measured on a few threads, each over its share: the same figures as one
  // thread's.
  struct Share {
    double maxError[3] = {0, 0, 0};
    double eta = 0.0;
    std::size_t black = 0;
  };
  UninitialisedVector<double> errors[3];  // every element is written below
  for (UninitialisedVector<double>& e : errors) e.resize(colours.size());
  std::vector<Share> shares(std::size_t(sharesOf(colours.size(), kColoursPerThread)));
  runOnShares(int(shares.size()), colours.size(), [&](int t, std::size_t from, std::size_t to) {
    Share& share = shares[std::size_t(t)];
    for (std::size_t i = from; i < to; ++i) {
      const glm::vec3& c = colours[i];
      const float m = largest(c);
      if (!(m > 0.0f)) {
        for (UninitialisedVector<double>& e : errors) e[i] = -1.0;
        ++share.black;
        continue;
      }
      const glm::dvec3 d = glm::dvec3(decode(words[i]));
      const double dm = std::max(d.x, std::max(d.y, d.z));
      for (int k = 0; k < 3; ++k) {
        const double e = std::abs(d[k] - double(c[k]));
        errors[k][i] = e / m;
        share.maxError[k] = std::max(share.maxError[k], e / m);
        share.eta = std::max(share.eta, std::max(e - slackFloor, 0.0) / dm);
      }
    }
  });
  double eta = 0.0;
  std::size_t black = 0;
  for (const Share& share : shares) {
    for (int k = 0; k < 3; ++k) maxError[k] = std::max(maxError[k], share.maxError[k]);
    eta = std::max(eta, share.eta);
    black += share.black;
  }
  // The three channels' selections at once, when large.
  const int threads = colours.size() >= kColoursPerThread ? 3 : 1;
  runOnThreads(threads, [&](int k) {
    for (int c = k; c < 3; c += threads) p99Error[c] = percentile99(errors[c], black);
  });
  // The shader decodes in single precision (pow, exp2): a few units in the last place.
  slack = eta * (1.0 + 1e-3) + 1e-5;
}

std::uint32_t NodeColourCoder::encode(glm::vec3 colour) const {
  return coding_ == NodeColourCoding::Fitted ? encodeFitted(glm::dvec3(colour), fit_)
                                             : encodeRgb9e5(glm::dvec3(colour) / double(scale_));
}

glm::vec3 NodeColourCoder::decode(std::uint32_t word) const {
  return glm::vec3(coding_ == NodeColourCoding::Fitted ? decodeFitted(word, fit_)
                                                       : decodeRgb9e5(word) * double(scale_));
}

}  // namespace manylight
