// manylight: the command line. Parses arguments, calls the libraries, turns errors into a
// one-line "manylight: FILE: problem" and a named exit code. No rendering logic lives here.
#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "gl/context.h"
#include "render/colour_calibration.h"
#include "scene/output_file.h"
#include "render/playback.h"
#include "render/progress.h"
#include "render/render_job.h"
#include "bake/baked_file.h"
#include "bake/light_tree_layout.h"
#include "scene/gltf_loader.h"
#include "scene/light_list.h"

namespace {

using namespace manylight;
using Clock = std::chrono::steady_clock;

enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,  // bad input or a failed render
  kExitUsage = 2,    // bad command line
  kExitNoContext = 3,  // no OpenGL 3.3 context could be created
  kExitDiffer = 4,     // compare: the images differ beyond the thresholds
};

double msSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

glm::vec3 parseRgb(const std::string& s) {
  glm::vec3 v;
  char tail = 0;
  if (std::sscanf(s.c_str(), "%f,%f,%f%c", &v.r, &v.g, &v.b, &tail) != 3 || !(v == v)) {
    throw CLI::ValidationError("--ambient", "expected R,G,B, got '" + s + "'");
  }
  return v;
}

nlohmann::json perChannel(const double (&v)[3]) { return nlohmann::json::array({v[0], v[1], v[2]}); }

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

// A context, or null after saying why there is none.
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

struct FitArgs {
  std::string pairs, calibrate, backend = "auto", codes = std::to_string(kFirstCalibrationCode) + "..255";
  bool verbose = false;
};

void printFit(const PowerFit& fit) {
  std::printf("pairs = %zu\ngamma = %.6f\nA = %.8g\nlog10(A) = %.6f\nR^2 = %.6f\nworst relative residual = %.6f\n",
              fit.pairs, fit.gamma, fit.a, fit.log10A, fit.r2, fit.worstRelative);
}

int runFitGamma(const FitArgs& a) {
  if (a.pairs.empty() == a.calibrate.empty()) {
    std::cerr << "manylight: fit-gamma: give either PAIRS.csv or --calibrate SCENE\n";
    return kExitUsage;
  }
  if (!a.pairs.empty()) {
    const std::vector<FitPair> pairs = readFitPairs(a.pairs);
    try {
      printFit(fitPowerLaw(pairs));
    } catch (const BakeError& e) {
      throw BakeError(a.pairs + ": " + e.what());
    }
    return kExitOk;
  }
  int first = 0, last = 0;
  char tail = 0;
  if (std::sscanf(a.codes.c_str(), "%d..%d%c", &first, &last, &tail) != 2 || first < 1 || last > 255 || first >= last) {
    std::cerr << "manylight: --codes: expected FIRST..LAST with 1 <= FIRST < LAST <= 255, got '" << a.codes << "'\n";
    return kExitUsage;
  }
  const Scene scene = loadGltf(a.calibrate);
  const std::unique_ptr<gl::Context> context = openContext(gl::parseBackend(a.backend), a.verbose);
  if (!context) return kExitNoContext;
  const ColourCalibration c = calibrateColour(scene, first, last);
  printFit(c.fit);
  std::printf("largest difference from the sRGB curve = %d codes (at code %d)\n", c.largestCodeDifference,
              c.worstCode);
  return kExitOk;
}

struct CompareArgs {
  std::string a, b, diff;
  CompareThresholds thresholds;
};

// "out/b.png" → "out/b.diff.png"
std::string defaultDiffPath(const std::string& b) {
  std::filesystem::path p(b);
  return (p.parent_path() / (p.stem().string() + ".diff.png")).string();
}

