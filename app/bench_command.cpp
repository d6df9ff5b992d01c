// `manylight bench`: the speed/accuracy sweep and the stability suite (tools/sweep.h),
// written as CSV and JSON after every case, so an interrupted run keeps what it measured.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <thread>
#include <variant>

#include "app/commands.h"
#include "base/output_file.h"
#include "base/text_table.h"
#include "generators/scene_builder.h"
#include "tools/progress.h"
#include "tools/sweep.h"

namespace manylight::cli {
namespace {

std::vector<std::string> splitList(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

template <typename T>
std::vector<T> parseNumbers(const std::string& option, const std::string& list, T low, T high) {
  std::vector<T> out;
  for (const std::string& item : splitList(list)) {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || !(v >= double(low) && v <= double(high)))
      throw CLI::ValidationError(option, "'" + item + "' is not a number in " +
                                             std::to_string(low) + ".." + std::to_string(high));
    out.push_back(T(v));
  }
  if (out.empty()) throw CLI::ValidationError(option, "the list is empty");
  return out;
}

std::string number(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::isnan(v)) return "nan";
  char s[32];
  std::snprintf(s, sizeof s, "%.6g", v);
  return s;
}

// JSON has no infinity: a PSNR of identical images is written as null.
nlohmann::json jsonNumber(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

bool isLightcuts(const SweepVariant& v) { return v.method == Method::Lightcuts; }

// One field of a run's record. The CSV has a column for every field with inCsv, in this
// order (empty where the value is absent); the JSON has a key for every present value
// with inJson (non-finite numbers as null: JSON has no infinity). A free-text field is
// quoted in the CSV, its own quotes replaced.
struct Field {
  using value_type = std::variant<std::monostate, long long, double, std::string>;
  const char* name;
  value_type value;
  bool inCsv = true, inJson = true, freeText = false;
};

std::vector<Field> fields(const RunRecord& r, double floorMs) {
  const ImageErrors& e = r.errors;
  const bool lightcuts = isLightcuts(r.variant), reference = r.variant.method == Method::Reference;
  auto ifLightcuts = [&](auto v) -> Field::value_type {
    return lightcuts ? Field::value_type(v) : std::monostate{};
  };
  // Cut statistics: 0 in the reference's CSV rows, absent from its JSON.
  auto cut = [&](const char* name, auto v) { return Field{name, v, true, !reference}; };
  return {
      {"case", r.caseName},
      {"layout", lightLayoutName(r.layout)},
      {"lights", (long long)r.lights},
      {"method", methodName(r.variant.method)},
      {"label", r.variant.label(), false, true},
      {"mode", ifLightcuts(std::string(r.variant.mode == ErrorMode::Total ? "total" : "node"))},
      {"error", ifLightcuts(double(r.variant.error))},
      {"max_cut", reference ? Field::value_type{} : (long long)r.maxCut},
      {"width", (long long)r.width},
      {"height", (long long)r.height},
      {"repeats", (long long)r.repeats},
      {"render_ms", r.renderMs},
      {"render_ms_min", r.renderMsMin},
      {"render_ms_max", r.renderMsMax},
      {"ratio_to_reference", r.ratioToReference},
      {"ratio_to_floor", r.ratioToFloor},
      {"floor_ms", floorMs, true, false},
      {"light_evals_per_px", r.lightEvaluationsPerPixel},
      {"node_evals_per_px", r.nodeEvaluationsPerPixel},
      cut("avg_cut", r.averageCut),
      cut("largest_cut", (long long)r.largestCut),
      cut("pixels_at_max_cut", (long long)r.pixelsAtMaxCut),
      cut("pixels_shared_cut", (long long)r.pixelsSharedCut),
      {"bake_ms", r.bakeMs},
      {"peak_rss_mb", r.peakRssMb},
      {"pixels_compared", (long long)e.pixels},
      {"non_finite_pixels", (long long)e.nonFinite},
      {"max_rel_error", e.maxRelative},
      {"p99_rel_error", e.p99Relative},
      {"max_abs_error", e.maxAbsolute},
      {"rmse_8bit", e.rmse8},
      {"psnr_8bit", e.psnr8},
      {"share_off_gt_1_code", e.offByMoreThanOneCode},
      {"reference_row_share", 1.0 / r.rowBandStride},
      {"failure", r.failure, true, true, true},
  };
}

std::string csvHeader() {
  std::string out;
  for (const Field& f : fields(RunRecord{}, 0.0)) {
    if (f.inCsv) out += std::string(out.empty() ? "" : ",") + f.name;
  }
  return out;
}

std::string csvRow(const RunRecord& r, double floorMs) {
  std::string out;
  bool first = true;
  for (const Field& f : fields(r, floorMs)) {
    if (!f.inCsv) continue;
    if (!first) out += ',';
    first = false;
    if (const auto* i = std::get_if<long long>(&f.value)) {
      out += std::to_string(*i);
    } else if (const auto* d = std::get_if<double>(&f.value)) {
      out += number(*d);
    } else if (const auto* text = std::get_if<std::string>(&f.value)) {
      if (!f.freeText) {
        out += *text;
        continue;
      }
      std::string quoted = *text;
      std::replace(quoted.begin(), quoted.end(), '"', '\'');
      out += '"' + quoted + '"';
    }
  }
  return out;
}

nlohmann::json runJson(const RunRecord& r) {
  nlohmann::json j = nlohmann::json::object();
  for (const Field& f : fields(r, 0.0)) {
    if (!f.inJson) continue;
    if (const auto* i = std::get_if<long long>(&f.value)) {
      j[f.name] = *i;
    } else if (const auto* d = std::get_if<double>(&f.value)) {
      j[f.name] = jsonNumber(*d);
    } else if (const auto* text = std::get_if<std::string>(&f.value)) {
      j[f.name] = *text;
    }
  }
  return j;
}

// The scene the sweep lights: the user's, or the generated room (generators/scene_builder.h).
Scene sweepScene(const std::string& path) {
  if (!path.empty()) return loadGltf(path);
  RoomOptions o;
  o.lightCount = 1;
  const auto file = std::filesystem::temp_directory_path() /
                    ("manylight-bench-room-" + std::to_string(::getpid()) + ".glb");
  writeRoomScene(file.string(), o);
  Scene scene = loadGltf(file.string());
  std::error_code ec;
  std::filesystem::remove(file, ec);
  return scene;
}

constexpr std::uintmax_t kMaxResultBytes = 1u << 28;

// This program's build: FNV-1a over its executable's bytes, in hex ("unknown" when it cannot
// be read). --resume keeps only runs of the same build: a results file from an older one
// (a copied folder, a rebuilt binary) would mix two programs' numbers in one chart.
std::string buildId() {
  std::ifstream exe("/proc/self/exe", std::ios::binary);
  if (!exe) return "unknown";
  std::uint64_t h = 1469598103934665603ull;
  std::vector<char> chunk(1 << 16);
  while (exe.read(chunk.data(), std::streamsize(chunk.size())) || exe.gcount() > 0) {
    for (std::streamsize i = 0; i < exe.gcount(); ++i)
      h = (h ^ static_cast<unsigned char>(chunk[std::size_t(i)])) * 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

// --resume: the cases already measured in a.json with the same settings, build and GL
// renderer as `json`, whose runs (and rows of a.csv) are kept in `json` and `csv`. Throws
// Error when the files disagree with them.
std::set<std::string> resumeFrom(const BenchArgs& a, nlohmann::json* json, std::string* csv) {
  std::set<std::string> done;
  if (a.json.empty()) throw Error("bench: --resume needs --json, which records the settings");
  if (!std::filesystem::exists(a.json)) return done;
  nlohmann::json before;
  try {
    before = nlohmann::json::parse(readTextFile(a.json, kMaxResultBytes));
  } catch (const nlohmann::json::exception& e) {
    throw Error(a.json + ": cannot resume: " + e.what());
  }
  for (const char* key : {"suite", "width", "height", "repeats", "reference_seconds", "max_cut",
                          "cut_tile", "build", "gl_renderer"}) {
    if (!before.contains(key) || before[key] != (*json)[key])
      throw Error(a.json + ": cannot resume: it was measured with another " + key +
                  "; remove it or run without --resume");
  }
  for (const auto& run : before["runs"]) {
    done.insert(run.value("case", ""));
    (*json)["runs"].push_back(run);
  }
  if (!a.csv.empty() && std::filesystem::exists(a.csv)) {
    const std::string text = readTextFile(a.csv, kMaxResultBytes);
    for (const TextLine& line : contentLines(text)) {
      const std::string row(line.text);
      if (row.rfind("case,", 0) != 0 && done.count(row.substr(0, row.find(','))))
        *csv += row + "\n";
    }
  }
  return done;
}

}  // namespace

CLI::App* addBenchCommand(CLI::App& app, BenchArgs& a) {
  CLI::App* bench = app.add_subcommand(
      "bench",
      "Time every method against the reference over light layouts and counts (the sweep), or "
      "run the stability suite; writes CSV and JSON");
  bench->add_option("--suite", a.suite, "sweep (layouts x counts) or stability (adversarial cases)")
      ->capture_default_str()
      ->check(CLI::IsMember({"sweep", "stability"}));
  bench->add_option("--csv", a.csv, "Write one row per method and case here");
  bench->add_option("--json", a.json, "Write the settings and every result here");
  bench->add_option("--scene", a.scene,
                    "glTF scene with a camera whose lights are replaced (default: the generated "
                    "room of the sample)");
  std::string layouts;
  for (const auto& [l, name] : lightLayoutNames()) layouts += (layouts.empty() ? "" : ", ") + name;
  bench->add_option("--layouts", a.layouts, "sweep: light layouts, from " + layouts)
      ->capture_default_str();
  bench->add_option("--cases", a.cases,
                    "stability: run only these cases (names as in docs/stability.md)");
  bench->add_option("--counts", a.counts, "sweep: light counts")->capture_default_str();
  bench
      ->add_option("--methods", a.methods,
                   "reference, lightcuts, lightcuts-distance, octree (timed where most lights "
                   "have a range)")
      ->capture_default_str();
  bench->add_option("--modes", a.modes, "lightcuts error modes: node, total")
      ->capture_default_str();
  bench->add_option("--errors", a.errors,
                    "lightcuts ε values (default: 0.005,0.01,0.02,0.05,0.1 sweep; 0.02 stability)");
  bench->add_option("--size", a.size, "Image size WxH (default: 640x480 sweep, 320x240 stability)");
  bench->add_option("--repeats", a.repeats, "Timed renders after a warm-up; the median is kept")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  bench
      ->add_option("--reference-seconds", a.referenceSeconds,
                   "A reference frame estimated longer lights only every k-th band of 8 rows, "
                   "and the errors cover those rows")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 1e6));
  bench->add_option("--max-cut", a.maxCut, maxCutHelp())
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxCutLimit));
  bench->add_flag("--resume", a.resume,
                  "Keep the cases already in --json (and --csv) from an interrupted run with the "
                  "same settings, build and GL renderer, and run only the others");
  bench->add_option("--frames", a.frames, "stability: frames of the turntable (0: none)")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  bench->add_option("--light-budget", a.lightBudget, "Most lights in any case")
      ->capture_default_str()
      ->check(CLI::Range(1, 1 << 26));
  bench->add_option("--backend", a.backend, "Context: auto, egl, osmesa")->capture_default_str();
  bench->add_flag("-v,--verbose", a.verbose, "Say which context was chosen, and each result");
  return bench;
}

