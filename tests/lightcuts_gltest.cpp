// Lightcuts against the GPU reference method on 15 light layouts chosen to break cuts, one
// parameterised case per layout: the `total` rule's guarantee, and ceilings on the errors of the
// node rule (the default) and the distance criterion. A failing case writes its reference,
// lightcuts and difference images under test-artefacts/lightcuts/ and prints the folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "cuts/tile_cuts.h"
#include "generators/light_layouts.h"
#include "render/playback.h"
#include "render/render_job.h"
#include "scene/gltf_loader.h"
#include "tests/gl_support.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

constexpr int kWidth = 96, kHeight = 72;
// Large enough that the total rule converges on nearly every pixel of these scenes.
constexpr int kMaxCut = 8000;

struct Errors {
  int compared = 0, atMaxCut = 0, failing = 0;
  double worst = 0.0, p99 = 0.0, mean = 0.0;
  double averageCut = 0.0;
};

// Per pixel: max over channels of |image − reference| / max over channels of reference;
// pixels whose cut hit the maximum (`cuts`) are counted apart. `difference`, when given, gets
// each pixel's relative error over ε in its colour channels (1 = at ε).
Errors compareImages(const Image& image, const Image& reference, const CutStats& cuts,
                     double epsilon, Image* difference = nullptr) {
  Errors e;
  e.averageCut = cuts.averageCut;
  if (difference) {
    difference->width = kWidth;
    difference->height = kHeight;
    difference->values = ImageValues::Data;
    difference->rgba.assign(std::size_t(kWidth) * kHeight * 4, 0.0f);
  }
  std::vector<double> relative;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const float* r = reference.pixel(x, y);
      const float* c = image.pixel(x, y);
      if (difference) difference->pixel(x, y)[3] = 1.0f;
      if (r[3] == 0.0f) continue;  // background
      if (cuts.atMaxCut[std::size_t(y) * kWidth + x]) {
        ++e.atMaxCut;
        continue;
      }
      ++e.compared;
      const double peak = std::max({double(r[0]), double(r[1]), double(r[2])});
      double diff = 0.0;
      for (int ch = 0; ch < 3; ++ch) diff = std::max(diff, std::abs(double(c[ch]) - double(r[ch])));
      const double rel = diff / std::max(peak, 1e-30);
      relative.push_back(rel);
      e.worst = std::max(e.worst, rel);
      e.mean += rel;
      if (diff > (epsilon + kFloatSlack) * peak + kAbsoluteFloor) ++e.failing;
      if (difference) {
        float* d = difference->pixel(x, y);
        d[0] = d[1] = d[2] = float(rel / epsilon);
      }
    }
  }
  if (!relative.empty()) {
    e.mean /= double(relative.size());
    std::sort(relative.begin(), relative.end());
    e.p99 = relative[std::size_t(0.99 * double(relative.size() - 1))];
  }
  return e;
}

// What the tests measure, as measured at ε = 0.02, kMaxCut, kWidth × kHeight.
struct Measured {
  double worst, p99, mean, averageCut;
};

struct Case {
  const char* name;  // the test's parameter name: filter with --gtest_filter='*/NAME'
  LightLayout layout;
  int count;
  bool specular;      // Phong materials (a metal box, a glossy sphere)
  Measured node;      // the node rule (Method::Lightcuts, ErrorMode::Node: the default)
  Measured distance;  // the distance criterion (Method::LightcutsDistance)
};