int runCompare(const CompareArgs& a) {
  const std::string diffPath = a.diff.empty() ? defaultDiffPath(a.b) : a.diff;
  const CompareOutcome out = compareImageFiles(a.a, a.b, a.thresholds, diffPath);
  const ImageComparison& v = out.values;
  if (!v.sameShape) {
    std::printf("%s %s: differ: %dx%d with %d channels against %dx%d with %d\n", a.a.c_str(), a.b.c_str(), v.width[0],
                v.height[0], v.channels[0], v.width[1], v.height[1], v.channels[1]);
    return kExitDiffer;
  }
  std::printf("%s %s: %s: %lld of %lld values (%.4g%%) off by more than %g; max %g at pixel (%d, %d) channel %d; "
              "mean %g; RMS %g; PSNR %.2f dB%s%s\n",
              a.a.c_str(), a.b.c_str(), out.passed ? "match" : "differ", v.failing, v.values,
              v.values > 0 ? 100.0 * double(v.failing) / double(v.values) : 0.0, a.thresholds.maxAbs, v.maxError,
              v.maxX, v.maxY, v.maxChannel, v.meanError, v.rmsError, v.psnr, out.diffWritten ? "; difference: " : "",
              out.diffWritten ? diffPath.c_str() : "");
  return out.passed ? kExitOk : kExitDiffer;
}

// "I/N" with 0 <= I < N.
bool parseShard(const std::string& text, Shard& shard) {
  char tail = 0;
  return std::sscanf(text.c_str(), "%d/%d%c", &shard.index, &shard.count, &tail) == 2 && shard.count >= 1 &&
         shard.index >= 0 && shard.index < shard.count;
}

// What render and bake share: how a scene is read, and how its light trees are built.
struct SceneArgs {
  std::string lightList, treeSplit = "metric", nodeColour = "rgb9e5";
  std::size_t lightBudget = 1u << 20;
  LoadOptions limits;
  CLI::Option* splitOption = nullptr;
  CLI::Option* colourOption = nullptr;

  LoadOptions options() const {
    LoadOptions o = limits;
    o.lightBudget = lightBudget;
    return o;
  }
  TreeOptions trees() const {
    TreeOptions t;
    t.split = treeSplit == "metric" ? Split::Metric : Split::LongestAxis;
    t.nodeColour = nodeColour == "fitted" ? NodeColourCoding::Fitted : NodeColourCoding::Rgb9e5;
    return t;
  }
};

void addSceneOptions(CLI::App* app, SceneArgs& a) {
  a.splitOption = app->add_option("--tree-split", a.treeSplit,
                                  "lightcuts: how the light trees pair lights: metric (the split with the smallest "
                                  "cluster metric) or longest-axis (the k-d baseline)")
                      ->capture_default_str()
                      ->check(CLI::IsMember({"metric", "longest-axis"}));
  a.colourOption = app->add_option("--node-colour", a.nodeColour,
                                   "lightcuts: how tree nodes store their colour in one word: rgb9e5 (9-bit "
                                   "mantissas, shared exponent; the more accurate) or fitted (8 bits per channel on "
                                   "a power law fitted to the scene, shared exponent)")
                       ->capture_default_str()
                       ->check(CLI::IsMember({"fitted", "rgb9e5"}));
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
  app->add_option("--max-texture-size", a.limits.maxTextureDimension, "Largest texture width or height")
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

// A glTF scene with its light list, or a baked scene (by its magic, or the .mlbake
// extension) with its trees. Throws Error.
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
  if (!a.lightList.empty()) throw Error(path + ": a baked scene's lights are baked in; bake it again with --lights");
  if (b.scene.lights.size() > a.lightBudget) {
    throw Error(path + ": " + std::to_string(b.scene.lights.size()) + " lights exceed the light budget of " +
                std::to_string(a.lightBudget) + " (--light-budget)");
  }
  const TreeOptions asked = a.trees();
  if ((a.splitOption->count() > 0 && asked.split != b.trees.split) ||
      (a.colourOption->count() > 0 && asked.nodeColour != b.trees.nodeColour)) {
    throw Error(path + ": baked with other --tree-split or --node-colour settings; bake it again to change them");
  }
  return b;
}

struct BakeArgs {
  std::string scene, output, statsPath;
  SceneArgs input;
};