namespace {

// The sweep's settings from `a`; false (having said why) where --size is not one. Throws
// CLI::ValidationError for a method, mode or error list that is not one.
bool benchSettings(const BenchArgs& a, bool stability, SweepSettings& settings) {
  if (stability) settings.width = 320, settings.height = 240;
  if (!a.size.empty() && !parseSize(a.size, &settings.width, &settings.height)) return false;
  settings.repeats = a.repeats;
  settings.referenceSeconds = a.referenceSeconds;
  settings.maxCut = a.maxCut;
  std::vector<Method> methods;
  for (const std::string& m : splitList(a.methods)) {
    methods.push_back(parseMethod(m));
    if (methods.back() == Method::Auto)
      throw CLI::ValidationError("--methods",
                                 "auto chooses a method per scene; name the methods to time");
  }
  std::vector<ErrorMode> modes;
  for (const std::string& m : splitList(a.modes)) {
    if (m != "node" && m != "total")
      throw CLI::ValidationError("--modes", "'" + m + "' is neither node nor total");
    modes.push_back(m == "total" ? ErrorMode::Total : ErrorMode::Node);
  }
  const std::vector<float> errors = parseNumbers<float>(
      "--errors", a.errors.empty() ? (stability ? "0.02" : "0.005,0.01,0.02,0.05,0.1") : a.errors,
      1e-6f, 1.0f);
  settings.variants = expandVariants(methods, modes, errors);
  if (settings.variants.empty()) throw CLI::ValidationError("--methods", "no method to run");
  return true;
}

// The cases `a` names: the stability suite's (all, or --cases), or --layouts × --counts.
// Throws CLI::ValidationError for an unknown case, Error for one past the light budget.
std::vector<SweepCase> benchCases(const BenchArgs& a, bool stability) {
  std::vector<SweepCase> cases;
  if (stability) {
    cases = stabilityCases();
    if (!a.cases.empty()) {
      std::vector<SweepCase> chosen;
      for (const std::string& name : splitList(a.cases)) {
        auto it = std::find_if(cases.begin(), cases.end(),
                               [&](const SweepCase& c) { return c.name == name; });
        if (it == cases.end()) {
          std::string names;
          for (const SweepCase& c : cases) names += (names.empty() ? "" : ", ") + c.name;
          throw CLI::ValidationError(
              "--cases", "no stability case '" + name + "' (choose from " + names + ")");
        }
        chosen.push_back(*it);
      }
      cases = chosen;
    }
  } else {
    const std::vector<int> counts = parseNumbers<int>("--counts", a.counts, 1, 1 << 26);
    for (const std::string& l : splitList(a.layouts))
      for (int n : counts) cases.push_back(layoutCase(parseLightLayout(l), n));
  }
  for (const SweepCase& c : cases)
    if (std::size_t(c.lights) > a.lightBudget)
      throw Error(c.name + ": " + std::to_string(c.lights) + " lights exceed the light budget of " +
                  std::to_string(a.lightBudget));
  return cases;
}

// The JSON results' header, before any run.
nlohmann::json benchHeader(const BenchArgs& a, const SweepSettings& settings,
                           const gl::Context& context) {
  return {
      {"suite", a.suite},
      {"scene", a.scene.empty() ? "generated room (scenes/sample.gltf's geometry)" : a.scene},
      {"width", settings.width},
      {"height", settings.height},
      {"repeats", settings.repeats},
      {"reference_seconds", settings.referenceSeconds},
      {"max_cut", settings.maxCut},
      {"cut_tile", LightcutsSettings{}.tileSize},
      {"backend", context.backend()},
      {"gl_renderer", context.renderer()},
      {"build", buildId()},
      {"hardware_threads", std::thread::hardware_concurrency()},
      {"runs", nlohmann::json::array()},
  };
}

// The stability suite's turntable of `frames` frames into json["temporal"]; returns the
// failures.
int benchTurntable(Sweep& sweep, int frames, Progress& progress, nlohmann::json& json) {
  int failures = 0;
  json["temporal"] = nlohmann::json::array();
  const SweepCase turntable = layoutCase(LightLayout::Uniform, 4096);
  for (const auto& t : sweep.temporal(turntable, frames, [&](const std::string& what) {
         progress.step(turntable.name + " turntable " + what);
       })) {
    json["temporal"].push_back({{"case", t.caseName},
                                {"label", t.variant.label()},
                                {"frames", t.frames},
                                {"mean_change", jsonNumber(t.meanChange)},
                                {"max_change", jsonNumber(t.maxChange)},
                                {"failure", t.failure}});
    if (!t.failure.empty()) ++failures;
  }
  return failures;
}

}  // namespace

