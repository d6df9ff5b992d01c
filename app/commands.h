#pragma once
// The manylight command line, one file per group of subcommands: main.cpp (options and
// dispatch), common.cpp (what several share), render_command.cpp, play_command.cpp,
// tool_commands.cpp (bake, fit-gamma, compare). Each run* function returns an exit code
// and throws Error for bad input, which main turns into one line.
#include <CLI/CLI.hpp>
#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bake/baked_file.h"
#include "gl/context.h"
#include "gl/limits.h"
#include "image/image.h"
#include "render/lightcuts_method.h"
#include "render/renderer.h"
#include "scene/gltf_loader.h"
#include "tools/colour_calibration.h"

namespace manylight::cli {

using Clock = std::chrono::steady_clock;

enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,        // bad input or a failed render
  kExitUsage = 2,          // bad command line
  kExitNoContext = 3,      // no OpenGL 3.3 context could be created
  kExitDiffer = 4,         // compare: the images differ beyond the thresholds
  kExitInterrupted = 130,  // play: Ctrl-C or SIGTERM
};

double msSince(Clock::time_point t);
// `text` as a finite number (NaN, infinities and trailing characters refused), for options
// whose text is a number or a word; throws CLI::ValidationError naming `option`.
double finiteNumber(const std::string& option, const std::string& text);
// Adds a finiteness check to every float and double option of app's subcommands (CLI11
// reads "nan" and "inf" as numbers, and its Range lets NaN through), and an integer check to
// every integer option, so each says which number it expected. Options holding numbers in
// text (--ambient, --size, lists) are checked by their parsers. Call after declaring them.
void requireFiniteNumbers(CLI::App& app);
// "R,G,B" of finite numbers → a colour; throws CLI::ValidationError.
glm::vec3 parseRgb(const std::string& s);
// --exposure: "auto" → nothing (image/display.h's automatic exposure), else a finite number
// of EV; throws CLI::ValidationError.
std::optional<float> parseExposure(const std::string& s);
// The most pixels a side of --size may have before the context's own limits are asked.
inline constexpr int kMaxSizeSide = 1 << 16;
// "WxH" within 1..kMaxSizeSide → width and height; otherwise says why on stderr and returns
// false.
bool parseSize(const std::string& text, int* width, int* height);
// Whether the current context can render width × height (gl::renderSizeExceeded); otherwise
// says which limit --size exceeds on stderr and returns false.
bool sizeFitsContext(int width, int height);
// The node colour coding's figures for --stats.
nlohmann::json nodeColourStats(const NodeColourCoder& c);
// The octree method's figures for --stats: its octree's, and the frame's per-pixel lists.
nlohmann::json octreeStats(const OctreeSummary& o, const OctreeFrameStats& frame);
// A frame's indirect light figures for --stats.
nlohmann::json indirectStats(const IndirectSettings& settings, const IndirectStats& s);
// The note a frame whose `--indirect` added nothing gets (no map: no spot or directional
// light, or none with the least share), or "" where maps were made.
std::string noIndirectNote(const IndirectSettings& settings, const IndirectStats& s);
// One line naming the lights an octree holds at every pixel because their support holds
// the whole scene, or "" when there are none.
std::string wholeSceneNote(const std::string& scene, const OctreeSummary& o);
// --max-cut's help, for render, play and bench.
std::string maxCutHelp();
// A context, or null after saying why there is none.
std::unique_ptr<gl::Context> openContext(gl::Backend backend, bool verbose);

struct SceneArgs {
  std::string lightList, treeSplit = "metric", nodeColour = "rgb9e5";
  std::size_t lightBudget = 1u << 20;
  float octreeLeaf = 0.0f;  // 0: the rule of bake/light_octree.h
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
  OctreeOptions octree() const {
    OctreeOptions o;
    o.leafEdge = octreeLeaf;
    return o;
  }
};

