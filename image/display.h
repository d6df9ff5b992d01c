#pragma once
// The display transform for people: PNG output is exposed, tone-mapped, then sRGB-encoded
// (image/image.cpp); EXR output stays linear radiance, exposed only. With ToneMap::None and
// exposure 0 a PNG is the linear radiance clamped to [0, 1] and sRGB-encoded, exactly.
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace manylight {

struct Image;

enum class ToneMap : std::uint8_t {
  None,        // clamp to [0, 1]
  PbrNeutral,  // Khronos PBR Neutral (made for product images): colours below 0.76 unchanged
  Aces,        // ACES filmic: Stephen Hill's fit of the RRT + ODT (the Sample Viewer's "ACES Hill")
};

// "none", "pbr-neutral", "aces" → ToneMap; throws Error naming the choices.
ToneMap parseToneMap(const std::string& name);
const char* toneMapName(ToneMap t);
std::vector<std::string> toneMapNames();

// `t` applied to linear colour `c` (after exposure); the result lies in [0, 1].
glm::vec3 toneMap(ToneMap t, glm::vec3 c);

struct Display {
  float exposure = 0.0f;  // EV: colour is scaled by 2^exposure
  ToneMap toneMap = ToneMap::None;
};

// Automatic exposure: the EV that brings the 95th percentile of the covered pixels' largest
// channel (straight colour) to kAutoExposureKey, where PBR Neutral begins to compress. The
// largest channel, not luminance, so a saturated colour is not pushed into the compression
// (a red surface's luminance is a fifth of its red); a percentile, so a few very bright
// pixels (a lamp's bulb, a highlight) do not darken the rest; deterministic (a selection
// among the image's own values). 0 when nothing covered
// is brighter than black; clamped to ±kAutoExposureLimit.
inline constexpr float kAutoExposureKey = 0.76f;
inline constexpr float kAutoExposurePercentile = 0.95f;
inline constexpr float kAutoExposureLimit = 20.0f;
float autoExposure(const Image& image);

}  // namespace manylight