// The node rule and the distance criterion guarantee nothing; their errors and cut sizes are
// held to ceilings of kMargin × the values in this table, so that a regression of either fails.
// The values were measured by these tests (their printed lines) with the auto GL backend and
// rounded up to three significant digits; errors of the exact layouts (one to three lights)
// are held to kFloatSlack instead of 1.5 × 0.
constexpr double kMargin = 1.5;
// clang-format off
const Case kCases[] = {
    // name                  layout                       count  specular
    //   node rule: worst, p99, mean, average cut        distance criterion: the same
    {"uniform_4096",           LightLayout::Uniform,         4096, false,
     {0.0426, 0.0204, 0.00596, 593},  {0.0284, 0.0154, 0.00515, 668}},
    {"clustered_4096",         LightLayout::Clustered,       4096, false,
     {0.0307, 0.00876, 0.00184, 416}, {0.293, 0.131, 0.0165, 63.2}},
    {"coincident_1000",        LightLayout::Coincident,      1000, false,
     {0.00755, 0.00334, 0.000494, 502}, {0.000906, 0.000906, 0.000789, 1}},
    {"wide_intensities_2000",  LightLayout::WideIntensities, 2000, false,
     {0.0213, 0.0139, 0.00358, 455},  {0.134, 0.0229, 0.00615, 488}},
    // far_1000's node-rule worst pixel, under ε, rose from 0.0116 with 8×8 squares' cuts of up
    // to twice splitCut (kNearFinestSplit); its p99, mean and cut did not move.
    {"far_1000",               LightLayout::Far,             1000, false,
     {0.0194, 0.00722, 0.00256, 491}, {0.364, 0.0428, 0.00345, 120}},
    {"mixed_3000",             LightLayout::Mixed,           3000, false,
     {0.0672, 0.0368, 0.0123, 631},  {0.186, 0.0576, 0.0148, 806}},
    {"count_1",                LightLayout::Mixed,           1,    false,
     {0, 0, 0, 0.570},            {1.98e-07, 1.16e-07, 1.95e-08, 1}},
    {"count_2",                LightLayout::Mixed,           2,    false,
     {0, 0, 0, 1.48},             {2.53e-07, 1.38e-07, 3.46e-08, 2}},
    {"count_3",                LightLayout::Mixed,           3,    false,
     {0, 0, 0, 2.48},             {2.20e-07, 1.56e-07, 4.17e-08, 3}},
    {"count_1023",             LightLayout::Uniform,         1023, false,
     {0.0282, 0.0199, 0.00410, 546},  {0.0639, 0.0224, 0.00746, 325}},
    {"count_1025",             LightLayout::Uniform,         1025, false,
     {0.0400, 0.0224, 0.00473, 546},  {0.0537, 0.0246, 0.00797, 324}},
    {"count_prime_1009",       LightLayout::Mixed,           1009, false,
     {0.0469, 0.0223, 0.00636, 431},  {0.122, 0.0973, 0.032, 417}},
    {"mixed_specular_2000",    LightLayout::Mixed,           2000, true,
     {0.0469, 0.0317, 0.0115, 582},  {0.180, 0.0555, 0.0192, 654}},
    {"spots_away_16384",       LightLayout::SpotsAway,       16384, false,
     {0.0319, 0.0143, 0.000557, 144}, {2.80, 1.02, 0.0863, 1190}},
    {"eight_bit_colours_4096", LightLayout::EightBitColours, 4096, false,
     {0.0361, 0.0216, 0.00758, 608},  {0.182, 0.0270, 0.00972, 675}},
};
// clang-format on

// The case's name in gtest's listings, instead of its bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

// The generated room, plain or with Phong materials, loaded once per process.
const Scene& room(bool specular) {
  static const Scene* rooms[2] = {nullptr, nullptr};
  const Scene*& r = rooms[specular ? 1 : 0];
  if (!r) {
    context();
    RoomOptions o;
    o.lightCount = 1;
    o.textured = false;
    o.specular = specular;
    r = new Scene(
        loadGltf(roomScene(o, specular ? "lightcuts-specular-room.gltf" : "lightcuts-room.gltf")));
  }
  return *r;
}

// The room lit by `count` lights of `layout` (seed 7).
Scene litRoom(bool specular, LightLayout layout, int count) {
  Scene scene = room(specular);
  scene.lights = layoutLights(layout, count, 7);
  return scene;
}

// A reference render at the tests' image size.
RenderRequest sizedRequest() {
  RenderRequest request;
  request.width = kWidth;
  request.height = kHeight;
  return request;
}

// sizedRequest() through lightcuts under the total rule at `epsilon`.
RenderRequest totalRuleRequest(double epsilon) {
  RenderRequest request = sizedRequest();
  request.method = Method::Lightcuts;
  request.lightcuts.mode = ErrorMode::Total;
  request.lightcuts.error = float(epsilon);
  return request;
}

// One layout through lightcuts against the reference.
struct CaseRun {
  Image reference, image, difference;
  Errors errors;
};

// Where a failing case's images go: artefactFolder()/lightcuts/TEST/CASE.
std::filesystem::path failureFolder() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string test = info->name();  // TEST/CASE
  std::replace(test.begin(), test.end(), '/', '-');
  return artefactFolder() / "lightcuts" / test;
}

