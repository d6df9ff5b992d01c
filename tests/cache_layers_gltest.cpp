// `--indirect caches` with several maps (render/light_caches.h): each map's light is kept in a
// layer of its own (past kMaxCacheLayers maps, shared), so a frame in which one chosen light
// changes renders and gathers that map (and its layer's others) alone, the others keep
// theirs, and the frame matches one made afresh.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <iostream>

#include "render/render_job.h"
#include "tests/gl_support.h"

namespace manylight::testing {
namespace {

constexpr int kWidth = 96, kHeight = 72;

// Caches with every candidate given a map, in any renderer: the same maps.
RenderRequest everyMap() {
  RenderRequest request;
  request.width = kWidth;
  request.height = kHeight;
  request.indirect.mode = Indirect::Caches;
  request.indirect.rsmLights = 8;
  return request;
}

// `room` with its last light that may have a map, other than the room's spot, 1.5× as bright,
// as `p`'s renderer is told.
Scene brightened(const Scene& room, PreparedRender& p) {
  int changed = -1;
  for (std::size_t i = 1; i < room.lights.size(); ++i)
    if (room.lights[i].type != LightType::Point) changed = int(i);
  EXPECT_GT(changed, 0);
  Scene out = room;
  out.lights[std::size_t(changed)].intensity *= 1.5f;
  p.renderer->moveLights(out.lights, {changed}, BakeOptions{});
  return out;
}

TEST(Indirect, OneChangedLightGathersItsMapAlone) {
  const Scene room = cornellWith(5);  // four maps
  const RenderRequest request = everyMap();
  PreparedRender p(room, request);
  View view = makeView(p.camera, kWidth, kHeight);
  FrameStats first;
  const Image before = p.renderer->render(view, p.settings, &first);
  ASSERT_EQ(first.indirect.rsmLights, 4);
  EXPECT_EQ(first.indirect.mapsRendered, 4);
  EXPECT_EQ(first.indirect.cachesGathered, 4LL * first.indirect.caches);

  // The camera moves: every map stays, and each gathers only the new caches.
  view.eye += glm::vec3(0.05f, 0.02f, 0.0f);
  view.view = glm::lookAt(view.eye, view.eye + view.forward, glm::vec3(0, 1, 0));
  FrameStats moved;
  p.renderer->render(view, p.settings, &moved);
  EXPECT_TRUE(moved.indirect.mapsKept);
  EXPECT_EQ(moved.indirect.mapsRendered, 0);
  EXPECT_GT(moved.indirect.cachesKept, moved.indirect.caches / 2);
  EXPECT_EQ(moved.indirect.cachesGathered,
            4LL * (moved.indirect.caches - moved.indirect.cachesKept));

  // One chosen light other than the room's spot brightens: its map alone is rendered anew and
  // gathers every cache; the camera stays, so the other three gather none.
  const Scene changed = brightened(room, p);
  FrameStats relit;
  const Image lit = p.renderer->render(view, p.settings, &relit);
  EXPECT_FALSE(relit.indirect.mapsKept);
  EXPECT_EQ(relit.indirect.mapsRendered, 1);
  EXPECT_EQ(relit.indirect.cachesKept, 0);
  EXPECT_EQ(relit.indirect.cachesGathered, relit.indirect.caches);
  PreparedRender fresh(changed, request);
  FrameStats afreshStats;
  const Image afresh = fresh.renderer->render(view, fresh.settings, &afreshStats);
  EXPECT_EQ(afreshStats.indirect.cachesGathered, 4LL * afreshStats.indirect.caches);
  std::cout << relit.indirect.caches << " caches; largest difference from a fresh frame "
            << largestDifference(lit, afresh) << "\n";
  EXPECT_LE(largestDifference(lit, afresh), 1e-5);
  EXPECT_GT(largestDifference(lit, before), 1e-3);
}

// Seven maps in four layers: a changed light's layer gathers anew, for each of its maps, and
// the frame matches a fresh one; a frame with fewer maps, then one with all seven again, too.
TEST(Indirect, MapsPastTheLayersShareThem) {
  const Scene room = cornellWith(9);
  const RenderRequest request = everyMap();
  PreparedRender p(room, request);
  const View view = makeView(p.camera, kWidth, kHeight);
  FrameStats first;
  p.renderer->render(view, p.settings, &first);
  ASSERT_EQ(first.indirect.rsmLights, 7);
  EXPECT_EQ(first.indirect.cachesGathered, 7LL * first.indirect.caches);

  const Scene changed = brightened(room, p);
  FrameStats relit;
  const Image lit = p.renderer->render(view, p.settings, &relit);
  EXPECT_EQ(relit.indirect.mapsRendered, 1);
  // Its layer holds one or two maps (seven over four layers), the others gather nothing.
  EXPECT_GE(relit.indirect.cachesGathered, relit.indirect.caches);
  EXPECT_LE(relit.indirect.cachesGathered, 2LL * relit.indirect.caches);
  PreparedRender fresh(changed, request);
  const Image afresh = fresh.renderer->render(view, fresh.settings, nullptr);
  EXPECT_LE(largestDifference(lit, afresh), 1e-5);

  // One map, twice (the kept map's layer may be the last), then seven again.
  p.settings.indirect.rsmLights = 1;
  for (int frame = 0; frame < 2; ++frame) {
    FrameStats one;
    p.renderer->render(view, p.settings, &one);
    EXPECT_EQ(one.indirect.rsmLights, 1);
  }
  p.settings.indirect.rsmLights = 8;
  FrameStats again;
  const Image all = p.renderer->render(view, p.settings, &again);
  EXPECT_EQ(again.indirect.rsmLights, 7);
  std::cout << again.indirect.caches << " caches; largest difference from a fresh frame "
            << largestDifference(all, afresh) << "\n";
  EXPECT_LE(largestDifference(all, afresh), 1e-5);

  // Four of the seven: the kept maps that shared a layer take layers of their own (those
  // gather anew once), and the next frame keeps every layer.
  p.settings.indirect.rsmLights = 4;
  FrameStats four, still;
  const Image shrunk = p.renderer->render(view, p.settings, &four);
  EXPECT_EQ(four.indirect.rsmLights, 4);
  const Image kept = p.renderer->render(view, p.settings, &still);
  EXPECT_TRUE(still.indirect.mapsKept);
  EXPECT_EQ(still.indirect.cachesGathered, 0);
  EXPECT_LE(largestDifference(kept, shrunk), 1e-6);
}

// In the room of 4,096 lights (no light but the spot sends kRsmLeastShare of the flux) the
// spot goes dark, then lit, then dark again: no map, then the spot's alone, its caches
// allocated anew, then none again; each frame comes out as a fresh renderer makes it.
TEST(Indirect, MapsComeAndGoWithTheLeastShare) {
  Scene room = cornellWith(4095);
  ASSERT_EQ(room.lights[0].type, LightType::Spot);
  const float spot = room.lights[0].intensity;
  RenderRequest request = everyMap();
  request.indirect.rsmLights = 4;
  PreparedRender p(room, request);
  const View view = makeView(p.camera, kWidth, kHeight);
  Image frames[3];
  for (int f = 0; f < 3; ++f) {
    room.lights[0].intensity = f == 1 ? spot : 0.0f;
    p.renderer->moveLights(room.lights, {0}, BakeOptions{});
    FrameStats stats;
    frames[f] = p.renderer->render(view, p.settings, &stats);
    EXPECT_EQ(stats.indirect.rsmLights, f == 1 ? 1 : 0) << "frame " << f;
    EXPECT_EQ(stats.indirect.mapsRendered, f == 1 ? 1 : 0) << "frame " << f;
    EXPECT_EQ(stats.indirect.caches > 0, f == 1) << "frame " << f;
    PreparedRender fresh(room, request);
    const Image afresh = fresh.renderer->render(view, fresh.settings, nullptr);
    EXPECT_LE(largestDifference(frames[f], afresh), 1e-5) << "frame " << f;
  }
  EXPECT_EQ(frames[2].rgba, frames[0].rgba);
  EXPECT_GT(largestDifference(frames[1], frames[0]), 1e-3);
}

}  // namespace
}  // namespace manylight::testing
