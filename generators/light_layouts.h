#pragma once
// Generated light layouts over the room of writeRoomScene (x, z in [−4.5, 4.5], y in
// [0.3, 4.3]): the benchmark sweep's axes and the stability suite's adversarial cases, also
// used by the accuracy tests. Deterministic for a seed; the total power stays about the
// same whatever the count, so images are comparable across counts.
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace manylight {

enum class LightLayout {
  Uniform,          // point lights scattered over the room
  Clustered,        // twelve tight groups (5 cm across)
  Street,           // a line of street lights: spots 4 m up pointing down, with a range
  Mixed,            // point, spot and directional in turn, half with a range
  Coincident,       // every light at one point
  TwoGroups,        // two dense groups in opposite corners of the room
  WideIntensities,  // intensities spread log-uniformly over 1e-6..1e6
  BrightAmongDim,   // one light as bright as all the others together
  Far,              // 1e5 units from the origin (float precision), scaled to light the room
  SpotsAway,        // spot lights all pointing up: only the back wall above them is lit
  OnSurfaces,       // lights a millimetre above the floor and the back wall
  EightBitColours,  // 8-bit sRGB colours as light lists give them, often saturated
  // Ranged layouts, for the light octree: each light's range shrinks with the count so that
  // about kRangedReach lights reach a typical point whatever the count.
  UniformRanged,  // point lights scattered over the room, with a range
  StreetRanged,   // lamps over the floor on a jittered grid: spots pointing down, ranged
};

inline constexpr double kRangedReach = 100.0;

// The names used on the command line and in results ("uniform", "two-groups", ...).
const std::vector<std::pair<LightLayout, std::string>>& lightLayoutNames();
const std::string& lightLayoutName(LightLayout layout);
// Throws Error naming the choices for an unknown name.
LightLayout parseLightLayout(const std::string& name);

// `count` lights laid out as `layout`, from `seed`.
std::vector<Light> layoutLights(LightLayout layout, int count, std::uint32_t seed);

}  // namespace manylight