class Lightcuts : public ::testing::TestWithParam<Case> {
 protected:
  // GetParam()'s layout through `method` and `mode` at ε = 0.02, against the reference.
  CaseRun render(Method method, ErrorMode mode,
                 NodeColourCoding coding = NodeColourCoding::Rgb9e5) {
    const Case& c = GetParam();
    const Scene scene = litRoom(c.specular, c.layout, c.count);
    RenderRequest request = sizedRequest();
    CaseRun r;
    r.reference = renderScene(scene, request).image;
    request.method = method;
    request.lightcuts.mode = mode;
    request.lightcuts.error = float(kEpsilon);
    request.lightcuts.maxCut = kMaxCut;
    request.lightcuts.trees.nodeColour = coding;
    const RenderOutcome cut = renderScene(scene, request);
    r.image = cut.image;
    r.errors = compareImages(cut.image, r.reference, cut.frame.cuts, kEpsilon, &r.difference);
    const Errors& e = r.errors;
    std::cout << c.name << ": " << e.compared << " pixels, worst " << e.worst << ", p99 " << e.p99
              << ", mean " << e.mean << ", average cut " << e.averageCut << ", at max cut "
              << e.atMaxCut << ", node colour slack " << cut.nodeColour.slack << "\n";
    return r;
  }

  // On failure, the case's reference, lightcuts and difference images as EXR.
  void TearDown() override {
    if (!HasFailure() || last_.reference.rgba.empty()) return;
    const std::filesystem::path dir = failureFolder();
    writeImage(last_.reference, (dir / "reference.exr").string());
    writeImage(last_.image, (dir / "lightcuts.exr").string());
    writeImage(last_.difference, (dir / "difference.exr").string());
    std::cerr << "lightcuts test " << GetParam().name << ": images in " << dir.string() << "\n";
  }

  CaseRun& keep(CaseRun r) { return last_ = std::move(r); }

  static constexpr double kEpsilon = 0.02;
  CaseRun last_;
};

void expectTotalRuleHolds(const Errors& e) {
  EXPECT_GT(e.compared, 0);
  EXPECT_EQ(e.failing, 0) << "worst relative error " << e.worst;
  // Cuts that hit the maximum are excluded above; they must stay rare.
  EXPECT_LE(e.atMaxCut, (e.compared + e.atMaxCut) / 100);
}

// `e` within kMargin × `measured` (errors at least kFloatSlack).
void expectWithinCeilings(const Errors& e, const Measured& measured) {
  auto ceiling = [](double value) { return std::max(kMargin * value, kFloatSlack); };
  EXPECT_GT(e.compared, 0);
  EXPECT_LE(e.worst, ceiling(measured.worst))
      << "worst relative error, measured " << measured.worst;
  EXPECT_LE(e.p99, ceiling(measured.p99)) << "99th percentile, measured " << measured.p99;
  EXPECT_LE(e.mean, ceiling(measured.mean)) << "mean relative error, measured " << measured.mean;
  EXPECT_LE(e.averageCut, kMargin * measured.averageCut)
      << "average cut, measured " << measured.averageCut;
}

TEST_P(Lightcuts, TotalRuleErrorIsWithinEpsilonOfTheReference) {
  expectTotalRuleHolds(keep(render(Method::Lightcuts, ErrorMode::Total)).errors);
}

// Node colours are stored compactly (bake/node_colour.h); the guarantee holds with either
// coding, because the bounds are widened by the coding's slack.
TEST_P(Lightcuts, TotalRuleHoldsWithFittedNodeColours) {
  expectTotalRuleHolds(
      keep(render(Method::Lightcuts, ErrorMode::Total, NodeColourCoding::Fitted)).errors);
}

TEST_P(Lightcuts, NodeRuleErrorsStayUnderTheirCeilings) {
  const Errors& e = keep(render(Method::Lightcuts, ErrorMode::Node)).errors;
  expectWithinCeilings(e, GetParam().node);
  // Lights packed together (clusters, one point) were where the node rule's errors added up,
  // to 9–16 ε (the far field's remainders: tile_cuts.h's farBin). They stay within 3 ε.
  const LightLayout layout = GetParam().layout;
  if (layout == LightLayout::Clustered || layout == LightLayout::Coincident) {
    EXPECT_LE(e.worst, 3.0 * kEpsilon);
  }
}

TEST_P(Lightcuts, DistanceCriterionErrorsStayUnderTheirCeilings) {
  expectWithinCeilings(keep(render(Method::LightcutsDistance, ErrorMode::Node)).errors,
                       GetParam().distance);
}

