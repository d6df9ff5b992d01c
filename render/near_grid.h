#pragma once
// The near field's world-space grids (render/near_field.h): entries binned by cell, and per
// cell the list of cells a pixel in it reads. No GL; the lists are numbered in float texels.
#include <cstddef>
#include <glm/glm.hpp>
#include <vector>

namespace manylight {

// Records a texture of the near field holds at most: their indices are floats.
inline constexpr std::size_t kMostRecords = std::size_t(1) << 24;

// Bins `spheres` (an entry's centre and radius, the reach of its texels from the centre) by
// their centres (from `lo` to `hi`) in cells of edge `reach`, or of half that where cells of
// `reach` would hold more than kNearEntriesPerCell entries on average: `list` gets their
// indices ordered by cell. Returns per cell its first place in `list` and its count, and the
// cells' edge and count per axis.
std::vector<glm::vec2> binCascade(const std::vector<glm::vec4>& spheres, glm::vec3 lo, glm::vec3 hi,
                                  float reach, std::vector<int>& list, float& cell,
                                  glm::ivec3& cells);

// Per cell of a grid of `cells`, the sum of `cost` over the cells within `m` of it on each
// axis: a bound on what a pixel's window of cells holds.
std::vector<long long> windowSums(const std::vector<long long>& cost, glm::ivec3 cells, int m);

long long largest(const std::vector<long long>& v);

// Per cell of `ranges` (its entries' indices in `list`), the box of its entries' `spheres`
// from `origin`: least corner, then greatest (inverted in a cell without entries).
std::vector<glm::vec3> texelBounds(const std::vector<glm::vec4>& spheres,
                                   const std::vector<int>& list,
                                   const std::vector<glm::vec2>& ranges, glm::vec3 origin);

// Per cell of a grid of `cells` cells of edge `cell` from the origin: the cells holding entries
// (`ranges`) whose texels lie within `reach` of its box (all within `m` cells of it on each
// axis), appended to `out` in the cells' order as (x, y, z, 0) (listedCells makes them the
// shader's items). `bounds` holds per cell the box of its texels, least and greatest corner.
// Returns per cell its first place in `out` and their count: a pixel in the cell reads those
// cells only, instead of every cell of the window around it, most of them empty or out of
// reach. Throws gl::GlError past kMostRecords items.
std::vector<glm::vec2> neighbourLists(const std::vector<glm::vec2>& ranges,
                                      const std::vector<glm::vec3>& bounds, glm::ivec3 cells,
                                      float cell, float reach, int m, std::vector<glm::vec4>& out);

// The items of a cascade's neighbour lists, out[from, end) as neighbourLists left them: each
// listed cell's (x | y << 8 | z << 16, first entry, count, count before its plane's entries)
// per `ranges` (first entries counted over every cascade) and `before`, and its plane
// appended to `planesOut`: the near field reads a listed cell in two texels.
void listedCells(const std::vector<glm::vec2>& ranges, const std::vector<glm::vec4>& planes,
                 const std::vector<float>& before, glm::ivec3 cells, std::size_t from,
                 std::vector<glm::vec4>& out, std::vector<glm::vec4>& planesOut);

// Reorders each cell's list (`lists`, over `items` and their `planes` as listedCells left
// them) so that the listed cells whose entries all lie on one plane, the plane the most of
// them share, come last. Returns per cell (its first item, count, count before those): a
// pixel in or behind that plane reads only the items before them, as it would skip each
// of them by its own plane. Floors and walls make such runs: most pixels of a room sit on
// a plane that lights none of them.
std::vector<glm::vec3> homePlanes(const std::vector<glm::vec2>& lists,
                                  std::vector<glm::vec4>& items, std::vector<glm::vec4>& planes);

}  // namespace manylight
