#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "app/commands.h"
#include "base/output_file.h"
#include "render/playback.h"
#include "tools/progress.h"

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

// Where played frames go: files named by the -o pattern, or raw RGBA8 on stdout, through the
// display transform, whose automatic exposure is fixed from the first frame so a playback
// does not pump (EXR files stay linear: an explicit EV only, no tone map).
class FrameSink {
 public:
  explicit FrameSink(const PlayArgs& a)
      : a_(a),
        toStdout_(a.output == "-"),
        exposure_(parseExposure(a.exposure)),
        toneMap_(parseToneMap(a.toneMap)) {
    const std::string ext = toStdout_ ? "" : std::filesystem::path(a.output).extension().string();
    linear_ = ext == ".exr" || ext == ".EXR";
  }

  // Writes frame `frame`; false when stdout was closed.
  bool write(int frame, const Image& image) {
    if (frame == 0) {
      display_.exposure = exposure_ ? *exposure_ : linear_ ? 0.0f : autoExposure(image);
      display_.toneMap = linear_ ? ToneMap::None : toneMap_;
    }
    if (!toStdout_) {
      std::string name;
      frameName(a_.output, frame, &name);
      writeImage(image, name, display_);
      return true;
    }
    codes_ = displayCodes(image, display_);
    if (std::fwrite(codes_.data(), 1, codes_.size(), stdout) != codes_.size() ||
        std::fflush(stdout) != 0) {
      closed_ = true;
      return false;
    }
    return true;
  }

  const Display& display() const { return display_; }
  bool closed() const { return closed_; }

 private:
  const PlayArgs& a_;
  bool toStdout_, linear_ = false, closed_ = false;
  std::optional<float> exposure_;
  ToneMap toneMap_;
  Display display_;
  std::vector<std::uint8_t> codes_;
};

// The playback `a` asks for, but its scene; false (having said why) where its size or its -o
// pattern is not one. Throws Error for an output format no image is written in.
bool playbackRequest(const PlayArgs& a, PlaybackRequest& request) {
  RenderRequest& r = request.frame;
  if (!parseSize(a.size, &r.width, &r.height)) return false;
  if (a.output != "-") {
    std::string first;
    if (!frameName(a.output, 0, &first)) {
      std::cerr << "manylight: -o: expected a file name pattern with one %d or %0Nd (e.g. "
                   "frames/%04d.png), or - "
                   "for raw RGBA8 frames on stdout, got '"
                << a.output << "'\n";
      return false;
    }
    checkOutputPath(first);
  }
  r.camera = a.camera;
  r.rigAmbient = true;
  r.method = a.lighting.parsed();
  r.lightcuts = a.lighting.lightcuts();
  r.indirect = a.lighting.indirectSettings();
  r.lightcuts.trees = a.input.trees();
  r.octree = a.input.octree();
  request.frames = a.frames;
  request.fps = a.fps;
  request.orbitDegrees = a.orbit;
  request.keepCuts = !a.freshCuts;
  return true;
}

// The playback's own part of `stats`: the method, the frames and their timings.
void addPlaybackStats(nlohmann::json& stats, const PlaybackOutcome& out,
                      const nlohmann::json& indirectFrames) {
  stats["method"] = methodName(out.method);
  stats["lights"] = out.lightCount;
  stats["frames"] = out.framesRendered;
  stats["camera_animation"] = out.animated;
  stats["light_animation"] = out.lightsAnimated;
  stats["bake_ms"] = out.bakeMs;
  stats["frame_render_ms"] = out.renderMs;
  stats["interrupted"] = gInterrupted.load();
  if (out.lightsAnimated) stats["frame_move_lights_ms"] = out.moveMs;
  if (!indirectFrames.empty()) stats["frame_indirect"] = indirectFrames;
  if (!out.methodReason.empty()) stats["method_reason"] = out.methodReason;
  if (out.method == Method::Lightcuts || out.method == Method::LightcutsDistance) {
    stats["frame_cut_ms"] = out.cutMs;
    stats["frame_cuts_made"] = out.cutsMade;
    stats["frame_cuts_kept"] = out.cutsKept;
  }
}

