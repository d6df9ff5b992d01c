#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "app/commands.h"
#include "bake/light_tree_layout.h"
#include "scene/light_list.h"

namespace manylight::cli {
namespace {

nlohmann::json perChannel(const double (&v)[3]) {
  return nlohmann::json::array({v[0], v[1], v[2]});
}

// Whether all of `text` is one finite number (as std::stod reads it), and which.
bool readFinite(const std::string& text, double* v) {
  std::size_t used = 0;
  try {
    *v = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;  // no number, or one beyond double's range
  }
  return used == text.size() && std::isfinite(*v);
}

std::string notFinite(const std::string& text) {
  return "expected a finite number, got '" + text + "'";
}

}  // namespace

double msSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

double finiteNumber(const std::string& option, const std::string& text) {
  double v = 0.0;
  if (!readFinite(text, &v)) throw CLI::ValidationError(option, notFinite(text));
  return v;
}

void requireFiniteNumbers(CLI::App& app) {
  const CLI::Validator finite(
      [](std::string& text) {
        double v = 0.0;
        return readFinite(text, &v) ? std::string() : notFinite(text);
      },
      "", "finite");
  const CLI::Validator integer(
      [](std::string& text) {
        char* end = nullptr;
        errno = 0;
        std::strtoll(text.c_str(), &end, 0);  // base 0, as CLI11 reads integers
        return !text.empty() && *end == '\0' && errno == 0
                   ? std::string()
                   : "expected an integer, got '" + text + "'";
      },
      "", "integer");
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    for (CLI::Option* option : command->get_options()) {
      // Type names begin with FLOAT, INT or UINT (and go on with their checks' names).
      const std::string type = option->get_type_name();
      if (type.rfind("FLOAT", 0) == 0) option->check(finite);
      if (type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0) option->check(integer);
    }
  }
}

glm::vec3 parseRgb(const std::string& s) {
  glm::vec3 v;
  char tail = 0;
  if (std::sscanf(s.c_str(), "%f,%f,%f%c", &v.r, &v.g, &v.b, &tail) != 3 || !std::isfinite(v.r) ||
      !std::isfinite(v.g) || !std::isfinite(v.b)) {
    throw CLI::ValidationError("--ambient",
                               "expected R,G,B, three finite numbers, got '" + s + "'");
  }
  return v;
}

std::optional<float> parseExposure(const std::string& s) {
  if (s == "auto") return std::nullopt;
  const double ev = finiteNumber("--exposure", s);
  // 2^±128 leaves a float's range: such an exposure turns every pixel white or black.
  if (std::abs(ev) > 128.0)
    throw CLI::ValidationError("--exposure", "expected an EV within ±128 or auto, got '" + s + "'");
  return float(ev);
}

bool parseSize(const std::string& text, int* width, int* height) {
  char tail = 0;
  if (std::sscanf(text.c_str(), "%dx%d%c", width, height, &tail) == 2 && *width >= 1 &&
      *height >= 1 && *width <= kMaxSizeSide && *height <= kMaxSizeSide)
    return true;
  std::cerr << "manylight: --size: expected WxH within 1.." << kMaxSizeSide << ", got '" << text
            << "'\n";
  return false;
}

bool sizeFitsContext(int width, int height) {
  const std::string exceeded = gl::renderSizeExceeded(width, height);
  if (exceeded.empty()) return true;
  std::cerr << "manylight: --size " << width << "x" << height << " " << exceeded << "\n";
  return false;
}

nlohmann::json nodeColourStats(const NodeColourCoder& c) {
  nlohmann::json j = {
      {"coding", c.coding() == NodeColourCoding::Fitted ? "fitted" : "rgb9e5"},
      {"bytes_per_node", 4 * layout::kNodeWords},
      {"bytes_per_spot_node", 4 * layout::kSpotNodeWords},
      {"slack", c.slack},
      {"slack_floor", c.slackFloor},
      {"max_error", perChannel(c.maxError)},
      {"p99_error", perChannel(c.p99Error)},
  };
  if (c.coding() == NodeColourCoding::Fitted) {
    j["gamma"] = c.fit().gamma;
    j["a"] = c.fit().a;
    j["fit_worst_relative"] = c.fit().worstRelative;
    j["fitted_to_srgb"] = c.fittedToSrgb();
  } else {
    j["scale"] = c.scale();
  }
  return j;
}

std::unique_ptr<gl::Context> openContext(gl::Backend backend, bool verbose) {
  std::vector<std::string> attempts;
  std::unique_ptr<gl::Context> context;
  try {
    context = gl::createContext(backend, &attempts);
  } catch (const gl::GlError& e) {
    std::cerr << "manylight: " << e.what() << "\n";
    return nullptr;
  }
  if (verbose) {
    for (const std::string& line : attempts) std::cerr << "manylight: context " << line << "\n";
    std::cerr << "manylight: using " << context->backend() << ", " << context->renderer() << ", "
              << context->version() << "\n";
  }
  return context;
}

