#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <iostream>

#include "app/commands.h"
#include "base/output_file.h"
#include "cuts/tile_cuts.h"
#include "render/render_job.h"
#include "scene/image_io.h"
#include "tools/progress.h"

namespace manylight::cli {
namespace {

bool parseShard(const std::string& text, Shard& shard) {
  char tail = 0;
  return std::sscanf(text.c_str(), "%d/%d%c", &shard.index, &shard.count, &tail) == 2 &&
         shard.count >= 1 && shard.index >= 0 && shard.index < shard.count;
}

// A scene read on a worker thread, and how long reading it took there.
struct LoadedScene {
  BakedScene baked;
  double loadMs = 0.0;
};

// Starts reading `path` on a worker thread; get() gives the scene or rethrows its Error.
// Reading needs no GL, so the first scene (whose textures bring in OpenImageIO's libraries,
// hundreds of them to link) is read while the context opens and the driver compiles
// the G-buffer program, and each next one of a batch while the one before renders.
std::future<LoadedScene> startLoading(const RenderArgs& a, const std::string& path) {
  return std::async(std::launch::async, [&a, path] {
    const auto start = Clock::now();
    LoadedScene loaded{loadAnyScene(path, a.input)};
    // The image is written through it: its libraries load here, off the main thread, even
    // when the scene has no texture. After the scene, so a bad scene fails at once.
    imageIo();
    loaded.loadMs = msSince(start);
    return loaded;
  });
}

// The mask of `cuts`' pixels whose cut reached the maximum before its rule held: 1 there, 0
// elsewhere (everywhere for a method without cuts, which misses nothing).
Image maxCutMask(const CutStats& cuts, int width, int height) {
  Image mask;
  mask.width = width, mask.height = height;
  mask.values = ImageValues::Data;
  mask.rgba.assign(std::size_t(width) * height * 4, 0.0f);
  for (std::size_t i = 0; i < std::size_t(width) * height; ++i) {
    const float v = i < cuts.atMaxCut.size() && cuts.atMaxCut[i] ? 1.0f : 0.0f;
    mask.rgba[4 * i] = mask.rgba[4 * i + 1] = mask.rgba[4 * i + 2] = v;
    mask.rgba[4 * i + 3] = 1.0f;
  }
  return mask;
}

// The stats of a frame lit by lightcuts (or the distance criterion): its cuts, and on stderr
// the pixels whose cut reached the maximum.
void addCutStats(nlohmann::json& stats, const RenderArgs& a, const RenderRequest& request,
                 const RenderOutcome& out, const BakedScene& baked, const std::string& output) {
  const CutStats& c = out.frame.cuts;
  stats["bake_ms"] = out.bakeMs;
  stats["cut_ms"] = out.frame.cutMs;
  stats["avg_cut_size"] = c.averageCut;
  stats["max_cut_size"] = c.maxCut;
  stats["pixels_at_max_cut"] = c.pixelsAtMaxCut;
  if (c.pixelsAtMaxCut > 0) {
    std::cerr << "manylight: " << output << ": " << c.pixelsAtMaxCut << " of " << c.pixels
              << " pixels reached the maximum cut (--max-cut " << request.lightcuts.maxCut << "; "
              << kSharedCutLimit
              << " for cuts shared by groups of pixels) before the error rule held: their error "
                 "is not bounded"
              << (a.maxCutMask.empty() ? " (--max-cut-mask shows where)" : "") << "\n";
  }
  stats["pixels_shared_cut"] = c.pixelsSharedCut;
  stats["shared_cuts"] = c.sharedCuts;
  stats["exact_cuts"] = c.exactCuts;
  stats["per_pixel_groups"] = c.perPixelGroups;
  stats["surface_splits"] = c.surfaceSplits;
  stats["light_evaluations_per_pixel"] = c.lightEvaluations;
  stats["node_evaluations_per_pixel"] = c.nodeEvaluations;
  for (int k = 0; k < kCutKinds; ++k) {
    const CutWork& w = c.work[std::size_t(k)];
    stats["cut_work"][kCutKindNames[k]] = {
        {"cuts", w.cuts}, {"full", w.full}, {"bounds", w.bounds}};
  }
  stats["covered_pixels"] = c.pixels;
  if (out.method == Method::Lightcuts) {
    stats["error"] = request.lightcuts.error;
    stats["error_mode"] = a.lighting.errorMode;
  }
  stats["max_cut"] = request.lightcuts.maxCut;
  stats["cut_tile"] = request.lightcuts.tileSize;
  stats["tree_split"] = baked.hasTrees
                            ? (baked.trees.split == Split::Metric ? "metric" : "longest-axis")
                            : a.input.treeSplit;
  stats["baked_trees"] = baked.hasTrees;
  stats["node_colour"] = nodeColourStats(out.nodeColour);
}

// Writes the frame to `output`, and the --max-cut-mask if asked; returns the display transform
// it took. Throws Error, having removed `output` where the mask failed.
Display writeOutputs(const RenderArgs& a, const RenderRequest& request, const RenderOutcome& out,
                     const std::string& output) {
  // Exposure and the tone map are for light; an AOV holds material values, written as they are.
  // EXR stays linear: no tone map, and only an explicit exposure.
  Display display;
  const bool png = output.size() >= 4 && (output.substr(output.size() - 4) == ".png" ||
                                          output.substr(output.size() - 4) == ".PNG");
  if (request.aov == Aov::None) {
    const std::optional<float> ev = parseExposure(a.exposure);
    display.exposure = ev ? *ev : png ? autoExposure(out.image) : 0.0f;
    display.toneMap = png ? parseToneMap(a.toneMap) : ToneMap::None;
  }
  writeImage(out.image, output, display);
  if (!a.maxCutMask.empty()) {
    try {
      writeImage(maxCutMask(out.frame.cuts, request.width, request.height), a.maxCutMask);
    } catch (...) {
      std::error_code ec;
      std::filesystem::remove(output, ec);  // a failed run leaves nothing behind
      throw;
    }
  }
  return display;
}

// Renders and writes one scene; returns its stats. Throws Error.
// The scene's baked trees, if any, go to the renderer.
nlohmann::json renderOne(const RenderArgs& a, const RenderRequest& request,
                         const std::string& scenePath, LoadedScene loaded,
                         const std::string& output, const gl::Context& context) {
  const auto start = Clock::now();
  BakedScene& baked = loaded.baked;
  const Scene& scene = baked.scene;
  const double loadMs = loaded.loadMs;
  for (const std::string& w : scene.warnings)
    std::cerr << "manylight: " << scenePath << ": warning: " << w << "\n";
  if (a.verbose && !scene.ignoredExtensions.empty()) {
    std::cerr << "manylight: " << scenePath << ": extensions ignored (they change nothing here):";
    for (const std::string& e : scene.ignoredExtensions) std::cerr << " " << e;
    std::cerr << "\n";
  }
  RenderRequest bakedRequest = request;
  if (baked.hasTrees) bakedRequest.prebuiltTrees = &baked.packed;
  if (baked.hasOctree) bakedRequest.prebuiltOctree = &baked.octree;
  RenderOutcome out;
  try {
    out = renderScene(scene, bakedRequest);
  } catch (const gl::GlError& e) {
    throw Error(scenePath + ": " + e.what());  // the driver's message names no scene
  }
  if (out.framed && a.verbose)
    std::cerr << "manylight: " << scenePath << ": no camera; framing the bounds\n";
  if (out.defaultRig)
    std::cerr << "manylight: " << scenePath << ": no lights; using the default three-light rig\n";
  const Display display = writeOutputs(a, request, out, output);
  nlohmann::json stats = {
      {"scene", scenePath},
      {"output", output},
      {"method", methodName(out.method)},
      {"backend", context.backend()},
      {"renderer", context.renderer()},
      {"gl_version", context.version()},
      {"width", request.width},
      {"height", request.height},
      {"lights", out.lightCount},
      {"default_light_rig", out.defaultRig},
      {"framed_camera", out.framed},
      {"lighting_passes", out.frame.lightingPasses},
      {"exposure_ev", display.exposure},
      {"tone_map", toneMapName(display.toneMap)},
      {"load_ms", loadMs},
      {"render_ms", out.frame.renderMs},
      {"scene_ms", loadMs + msSince(start)},
      {"degenerate_triangles", scene.topology.degenerateTriangles},
      {"boundary_edges", scene.topology.boundaryEdges},
      {"non_manifold_edges", scene.topology.nonManifoldEdges},
  };
  if (!out.methodReason.empty()) {
    stats["method_reason"] = out.methodReason;
    if (a.verbose)
      std::cerr << "manylight: " << scenePath << ": auto: " << methodName(out.method) << ": "
                << out.methodReason << "\n";
  }
  const std::string note = wholeSceneNote(scenePath, out.octree);
  if (!note.empty()) std::cerr << "manylight: " << note << "\n";
  if (request.indirect.mode != Indirect::None && request.aov == Aov::None) {
    stats["indirect"] = indirectStats(request.indirect, out.frame.indirect);
    const std::string none = noIndirectNote(request.indirect, out.frame.indirect);
    if (!none.empty()) std::cerr << "manylight: " << output << ": " << none << "\n";
  }
  if (request.aov != Aov::None) {
    stats["aov"] = aovChannel(request.aov).name;
  } else if (out.method == Method::Octree) {
    stats["bake_ms"] = out.bakeMs;
    stats["octree"] = octreeStats(out.octree, out.frame.octree);
    stats["baked_octree"] = baked.hasOctree;
  } else if (out.method != Method::Reference) {
    addCutStats(stats, a, request, out, baked, output);
  }
  if (a.verbose) {
    std::cerr << "manylight: " << output << ": " << request.width << "x" << request.height << ", "
              << out.lightCount << " lights, load " << loadMs << " ms, render "
              << out.frame.renderMs << " ms\n";
  }
  return stats;
}

// The frame `a` asks for; false (having said why) where its size or its outputs are not one.
// Throws Error or CLI::ValidationError for a value that is not one.
bool renderRequest(const RenderArgs& a, RenderRequest& request) {
  if (!parseSize(a.size, &request.width, &request.height)) return false;
  const bool batch = !a.outDir.empty();
  if (batch == !a.output.empty()) {
    std::cerr
        << "manylight: render: give either -o OUTPUT (one scene) or --out-dir DIR (any number)\n";
    return false;
  }
  if (!batch && a.scenes.size() != 1) {
    std::cerr << "manylight: render: -o takes one scene, got " << a.scenes.size()
              << "; use --out-dir for several\n";
    return false;
  }
  if (batch && !a.maxCutMask.empty()) {
    std::cerr << "manylight: render: --max-cut-mask takes one scene (-o), not --out-dir\n";
    return false;
  }
  if (!batch && !a.maxCutMask.empty() &&
      std::filesystem::absolute(a.maxCutMask).lexically_normal() ==
          std::filesystem::absolute(a.output).lexically_normal()) {
    std::cerr << "manylight: render: --max-cut-mask names the output image " << a.output << "\n";
    return false;
  }
  request.camera = a.camera;
  request.ambient = a.ambient.empty() ? glm::vec3(0.0f) : parseRgb(a.ambient);
  request.rigAmbient = a.ambient.empty();
  parseExposure(a.exposure);  // refused before any work
  request.method = a.lighting.parsed();
  request.aov = parseAov(a.aov);
  request.lightcuts = a.lighting.lightcuts();
  request.lightcuts.trees = a.input.trees();
  request.octree = a.input.octree();
  request.indirect = a.lighting.indirectSettings();
  request.octreeStats = !a.statsPath.empty();
  return true;
}

// Renders `jobs` in one context, each scene loaded while the one before renders; a failing
// scene is reported and the rest go on. Returns the exit code.
int renderBatch(const RenderArgs& a, const RenderRequest& request,
                const std::vector<Thumbnail>& jobs, std::future<LoadedScene> next,
                const gl::Context& context, Clock::time_point processStart) {
  nlohmann::json all = nlohmann::json::array();
  int failed = 0;
  Progress progress(int(jobs.size()));
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const Thumbnail& job = jobs[i];
    progress.step(job.scene);
    try {
      std::future<LoadedScene> current = std::move(next);
      if (i + 1 < jobs.size()) next = startLoading(a, jobs[i + 1].scene);
      all.push_back(renderOne(a, request, job.scene, current.get(), job.output, context));
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
  std::cerr << "manylight: rendered " << jobs.size() - failed << " of " << jobs.size()
            << " scenes into " << a.outDir
            << (failed ? ", " + std::to_string(failed) + " failed" : std::string()) << " ("
            << std::lround(totalMs) << " ms)\n";
  if (!a.statsPath.empty()) {
    const nlohmann::json stats = {{"scenes", all},
                                  {"rendered", int(jobs.size()) - failed},
                                  {"failed", failed},
                                  {"shard", a.shard.empty() ? "0/1" : a.shard},
                                  {"backend", context.backend()},
                                  {"total_ms", totalMs}};
    writeFileAtomic(a.statsPath, stats.dump(2) + "\n");
  }
  return failed ? kExitFailure : kExitOk;
}

}  // namespace

int runRender(const RenderArgs& a, Clock::time_point processStart) {
  RenderRequest request;
  if (!renderRequest(a, request)) return kExitUsage;
  const bool batch = !a.outDir.empty();
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
    if (!a.maxCutMask.empty()) checkOutputPath(a.maxCutMask);
    jobs.push_back({a.scenes[0], a.output});
  }

