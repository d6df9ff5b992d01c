// manylight: the command line. Parses arguments, calls the libraries, turns errors into a
// one-line "manylight: FILE: problem" and a named exit code. No rendering logic lives here;
// the subcommands are in the other files of app/ (see commands.h).
#include <iostream>

#include "app/commands.h"
#include "base/huge_pages.h"

using namespace manylight;
using namespace manylight::cli;

namespace {

// --camera: a glTF camera index, never negative (the default, −1, means "the first").
const CLI::Validator kCameraIndex(
    [](std::string& text) {
      return !text.empty() && text[0] != '-' ? std::string()
                                             : "expected a camera index >= 0, got '" + text + "'";
    },
    "INDEX");

// The render subcommand's arguments and options, parsed into `r`.
CLI::App* addRenderCommand(CLI::App& app, RenderArgs& r) {
  CLI::App* render = app.add_subcommand("render", "Render glTF scenes (.gltf or .glb) to images");
  render
      ->add_option(
          "scenes", r.scenes,
          "glTF 2.0 scenes (.gltf or .glb) or baked scenes (.mlbake); several with --out-dir")
      ->required();
  render->add_option("-o,--output", r.output,
                     "Output image: .png (8-bit sRGB) or .exr (linear float)");
  render->add_option(
      "--out-dir", r.outDir,
      "Render every scene into DIR/NAME.png (or --format) in one process and one context; a "
      "failing scene is reported and the others go on");
  render->add_option("--format", r.format, "--out-dir: png or exr")
      ->capture_default_str()
      ->check(CLI::IsMember({"png", "exr"}));
  render->add_option(
      "--shard", r.shard,
      "--out-dir: I/N renders scenes I, I+N, I+2N, ... (0 <= I < N) of the list, to spread a batch "
      "over machines");
  render->add_option("--size", r.size, "Image size WxH")->capture_default_str();
  render
      ->add_option("--camera", r.camera,
                   "Index of the glTF camera to use (default: the first; with none, frame the "
                   "scene's bounds from a 3/4 view)")
      ->check(kCameraIndex);
  addMethodOptions(render, r.lighting);
  render
      ->add_option("--backend", r.backend,
                   "Context: auto (EGL device, EGL surfaceless, OSMesa), egl, osmesa")
      ->capture_default_str();
  render->add_option("--ambient", r.ambient,
                     "Ambient radiance R,G,B, times albedo + specular (default: 0, or 0.1 with "
                     "the default light rig)");
  render
      ->add_option("--exposure", r.exposure,
                   "Exposure in EV (colour scaled by 2^EV), or auto: PNG from the image's 95th "
                   "percentile of luminance; EXR takes only an explicit EV")
      ->capture_default_str();
  render
      ->add_option("--tone-map", r.toneMap,
                   "PNG display transform after exposure: none (clamp), pbr-neutral (Khronos PBR "
                   "Neutral), aces; EXR stays linear")
      ->check(CLI::IsMember(toneMapNames()))
      ->capture_default_str();
  render
      ->add_option("--aov", r.aov,
                   "Write this material channel instead of the lit image, encoded as the glTF "
                   "Sample Viewer's debug output of that name (see the README)")
      ->check(CLI::IsMember(aovNames()));
  render->add_option("--max-cut-mask", r.maxCutMask,
                     "Also write an image (.png or .exr) that is white where a pixel's cut "
                     "reached --max-cut before its error rule held, black elsewhere (one scene)");
  addSceneOptions(render, r.input);
  render->add_option("--stats", r.statsPath, "Write timings and facts about the render as JSON");
  render->add_flag("-v,--verbose", r.verbose,
                   "Say which context was chosen and how long things took");
  return render;
}

// The play subcommand's arguments and options, parsed into `p`.
CLI::App* addPlayCommand(CLI::App& app, PlayArgs& p) {
  CLI::App* playCmd = app.add_subcommand("play",
                                         "Play a scene or baked scene: its camera animation, or a "
                                         "turntable orbit; one context, only the "
                                         "camera changing");
  playCmd->add_option("scene", p.scene, "glTF 2.0 scene or baked scene (.mlbake)")->required();
  playCmd
      ->add_option("-o,--output", p.output,
                   "Frames: a pattern with one %d or %0Nd (frames/%04d.png, .exr), or - for raw "
                   "RGBA8 frames "
                   "(sRGB, rows top-down, W*H*4 bytes each) on stdout")
      ->required();
  playCmd
      ->add_option("--frames", p.frames,
                   "Frames to play (default: the camera animation to its last key at --fps, or 120 "
                   "for an orbit)")
      ->check(CLI::Range(1, 1000000));
  playCmd->add_option("--fps", p.fps, "Frames per second of animation time")
      ->capture_default_str()
      ->check(CLI::Range(0.001f, 10000.0f));
  playCmd
      ->add_option("--orbit", p.orbit,
                   "Without a camera animation: degrees the camera turns about the scene's "
                   "vertical axis over "
                   "all frames")
      ->capture_default_str();
  playCmd->add_option("--size", p.size, "Frame size WxH")->capture_default_str();
  playCmd
      ->add_option("--camera", p.camera,
                   "Index of the glTF camera the orbit starts from (default: the first; "
                   "with none, the thumbnail framing)")
      ->check(kCameraIndex);
  addMethodOptions(playCmd, p.lighting);
  playCmd
      ->add_option("--exposure", p.exposure,
                   "Exposure in EV, or auto: fixed from the first frame (PNG and raw frames)")
      ->capture_default_str();
  playCmd->add_option("--tone-map", p.toneMap, "Display transform: none, pbr-neutral, aces")
      ->check(CLI::IsMember(toneMapNames()))
      ->capture_default_str();
  playCmd->add_option("--backend", p.backend, "Context: auto, egl, osmesa")->capture_default_str();
  addSceneOptions(playCmd, p.input);
  playCmd->add_option("--stats", p.statsPath,
                      "Write per-frame times and facts about the playback as JSON");
  playCmd->add_flag("--fresh-cuts", p.freshCuts,
                    "Lightcuts: find every frame's shared cuts per square of the screen, as "
                    "render does, instead of keeping cuts per cell of the scene from frame to "
                    "frame");
  playCmd->add_flag("-v,--verbose", p.verbose, "Say which context was chosen and the frame rate");
  return playCmd;
}

CLI::App* addBakeCommand(CLI::App& app, BakeArgs& b) {
  CLI::App* bake = app.add_subcommand("bake",
                                      "Bake a glTF scene (and a light list) into one file that "
                                      "render loads without rebuilding anything");
  bake->add_option("scene", b.scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  bake->add_option("-o,--output", b.output, "The baked scene, NAME.mlbake")->required();
  addSceneOptions(bake, b.input);
  bake->add_option("--stats", b.statsPath, "Write timings and facts about the bake as JSON");
  return bake;
}

CLI::App* addFitGammaCommand(CLI::App& app, FitArgs& f) {
  CLI::App* fit = app.add_subcommand("fit-gamma",
                                     "Fit out = A·in^γ by least squares in log–log space, to pairs "
                                     "from a file or measured by rendering");
  fit->add_option("pairs", f.pairs, "CSV of in,out pairs (a header line 'in,out' is allowed)");
  fit->add_option(
      "--calibrate", f.calibrate,
      "Measure the pairs: render the scene lit by its first light in each grey 8-bit colour "
      "(--codes) on the reference path");
  fit->add_option(
         "--codes", f.codes,
         "--calibrate: the 8-bit codes probed, FIRST..LAST (the default skips the sRGB curve's "
         "linear segment, codes 0-10, which no power law fits)")
      ->capture_default_str();
  fit->add_option("--backend", f.backend, "Context for --calibrate: auto, egl, osmesa")
      ->capture_default_str();
  fit->add_flag("-v,--verbose", f.verbose, "Say which context was chosen");
  return fit;
}

CLI::App* addCompareCommand(CLI::App& app, CompareArgs& c) {
  CLI::App* compare = app.add_subcommand("compare",
                                         "Compare two images value by value (OpenImageIO); exit 0 "
                                         "when they match, 4 when they differ");
  compare->add_option("a", c.a, "First image (any format OpenImageIO reads)")->required();
  compare->add_option("b", c.b, "Second image")->required();
  compare
      ->add_option("--max-abs", c.thresholds.maxAbs,
                   "A value may differ by this much (8-bit files are read as code/255: 0.004 "
                   "allows one code)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e30));
  compare
      ->add_option("--max-fraction", c.thresholds.maxFraction,
                   "The share of values (0..1) allowed to differ by more than --max-abs")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  CLI::Option* relative =
      compare
          ->add_option("--max-relative", c.thresholds.maxRelative,
                       "Instead of value by value: B is the reference, and a pixel it covers "
                       "(alpha > 0) may be off by this share of its largest channel "
                       "(max over channels of |A - B| / max of B; 8-bit files are read as "
                       "code/255, so compare radiance as EXR)")
          ->check(CLI::Range(0.0, 1e30));
  compare
      ->add_option("--percentile", c.thresholds.percentile,
                   "With --max-relative: this percentile of the pixels' relative errors is "
                   "what must stay within it (100: every pixel)")
      ->capture_default_str()
      ->check(CLI::Range(1e-9, 100.0))
      ->needs(relative);
  compare->add_option("--diff", c.diff,
                      "Where to write the difference image when they differ (default: B.diff.png)");
  return compare;
}

}  // namespace

int main(int argc, char** argv) {
  restartWithHugePages(argv);
  const auto processStart = Clock::now();
  CLI::App app{"manylight: headless OpenGL renderer for glTF scenes with many lights"};
  app.require_subcommand(1);
  RenderArgs r;
  CLI::App* render = addRenderCommand(app, r);
  PlayArgs p;
  CLI::App* playCmd = addPlayCommand(app, p);
  BakeArgs b;
  CLI::App* bake = addBakeCommand(app, b);
  FitArgs f;
  CLI::App* fit = addFitGammaCommand(app, f);
  CompareArgs c;
  CLI::App* compare = addCompareCommand(app, c);
  BenchArgs benchArgs;
  CLI::App* bench = addBenchCommand(app, benchArgs);
  requireFiniteNumbers(app);
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "manylight: " + std::string(e.what()) + "\n";
  });
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
    if (*bench) return runBench(benchArgs);
  } catch (const CLI::ParseError& e) {
    std::cerr << "manylight: " << e.what() << "\n";
    return kExitUsage;
  } catch (const Error& e) {
    std::cerr << "manylight: " << e.what() << "\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    const std::string& subject = *fit               ? (f.pairs.empty() ? f.calibrate : f.pairs)
                                 : *compare         ? c.a
                                 : *bench           ? std::string("bench")
                                 : *bake            ? b.scene
                                 : *playCmd         ? p.scene
                                 : r.scenes.empty() ? std::string("render")
                                                    : r.scenes[0];
    std::cerr << "manylight: " << subject << ": " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitUsage;
}