int runBench(const BenchArgs& a) {
  if (a.csv.empty() && a.json.empty()) {
    std::cerr << "manylight: bench: give --csv FILE, --json FILE or both\n";
    return kExitUsage;
  }
  const bool stability = a.suite == "stability";
  SweepSettings settings;
  if (!benchSettings(a, stability, settings)) return kExitUsage;
  const std::vector<SweepCase> cases = benchCases(a, stability);
  for (const std::string& path : {a.csv, a.json})
    if (!path.empty()) prepareTemporaryFor(path);  // fails early on an unwritable folder

  const std::unique_ptr<gl::Context> context = openContext(gl::parseBackend(a.backend), a.verbose);
  if (!context) return kExitNoContext;
  if (!sizeFitsContext(settings.width, settings.height)) return kExitFailure;
  const Scene scene = sweepScene(a.scene);
  Sweep sweep(scene, settings);

  nlohmann::json json = benchHeader(a, settings, *context);
  std::string csv = csvHeader() + "\n";
  const std::set<std::string> done =
      a.resume ? resumeFrom(a, &json, &csv) : std::set<std::string>{};
  const int steps = int(cases.size() * settings.variants.size()) + (stability ? a.frames : 0) + 1;
  Progress progress(steps);
  progress.step("1-light floor");
  const double floorMs = sweep.floorMs();
  json["floor_ms"] = floorMs;
  auto save = [&] {
    if (!a.csv.empty()) writeFileAtomic(a.csv, csv);
    if (!a.json.empty()) writeFileAtomic(a.json, json.dump(1) + "\n");
  };
  int failures = 0;
  for (const SweepCase& c : cases) {
    if (done.count(c.name)) {
      for (std::size_t i = 0; i < settings.variants.size(); ++i) progress.step(c.name + " (kept)");
      continue;
    }
    const auto records =
        sweep.run(c, [&](const std::string& what) { progress.step(c.name + " " + what); });
    for (const RunRecord& r : records) {
      csv += csvRow(r, floorMs) + "\n";
      json["runs"].push_back(runJson(r));
      if (!r.failure.empty()) ++failures;
      if (a.verbose || !r.failure.empty()) {
        progress.clear();
        std::cerr << "manylight: " << c.name << " " << r.variant.label() << ": "
                  << (r.failure.empty()
                          ? number(r.renderMs) + " ms, max error " + number(r.errors.maxRelative)
                          : "failed: " + r.failure)
                  << "\n";
      }
    }
    save();
  }
  if (stability && a.frames > 0) {
    failures += benchTurntable(sweep, a.frames, progress, json);
    save();
  }
  progress.clear();
  std::cerr << "manylight: bench: " << cases.size() << " cases x " << settings.variants.size()
            << " methods" << (failures ? ", " + std::to_string(failures) + " failed" : "") << "\n";
  return failures ? kExitFailure : kExitOk;
}

}  // namespace manylight::cli
