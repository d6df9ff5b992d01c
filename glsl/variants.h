#pragma once
// The one description of every shader program's variants and of the layout constants its
// GLSL shares with C++. Each program has flags (one #define each); `*Defines` gives the
// #define lines of a flag set, and `programs()` lists every flag set the renderer uses.
// The same description builds the programs at run time (render/*), drives the build-time
// glslangValidator run over every variant used (glsl/shader_variants_main.cpp writes the
// lists that cmake/BuildShader.cmake reads) and the GL test that links each of them. A new
// variant is a new flag here and, where it is used, a line in `programs()`.
#include <string>
#include <vector>

#include "render/aov.h"

namespace manylight::glsl {

// glsl/lighting_lightcuts.frag. SharedPass and OwnPass are the two passes of shared
// (tile) cuts, render/lightcuts_method.cpp; SharedPass comes with TileCuts.
enum LightcutsFlag : unsigned {
  kLightcutsDistance = 1u << 0,
  kLightcutsHasSpecular = 1u << 1,
  kLightcutsFittedColour = 1u << 2,
  kLightcutsTileCuts = 1u << 3,
  kLightcutsSharedPass = 1u << 4,
  kLightcutsOwnPass = 1u << 5,
};
std::vector<std::string> lightcutsDefines(unsigned flags);

// glsl/lighting_reference.frag: the light types present, and a specular material.
enum ReferenceFlag : unsigned {
  kReferenceHasDirectional = 1u << 0,
  kReferenceHasPoint = 1u << 1,
  kReferenceHasSpot = 1u << 2,
  kReferenceHasSpecular = 1u << 3,
};
std::vector<std::string> referenceDefines(unsigned flags);

// glsl/lighting_octree.frag: a specular material.
enum OctreeFlag : unsigned {
  kOctreeHasSpecular = 1u << 0,
};
std::vector<std::string> octreeDefines(unsigned flags);

// glsl/gbuffer.frag: lit (Aov::None), or one channel of render/aov.h's kAovChannels.
std::vector<std::string> gbufferDefines(Aov aov);

// The w of glsl/lighting_lightcuts.frag's oCutStats on a covered pixel (0 on background).
enum CutStatsKind : int {
  kCutStatsOwnCut = 1,          // a cut of its own
  kCutStatsOwnCutAtMax = 2,     // a cut of its own that hit uMaxCut
  kCutStatsSharedCut = 3,       // its group's shared cut
  kCutStatsSharedCutAtMax = 4,  // its group's full cut, whose rule failed (kFullCutBit)
};

struct ProgramVariants {
  const char* vertex;
  const char* fragment;
  std::vector<std::string> outputs;
  std::vector<std::vector<std::string>> variants;  // each a list of #defines
};
// Every program the renderer builds, with every variant it uses.
std::vector<ProgramVariants> programs();

// The GLSL `const` lines of the constants GLSL shares with C++ (scene/shading_model.h,
// bake/light_texture_layout.h, bake/light_tree_layout.h, bake/octree_layout.h, cuts/far_field.h,
// cuts/tile_cuts.h, CutStatsKind): the first part of the G-buffer and lighting stages.
std::string layoutPrelude();

}  // namespace manylight::glsl