int runBake(const BakeArgs& a, Clock::time_point processStart) {
  if (std::filesystem::path(a.output).extension() != ".mlbake") {
    std::cerr << "manylight: " << a.output << ": a baked scene's file name must end in .mlbake\n";
    return kExitUsage;
  }
  if (isBakedFile(a.scene)) throw Error(a.scene + ": already baked");
  auto start = Clock::now();
  Scene scene = loadGltf(a.scene, a.input.options());
  if (!a.input.lightList.empty()) appendLightList(a.input.lightList, scene, a.input.options());
  for (const std::string& w : scene.warnings) std::cerr << "manylight: " << a.scene << ": warning: " << w << "\n";
  const double loadMs = msSince(start);
  start = Clock::now();
  const BakedScene baked = bakeScene(std::move(scene), a.input.trees());
  const double bakeMs = msSince(start);
  start = Clock::now();
  writeBakedScene(a.output, baked);
  const double writeMs = msSince(start);
  const auto bytes = std::filesystem::file_size(a.output);
  std::printf("%s: %zu lights, %zu tree words, %ju bytes; load %.0f ms, trees %.0f ms, write %.0f ms\n",
              a.output.c_str(), baked.scene.lights.size(), baked.packed.words.size(), std::uintmax_t(bytes), loadMs,
              bakeMs, writeMs);
  if (!a.statsPath.empty()) {
    nlohmann::json stats = {{"scene", a.scene},        {"output", a.output},   {"lights", baked.scene.lights.size()},
                            {"bytes", bytes},          {"load_ms", loadMs},    {"bake_ms", bakeMs},
                            {"write_ms", writeMs},     {"total_ms", msSince(processStart)},
                            {"format_version", kBakedFormatVersion}};
    if (baked.hasTrees) stats["node_colour"] = nodeColourStats(baked.packed.colour);
    writeFileAtomic(a.statsPath, stats.dump(2) + "\n");
  }
  return kExitOk;
}

// A frame file name pattern: exactly one %d or %0Nd (and %% for a percent sign).
bool frameName(const std::string& pattern, int frame, std::string* name) {
  std::string out;
  int conversions = 0;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') {
      out += pattern[i];
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      out += '%';
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    const bool zero = j < pattern.size() && pattern[j] == '0';
    if (zero) ++j;
    int width = 0;
    while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])) && width < 100) {
      width = width * 10 + (pattern[j++] - '0');
    }
    if (j >= pattern.size() || pattern[j] != 'd' || width > 12) return false;
    std::string digits = std::to_string(frame);
    if (int(digits.size()) < width) digits.insert(0, std::size_t(width) - digits.size(), zero ? '0' : ' ');
    out += digits;
    ++conversions;
    i = j;
  }
  if (name) *name = out;
  return conversions == 1;
}

std::atomic<bool> gInterrupted{false};
extern "C" void onInterrupt(int) { gInterrupted = true; }

struct PlayArgs {
  std::string scene, output, size = "640x360", method = "lightcuts", backend = "auto", statsPath;
  std::string errorMode = "node";
  float error = 0.02f;
  int maxCut = LightcutsSettings{}.maxCut;
  int camera = -1, frames = 0;
  float orbit = 360.0f, exposure = 0.0f, fps = 30.0f;
  SceneArgs input;
  bool verbose = false;
};

