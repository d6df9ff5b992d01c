#include "tools/sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>

#include "base/error.h"
#include "gl/context.h"
#include "render/render_job.h"

namespace manylight {
namespace {

// The octree evaluates lights without a range at every pixel, as the reference does: it is
// measured only where most lights are ranged.
bool measured(const SweepVariant& v, const std::vector<Light>& lights) {
  if (v.method != Method::Octree) return true;
  std::size_t ranged = 0;
  for (const Light& l : lights) ranged += isRanged(l);
  return 2 * ranged >= lights.size();
}

// Linux keeps a per-process high-water mark of resident memory (VmHWM), which writing "5"
// to /proc/self/clear_refs resets to the current size. Where that is refused, the mark
// covers the whole process so far.
void resetPeakMemory() { std::ofstream("/proc/self/clear_refs") << "5"; }

double peakMemoryMb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    long long kb = 0;
    if (std::sscanf(line.c_str(), "VmHWM: %lld kB", &kb) == 1) return double(kb) / 1024.0;
  }
  return 0.0;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// Fills a record's timing fields from its timed frames (at least one).
void setTimes(RunRecord& r, const std::vector<double>& ms) {
  r.repeats = int(ms.size());
  r.renderMs = median(ms);
  r.renderMsMin = *std::min_element(ms.begin(), ms.end());
  r.renderMsMax = *std::max_element(ms.begin(), ms.end());
}

// The frame settings of a lightcuts variant in case `c`.
FrameSettings variantSettings(const SweepVariant& v, const SweepCase& c, int defaultMaxCut) {
  FrameSettings fs;
  fs.lightcuts.error = v.error;
  fs.lightcuts.mode = v.mode;
  fs.lightcuts.maxCut = c.maxCut > 0 ? c.maxCut : defaultMaxCut;
  return fs;
}

// A reference frame costs about this many light evaluations per millisecond at least (below
// the reference throughput of docs/performance.md): used only to pick the warm-up's share
// of rows.
constexpr double kSlowestEvaluationsPerMs = 2.0e5;

}  // namespace

std::string SweepVariant::label() const {
  if (method != Method::Lightcuts) return methodName(method);
  char eps[32];
  std::snprintf(eps, sizeof eps, "%g", double(error));
  return std::string("lightcuts-") + (mode == ErrorMode::Total ? "total-" : "node-") + eps;
}

std::vector<SweepVariant> expandVariants(const std::vector<Method>& methods,
                                         const std::vector<ErrorMode>& modes,
                                         const std::vector<float>& errors) {
  std::vector<SweepVariant> out;
  for (Method m : methods) {
    if (m != Method::Lightcuts) {
      out.push_back({m});
      continue;
    }
    for (ErrorMode mode : modes)
      for (float e : errors) out.push_back({m, mode, e});
  }
  return out;
}

SweepCase layoutCase(LightLayout layout, int lights) {
  return {lightLayoutName(layout) + "-" + std::to_string(lights), layout, lights};
}

std::vector<SweepCase> stabilityCases() {
  using L = LightLayout;
  std::vector<SweepCase> cases = {
      layoutCase(L::Coincident, 16384),
      layoutCase(L::TwoGroups, 16384),
      layoutCase(L::WideIntensities, 16384),
      layoutCase(L::BrightAmongDim, 1 << 20),
      layoutCase(L::Far, 16384),
      layoutCase(L::SpotsAway, 16384),
      layoutCase(L::OnSurfaces, 16384),
  };
  // Below ε = 0.02 dense clusters once needed shared cuts larger than --max-cut: every pixel
  // walked its own.
  SweepCase fine = layoutCase(L::Clustered, 16384);
  fine.name = "clustered-fine-16384";
  fine.error = 0.005f;
  cases.push_back(fine);
  SweepCase capped = layoutCase(L::Uniform, 16384);
  capped.name = "max-cut-16";
  capped.maxCut = 16;
  cases.push_back(capped);
  for (int n : {1, 2, 3, 1023, 1025, 65535, 65537}) {
    SweepCase c = layoutCase(L::Mixed, n);
    c.name = "count-" + std::to_string(n);
    cases.push_back(c);
  }
  return cases;
}