// Cases named by their layout, e.g. Lightcuts.NodeRuleErrorsStayUnderTheirCeilings/far_1000.
INSTANTIATE_TEST_SUITE_P(, Lightcuts, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           return std::string(info.param.name);
                         });

// Playback keeps its shared cuts per cell of the scene from frame to frame
// (cuts/cell_cuts.h): along an orbit, every frame keeps the total rule's guarantee against
// the reference of the same view, and later frames keep most of their cuts.
TEST_F(Lightcuts, KeptCutsHoldTheTotalRuleFrameByFrame) {
  Scene scene = room(false);
  scene.lights = layoutLights(LightLayout::Mixed, 3000, 7);
  PlaybackRequest request;
  request.frame.width = kWidth;
  request.frame.height = kHeight;
  request.frames = 8;
  request.orbitDegrees = 90.0f;
  std::vector<Image> reference;
  play(scene, request, [&](int, const Image& image, const FrameStats&) {
    reference.push_back(image);
    return true;
  });
  request.frame.method = Method::Lightcuts;
  request.frame.lightcuts.mode = ErrorMode::Total;
  request.frame.lightcuts.maxCut = kMaxCut;
  request.cutStatsEveryFrame = true;
  int frames = 0;
  const PlaybackOutcome out =
      play(scene, request, [&](int i, const Image& image, const FrameStats& stats) {
        const Errors e = compareImages(image, reference[std::size_t(i)], stats.cuts, 0.02);
        std::cout << "kept cuts, frame " << i << ": " << e.compared << " pixels, worst " << e.worst
                  << ", cuts made " << stats.cutsMade << ", kept " << stats.cutsKept << "\n";
        EXPECT_EQ(e.failing, 0) << "frame " << i << ": worst " << e.worst;
        EXPECT_LE(e.atMaxCut, (e.compared + e.atMaxCut) / 100) << "frame " << i;
        ++frames;
        return true;
      });
  EXPECT_EQ(frames, 8);
  ASSERT_EQ(out.cutsKept.size(), 8u);
  EXPECT_EQ(out.cutsKept[0], 0);
  for (int i = 1; i < 8; ++i) EXPECT_GT(out.cutsKept[std::size_t(i)], out.cutsMade[std::size_t(i)]);
}

// Specular pixels take their group's shared cut (cuts/tile_cuts.h: bounds on the Phong lobe
// over the group's mirror directions and exponents) instead of walking cuts of their own: on
// the specular room (measured: 4,986 and 5,258 of 5,266 pixels under the node and total
// rules; before, the sphere's and the box's pixels all walked their own), the total rule keeps its
// guarantee, and the node rule's worst pixel stays within 3 ε (measured 0.0583).
TEST(LightcutsSpecular, SpecularPixelsShareCutsWithinTheRule) {
  constexpr double kEpsilon = 0.02;
  const Scene scene = litRoom(true, LightLayout::Mixed, 2000);
  RenderRequest request = sizedRequest();
  const Image reference = renderScene(scene, request).image;
  request.method = Method::Lightcuts;
  request.lightcuts.error = float(kEpsilon);
  for (const ErrorMode mode : {ErrorMode::Node, ErrorMode::Total}) {
    request.lightcuts.mode = mode;
    request.lightcuts.maxCut = mode == ErrorMode::Total ? kMaxCut : 2000;
    const RenderOutcome out = renderScene(scene, request);
    const CutStats& cuts = out.frame.cuts;
    const Errors e = compareImages(out.image, reference, cuts, kEpsilon);
    std::cout << "specular room, " << (mode == ErrorMode::Total ? "total" : "node")
              << " rule: " << cuts.pixelsSharedCut << " of " << cuts.pixels
              << " pixels shared, worst " << e.worst << ", p99 " << e.p99 << "\n";
    EXPECT_EQ(cuts.pixels, e.compared + e.atMaxCut);
    EXPECT_GE(cuts.pixelsSharedCut, cuts.pixels * (mode == ErrorMode::Total ? 72 : 94) / 100);
    if (mode == ErrorMode::Total) {
      expectTotalRuleHolds(e);
    } else {
      EXPECT_LE(e.worst, 3.0 * kEpsilon);
    }
  }
}

