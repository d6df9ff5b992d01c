#include "image/display.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "image/image.h"

namespace manylight {
namespace {

// Khronos PBR Neutral, as its specification writes it (KhronosGroup/ToneMapping).
glm::vec3 pbrNeutral(glm::vec3 c) {
  constexpr float kStartCompression = 0.8f - 0.04f;
  constexpr float kDesaturation = 0.15f;
  const float x = std::min({c.r, c.g, c.b});
  const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
  c -= offset;
  const float peak = std::max({c.r, c.g, c.b});
  if (peak < kStartCompression) return c;
  constexpr float d = 1.0f - kStartCompression;
  const float newPeak = 1.0f - d * d / (peak + d - kStartCompression);
  c *= newPeak / peak;
  const float g = 1.0f - 1.0f / (kDesaturation * (peak - newPeak) + 1.0f);
  return glm::mix(c, glm::vec3(newPeak), g);
}

// ACES filmic: Stephen Hill's fit (sRGB → ACES AP1-ish input matrix, the RRT + ODT rational
// fit, back), the variant the Khronos glTF Sample Viewer offers as "ACES Hill".
glm::vec3 acesHill(glm::vec3 c) {
  const glm::mat3 in(0.59719f, 0.07600f, 0.02840f, 0.35458f, 0.90834f, 0.13383f, 0.04823f, 0.01566f,
                     0.83777f);
  const glm::mat3 out(1.60475f, -0.10208f, -0.00327f, -0.53108f, 1.10813f, -0.07276f, -0.07367f,
                      -0.00605f, 1.07602f);
  c = in * c;
  const glm::vec3 a = c * (c + 0.0245786f) - 0.000090537f;
  const glm::vec3 b = c * (0.983729f * c + 0.4329510f) + 0.238081f;
  return out * (a / b);
}

}  // namespace

ToneMap parseToneMap(const std::string& name) {
  if (name == "none") return ToneMap::None;
  if (name == "pbr-neutral") return ToneMap::PbrNeutral;
  if (name == "aces") return ToneMap::Aces;
  throw Error("unknown tone map '" + name + "', expected none, pbr-neutral or aces");
}

const char* toneMapName(ToneMap t) {
  switch (t) {
    case ToneMap::PbrNeutral:
      return "pbr-neutral";
    case ToneMap::Aces:
      return "aces";
    default:
      return "none";
  }
}

std::vector<std::string> toneMapNames() { return {"none", "pbr-neutral", "aces"}; }

glm::vec3 toneMap(ToneMap t, glm::vec3 c) {
  c = glm::max(c, glm::vec3(0.0f));
  if (t == ToneMap::PbrNeutral) c = pbrNeutral(c);
  if (t == ToneMap::Aces) c = acesHill(c);
  return glm::clamp(c, glm::vec3(0.0f), glm::vec3(1.0f));
}

float autoExposure(const Image& image) {
  std::vector<float> peak;
  const std::size_t n = std::size_t(image.width) * image.height;
  for (std::size_t i = 0; i < n; ++i) {
    const float* p = &image.rgba[i * 4];
    if (!(p[3] > 0.0f)) continue;
    const float y = std::max({p[0], p[1], p[2]}) / std::min(p[3], 1.0f);
    if (std::isfinite(y)) peak.push_back(std::max(y, 0.0f));
  }
  if (peak.empty()) return 0.0f;
  const std::size_t k =
      std::min(peak.size() - 1, std::size_t(kAutoExposurePercentile * float(peak.size())));
  std::nth_element(peak.begin(), peak.begin() + std::ptrdiff_t(k), peak.end());
  const float key = peak[k];
  if (!(key > 0.0f)) return 0.0f;
  return std::clamp(std::log2(kAutoExposureKey / key), -kAutoExposureLimit, kAutoExposureLimit);
}

}  // namespace manylight
