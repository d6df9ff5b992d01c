#include "glsl/variants.h"

#include <cstdio>

#include "bake/light_texture_layout.h"
#include "bake/light_tree_layout.h"
#include "bake/octree_layout.h"
#include "cuts/far_field.h"
#include "cuts/tile_cuts.h"
#include "render/cache_layout.h"
#include "render/rsm_clusters.h"
#include "scene/shading_model.h"

namespace manylight::glsl {
namespace {

std::vector<std::string> definesOf(unsigned flags, std::initializer_list<const char*> names) {
  std::vector<std::string> out;
  unsigned bit = 1;
  for (const char* name : names) {
    if (flags & bit) out.emplace_back(name);
    bit <<= 1;
  }
  return out;
}

std::vector<std::vector<std::string>> lightcutsVariants() {
  std::vector<std::vector<std::string>> out;
  for (unsigned base = 0; base < 8; ++base) {  // Distance, HasSpecular, FittedColour
    out.push_back(lightcutsDefines(base));
    if (base & kLightcutsDistance) continue;  // the distance criterion has no shared cuts
    out.push_back(lightcutsDefines(base | kLightcutsTileCuts | kLightcutsSharedPass));
    out.push_back(lightcutsDefines(base | kLightcutsOwnPass));
  }
  return out;
}

// `value` as a GLSL float literal that reads back as the same float.
std::string floatLiteral(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(float(value)));
  std::string out = text;
  if (out.find_first_of(".e") == std::string::npos) out += ".0";
  return out;
}

std::string constLine(const char* type, const char* name, const std::string& value) {
  return std::string("const ") + type + " " + name + " = " + value + ";\n";
}

}  // namespace

std::vector<std::string> lightcutsDefines(unsigned flags) {
  return definesOf(
      flags, {"DISTANCE", "HAS_SPECULAR", "FITTED_COLOUR", "TILE_CUTS", "SHARED_PASS", "OWN_PASS"});
}

std::vector<std::string> referenceDefines(unsigned flags) {
  return definesOf(flags, {"HAS_DIRECTIONAL", "HAS_POINT", "HAS_SPOT", "HAS_SPECULAR"});
}

std::vector<std::string> octreeDefines(unsigned flags) {
  return definesOf(flags, {"HAS_SPECULAR"});
}

std::vector<std::string> gbufferDefines(Aov aov) {
  for (const AovChannel& c : kAovChannels) {
    if (c.aov == aov) return {"AOV", c.define};
  }
  return {};
}

std::vector<ProgramVariants> programs() {
  std::vector<ProgramVariants> out;
  out.push_back({"gbuffer.vert", "gbuffer.frag", {"gPosition"}, {gbufferDefines(Aov::None)}});
  for (const AovChannel& c : kAovChannels) out[0].variants.push_back(gbufferDefines(c.aov));
  out.push_back({"fullscreen.vert", "blend_composite.frag", {"oColour"}, {{}}});
  ProgramVariants reference{"fullscreen.vert", "lighting_reference.frag", {"oRadiance"}, {}};
  for (unsigned flags = 0; flags < 16; ++flags) {
    reference.variants.push_back(referenceDefines(flags));
  }
  out.push_back(reference);
  out.push_back({"fullscreen.vert",
                 "lighting_lightcuts.frag",
                 {"oRadiance", "oCutStats"},
                 lightcutsVariants()});
  out.push_back({"fullscreen.vert",
                 "lighting_octree.frag",
                 {"oRadiance"},
                 {octreeDefines(0), octreeDefines(kOctreeHasSpecular)}});
  out.push_back({"fullscreen.vert", "rsm_flux.frag", {"oRadiance"}, {{}}});
  out.push_back({"fullscreen.vert", "indirect_exact.frag", {"oRadiance"}, {{}}});
  const std::vector<std::string> sh = {"oSh0", "oSh1", "oSh2", "oSh3",
                                       "oSh4", "oSh5", "oSh6", "oExact"};
  out.push_back({"fullscreen.vert", "cache_gather.frag", sh, {{}, {"SH_L2"}}});
  out.push_back({"fullscreen.vert",
                 "cache_copy.frag",
                 sh,
                 {{}, {"SH_L2"}, {"CACHE_SUM"}, {"CACHE_SUM", "SH_L2"}}});
  std::vector<std::vector<std::string>> interpolation;
  for (const char* basis : {"", "SH_L2"})
    for (const char* normals : {"", "CENTRED_NORMALS"})
      for (const char* cascade : {"", "NEXT_CASCADE"}) {
        std::vector<std::string> defines;
        for (const char* d : {basis, normals, cascade})
          if (*d) defines.push_back(d);
        interpolation.push_back(defines);
      }
  out.push_back({"fullscreen.vert", "cache_interpolate.frag", {"oRadiance"}, interpolation});
  out.push_back({"fullscreen.vert", "cache_near.frag", {"oRadiance"}, {{}}});
  return out;
}

