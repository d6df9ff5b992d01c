#pragma once
// The benchmark sweep and the stability suite behind `manylight bench` (bench/sweep.sh):
// method variants render generated light layouts (generators/light_layouts.h) in one scene,
// timed, and compared with the reference method on the same view.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "generators/light_layouts.h"
#include "image/image_errors.h"
#include "render/renderer.h"

namespace manylight {

// One method with its settings.
struct SweepVariant {
  Method method = Method::Reference;
  ErrorMode mode = ErrorMode::Node;  // lightcuts only
  float error = 0.02f;               // lightcuts only
  // "reference", "lightcuts-node-0.02", "lightcuts-distance"
  std::string label() const;
};

// Each method once, lightcuts once per mode and ε.
std::vector<SweepVariant> expandVariants(const std::vector<Method>& methods,
                                         const std::vector<ErrorMode>& modes,
                                         const std::vector<float>& errors);

struct SweepCase {
  std::string name;  // unique in a run: "uniform-1024", or a stability case's name
  LightLayout layout = LightLayout::Uniform;
  int lights = 0;
  int maxCut = 0;      // > 0: every lightcuts variant's maximum cut size in this case
  float error = 0.0f;  // > 0: every lightcuts variant's ε in this case (instead of its own)
};

// "uniform-1024": `lights` lights laid out as `layout`.
SweepCase layoutCase(LightLayout layout, int lights);

// The stability suite's adversarial cases (docs/stability.md): coincident lights, two far
// groups, intensities over twelve decades, one bright light among a million dim ones, lights
// 1e5 away, spots facing away, shading points inside cluster boxes, the maximum cut reached,
// dense clusters at ε = 0.005, and counts 1, 2, 3 and 2^k ± 1.
std::vector<SweepCase> stabilityCases();

// The variants run on case `c`: `variants`, with every lightcuts ε replaced by the case's own
// where it sets one (one variant per rule then, in the order first met).
std::vector<SweepVariant> caseVariants(const std::vector<SweepVariant>& variants,
                                       const SweepCase& c);

struct SweepSettings {
  int width = 640, height = 480;
  int repeats = 3;  // timed renders (after a warm-up for each new renderer); the median is kept
  int maxCut = LightcutsSettings{}.maxCut;  // lightcuts, unless a case sets its own
  double referenceSeconds = 60;  // a reference frame estimated longer lights a subset of rows
  std::uint32_t seed = 7;        // of the light layouts
  std::vector<SweepVariant> variants;
};

// One variant on one case.
struct RunRecord {
  std::string caseName;
  LightLayout layout = LightLayout::Uniform;
  int lights = 0;
  SweepVariant variant;
  int maxCut = 0;  // lightcuts: the maximum cut size used
  int width = 0, height = 0;
  int repeats = 0;                                        // timed renders behind renderMs
  double renderMs = 0, renderMsMin = 0, renderMsMax = 0;  // median, fastest, slowest
  double ratioToReference = 0;  // renderMs / the reference's renderMs in this case
  double ratioToFloor = 0;      // renderMs / the 1-light floor of this run
  double lightEvaluationsPerPixel = 0, nodeEvaluationsPerPixel = 0;  // per covered pixel
  double averageCut = 0;
  int largestCut = 0;
  long long pixelsAtMaxCut = 0;
  long long pixelsSharedCut = 0;  // pixels that took their group's shared cut
  double bakeMs = 0;              // light trees built and uploaded
  double peakRssMb = 0;           // the process's peak resident memory while this variant ran
  ImageErrors errors;             // against the reference, on the rows it lit
  // The reference lit every rowBandStride-th band of kRowBand rows (1: all); its renderMs
  // is then its time scaled up by the share of rows lit, and errors cover those rows only.
  int rowBandStride = 1;
  std::string failure;  // what went wrong (an exception's text); empty when it worked
};

class Sweep {
 public:
  // Needs a current context. `scene` gives the geometry, materials and first camera; its
  // own lights are ignored. Keeps references to both arguments.
  Sweep(const Scene& scene, const SweepSettings& settings);

  // The reference method with one light: the cost of a frame that does almost no lighting.
  double floorMs();

  // Every variant of the settings on `c`. `step` is called before each variant.
  std::vector<RunRecord> run(const SweepCase& c,
                             const std::function<void(const std::string&)>& step);

  // A turntable of `frames` frames through every variant but the reference: the mean and
  // largest change from one frame to the next of (variant − reference), per pixel covered
  // in both frames (largest channel), relative to the pixel's largest reference channel in
  // either frame, floored at 1% of the frame's mean brightness.
  struct Temporal {
    std::string caseName;
    SweepVariant variant;
    int frames = 0;
    double meanChange = 0.0, maxChange = 0.0;
    std::string failure;
  };
  std::vector<Temporal> temporal(const SweepCase& c, int frames,
                                 const std::function<void(const std::string&)>& step);

 private:
  const Scene& scene_;
  const SweepSettings& settings_;
  double floorMs_ = -1.0;
  // The reference's frames of `lights` into `ref` (times, rows lit, memory); returns its image.
  Image referenceFrames(const std::vector<Light>& lights, const View& view, RunRecord& ref) const;
};

}  // namespace manylight