std::vector<SweepVariant> caseVariants(const std::vector<SweepVariant>& variants,
                                       const SweepCase& c) {
  if (c.error <= 0.0f) return variants;
  std::vector<SweepVariant> out;
  for (SweepVariant v : variants) {
    if (v.method == Method::Lightcuts) v.error = c.error;
    const bool seen = std::any_of(out.begin(), out.end(),
                                  [&](const SweepVariant& o) { return o.label() == v.label(); });
    if (!seen) out.push_back(v);
  }
  return out;
}

Sweep::Sweep(const Scene& scene, const SweepSettings& settings)
    : scene_(scene), settings_(settings) {
  if (scene.cameras.empty()) throw Error("the sweep's scene has no camera");
}

double Sweep::floorMs() {
  if (floorMs_ >= 0.0) return floorMs_;
  const std::vector<Light> one = layoutLights(LightLayout::Uniform, 1, settings_.seed);
  Renderer renderer(scene_, one, settings_.width, settings_.height, Method::Reference);
  const View view = makeView(scene_.cameras[0], settings_.width, settings_.height);
  // Frames this short take several frames to settle: warm up with three, and take the median
  // of at least five.
  FrameStats stats;
  for (int i = 0; i < 3; ++i) renderer.render(view, {}, &stats);
  std::vector<double> ms;
  for (int i = 0; i < std::max(settings_.repeats, 5); ++i) {
    renderer.render(view, {}, &stats);
    ms.push_back(stats.renderMs);
  }
  return floorMs_ = median(ms);
}

Image Sweep::referenceFrames(const std::vector<Light>& lights, const View& view,
                             RunRecord& ref) const {
  const int w = settings_.width, h = settings_.height;
  resetPeakMemory();
  Renderer renderer(scene_, lights, w, h, Method::Reference);
  // The warm-up lights a share of the rows small enough to take seconds, and its time
  // estimates a whole frame's.
  FrameSettings fs;
  const double evaluations = double(lights.size()) * double(w) * double(h);
  const int bands = (h + kRowBand - 1) / kRowBand;
  fs.rowBandStride =
      std::clamp(int(std::ceil(evaluations / (kSlowestEvaluationsPerMs * 5000.0))), 1, bands);
  FrameStats stats;
  Image reference = renderer.render(view, fs, &stats);
  const double estimate = stats.renderMs * fs.rowBandStride;
  std::vector<double> ms;
  if (estimate > settings_.referenceSeconds * 1000.0) {
    fs.rowBandStride =
        int(std::min<double>(std::ceil(estimate / (settings_.referenceSeconds * 1000.0)), bands));
    reference = renderer.render(view, fs, &stats);
    ms.push_back(stats.renderMs * fs.rowBandStride);
  } else {
    fs.rowBandStride = 1;
    for (int i = 0; i < std::max(settings_.repeats, 1); ++i) {
      reference = renderer.render(view, fs, &stats);
      ms.push_back(stats.renderMs);
    }
  }
  ref.rowBandStride = fs.rowBandStride;
  setTimes(ref, ms);
  ref.lightEvaluationsPerPixel = double(lights.size());
  ref.peakRssMb = peakMemoryMb();
  return reference;
}

