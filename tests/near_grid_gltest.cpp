// The near field's grid lists (render/near_grid.h), on the CPU. In the GL test binary since
// render/ links GL; no context is needed.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace manylight::testing