int runPlay(const PlayArgs& a, Clock::time_point processStart) {
  PlaybackRequest request;
  RenderRequest& r = request.frame;
  char tail = 0;
  if (std::sscanf(a.size.c_str(), "%dx%d%c", &r.width, &r.height, &tail) != 2 || r.width < 1 || r.height < 1 ||
      r.width > 16384 || r.height > 16384) {
    std::cerr << "manylight: --size: expected WxH within 1..16384, got '" << a.size << "'\n";
    return kExitUsage;
  }
  const bool toStdout = a.output == "-";
  if (!toStdout) {
    std::string first;
    if (!frameName(a.output, 0, &first)) {
      std::cerr << "manylight: -o: expected a file name pattern with one %d or %0Nd (e.g. frames/%04d.png), or - "
                   "for raw RGBA8 frames on stdout, got '"
                << a.output << "'\n";
      return kExitUsage;
    }
    checkOutputPath(first);
  }
  r.camera = a.camera;
  r.method = parseMethod(a.method);
  r.lightcuts.error = a.error;
  r.lightcuts.maxCut = a.maxCut;
  r.lightcuts.mode = a.errorMode == "total" ? ErrorMode::Total : ErrorMode::Node;
  r.lightcuts.trees = a.input.trees();
  request.frames = a.frames;
  request.fps = a.fps;
  request.orbitDegrees = a.orbit;
  const gl::Backend backend = gl::parseBackend(a.backend);

  const auto loadStart = Clock::now();
  const BakedScene baked = loadAnyScene(a.scene, a.input);
  const double loadMs = msSince(loadStart);
  for (const std::string& w : baked.scene.warnings) std::cerr << "manylight: " << a.scene << ": warning: " << w << "\n";
  if (baked.hasTrees) r.prebuiltTrees = &baked.packed;
  const std::unique_ptr<gl::Context> context = openContext(backend, a.verbose);
  if (!context) return kExitNoContext;

  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  std::signal(SIGPIPE, SIG_IGN);  // a closed pipe shows as a failed write, and stops the playback
  bool outputClosed = false;
  std::vector<std::uint8_t> codes;
  Progress progress(a.frames > 0 ? a.frames : 0);
  const auto playStart = Clock::now();
  const PlaybackOutcome out = play(
      baked.scene, request,
      [&](int frame, const Image& image, const FrameStats&) {
        if (toStdout) {
          codes.resize(image.rgba.size());
          const double scale = std::exp2(double(a.exposure));
          for (std::size_t i = 0; i < codes.size(); ++i) {
            codes[i] = i % 4 == 3 ? std::uint8_t(std::lround(std::clamp(image.rgba[i], 0.0f, 1.0f) * 255.0f))
                                  : encodeSrgb8(image.rgba[i] * scale);
          }
          if (std::fwrite(codes.data(), 1, codes.size(), stdout) != codes.size() || std::fflush(stdout) != 0) {
            outputClosed = true;
            return false;
          }
        } else {
          std::string name;
          frameName(a.output, frame, &name);
          writeImage(image, name, a.exposure);
        }
        progress.step("frame " + std::to_string(frame));
        return true;
      },
      &gInterrupted);
  progress.clear();
  const double wallMs = msSince(playStart);
  double renderSum = 0.0;
  for (double ms : out.renderMs) renderSum += ms;
  if (!a.statsPath.empty()) {
    nlohmann::json stats = {{"scene", a.scene},
                            {"output", a.output},
                            {"method", methodName(r.method)},
                            {"backend", context->backend()},
                            {"renderer", context->renderer()},
                            {"width", r.width},
                            {"height", r.height},
                            {"lights", out.lightCount},
                            {"baked_trees", baked.hasTrees},
                            {"frames", out.framesRendered},
                            {"camera_animation", out.animated},
                            {"load_ms", loadMs},
                            {"bake_ms", out.bakeMs},
                            {"frame_render_ms", out.renderMs},
                            {"render_fps", renderSum > 0.0 ? 1000.0 * out.framesRendered / renderSum : 0.0},
                            {"wall_fps", wallMs > 0.0 ? 1000.0 * out.framesRendered / wallMs : 0.0},
                            {"interrupted", gInterrupted.load()},
                            {"output_closed", outputClosed},
                            {"total_ms", msSince(processStart)}};
    writeFileAtomic(a.statsPath, stats.dump(2) + "\n");
  }
  if (gInterrupted) {
    std::cerr << "manylight: interrupted after " << out.framesRendered << " frames\n";
    return 130;
  }
  if (outputClosed) std::cerr << "manylight: output closed after " << out.framesRendered - 1 << " frames\n";
  if (a.verbose) {
    std::cerr << "manylight: " << out.framesRendered << " frames, " << (renderSum > 0 ? 1000.0 * out.framesRendered / renderSum : 0)
              << " fps rendering, " << 1000.0 * out.framesRendered / std::max(wallMs, 1e-9) << " fps overall\n";
  }
  return kExitOk;
}