std::vector<RunRecord> Sweep::run(const SweepCase& c,
                                  const std::function<void(const std::string&)>& step) {
  const int w = settings_.width, h = settings_.height;
  const std::vector<Light> lights = layoutLights(c.layout, c.lights, settings_.seed);
  const View view = makeView(scene_.cameras[0], w, h);
  const double floor = floorMs();
  auto blank = [&](const SweepVariant& v) {
    RunRecord r;
    r.caseName = c.name;
    r.layout = c.layout;
    r.lights = c.lights;
    r.variant = v;
    r.width = w;
    r.height = h;
    return r;
  };

  // The reference first: every other variant is compared with it.
  step("reference");
  RunRecord ref = blank(SweepVariant{});
  Image reference;
  std::vector<bool> rows;
  try {
    reference = referenceFrames(lights, view, ref);
    rows = rowsLit(h, ref.rowBandStride);
    ref.errors = measureErrors(reference, reference, rows);
  } catch (const std::exception& e) {
    ref.failure = e.what();
  }
  if (ref.renderMs > 0.0) ref.ratioToReference = 1.0;
  ref.ratioToFloor = floor > 0.0 ? ref.renderMs / floor : 0.0;

  std::vector<RunRecord> out;
  std::map<Method, std::unique_ptr<Renderer>> renderers;
  std::map<Method, double> bakeMs;  // per renderer: its trees baked and uploaded
  for (const SweepVariant& v : caseVariants(settings_.variants, c)) {
    if (v.method == Method::Reference) {
      out.push_back(ref);
      continue;
    }
    if (!measured(v, lights)) continue;
    step(v.label());
    RunRecord r = blank(v);
    r.rowBandStride = ref.rowBandStride;
    try {
      resetPeakMemory();
      std::unique_ptr<Renderer>& renderer = renderers[v.method];
      // A new renderer's first frame compiles programs and touches fresh buffers: warm up.
      // The variants after it differ only in uniforms.
      const bool warmUp = !renderer;
      if (!renderer) {
        renderer = prepareRenderer(scene_, lights, w, h, v.method, {}, {}, &bakeMs[v.method]);
      }
      r.bakeMs = bakeMs[v.method];
      FrameSettings fs = variantSettings(v, c, settings_.maxCut);
      r.maxCut = v.method == Method::Octree ? 0 : fs.lightcuts.maxCut;
      FrameStats stats;
      Image image;
      // Cut statistics are read back (outside the timed part) from the last frame only.
      fs.readCutStats = false;
      if (warmUp) renderer->render(view, fs, &stats);
      std::vector<double> ms;
      const int repeats = std::max(settings_.repeats, 1);
      for (int i = 0; i < repeats; ++i) {
        fs.readCutStats = i == repeats - 1;
        fs.octreeStats = i == repeats - 1;
        image = renderer->render(view, fs, &stats);
        ms.push_back(stats.renderMs);
      }
      setTimes(r, ms);
      r.lightEvaluationsPerPixel =
          v.method == Method::Octree ? stats.octree.listEntries : stats.cuts.lightEvaluations;
      r.nodeEvaluationsPerPixel = stats.cuts.nodeEvaluations;
      r.averageCut = stats.cuts.averageCut;
      r.largestCut = stats.cuts.maxCut;
      r.pixelsAtMaxCut = stats.cuts.pixelsAtMaxCut;
      r.pixelsSharedCut = stats.cuts.pixelsSharedCut;
      r.peakRssMb = peakMemoryMb();
      if (ref.failure.empty()) r.errors = measureErrors(image, reference, rows);
      if (ref.renderMs > 0.0) r.ratioToReference = r.renderMs / ref.renderMs;
      if (floor > 0.0) r.ratioToFloor = r.renderMs / floor;
    } catch (const std::exception& e) {
      r.failure = e.what();
    }
    out.push_back(r);
  }
  return out;
}

