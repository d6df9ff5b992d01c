#pragma once
// Arbitrary output values (render --aov): one material channel, as the G-buffer pass
// evaluates it, written instead of the lit image, in the encodings of the Khronos glTF
// Sample Viewer's debug outputs of the same name.
#include <string>
#include <vector>

#include "image/image.h"

namespace manylight {

enum class Aov { None, BaseColour, Metallic, Roughness, Normal, Emissive, Occlusion, Alpha };

struct AovChannel {
  Aov aov;
  const char* name;    // the --aov value
  const char* define;  // glsl/gbuffer.frag's variant, with "AOV"
  ImageValues values;  // colours go through the sRGB curve in a PNG, data do not
};

// Every channel but Aov::None; glsl/variants.h lists each one's G-buffer variant.
inline constexpr AovChannel kAovChannels[] = {
    {Aov::BaseColour, "base-colour", "AOV_BASE_COLOUR", ImageValues::Colour},
    {Aov::Metallic, "metallic", "AOV_METALLIC", ImageValues::Data},
    {Aov::Roughness, "roughness", "AOV_ROUGHNESS", ImageValues::Data},
    {Aov::Normal, "normal", "AOV_NORMAL", ImageValues::Data},
    {Aov::Emissive, "emissive", "AOV_EMISSIVE", ImageValues::Colour},
    {Aov::Occlusion, "occlusion", "AOV_OCCLUSION", ImageValues::Data},
    {Aov::Alpha, "alpha", "AOV_ALPHA", ImageValues::Data},
};

// The channel of `aov`, which must not be Aov::None.
const AovChannel& aovChannel(Aov aov);
// The #define lines of the G-buffer program for `aov`: none for Aov::None.
std::vector<std::string> aovDefines(Aov aov);
// "base-colour" → Aov::BaseColour, and so on; "" → Aov::None. Throws Error naming the choices
// for anything else.
Aov parseAov(const std::string& name);
// The --aov names, in kAovChannels order.
std::vector<std::string> aovNames();

}  // namespace manylight