std::string maxCutHelp() {
  return "lightcuts: most nodes of a cut a pixel walks itself (the cuts shared by groups of "
         "pixels, --cut-tile, hold up to " +
         std::to_string(kSharedCutLimit) + " entries)";
}

void addMethodOptions(CLI::App* app, MethodArgs& a) {
  a.methodOption =
      app->add_option(
             "--method", a.method,
             "Lighting method: reference (every light at every pixel), lightcuts (error-bounded "
             "cuts through a light tree), lightcuts-distance (cuts by radius of influence), "
             "octree (exact: each pixel's lights from a hashed light octree), auto (the "
             "fastest of them for the scene; --verbose says which and why)")
          ->capture_default_str()
          ->check(
              CLI::IsMember({"reference", "lightcuts", "lightcuts-distance", "octree", "auto"}));
  app->add_option("--error", a.error, "lightcuts: relative error ε of the stopping rule")
      ->capture_default_str()
      ->check(CLI::Range(1e-6f, 1.0f));
  app->add_option("--error-mode", a.errorMode,
                  "lightcuts: node (the paper's rule: each node's bound ≤ ε·estimate) or total "
                  "(guaranteed: the sum of the cut's error bounds ≤ ε·estimate)")
      ->capture_default_str()
      ->check(CLI::IsMember({"node", "total"}));
  app->add_option("--max-cut", a.maxCut, maxCutHelp())
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxCutLimit));
  app->add_option("--cut-tile", a.cutTile,
                  "lightcuts: pixels share the cut of their N x N square where the rule holds for "
                  "them (cuts/tile_cuts.h); 1: a cut per pixel")
      ->capture_default_str()
      ->check(CLI::IsMember({1, 4, 8, 16, 32, 64}));
  app->add_option("--indirect", a.indirect,
                  "One bounce of diffuse indirect light from reflective shadow maps: none, "
                  "exact (every map texel at every pixel) or caches (at light caches on "
                  "cascaded grids, interpolated per pixel; see docs/indirect.md)")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "exact", "caches"}));
  app->add_option("--cache-basis", a.cacheBasis,
                  "--indirect caches: spherical harmonics sh1 (4 coefficients) or sh2 (9)")
      ->capture_default_str()
      ->check(CLI::IsMember({"sh1", "sh2"}));
  app->add_option("--cache-cell", a.cacheCell,
                  "--indirect caches: the smallest cascade's cell edge in scene units (0: the "
                  "scene's diagonal / 128)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app->add_option("--rsm-lights", a.rsmLights,
                  "--indirect: the spot and directional lights sending the most flux into the "
                  "view that get a reflective shadow map")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  app->add_option("--rsm-least-share", a.rsmLeastShare,
                  "--indirect: the least share of the direct flux into the view a light sends "
                  "for a map (0: the --rsm-lights largest get maps whatever their share)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  app->add_option("--rsm-size", a.rsmSize, "--indirect: a reflective shadow map's width and height")
      ->capture_default_str()
      ->check(CLI::IsMember({16, 32, 64, 128, 256, 512}));
}

LightcutsSettings MethodArgs::lightcuts() const {
  LightcutsSettings s;
  s.error = error;
  s.maxCut = maxCut;
  s.tileSize = cutTile;
  s.mode = errorMode == "total" ? ErrorMode::Total : ErrorMode::Node;
  return s;
}

nlohmann::json octreeStats(const OctreeSummary& o, const OctreeFrameStats& frame) {
  return {{"levels", o.levels},
          {"leaf_edge", o.leafEdge},
          {"nodes", o.nodes},
          {"hash_slots", o.slots},
          {"hash_offsets", o.offsetEntries},
          {"hash_attempts", o.hashAttempts},
          {"index_list_length", o.indices},
          {"bytes", o.bytes},
          {"global_lights", o.globalCount},
          {"whole_scene_lights", o.wholeScene.size()},
          {"unreached_lights", o.unreached},
          {"max_leaf_list", o.maxLeafCount},
          {"covered_pixels", frame.pixels},
          {"list_entries_per_pixel", frame.listEntries},
          {"light_evaluations_per_pixel", frame.lightEvaluations},
          {"lights_reaching_per_pixel", frame.lightsReaching},
          {"lights_lit_per_pixel", frame.lightsLit}};
}

std::string noIndirectNote(const IndirectSettings& settings, const IndirectStats& s) {
  if (settings.mode == Indirect::None || s.rsmLights > 0) return "";
  std::ostringstream out;
  out << "--indirect " << indirectName(settings.mode) << ": ";
  if (s.candidates == 0)
    out << "the scene has no spot or directional light to cast it";
  else
    out << "no spot or directional light sends " << settings.rsmLeastShare
        << " of the view's flux (--rsm-least-share)";
  out << ": no indirect light added";
  return out.str();
}

