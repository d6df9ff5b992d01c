#include <cstdio>
#include <filesystem>
#include <iostream>

#include "app/commands.h"
#include "base/output_file.h"
#include "scene/light_list.h"

namespace manylight::cli {

static void printFit(const PowerFit& fit) {
  std::printf(
      "pairs = %zu\ngamma = %.6f\nA = %.8g\nlog10(A) = %.6f\nR^2 = %.6f\nworst relative residual = "
      "%.6f\n",
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
  if (std::sscanf(a.codes.c_str(), "%d..%d%c", &first, &last, &tail) != 2 || first < 1 ||
      last > 255 || first >= last) {
    std::cerr << "manylight: --codes: expected FIRST..LAST with 1 <= FIRST < LAST <= 255, got '"
              << a.codes << "'\n";
    return kExitUsage;
  }
  const Scene scene = loadGltf(a.calibrate);
  const std::unique_ptr<gl::Context> context = openContext(gl::parseBackend(a.backend), a.verbose);
  if (!context) return kExitNoContext;
  const ColourCalibration c = calibrateColour(scene, first, last);
  printFit(c.fit);
  std::printf("largest difference from the sRGB curve = %d codes (at code %d)\n",
              c.largestCodeDifference, c.worstCode);
  return kExitOk;
}

// "out/b.png" → "out/b.diff.png"
static std::string defaultDiffPath(const std::string& b) {
  std::filesystem::path p(b);
  return (p.parent_path() / (p.stem().string() + ".diff.png")).string();
}

int runCompare(const CompareArgs& a) {
  const std::string diffPath = a.diff.empty() ? defaultDiffPath(a.b) : a.diff;
  const CompareOutcome out = compareImageFiles(a.a, a.b, a.thresholds, diffPath);
  const ImageComparison& v = out.values;
  if (!v.sameShape) {
    std::printf("%s %s: differ: %dx%d with %d channels against %dx%d with %d\n", a.a.c_str(),
                a.b.c_str(), v.width[0], v.height[0], v.channels[0], v.width[1], v.height[1],
                v.channels[1]);
    return kExitDiffer;
  }
  if (out.relative) {
    const RelativeOutcome& e = out.errors;
    std::printf(
        "%s %s: %s: relative error against the second, at percentile %g: %g (limit %g); max %g "
        "at pixel (%d, %d); %lld pixels compared%s%s\n",
        a.a.c_str(), a.b.c_str(), out.passed ? "match" : "differ", a.thresholds.percentile,
        e.atPercentile, a.thresholds.maxRelative, e.largest, e.maxX, e.maxY, e.pixels,
        out.diffWritten ? "; difference: " : "", out.diffWritten ? diffPath.c_str() : "");
    return out.passed ? kExitOk : kExitDiffer;
  }
  std::printf(
      "%s %s: %s: %lld of %lld values (%.4g%%) off by more than %g; max %g at pixel (%d, %d) "
      "channel %d; "
      "mean %g; RMS %g; PSNR %.2f dB%s%s\n",
      a.a.c_str(), a.b.c_str(), out.passed ? "match" : "differ", v.failing, v.values,
      v.values > 0 ? 100.0 * double(v.failing) / double(v.values) : 0.0, a.thresholds.maxAbs,
      v.maxError, v.maxX, v.maxY, v.maxChannel, v.meanError, v.rmsError, v.psnr,
      out.diffWritten ? "; difference: " : "", out.diffWritten ? diffPath.c_str() : "");
  return out.passed ? kExitOk : kExitDiffer;
}

// "I/N" with 0 <= I < N.

int runBake(const BakeArgs& a, Clock::time_point processStart) {
  if (std::filesystem::path(a.output).extension() != ".mlbake") {
    std::cerr << "manylight: " << a.output << ": a baked scene's file name must end in .mlbake\n";
    return kExitUsage;
  }
  if (isBakedFile(a.scene)) throw Error(a.scene + ": already baked");
  auto start = Clock::now();
  Scene scene = loadGltf(a.scene, a.input.options());
  if (!a.input.lightList.empty()) appendLightList(a.input.lightList, scene, a.input.options());
  for (const std::string& w : scene.warnings)
    std::cerr << "manylight: " << a.scene << ": warning: " << w << "\n";
  const double loadMs = msSince(start);
  start = Clock::now();
  const BakedScene baked = bakeScene(std::move(scene), a.input.trees(), a.input.octree());
  const double bakeMs = msSince(start);
  start = Clock::now();
  writeBakedScene(a.output, baked);
  const double writeMs = msSince(start);
  const auto bytes = std::filesystem::file_size(a.output);
  std::printf(
      "%s: %zu lights, %zu tree words, %ju bytes; load %.0f ms, trees %.0f ms, write %.0f ms\n",
      a.output.c_str(), baked.scene.lights.size(), baked.packed.words.size(), std::uintmax_t(bytes),
      loadMs, bakeMs, writeMs);
  if (!a.statsPath.empty()) {
    nlohmann::json stats = {{"scene", a.scene},
                            {"output", a.output},
                            {"lights", baked.scene.lights.size()},
                            {"bytes", bytes},
                            {"load_ms", loadMs},
                            {"bake_ms", bakeMs},
                            {"write_ms", writeMs},
                            {"total_ms", msSince(processStart)},
                            {"format_version", kBakedFormatVersion}};
    if (baked.hasTrees) stats["node_colour"] = nodeColourStats(baked.packed.colour);
    writeFileAtomic(a.statsPath, stats.dump(2) + "\n");
  }
  return kExitOk;
}

// A frame file name pattern: exactly one %d or %0Nd (and %% for a percent sign).
}  // namespace manylight::cli