std::string layoutPrelude() {
  std::string out;
  out += constLine("float", "kPi", floatLiteral(shading::kPi));
  out += constLine("float", "kBandCells", floatLiteral(kBandCells));
  out += constLine("float", "kNearCells", floatLiteral(kNearCells));
  out += constLine("float", "kPlaneTolerance", floatLiteral(kPlaneTolerance));
  out += constLine("float", "kCorrectionCosine", floatLiteral(kCorrectionCosine));
  out += constLine("int", "kNormalBinGrid", std::to_string(kNormalBinGrid));
  out += constLine("int", "kCacheTextureShift", std::to_string(kCacheTextureShift));
  out += constLine("int", "kNearTextureShift", std::to_string(kNearTextureShift));
  out += constLine("int", "kRsmClusterEdge", std::to_string(kRsmClusterEdge));
  out += constLine("float", "kRsmClusterDistance", floatLiteral(kRsmClusterDistance));
  out += constLine("float", "kMinDistanceSquared", floatLiteral(shading::kMinDistanceSquared));
  out += constLine("float", "kDielectricF0", floatLiteral(shading::kDielectricF0));
  out += constLine("float", "kMaxPhongExponent", floatLiteral(shading::kMaxPhongExponent));
  out += constLine("int", "kTexelsPerLight", std::to_string(layout::kTexelsPerLight));
  out += constLine("int", "kFarFieldTexels", std::to_string(kFarFieldTexels));
  out += constLine("uint", "kNoSharedCut", std::to_string(kNoSharedCut) + "u");
  out += constLine("float", "kAbsoluteFloor", floatLiteral(kAbsoluteFloor));
  out += constLine("float", "kSpotReachSlack", floatLiteral(kSpotReachSlack));
  out += constLine("float", "kSpotCosineMargin", floatLiteral(kSpotCosineMargin));
  out += constLine("int", "kNodeWords", std::to_string(layout::kNodeWords));
  out += constLine("int", "kSpotNodeWords", std::to_string(layout::kSpotNodeWords));
  out += constLine("int", "kCutStatsOwnCut", std::to_string(kCutStatsOwnCut));
  out += constLine("int", "kCutStatsOwnCutAtMax", std::to_string(kCutStatsOwnCutAtMax));
  out += constLine("int", "kCutStatsSharedCut", std::to_string(kCutStatsSharedCut));
  out += constLine("int", "kCutStatsSharedCutAtMax", std::to_string(kCutStatsSharedCutAtMax));
  out += constLine("uint", "kFullCutBit", std::to_string(kFullCutBit) + "u");
  out += constLine("int", "kIterationBudget", std::to_string(kIterationBudget));
  out += constLine("int", "kMaxOctreeLevels", std::to_string(layout::kMaxOctreeLevels));
  out += constLine("uint", "kOctreeLeafBit", std::to_string(layout::kOctreeLeafBit) + "u");
  out += constLine("int", "kOctreeEntriesPerPass", std::to_string(layout::kOctreeEntriesPerPass));
  return out;
}

}  // namespace manylight::glsl