// --verbose's lines after a playback: the method's reason where `auto` chose, the frame rates.
void sayPlayback(const PlayArgs& a, const PlaybackOutcome& out, double renderSum, double wallMs) {
  if (!out.methodReason.empty()) {
    std::cerr << "manylight: " << a.scene << ": auto: " << methodName(out.method) << ": "
              << out.methodReason << "\n";
  }
  std::cerr << "manylight: " << out.framesRendered << " frames, "
            << (renderSum > 0 ? 1000.0 * out.framesRendered / renderSum : 0) << " fps rendering, "
            << 1000.0 * out.framesRendered / std::max(wallMs, 1e-9) << " fps overall\n";
}

}  // namespace

int runPlay(const PlayArgs& a, Clock::time_point processStart) {
  PlaybackRequest request;
  if (!playbackRequest(a, request)) return kExitUsage;
  RenderRequest& r = request.frame;
  FrameSink sink(a);
  const gl::Backend backend = gl::parseBackend(a.backend);

  const auto loadStart = Clock::now();
  BakedScene baked = loadAnyScene(a.scene, a.input);  // its trees go to the renderer
  const double loadMs = msSince(loadStart);
  for (const std::string& w : baked.scene.warnings)
    std::cerr << "manylight: " << a.scene << ": warning: " << w << "\n";
  if (baked.hasTrees) r.prebuiltTrees = &baked.packed;
  if (baked.hasOctree) r.prebuiltOctree = &baked.octree;
  const std::unique_ptr<gl::Context> context = openContext(backend, a.verbose);
  if (!context) return kExitNoContext;
  if (!sizeFitsContext(r.width, r.height)) return kExitFailure;

  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  std::signal(SIGPIPE, SIG_IGN);  // a closed pipe shows as a failed write, and stops the playback
  Progress progress(a.frames > 0 ? a.frames : 0);
  const auto playStart = Clock::now();
  nlohmann::json indirectFrames = nlohmann::json::array();
  std::string noIndirect;  // the first frame's whose --indirect added nothing
  int framesWithout = 0;
  const PlaybackOutcome out = play(
      baked.scene, request,
      [&](int frame, const Image& image, const FrameStats& frameStats) {
        if (r.indirect.mode != Indirect::None) {
          indirectFrames.push_back(indirectStats(r.indirect, frameStats.indirect));
          const std::string note = noIndirectNote(r.indirect, frameStats.indirect);
          if (!note.empty() && framesWithout++ == 0) noIndirect = note;
        }
        if (!sink.write(frame, image)) return false;
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
        {"backend", context->backend()},
        {"renderer", context->renderer()},
        {"width", r.width},
        {"height", r.height},
        {"baked_trees", baked.hasTrees},
        {"exposure_ev", sink.display().exposure},
        {"tone_map", toneMapName(sink.display().toneMap)},
        {"load_ms", loadMs},
        {"render_fps", renderSum > 0.0 ? 1000.0 * out.framesRendered / renderSum : 0.0},
        {"wall_fps", wallMs > 0.0 ? 1000.0 * out.framesRendered / wallMs : 0.0},
        {"output_closed", sink.closed()},
        {"total_ms", msSince(processStart)}};
    addPlaybackStats(stats, out, indirectFrames);
    writeFileAtomic(a.statsPath, stats.dump(2) + "\n");
  }
  if (framesWithout > 0)
    std::cerr << "manylight: " << (a.output == "-" ? "stdout" : a.output) << ": " << noIndirect
              << " (" << framesWithout << " of " << out.framesRendered << " frames)\n";
  if (gInterrupted) {
    std::cerr << "manylight: interrupted after " << out.framesRendered << " frames\n";
    return kExitInterrupted;
  }
  if (sink.closed())
    std::cerr << "manylight: output closed after " << out.framesRendered - 1 << " frames\n";
  if (a.verbose) sayPlayback(a, out, renderSum, wallMs);
  return kExitOk;
}

}  // namespace manylight::cli