namespace {

// Per pixel of a reference frame: whether it is covered and its largest channel. Returns the
// floor of a pixel's scale: each pixel's change is relative to its largest reference channel
// in either frame (a bright spot moving in or out counts at its own scale), but never to less
// than 1% of the frame's mean brightness, so near-black pixels do not make ratios huge.
double referencePeaks(const Image& r, std::vector<bool>& covered, std::vector<float>& peak) {
  covered.assign(std::size_t(r.width) * r.height, false);
  peak.assign(covered.size(), 0.0f);
  double brightness = 0.0;
  long long coveredPixels = 0;
  for (std::size_t p = 0; p < covered.size(); ++p) {
    covered[p] = r.rgba[p * 4 + 3] > 0.0f;
    peak[p] = std::max({r.rgba[p * 4], r.rgba[p * 4 + 1], r.rgba[p * 4 + 2]});
    if (!covered[p]) continue;
    brightness += peak[p];
    ++coveredPixels;
  }
  return std::max(0.01 * brightness / double(std::max(coveredPixels, 1ll)), kRelativeErrorFloor);
}

}  // namespace

std::vector<Sweep::Temporal> Sweep::temporal(const SweepCase& c, int frames,
                                             const std::function<void(const std::string&)>& step) {
  const int w = settings_.width, h = settings_.height;
  const std::vector<Light> lights = layoutLights(c.layout, c.lights, settings_.seed);
  const Bounds bounds = scene_.bounds();
  const glm::vec3 centre = bounds.empty ? glm::vec3(0.0f) : 0.5f * (bounds.min + bounds.max);

  std::vector<Temporal> out;
  std::map<Method, std::unique_ptr<Renderer>> renderers;
  std::vector<std::vector<float>> previous;  // per variant: last frame's variant − reference
  std::vector<double> sums;
  std::vector<long long> counts;
  Renderer reference(scene_, lights, w, h, Method::Reference);
  for (const SweepVariant& v : caseVariants(settings_.variants, c)) {
    if (v.method == Method::Reference || !measured(v, lights)) continue;
    Temporal t;
    t.caseName = c.name;
    t.variant = v;
    t.frames = frames;
    out.push_back(t);
    auto& renderer = renderers[v.method];
    if (!renderer) renderer = prepareRenderer(scene_, lights, w, h, v.method);
  }
  previous.resize(out.size());
  sums.assign(out.size(), 0.0);
  counts.assign(out.size(), 0);
  std::vector<bool> coveredBefore;
  std::vector<float> peakBefore;
  for (int f = 0; f < frames; ++f) {
    step("frame " + std::to_string(f + 1));
    const float angle = 6.28318530718f * float(f) / float(frames);
    const View view = makeView(orbitCamera(scene_.cameras[0], centre, angle), w, h);
    const Image r = reference.render(view, {});
    std::vector<bool> covered;
    std::vector<float> peak;
    const double floor = referencePeaks(r, covered, peak);
    for (std::size_t k = 0; k < out.size(); ++k) {
      Temporal& t = out[k];
      if (!t.failure.empty()) continue;
      try {
        FrameSettings fs = variantSettings(t.variant, c, settings_.maxCut);
        fs.readCutStats = false;
        const Image m = renderers[t.variant.method]->render(view, fs);
        std::vector<float> diff(std::size_t(w) * h * 3);
        for (std::size_t p = 0; p < covered.size(); ++p) {
          double change = 0.0;
          for (int ch = 0; ch < 3; ++ch) {
            diff[p * 3 + ch] = m.rgba[p * 4 + ch] - r.rgba[p * 4 + ch];
            if (f > 0)
              change = std::max(
                  change, std::abs(double(diff[p * 3 + ch]) - double(previous[k][p * 3 + ch])));
          }
          if (f == 0 || !covered[p] || !coveredBefore[p]) continue;
          if (std::isnan(change)) change = HUGE_VAL;
          const double relative =
              change / std::max({double(peak[p]), double(peakBefore[p]), floor});
          sums[k] += relative;
          ++counts[k];
          t.maxChange = std::max(t.maxChange, relative);
        }
        previous[k] = std::move(diff);
      } catch (const std::exception& e) {
        t.failure = e.what();
      }
    }
    coveredBefore = std::move(covered);
    peakBefore = std::move(peak);
  }
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k].meanChange = counts[k] ? sums[k] / double(counts[k]) : 0.0;
  return out;
}

}  // namespace manylight
