// The near field's grid lists (render/near_grid.h), on the CPU. In the GL test binary since
// render/ links GL; no context is needed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "render/near_grid.h"

namespace manylight::testing {
namespace {

// One cell's list of four listed cells: two wholly on plane a, one wholly on plane b, one
// with entries off its plane. Those on a, the plane the most share, go last, in their order;
// the count before them is 2.
TEST(NearGrid, CellsWhollyOnTheMostSharedPlaneComeLast) {
  const glm::vec4 a(0, 1, 0, 0), b(1, 0, 0, 2);
  // (coordinates, first entry, count, count before its plane's entries)
  std::vector<glm::vec4> items = {{10, 0, 3, 0}, {11, 3, 2, 0}, {12, 5, 4, 0}, {13, 9, 5, 2}};
  std::vector<glm::vec4> planes = {a, b, a, a};
  const std::vector<glm::vec3> lists = homePlanes({glm::vec2(0, 4)}, items, planes);
  ASSERT_EQ(lists.size(), 1u);
  EXPECT_EQ(lists[0], glm::vec3(0, 4, 2));
  const float order[4] = {11, 13, 10, 12};
  for (int i = 0; i < 4; ++i) EXPECT_EQ(items[std::size_t(i)].x, order[i]) << i;
  EXPECT_EQ(planes[0], b);
  EXPECT_EQ(planes[1], a);  // the cell with entries off its plane stays before the run
  EXPECT_EQ(planes[2], a);
  EXPECT_EQ(planes[3], a);
}

// Two cells' lists side by side: the second, from its first item on, is reordered within its
// own range only.
TEST(NearGrid, EachListIsReorderedInItsOwnRange) {
  const glm::vec4 a(0, 0, 1, 1), none(0.0f);
  std::vector<glm::vec4> items = {{1, 0, 1, 1}, {2, 1, 1, 0}, {3, 2, 1, 1}, {4, 3, 1, 0}};
  std::vector<glm::vec4> planes = {none, a, none, a};
  const std::vector<glm::vec3> lists =
      homePlanes({glm::vec2(0, 1), glm::vec2(1, 3)}, items, planes);
  EXPECT_EQ(lists[0], glm::vec3(0, 1, 1));
  EXPECT_EQ(lists[1], glm::vec3(1, 3, 1));
  const float order[4] = {1, 3, 2, 4};
  for (int i = 0; i < 4; ++i) EXPECT_EQ(items[std::size_t(i)].x, order[i]) << i;
  EXPECT_EQ(planes[1], none);
  EXPECT_EQ(planes[2], a);
  EXPECT_EQ(planes[3], a);
}

// A cell whose list has no cell wholly on a plane keeps its order, every cell before the run.
TEST(NearGrid, ListsWithoutAPlaneKeepTheirOrder) {
  std::vector<glm::vec4> items = {{1, 0, 2, 2}, {2, 2, 1, 0}};
  std::vector<glm::vec4> planes = {glm::vec4(0, 0, 1, 0), glm::vec4(0.0f)};
  const std::vector<glm::vec3> lists = homePlanes({glm::vec2(0, 2)}, items, planes);
  EXPECT_EQ(lists[0], glm::vec3(0, 2, 2));
  EXPECT_EQ(items[0].x, 1.0f);
  EXPECT_EQ(items[1].x, 2.0f);
}

// Four cells of edge 1 along x, texels only in the first, within 0.1 of its left face: the
// cell beside it lies within reach (1.2) of them, the one after that does not, though its box
// lies within reach of the first cell's box.
TEST(NearGrid, ACellListsTheCellsWhoseTexelsLieWithinReach) {
  const glm::ivec3 cells(4, 1, 1);
  const std::vector<glm::vec2> ranges = {{0, 3}, {3, 0}, {3, 0}, {3, 0}};
  std::vector<glm::vec3> bounds(8, glm::vec3(0.0f));
  bounds[0] = glm::vec3(0.0f, 0.2f, 0.2f);
  bounds[1] = glm::vec3(0.1f, 0.8f, 0.8f);
  for (std::size_t c = 1; c < 4; ++c)
    bounds[2 * c] = glm::vec3(1e30f), bounds[2 * c + 1] = glm::vec3(-1e30f);
  std::vector<glm::vec4> out;
  const std::vector<glm::vec2> lists = neighbourLists(ranges, bounds, cells, 1.0f, 1.2f, 3, out);
  ASSERT_EQ(lists.size(), 4u);
  EXPECT_EQ(lists[0].y, 1.0f);
  EXPECT_EQ(lists[1].y, 1.0f);
  EXPECT_EQ(lists[2].y, 0.0f);
  EXPECT_EQ(lists[3].y, 0.0f);
  for (const glm::vec4& item : out) EXPECT_EQ(glm::vec3(item), glm::vec3(0.0f));
}

// The mirror image: texels within 0.1 of the last cell's right face list the cell beside it,
// not the one before that.
TEST(NearGrid, ReachIsMeasuredFromTheTexelsFacingTheCell) {
  const glm::ivec3 cells(4, 1, 1);
  const std::vector<glm::vec2> ranges = {{0, 0}, {0, 0}, {0, 0}, {0, 3}};
  std::vector<glm::vec3> bounds(8, glm::vec3(1e30f));
  for (std::size_t c = 0; c < 3; ++c) bounds[2 * c + 1] = glm::vec3(-1e30f);
  bounds[6] = glm::vec3(3.9f, 0.2f, 0.2f);
  bounds[7] = glm::vec3(4.0f, 0.8f, 0.8f);
  std::vector<glm::vec4> out;
  const std::vector<glm::vec2> lists = neighbourLists(ranges, bounds, cells, 1.0f, 1.2f, 3, out);
  EXPECT_EQ(lists[0].y, 0.0f);
  EXPECT_EQ(lists[1].y, 0.0f);
  EXPECT_EQ(lists[2].y, 1.0f);
  EXPECT_EQ(lists[3].y, 1.0f);
}

// Random entries (spheres of their texels) binned as the near field bins them: every entry
// within reach of a pixel, in the grid or beyond it (its cell clamped to the grid, as the
// shader's is), lies in a cell that the pixel's cell lists.
TEST(NearGrid, EveryEntryWithinReachIsInAListedCell) {
  std::mt19937 random(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<glm::vec4> spheres;
  float spread = 0.0f;
  for (int i = 0; i < 3000; ++i) {
    // On three faces of a unit box, as texels on walls, or anywhere in it.
    glm::vec3 p(unit(random), unit(random), unit(random));
    if (i % 4 < 3) p[i % 4] = 0.0f;
    const float radius = i % 3 == 0 ? 0.04f * unit(random) : 0.0f;
    spheres.push_back(glm::vec4(p, radius));
    spread = std::max(spread, radius);
  }
  const float twoR = 0.12f, reach = twoR + spread;
  std::vector<int> list;
  float cell = 0.0f;
  glm::ivec3 cells;
  const glm::vec3 lo(0.0f), hi(1.0f);
  const std::vector<glm::vec2> ranges = binCascade(spheres, lo, hi, reach, list, cell, cells);
  const int m = int(std::ceil(reach / cell)) + 1;
  std::vector<glm::vec4> out;
  const std::vector<glm::vec2> lists =
      neighbourLists(ranges, texelBounds(spheres, list, ranges, lo), cells, cell, twoR, m, out);
  // The cell of each entry.
  std::vector<int> cellOf(spheres.size());
  for (std::size_t c = 0; c < ranges.size(); ++c)
    for (int j = int(ranges[c].x); j < int(ranges[c].x + ranges[c].y); ++j)
      cellOf[std::size_t(list[std::size_t(j)])] = int(c);
  long long reached = 0, missing = 0;
  for (int i = 0; i < 4000; ++i) {
    const glm::vec3 x = glm::vec3(unit(random), unit(random), unit(random)) * 1.2f - 0.1f;
    const glm::ivec3 home =
        glm::clamp(glm::ivec3(glm::floor((x - lo) / cell)), glm::ivec3(0), cells - 1);
    const glm::vec2 l = lists[std::size_t((home.z * cells.y + home.y) * cells.x + home.x)];
    std::vector<int> listed;
    for (int j = int(l.x); j < int(l.x + l.y); ++j) {
      const glm::ivec3 s(out[std::size_t(j)]);
      listed.push_back((s.z * cells.y + s.y) * cells.x + s.x);
    }
    for (std::size_t e = 0; e < spheres.size(); ++e) {
      if (glm::length(glm::vec3(spheres[e]) - x) - spheres[e].w >= twoR) continue;
      ++reached;
      if (std::find(listed.begin(), listed.end(), cellOf[e]) == listed.end()) ++missing;
    }
  }
  std::cout << reached << " entries within reach of a pixel, " << missing << " unlisted\n";
  EXPECT_GT(reached, 10000);
  EXPECT_EQ(missing, 0);
}

}  // namespace
}  // namespace manylight::testing