struct RenderArgs {
  std::vector<std::string> scenes;
  std::string output, outDir, format = "png", shard, size = "640x480", method = "reference", backend = "auto";
  std::string ambient = "0,0,0", statsPath, errorMode = "node";
  float error = 0.02f;
  int maxCut = LightcutsSettings{}.maxCut;
  int camera = -1;
  float exposure = 0.0f;
  SceneArgs input;
  bool verbose = false;
};

// Loads, renders and writes one scene; returns its stats. Throws Error.
nlohmann::json renderOne(const RenderArgs& a, const RenderRequest& request, const std::string& scenePath,
                         const std::string& output, const gl::Context& context) {
  const auto start = Clock::now();
  const BakedScene baked = loadAnyScene(scenePath, a.input);
  const Scene& scene = baked.scene;
  const double loadMs = msSince(start);
  for (const std::string& w : scene.warnings) std::cerr << "manylight: " << scenePath << ": warning: " << w << "\n";
  RenderRequest bakedRequest = request;
  if (baked.hasTrees) bakedRequest.prebuiltTrees = &baked.packed;
  const RenderOutcome out = renderScene(scene, bakedRequest);
  if (out.framed && a.verbose) std::cerr << "manylight: " << scenePath << ": no camera; framing the bounds\n";
  if (out.defaultRig) std::cerr << "manylight: " << scenePath << ": no lights; using the default three-light rig\n";
  writeImage(out.image, output, a.exposure);
  nlohmann::json stats = {
      {"scene", scenePath},
      {"output", output},
      {"method", methodName(request.method)},
      {"backend", context.backend()},
      {"renderer", context.renderer()},
      {"gl_version", context.version()},
      {"width", request.width},
      {"height", request.height},
      {"lights", out.lightCount},
      {"default_light_rig", out.defaultRig},
      {"framed_camera", out.framed},
      {"lighting_passes", out.frame.lightingPasses},
      {"load_ms", loadMs},
      {"render_ms", out.frame.renderMs},
      {"scene_ms", msSince(start)},
      {"degenerate_triangles", scene.topology.degenerateTriangles},
      {"boundary_edges", scene.topology.boundaryEdges},
      {"non_manifold_edges", scene.topology.nonManifoldEdges},
  };
  if (request.method != Method::Reference) {
    const CutStats& c = out.frame.cuts;
    stats["bake_ms"] = out.bakeMs;
    stats["avg_cut_size"] = c.averageCut;
    stats["max_cut_size"] = c.maxCut;
    stats["pixels_at_max_cut"] = c.pixelsAtMaxCut;
    stats["light_evaluations_per_pixel"] = c.lightEvaluations;
    stats["node_evaluations_per_pixel"] = c.nodeEvaluations;
    stats["covered_pixels"] = c.pixels;
    if (request.method == Method::Lightcuts) {
      stats["error"] = request.lightcuts.error;
      stats["error_mode"] = a.errorMode;
    }
    stats["max_cut"] = request.lightcuts.maxCut;
    stats["tree_split"] = baked.hasTrees ? (baked.trees.split == Split::Metric ? "metric" : "longest-axis")
                                         : a.input.treeSplit;
    stats["baked_trees"] = baked.hasTrees;
    stats["node_colour"] = nodeColourStats(out.nodeColour);
  }
  if (a.verbose) {
    std::cerr << "manylight: " << output << ": " << request.width << "x" << request.height << ", " << out.lightCount
              << " lights, load " << loadMs << " ms, render " << out.frame.renderMs << " ms\n";
  }
  return stats;
}