// Shared cuts are not held to --max-cut, which bounds the cuts pixels walk themselves
// (cuts/tile_cuts.h, kSharedCutLimit), and under the total rule the CPU stops at a quarter of
// the target at a group's centre (cut_region_cut.h, kTotalMargin). With 4,096 mixed lights
// the total rule asks for cuts of 2,000–4,000 nodes. Measured on this image: with groups'
// cuts held to the default --max-cut of 2,000, 278 of its 5,266 pixels shared one and 4,667
// reached the maximum in their own walks; with cuts up to 8,000 entries found at half the
// target, 3,998 shared and 1,225 (darker than their group's centre) failed their check and
// reached the maximum; now 5,259 share and none reaches it.
TEST(LightcutsSharedCuts, GroupCutsMayExceedTheWalkLimit) {
  constexpr double kEpsilon = 0.02;
  const Scene scene = litRoom(false, LightLayout::Mixed, 4096);
  const Image reference = renderScene(scene, sizedRequest()).image;
  RenderRequest request = totalRuleRequest(kEpsilon);
  ASSERT_EQ(request.lightcuts.maxCut, 2000);
  const RenderOutcome out = renderScene(scene, request);
  const CutStats& cuts = out.frame.cuts;
  const Errors e = compareImages(out.image, reference, cuts, kEpsilon);
  std::cout << "4,096 mixed lights, total rule: " << cuts.pixelsSharedCut << " of " << cuts.pixels
            << " pixels shared, largest cut " << cuts.maxCut << ", at max cut " << e.atMaxCut
            << ", worst " << e.worst << "\n";
  EXPECT_GT(cuts.maxCut, request.lightcuts.maxCut);
  EXPECT_GE(cuts.pixelsSharedCut, cuts.pixels * 99 / 100);
  EXPECT_EQ(cuts.pixelsAtMaxCut, 0);
  EXPECT_EQ(cuts.pixels, e.compared);
  EXPECT_EQ(e.failing, 0) << "worst relative error " << e.worst;
}

// Under the total rule, 65,536 mixed lights ask for cuts of more than half the lights (at
// 160×120 with shared cuts of up to 32,767 entries, 12,252 of 14,706 pixels still reached the
// maximum): no group's cut fits in kSharedCutLimit. Each group's full cut is then shared and
// every pixel counted at the maximum (cuts/tile_cuts.h, RegionCut::full), instead of every
// pixel walking a cut of at most --max-cut nodes itself, which is slower and further off.
// Measured: 5,030 of 5,266 pixels on full shared cuts (the rest, darker than their group's
// centre, failed a cut that met the rule there and walked their own), p99 0.027 against
// the walks' 0.080; the worst pixel (0.156) is one that walks either way.
TEST(LightcutsSharedCuts, FullCutsAreTakenAndCountedAtTheMaximum) {
  constexpr double kEpsilon = 0.02;
  const Scene scene = litRoom(false, LightLayout::Mixed, 65536);
  const Image reference = renderScene(scene, sizedRequest()).image;
  RenderRequest request = totalRuleRequest(kEpsilon);
  const RenderOutcome shared = renderScene(scene, request);
  request.lightcuts.tileSize = 1;  // every pixel walks its own cut
  const RenderOutcome walked = renderScene(scene, request);
  CutStats all;  // compare every pixel, at the maximum or not
  all.atMaxCut.assign(std::size_t(kWidth) * kHeight, 0);
  const Errors s = compareImages(shared.image, reference, all, kEpsilon);
  const Errors w = compareImages(walked.image, reference, all, kEpsilon);
  const CutStats& cuts = shared.frame.cuts;
  std::cout << "65,536 mixed lights, total rule: " << cuts.pixelsSharedCut << " of " << cuts.pixels
            << " pixels on full shared cuts, worst " << s.worst << ", p99 " << s.p99
            << "; own walks worst " << w.worst << ", p99 " << w.p99 << "\n";
  EXPECT_EQ(cuts.pixels, s.compared);
  EXPECT_GE(cuts.pixelsSharedCut, cuts.pixels * 9 / 10);
  EXPECT_EQ(cuts.pixelsAtMaxCut, cuts.pixels);
  EXPECT_EQ(walked.frame.cuts.pixelsAtMaxCut, cuts.pixels);
  EXPECT_LT(s.p99, 0.5 * w.p99);
  EXPECT_LE(s.worst, w.worst);
}