nlohmann::json indirectStats(const IndirectSettings& settings, const IndirectStats& s) {
  return {{"mode", indirectName(settings.mode)},
          {"rsm_size", settings.rsmSize},
          {"rsm_lights", s.rsmLights},
          {"maps_kept", s.mapsKept},
          {"maps_rendered", s.mapsRendered},
          {"rsm_candidates", s.candidates},
          {"rsm_texels", s.rsmTexels},
          {"rsm_flux_share", s.fluxShare},
          {"rsm_below_share", s.belowShare},
          {"gather_passes", s.passes},
          {"choose_ms", s.chooseMs},
          {"rsm_ms", s.rsmMs},
          {"gather_ms", s.gatherMs},
          {"caches", s.caches},
          {"caches_kept", s.cachesKept},
          {"caches_gathered", s.cachesGathered},
          {"caches_refused", s.cachesRefused},
          {"cascades", s.cascades},
          {"cache_cell", s.cacheCell},
          {"allocate_ms", s.allocateMs},
          {"near_passes", s.nearPasses},
          {"near_clusters", s.nearClusters},
          {"near_ms", s.nearMs},
          {"interpolate_ms", s.interpolateMs}};
}

std::string wholeSceneNote(const std::string& scene, const OctreeSummary& o) {
  if (o.wholeScene.empty()) return {};
  std::string names;
  for (std::size_t i = 0; i < o.wholeScene.size() && i < 8; ++i)
    names += (i ? ", " : "") + std::to_string(o.wholeScene[i]);
  if (o.wholeScene.size() > 8) names += ", …";
  return scene + ": warning: " + std::to_string(o.wholeScene.size()) +
         " ranged lights reach the whole scene (their range holds its bounds), so the octree "
         "leaves them to the list every pixel evaluates: light " +
         names;
}

void addSceneOptions(CLI::App* app, SceneArgs& a) {
  a.splitOption =
      app->add_option(
             "--tree-split", a.treeSplit,
             "lightcuts: how the light trees pair lights: metric (the split with the smallest "
             "cluster metric) or longest-axis (the k-d baseline)")
          ->capture_default_str()
          ->check(CLI::IsMember({"metric", "longest-axis"}));
  a.colourOption =
      app->add_option(
             "--node-colour", a.nodeColour,
             "lightcuts: how tree nodes store their colour in one word: rgb9e5 (9-bit "
             "mantissas, shared exponent; the more accurate) or fitted (8 bits per channel on "
             "a power law fitted to the scene, shared exponent)")
          ->capture_default_str()
          ->check(CLI::IsMember({"fitted", "rgb9e5"}));
  app->add_option("--octree-leaf", a.octreeLeaf,
                  "octree: edge of the smallest cells, in scene units (0: a quarter of the "
                  "median light range; see docs/octree.md)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app->add_option("--lights", a.lightList,
                  "Add point lights from a list: .csv, .json, or the Lightcuts-in-UE4 text dump "
                  "(8-bit sRGB colours; see README)");
  app->add_option("--light-budget", a.lightBudget, "Most lights a scene may have")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t(1), std::size_t(1) << 26));
  app->add_option("--max-file-bytes", a.limits.maxFileBytes,
                  "Most bytes a scene may read: the glTF/GLB and its external files")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app->add_option("--max-texture-size", a.limits.maxTextureDimension,
                  "Largest texture width or height")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app->add_option("--max-texture-pixels", a.limits.maxTexturePixels, "Most pixels in one texture")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app->add_option("--max-triangles", a.limits.maxTriangles, "Most triangles over all meshes")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app->add_option("--crease-angle", a.limits.creaseAngleDegrees,
                  "Degrees: normals built for meshes without them are smooth across gentler edges, "
                  "split across sharper ones")
      ->capture_default_str()
      ->check(CLI::Range(0.0f, 180.0f));
}

BakedScene loadAnyScene(const std::string& path, const SceneArgs& a) {
  const bool baked = isBakedFile(path) || std::filesystem::path(path).extension() == ".mlbake";
  if (!baked) {
    BakedScene b;
    b.scene = loadGltf(path, a.options());
    if (!a.lightList.empty()) appendLightList(a.lightList, b.scene, a.options());
    return b;
  }
  BakedScene b = readBakedScene(path, a.limits.maxFileBytes);
  b.scene.name = path;  // messages name the file the user gave
  if (!a.lightList.empty())
    throw Error(path + ": a baked scene's lights are baked in; bake it again with --lights");
  if (b.scene.lights.size() > a.lightBudget) {
    throw Error(path + ": " + std::to_string(b.scene.lights.size()) +
                " lights exceed the light budget of " + std::to_string(a.lightBudget) +
                " (--light-budget)");
  }
  const TreeOptions asked = a.trees();
  if ((a.splitOption->count() > 0 && asked.split != b.trees.split) ||
      (a.colourOption->count() > 0 && asked.nodeColour != b.trees.nodeColour)) {
    throw Error(
        path +
        ": baked with other --tree-split or --node-colour settings; bake it again to change them");
  }
  return b;
}

}  // namespace manylight::cli