void addSceneOptions(CLI::App* app, SceneArgs& a);
// A glTF scene with its light list, or a baked scene (by its magic, or the .mlbake
// extension) with its trees. Throws Error.
BakedScene loadAnyScene(const std::string& path, const SceneArgs& a);

// The lighting method and its lightcuts settings, as render and play take them.
struct MethodArgs {
  std::string method, errorMode = "node";
  float error = 0.02f;
  int maxCut = LightcutsSettings{}.maxCut;
  int cutTile = LightcutsSettings{}.tileSize;
  CLI::Option* methodOption = nullptr;  // --method, to tell a default from a choice

  std::string indirect = "none";
  int rsmLights = IndirectSettings{}.rsmLights, rsmSize = IndirectSettings{}.rsmSize;
  std::string cacheBasis = "sh2";
  float cacheCell = 0.0f;
  double rsmLeastShare = IndirectSettings{}.rsmLeastShare;

  // Throws Error for an unknown method.
  Method parsed() const { return parseMethod(method); }
  // The indirect light these options ask for.
  IndirectSettings indirectSettings() const {
    return {parseIndirect(indirect), rsmLights, rsmSize,
            cacheBasis == "sh2",     cacheCell, rsmLeastShare};
  }
  // The lightcuts settings these options give (trees aside).
  LightcutsSettings lightcuts() const;
};

void addMethodOptions(CLI::App* app, MethodArgs& a);

struct RenderArgs {
  std::vector<std::string> scenes;
  std::string output, outDir, format = "png", shard, size = "640x480", backend = "auto";
  std::string ambient, statsPath;  // ambient empty: 0, or the default rig's
  std::string aov;                 // empty: the lit image
  std::string maxCutMask;          // lightcuts: where cuts reached the maximum (one scene)
  std::string exposure = "auto", toneMap = "pbr-neutral";
  MethodArgs lighting{"auto"};
  int camera = -1;
  SceneArgs input;
  bool verbose = false;
};

int runRender(const RenderArgs& a, Clock::time_point processStart);

struct PlayArgs {
  std::string scene, output, size = "640x360", backend = "auto", statsPath;
  MethodArgs lighting{"auto"};
  int camera = -1, frames = 0;
  float orbit = 360.0f, fps = 30.0f;
  std::string exposure = "auto", toneMap = "pbr-neutral";
  SceneArgs input;
  bool verbose = false;
  bool freshCuts = false;  // lightcuts: every frame's shared cuts per square, none kept
};

int runPlay(const PlayArgs& a, Clock::time_point processStart);

struct BakeArgs {
  std::string scene, output, statsPath;
  SceneArgs input;
};

int runBake(const BakeArgs& a, Clock::time_point processStart);

struct FitArgs {
  std::string pairs, calibrate, backend = "auto",
                                codes = std::to_string(kFirstCalibrationCode) + "..255";
  bool verbose = false;
};

int runFitGamma(const FitArgs& a);

struct CompareArgs {
  std::string a, b, diff;
  CompareThresholds thresholds;
};

int runCompare(const CompareArgs& a);

struct BenchArgs {
  std::string suite = "sweep", csv, json, scene, size, backend = "auto", cases;
  std::string layouts = "uniform,clustered,street,mixed,uniform-ranged,street-ranged";
  std::string counts = "64,1024,16384,65536,262144,1048576";
  std::string methods = "reference,lightcuts,lightcuts-distance,octree", modes = "node,total";
  std::string errors;  // empty: the suite's (sweep 0.005,0.01,0.02,0.05,0.1; stability 0.02)
  int repeats = 3, frames = 60, maxCut = LightcutsSettings{}.maxCut;
  double referenceSeconds = 60.0;
  std::size_t lightBudget = 1u << 20;
  bool resume = false;
  bool verbose = false;
};

// Declares `bench` and its options on `app`.
CLI::App* addBenchCommand(CLI::App& app, BenchArgs& a);
int runBench(const BenchArgs& a);

}  // namespace manylight::cli