  // The context first: its driver is loaded by dlopen, which waits while another thread
  // is inside dlopen (the first scene's OpenImageIO).
  const std::unique_ptr<gl::Context> context = openContext(backend, a.verbose);
  if (!context) return kExitNoContext;
  if (!sizeFitsContext(request.width, request.height)) return kExitFailure;
  // A shard past the end of a short list has no scene.
  std::future<LoadedScene> next;
  if (!jobs.empty()) next = startLoading(a, jobs[0].scene);
  // A scene that fails does so at once (a missing file, bad JSON) and then has no use for
  // the compiled code; one still reading after a 10 ms wait is a scene that will render.
  if (next.valid() && next.wait_for(std::chrono::milliseconds(10)) != std::future_status::ready) {
    warmUpGeometryPass(request.aov);
    // A scene still reading now (a large one) would link the image module after it: this
    // thread, otherwise idle, links it meanwhile (the loader's call then waits for it, if
    // needed, and returns at once).
    if (next.wait_for(std::chrono::seconds(0)) != std::future_status::ready) preloadImageIo();
  }
  if (!batch) {
    nlohmann::json stats =
        renderOne(a, request, jobs[0].scene, next.get(), jobs[0].output, *context);
    stats["total_ms"] = msSince(processStart);
    if (!a.statsPath.empty()) writeFileAtomic(a.statsPath, stats.dump(2) + "\n");
    return kExitOk;
  }
  return renderBatch(a, request, jobs, std::move(next), *context, processStart);
}

}  // namespace manylight::cli
