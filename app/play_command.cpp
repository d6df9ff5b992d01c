#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "app/commands.h"
#include "render/playback.h"
#include "render/progress.h"
#include "scene/output_file.h"

namespace manylight::cli {
namespace {

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
    while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])) &&
           width < 100) {
      width = width * 10 + (pattern[j++] - '0');
    }
    if (j >= pattern.size() || pattern[j] != 'd' || width > 12) return false;
    std::string digits = std::to_string(frame);
    if (int(digits.size()) < width)
      digits.insert(0, std::size_t(width) - digits.size(), zero ? '0' : ' ');
    out += digits;
    ++conversions;
    i = j;
  }
  if (name) *name = out;
  return conversions == 1;
}

std::atomic<bool> gInterrupted{false};
extern "C" void onInterrupt(int) { gInterrupted = true; }

}  // namespace

int runPlay(const PlayArgs& a, Clock::time_point processStart) {
  PlaybackRequest request;
  RenderRequest& r = request.frame;
  if (!parseSize(a.size, &r.width, &r.height)) return kExitUsage;
  const bool toStdout = a.output == "-";
  if (!toStdout) {
    std::string first;
    if (!frameName(a.output, 0, &first)) {
      std::cerr << "manylight: -o: expected a file name pattern with one %d or %0Nd (e.g. "
                   "frames/%04d.png), or - "
                   "for raw RGBA8 frames on stdout, got '"
                << a.output << "'\n";
      return kExitUsage;
    }
    checkOutputPath(first);
  }
  r.camera = a.camera;
  r.rigAmbient = true;
  const std::optional<float> exposure = parseExposure(a.exposure);
  const ToneMap toneMap = parseToneMap(a.toneMap);
  const std::string ext = toStdout ? "" : std::filesystem::path(a.output).extension().string();
  const bool linearOutput = ext == ".exr" || ext == ".EXR";
  r.method = a.lighting.parsed();
  r.lightcuts = a.lighting.lightcuts();
  r.lightcuts.trees = a.input.trees();
  request.frames = a.frames;
  request.fps = a.fps;
  request.orbitDegrees = a.orbit;
  request.keepCuts = !a.freshCuts;
  const gl::Backend backend = gl::parseBackend(a.backend);

  const auto loadStart = Clock::now();
  const BakedScene baked = loadAnyScene(a.scene, a.input);
  const double loadMs = msSince(loadStart);
  for (const std::string& w : baked.scene.warnings)
    std::cerr << "manylight: " << a.scene << ": warning: " << w << "\n";
  if (baked.hasTrees) r.prebuiltTrees = &baked.packed;
  const std::unique_ptr<gl::Context> context = openContext(backend, a.verbose);
  if (!context) return kExitNoContext;
  if (!sizeFitsContext(r.width, r.height)) return kExitFailure;

  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  std::signal(SIGPIPE, SIG_IGN);  // a closed pipe shows as a failed write, and stops the playback
  bool outputClosed = false;
  std::vector<std::uint8_t> codes;
  Display display;
  Progress progress(a.frames > 0 ? a.frames : 0);
  const auto playStart = Clock::now();
  const PlaybackOutcome out = play(
      baked.scene, request,
      [&](int frame, const Image& image, const FrameStats&) {
        // Automatic exposure is fixed from the first frame, so a playback does not pump.
        if (frame == 0) {
          display.exposure = exposure ? *exposure : linearOutput ? 0.0f : autoExposure(image);
          display.toneMap = linearOutput ? ToneMap::None : toneMap;
        }
        if (toStdout) {
          codes = displayCodes(image, display);
          if (std::fwrite(codes.data(), 1, codes.size(), stdout) != codes.size() ||
              std::fflush(stdout) != 0) {
            outputClosed = true;
            return false;
          }
        } else {
          std::string name;
          frameName(a.output, frame, &name);
          writeImage(image, name, display);
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
    nlohmann::json stats = {
        {"scene", a.scene},
        {"output", a.output},
        {"method", methodName(r.method)},
        {"backend", context->backend()},
        {"renderer", context->renderer()},
        {"width", r.width},
        {"height", r.height},
        {"lights", out.lightCount},
        {"baked_trees", baked.hasTrees},
        {"frames", out.framesRendered},
        {"exposure_ev", display.exposure},
        {"tone_map", toneMapName(display.toneMap)},
        {"camera_animation", out.animated},
        {"load_ms", loadMs},
        {"bake_ms", out.bakeMs},
        {"frame_render_ms", out.renderMs},
        {"render_fps", renderSum > 0.0 ? 1000.0 * out.framesRendered / renderSum : 0.0},
        {"wall_fps", wallMs > 0.0 ? 1000.0 * out.framesRendered / wallMs : 0.0},
        {"interrupted", gInterrupted.load()},
        {"output_closed", outputClosed},
        {"total_ms", msSince(processStart)}};
    if (r.method != Method::Reference) {
      stats["frame_cut_ms"] = out.cutMs;
      stats["frame_cuts_made"] = out.cutsMade;
      stats["frame_cuts_kept"] = out.cutsKept;
    }
    writeFileAtomic(a.statsPath, stats.dump(2) + "\n");
  }
  if (gInterrupted) {
    std::cerr << "manylight: interrupted after " << out.framesRendered << " frames\n";
    return kExitInterrupted;
  }
  if (outputClosed)
    std::cerr << "manylight: output closed after " << out.framesRendered - 1 << " frames\n";
  if (a.verbose) {
    std::cerr << "manylight: " << out.framesRendered << " frames, "
              << (renderSum > 0 ? 1000.0 * out.framesRendered / renderSum : 0) << " fps rendering, "
              << 1000.0 * out.framesRendered / std::max(wallMs, 1e-9) << " fps overall\n";
  }
  return kExitOk;
}

}  // namespace manylight::cli
