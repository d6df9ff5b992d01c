#pragma once
// Light lists (`--lights FILE`): point lights with 8-bit sRGB colours, added to a scene's
// own lights. Three formats, chosen by the file's extension:
//   .csv   a header naming the columns, then one light per line:
//            x,y,z,r,g,b,brightness[,radius][,falloff]
//   .json  an array of lights, or {"lights": [...]}, each
//            {"position": [x, y, z], "color": [r, g, b], "brightness": B,
//             "radius": R (optional), "falloff": "inverse-square" (optional)}
//   other  the Lightcuts-in-UE4 work's text dump, one light per line:
//            GUID C2C1… - Position X=-300.000 Y=0.000 Z=150.000 W=1.000 - Radius 250 -
//            Color (R=255,G=76,B=216,A=0) - Brightness = 5000
// Mapping onto KHR_lights_punctual point lights:
//   position    → position, in the scene's units, unchanged (a UE4 dump is in centimetres,
//                 so it belongs with geometry in centimetres)
//   r, g, b     → colour: 8-bit sRGB codes (0–255), decoded to linear with the exact sRGB
//                 curve (scene/srgb.h), once, here; the dump's alpha is ignored
//   brightness  → intensity in candela (≥ 0)
//   radius      → range (> 0); absent: infinite, as glTF's default
//   falloff     → only "inverse-square", glTF's 1/d² with its range window, the one falloff
//                 the shading model has (scene/shading_model.h); anything else is refused
//                 rather than rendered differently from what it says
// Blank lines and lines starting with '#' are ignored in the text formats.
#include <string>

#include "scene/gltf_loader.h"
#include "scene/scene.h"

namespace manylight {

// Appends the lights of the list at `path` to scene.lights. Throws SceneError
// "PATH:LINE: problem" for a malformed line ("PATH: light N: problem" in JSON), and
// "PATH: ..." when the file cannot be read, exceeds options.maxFileBytes, or its lights and
// the scene's together exceed options.lightBudget (checked before any light is stored).
void appendLightList(const std::string& path, Scene& scene, const LoadOptions& options);

}  // namespace manylight