int runRender(const RenderArgs& a, Clock::time_point processStart) {
  RenderRequest request;
  char tail = 0;
  if (std::sscanf(a.size.c_str(), "%dx%d%c", &request.width, &request.height, &tail) != 2 ||
      request.width < 1 || request.height < 1 || request.width > 16384 || request.height > 16384) {
    std::cerr << "manylight: --size: expected WxH within 1..16384, got '" << a.size << "'\n";
    return kExitUsage;
  }
  const bool batch = !a.outDir.empty();
  if (batch == !a.output.empty()) {
    std::cerr << "manylight: render: give either -o OUTPUT (one scene) or --out-dir DIR (any number)\n";
    return kExitUsage;
  }
  if (!batch && a.scenes.size() != 1) {
    std::cerr << "manylight: render: -o takes one scene, got " << a.scenes.size() << "; use --out-dir for several\n";
    return kExitUsage;
  }
  request.camera = a.camera;
  request.ambient = parseRgb(a.ambient);
  request.method = parseMethod(a.method);
  request.lightcuts.error = a.error;
  request.lightcuts.maxCut = a.maxCut;
  request.lightcuts.mode = a.errorMode == "total" ? ErrorMode::Total : ErrorMode::Node;
  request.lightcuts.trees = a.input.trees();
  const gl::Backend backend = gl::parseBackend(a.backend);
  std::vector<Thumbnail> jobs;
  if (batch) {
    Shard shard;
    if (!a.shard.empty() && !parseShard(a.shard, shard)) {
      std::cerr << "manylight: --shard: expected I/N with 0 <= I < N, got '" << a.shard << "'\n";
      return kExitUsage;
    }
    jobs = planThumbnails(a.scenes, a.outDir, a.format, shard);
  } else {
    checkOutputPath(a.output);
    jobs.push_back({a.scenes[0], a.output});
  }

  const std::unique_ptr<gl::Context> context = openContext(backend, a.verbose);
  if (!context) return kExitNoContext;
  if (!batch) {
    nlohmann::json stats = renderOne(a, request, jobs[0].scene, jobs[0].output, *context);
    stats["total_ms"] = msSince(processStart);
    if (!a.statsPath.empty()) writeFileAtomic(a.statsPath, stats.dump(2) + "\n");
    return kExitOk;
  }
  // A batch: one context for all; a failing scene is reported and the rest go on.
  nlohmann::json all = nlohmann::json::array();
  int failed = 0;
  Progress progress(int(jobs.size()));
  for (const Thumbnail& job : jobs) {
    progress.step(job.scene);
    try {
      all.push_back(renderOne(a, request, job.scene, job.output, *context));
    } catch (const Error& e) {
      progress.clear();
      std::cerr << "manylight: " << e.what() << "\n";
      all.push_back({{"scene", job.scene}, {"output", job.output}, {"error", e.what()}});
      ++failed;
    } catch (const std::exception& e) {
      progress.clear();
      std::cerr << "manylight: " << job.scene << ": " << e.what() << "\n";
      all.push_back({{"scene", job.scene}, {"output", job.output}, {"error", e.what()}});
      ++failed;
    }
  }
  progress.clear();
  const double totalMs = msSince(processStart);
  std::cerr << "manylight: rendered " << jobs.size() - failed << " of " << jobs.size() << " scenes into " << a.outDir
            << (failed ? ", " + std::to_string(failed) + " failed" : std::string()) << " (" << std::lround(totalMs)
            << " ms)\n";
  if (!a.statsPath.empty()) {
    const nlohmann::json stats = {{"scenes", all},
                                  {"rendered", int(jobs.size()) - failed},
                                  {"failed", failed},
                                  {"shard", a.shard.empty() ? "0/1" : a.shard},
                                  {"backend", context->backend()},
                                  {"total_ms", totalMs}};
    writeFileAtomic(a.statsPath, stats.dump(2) + "\n");
  }
  return failed ? kExitFailure : kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  const auto processStart = Clock::now();
  CLI::App app{"manylight: headless OpenGL renderer for glTF scenes with many lights"};
  app.require_subcommand(1);
  RenderArgs r;
  CLI::App* render = app.add_subcommand("render", "Render glTF scenes (.gltf or .glb) to images");
  render->add_option("scenes", r.scenes, "glTF 2.0 scenes (.gltf or .glb) or baked scenes (.mlbake); several with --out-dir")->required();
  render->add_option("-o,--output", r.output, "Output image: .png (8-bit sRGB) or .exr (linear float)");
  render->add_option("--out-dir", r.outDir,
                     "Render every scene into DIR/NAME.png (or --format) in one process and one context; a "
                     "failing scene is reported and the others go on");
  render->add_option("--format", r.format, "--out-dir: png or exr")->capture_default_str()->check(
      CLI::IsMember({"png", "exr"}));
  render->add_option("--shard", r.shard,
                     "--out-dir: I/N renders scenes I, I+N, I+2N, ... (0 <= I < N) of the list, to spread a batch "
                     "over machines");
  render->add_option("--size", r.size, "Image size WxH")->capture_default_str();
  render->add_option("--camera", r.camera,
                     "Index of the glTF camera to use (default: the first; with none, frame the "
                     "scene's bounds from a 3/4 view)");
  render->add_option("--method", r.method,
                     "Lighting method: reference (every light at every pixel), lightcuts (error-bounded "
                     "cuts through a light tree), lightcuts-distance (cuts by radius of influence)")
      ->capture_default_str()
      ->check(CLI::IsMember({"reference", "lightcuts", "lightcuts-distance"}));
  render->add_option("--error", r.error, "lightcuts: relative error ε of the stopping rule")
      ->capture_default_str()
      ->check(CLI::Range(1e-6f, 1.0f));
  render->add_option("--error-mode", r.errorMode,
                     "lightcuts: node (the paper's rule: each node's bound ≤ ε·estimate) or total "
                     "(guaranteed: the sum of the cut's error bounds ≤ ε·estimate)")
      ->capture_default_str()
      ->check(CLI::IsMember({"node", "total"}));
  render->add_option("--max-cut", r.maxCut, "lightcuts: most nodes in a pixel's cut")
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxCutLimit));
  render->add_option("--backend", r.backend, "Context: auto (EGL device, EGL surfaceless, OSMesa), egl, osmesa")
      ->capture_default_str();
  render->add_option("--ambient", r.ambient, "Ambient radiance R,G,B, multiplied by the albedo")
      ->capture_default_str();
  render->add_option("--exposure", r.exposure, "Exposure in EV: the image is scaled by 2^EV")
      ->capture_default_str();
  addSceneOptions(render, r.input);
  render->add_option("--stats", r.statsPath, "Write timings and facts about the render as JSON");
  render->add_flag("-v,--verbose", r.verbose, "Say which context was chosen and how long things took");
  PlayArgs p;
  CLI::App* playCmd = app.add_subcommand(
      "play", "Play a scene or baked scene: its camera animation, or a turntable orbit; one context, only the "
              "camera changing");
  playCmd->add_option("scene", p.scene, "glTF 2.0 scene or baked scene (.mlbake)")->required();
  playCmd->add_option("-o,--output", p.output,
                      "Frames: a pattern with one %d or %0Nd (frames/%04d.png, .exr), or - for raw RGBA8 frames "
                      "(sRGB, rows top-down, W*H*4 bytes each) on stdout")
      ->required();
  playCmd->add_option("--frames", p.frames,
                      "Frames to play (default: the camera animation to its last key at --fps, or 120 for an orbit)")
      ->check(CLI::Range(1, 1000000));
  playCmd->add_option("--fps", p.fps, "Frames per second of animation time")
      ->capture_default_str()
      ->check(CLI::Range(0.001f, 10000.0f));
  playCmd->add_option("--orbit", p.orbit,
                      "Without a camera animation: degrees the camera turns about the scene's vertical axis over "
                      "all frames")
      ->capture_default_str();
  playCmd->add_option("--size", p.size, "Frame size WxH")->capture_default_str();
  playCmd->add_option("--camera", p.camera, "Index of the glTF camera the orbit starts from (default: the first; "
                                            "with none, the thumbnail framing)");
  playCmd->add_option("--method", p.method, "reference, lightcuts or lightcuts-distance")
      ->capture_default_str()
      ->check(CLI::IsMember({"reference", "lightcuts", "lightcuts-distance"}));
  playCmd->add_option("--error", p.error, "lightcuts: relative error ε")->capture_default_str()->check(
      CLI::Range(1e-6f, 1.0f));
  playCmd->add_option("--error-mode", p.errorMode, "lightcuts: node or total")
      ->capture_default_str()
      ->check(CLI::IsMember({"node", "total"}));
  playCmd->add_option("--max-cut", p.maxCut, "lightcuts: most nodes in a pixel's cut")
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxCutLimit));
  playCmd->add_option("--exposure", p.exposure, "Exposure in EV")->capture_default_str();
  playCmd->add_option("--backend", p.backend, "Context: auto, egl, osmesa")->capture_default_str();
  addSceneOptions(playCmd, p.input);
  playCmd->add_option("--stats", p.statsPath, "Write per-frame times and facts about the playback as JSON");
  playCmd->add_flag("-v,--verbose", p.verbose, "Say which context was chosen and the frame rate");
  BakeArgs b;
  CLI::App* bake = app.add_subcommand(
      "bake", "Bake a glTF scene (and a light list) into one file that render loads without rebuilding anything");
  bake->add_option("scene", b.scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  bake->add_option("-o,--output", b.output, "The baked scene, NAME.mlbake")->required();
  addSceneOptions(bake, b.input);
  bake->add_option("--stats", b.statsPath, "Write timings and facts about the bake as JSON");
  FitArgs f;
  CLI::App* fit = app.add_subcommand(
      "fit-gamma", "Fit out = A·in^γ by least squares in log–log space, to pairs from a file or measured by rendering");
  fit->add_option("pairs", f.pairs, "CSV of in,out pairs (a header line 'in,out' is allowed)");
  fit->add_option("--calibrate", f.calibrate,
                  "Measure the pairs: render the scene lit by its first light in each grey 8-bit colour "
                  "1..255 on the reference path");
  fit->add_option("--codes", f.codes,
                  "--calibrate: the 8-bit codes probed, FIRST..LAST (the default skips the sRGB curve's "
                  "linear segment, codes 0-10, which no power law fits)")
      ->capture_default_str();
  fit->add_option("--backend", f.backend, "Context for --calibrate: auto, egl, osmesa")->capture_default_str();
  fit->add_flag("-v,--verbose", f.verbose, "Say which context was chosen");
  CompareArgs c;
  CLI::App* compare = app.add_subcommand(
      "compare", "Compare two images value by value (OpenImageIO); exit 0 when they match, 4 when they differ");
  compare->add_option("a", c.a, "First image (any format OpenImageIO reads)")->required();
  compare->add_option("b", c.b, "Second image")->required();
  compare->add_option("--max-abs", c.thresholds.maxAbs,
                      "A value may differ by this much (8-bit files are read as code/255: 0.004 allows one code)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e30));
  compare->add_option("--max-fraction", c.thresholds.maxFraction,
                      "The share of values (0..1) allowed to differ by more than --max-abs")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  compare->add_option("--diff", c.diff, "Where to write the difference image when they differ (default: B.diff.png)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  try {
    if (*render) return runRender(r, processStart);
    if (*fit) return runFitGamma(f);
    if (*bake) return runBake(b, processStart);
    if (*playCmd) return runPlay(p, processStart);
    if (*compare) return runCompare(c);
  } catch (const CLI::ParseError& e) {
    std::cerr << "manylight: " << e.what() << "\n";
    return kExitUsage;
  } catch (const Error& e) {
    std::cerr << "manylight: " << e.what() << "\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    const std::string& subject = *fit       ? (f.pairs.empty() ? f.calibrate : f.pairs)
                                 : *compare ? c.a
                                 : *bake    ? b.scene
                                 : *playCmd ? p.scene
                                 : r.scenes.empty() ? std::string("render") : r.scenes[0];
    std::cerr << "manylight: " << subject << ": " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitUsage;
}