// Under the total rule a pixel whose cut reaches the maximum sums every light where the scene
// has at most LightcutsSettings::exactLimit (glsl/lighting_lightcuts.frag, exactIfAtMax):
// with walks of at most 16 nodes, no pixel is left at the maximum, and each is within ε.
TEST(LightcutsTotalRule, PixelsAtTheMaximumSumEveryLight) {
  constexpr double kEpsilon = 0.02;
  const Scene scene = litRoom(false, LightLayout::Mixed, 4096);
  const Image reference = renderScene(scene, sizedRequest()).image;
  for (const int tile : {1, 16}) {
    RenderRequest request = totalRuleRequest(kEpsilon);
    request.lightcuts.maxCut = 16;
    request.lightcuts.tileSize = tile;
    request.lightcuts.exactLimit = 0;
    const long long capped = renderScene(scene, request).frame.cuts.pixelsAtMaxCut;
    request.lightcuts.exactLimit = kExactLimit;
    const RenderOutcome out = renderScene(scene, request);
    const CutStats& cuts = out.frame.cuts;
    const Errors e = compareImages(out.image, reference, cuts, kEpsilon);
    EXPECT_GT(capped, tile == 1 ? cuts.pixels / 10 : 0) << "tile " << tile;
    EXPECT_EQ(cuts.pixelsAtMaxCut, 0) << "tile " << tile;
    EXPECT_EQ(e.compared, cuts.pixels) << "tile " << tile;
    EXPECT_EQ(e.failing, 0) << "tile " << tile;
  }
}

// Past kSharedCutLimit lights (16,384 far away: every node's bound is much the same) groups
// whose cuts fill up get exact cuts (cuts/tile_cuts.h, RegionCut::exact), whose pixels sum
// every light: none is left at the maximum, and each is within ε. Without, most are.
TEST(LightcutsTotalRule, GroupsWhoseCutsFillUpSumEveryLight) {
  constexpr double kEpsilon = 0.02;
  const Scene scene = litRoom(false, LightLayout::Far, 16384);
  const Image reference = renderScene(scene, sizedRequest()).image;
  RenderRequest request = totalRuleRequest(kEpsilon);
  request.lightcuts.exactLimit = 0;
  const CutStats capped = renderScene(scene, request).frame.cuts;
  request.lightcuts.exactLimit = kExactLimit;
  const RenderOutcome out = renderScene(scene, request);
  const CutStats& cuts = out.frame.cuts;
  const Errors e = compareImages(out.image, reference, cuts, kEpsilon);
  EXPECT_GT(capped.pixelsAtMaxCut, capped.pixels / 2);
  EXPECT_EQ(capped.exactCuts, 0);
  EXPECT_GT(cuts.exactCuts, 0);
  EXPECT_EQ(cuts.pixelsAtMaxCut, 0);
  EXPECT_EQ(e.compared, cuts.pixels);
  EXPECT_EQ(e.failing, 0);
}

// Moved lights (Renderer::moveLights: the trees refitted in place, the cuts found anew) keep
// the total rule's guarantee against the reference of the moved lights.
TEST(LightcutsMoving, RefittedTreesHoldTheTotalRule) {
  constexpr double kEpsilon = 0.02;
  const Scene scene = litRoom(false, LightLayout::Mixed, 2000);
  RenderRequest request = totalRuleRequest(kEpsilon);
  request.lightcuts.maxCut = kMaxCut;
  PreparedRender p(scene, request);
  std::vector<Light> lights = scene.lights;
  for (int frame = 0; frame < 2; ++frame) {
    std::vector<int> changed;
    for (int i = frame; i < int(lights.size()); i += 10) {
      changed.push_back(i);
      lights[std::size_t(i)].position += glm::vec3(0.3f, 0.1f, -0.2f);
      lights[std::size_t(i)].intensity *= 1.5f;
    }
    p.renderer->moveLights(lights, changed, {});
    FrameStats frame_;
    const Image image =
        p.renderer->render(makeView(p.camera, kWidth, kHeight), p.settings, &frame_);
    Scene moved = room(false);
    moved.lights = lights;
    RenderRequest reference;
    reference.width = kWidth;
    reference.height = kHeight;
    const Errors e =
        compareImages(image, renderScene(moved, reference).image, frame_.cuts, kEpsilon);
    EXPECT_EQ(e.failing, 0) << "frame " << frame << ": worst " << e.worst;
    EXPECT_GT(e.compared, kWidth * kHeight / 2);
  }
}

}  // namespace
}  // namespace manylight::testing
