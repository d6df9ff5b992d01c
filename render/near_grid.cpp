#include "render/near_grid.h"

#include <algorithm>
#include <limits>
#include <string>

#include "gl/context.h"
#include "render/near_field.h"

namespace manylight {

namespace {

// `list`: the indices of `spheres` ordered by the cell of their centres in the grid of `cells`
// cells of edge `cell` from `lo`. Returns per cell its first entry in `list` and its count.
std::vector<glm::vec2> binPoints(const std::vector<glm::vec4>& spheres, glm::vec3 lo, float cell,
                                 glm::ivec3 cells, std::vector<int>& list) {
  const std::size_t n = spheres.size();
  std::vector<int> home(n);
  std::vector<glm::vec2> r(std::size_t(cells.x * cells.y * cells.z), glm::vec2(0.0f));
  for (std::size_t i = 0; i < n; ++i) {
    const glm::ivec3 c = glm::clamp(glm::ivec3(glm::floor((glm::vec3(spheres[i]) - lo) / cell)),
                                    glm::ivec3(0), cells - 1);
    home[i] = (c.z * cells.y + c.y) * cells.x + c.x;
    r[std::size_t(home[i])].y += 1.0f;
  }
  float first = 0.0f;
  for (glm::vec2& range : r) {
    range.x = first;
    first += range.y;
  }
  list.assign(n, 0);
  std::vector<float> next(r.size());
  for (std::size_t c = 0; c < r.size(); ++c) next[c] = r[c].x;
  for (std::size_t i = 0; i < n; ++i) list[std::size_t(next[std::size_t(home[i])]++)] = int(i);
  return r;
}

}  // namespace

std::vector<glm::vec2> binCascade(const std::vector<glm::vec4>& spheres, glm::vec3 lo, glm::vec3 hi,
                                  float reach, std::vector<int>& list, float& cell,
                                  glm::ivec3& cells) {
  const float extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  std::vector<glm::vec2> r;
  for (float perReach : {1.0f, 2.0f}) {
    cell = std::max({reach / perReach, extent / float(kNearGridCells - 1), 1e-6f});
    cells = glm::clamp(glm::ivec3(glm::floor((hi - lo) / cell)) + 1, glm::ivec3(1),
                       glm::ivec3(kNearGridCells));
    r = binPoints(spheres, lo, cell, cells, list);
    std::size_t occupied = 0;
    for (const glm::vec2& range : r) occupied += range.y > 0.0f;
    if (spheres.size() <= kNearEntriesPerCell * occupied) break;
  }
  return r;
}

std::vector<long long> windowSums(const std::vector<long long>& cost, glm::ivec3 cells, int m) {
  std::vector<long long> sum = cost, next(cost.size());
  const int stride[3] = {1, cells.x, cells.x * cells.y};
  for (int axis = 0; axis < 3; ++axis) {
    for (int z = 0; z < cells.z; ++z)
      for (int y = 0; y < cells.y; ++y)
        for (int x = 0; x < cells.x; ++x) {
          const glm::ivec3 c(x, y, z);
          const int at = x + y * stride[1] + z * stride[2];
          long long s = 0;
          for (int o = std::max(c[axis] - m, 0); o <= std::min(c[axis] + m, cells[axis] - 1); ++o)
            s += sum[std::size_t(at + (o - c[axis]) * stride[axis])];
          next[std::size_t(at)] = s;
        }
    sum.swap(next);
  }
  return sum;
}

std::vector<glm::vec2> neighbourLists(const std::vector<glm::vec2>& ranges,
                                      const std::vector<glm::vec3>& bounds, glm::ivec3 cells,
                                      float cell, float reach, int m, std::vector<glm::vec4>& out) {
  const auto index = [&](glm::ivec3 c) {
    return std::size_t((c.z * cells.y + c.y) * cells.x + c.x);
  };
  // Calls visit(h) for each cell h whose box lies within reach of source cell s's texels.
  const auto forEachHome = [&](glm::ivec3 s, const auto& visit) {
    const glm::ivec3 lo = glm::max(s - m, glm::ivec3(0)), hi = glm::min(s + m, cells - 1);
    const std::size_t source = index(s);
    const glm::vec3 texelsLo = bounds[2 * source], texelsHi = bounds[2 * source + 1];
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          const glm::vec3 home = glm::vec3(x, y, z) * cell;
          const glm::vec3 gap = glm::max(glm::max(texelsLo - home - cell, home - texelsHi), 0.0f);
          if (glm::dot(gap, gap) < reach * reach) visit(index(glm::ivec3(x, y, z)));
        }
  };
  const auto forEachSource = [&](const auto& visit) {
    for (int z = 0; z < cells.z; ++z)
      for (int y = 0; y < cells.y; ++y)
        for (int x = 0; x < cells.x; ++x)
          if (ranges[index(glm::ivec3(x, y, z))].y > 0.0f) visit(glm::ivec3(x, y, z));
  };
  std::vector<std::size_t> count(ranges.size(), 0);
  forEachSource([&](glm::ivec3 s) { forEachHome(s, [&](std::size_t h) { ++count[h]; }); });
  std::vector<std::size_t> next(ranges.size());
  std::size_t first = out.size();
  for (std::size_t h = 0; h < count.size(); ++h) {
    next[h] = first;
    first += count[h];
  }
  // Listed by float texels: exact up to 2^24.
  if (first > kMostRecords)
    throw gl::GlError("the near field needs " + std::to_string(first) +
                      " cell lists, past 16,777,216: use fewer or smaller maps (--rsm-lights, "
                      "--rsm-size)");
  std::vector<glm::vec2> lists(ranges.size());
  for (std::size_t h = 0; h < count.size(); ++h)
    lists[h] = glm::vec2(float(next[h]), float(count[h]));
  out.resize(first);
  forEachSource([&](glm::ivec3 s) {
    forEachHome(s, [&](std::size_t h) { out[next[h]++] = glm::vec4(glm::vec3(s), 0.0f); });
  });
  return lists;
}

std::vector<glm::vec3> texelBounds(const std::vector<glm::vec4>& spheres,
                                   const std::vector<int>& list,
                                   const std::vector<glm::vec2>& ranges, glm::vec3 origin) {
  std::vector<glm::vec3> bounds(2 * ranges.size());
  for (std::size_t c = 0; c < ranges.size(); ++c) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    const std::size_t first = std::size_t(ranges[c].x), end = first + std::size_t(ranges[c].y);
    for (std::size_t j = first; j < end; ++j) {
      const glm::vec4 e = spheres[std::size_t(list[j])];
      lo = glm::min(lo, glm::vec3(e) - e.w);
      hi = glm::max(hi, glm::vec3(e) + e.w);
    }
    bounds[2 * c] = lo - origin;
    bounds[2 * c + 1] = hi - origin;
  }
  return bounds;
}

void listedCells(const std::vector<glm::vec2>& ranges, const std::vector<glm::vec4>& planes,
                 const std::vector<float>& before, glm::ivec3 cells, std::size_t from,
                 std::vector<glm::vec4>& out, std::vector<glm::vec4>& planesOut) {
  static_assert(kNearGridCells <= 256, "a cell's coordinates are packed in 8 bits each");
  for (std::size_t i = from; i < out.size(); ++i) {
    const glm::ivec3 s(out[i]);
    const std::size_t c = std::size_t((s.z * cells.y + s.y) * cells.x + s.x);
    out[i] = glm::vec4(float(s.x | s.y << 8 | s.z << 16), ranges[c].x, ranges[c].y, before[c]);
    planesOut.push_back(planes[c]);
  }
}

long long largest(const std::vector<long long>& v) {
  return v.empty() ? 0 : *std::max_element(v.begin(), v.end());
}

std::vector<glm::vec3> homePlanes(const std::vector<glm::vec2>& lists,
                                  std::vector<glm::vec4>& items, std::vector<glm::vec4>& planes) {
  std::vector<glm::vec3> out(lists.size());
  std::vector<glm::vec4> seen, movedItems, movedPlanes;
  std::vector<int> held;  // per plane seen, the listed cells wholly on it
  for (std::size_t h = 0; h < lists.size(); ++h) {
    const std::size_t first = std::size_t(lists[h].x), end = first + std::size_t(lists[h].y);
    out[h] = glm::vec3(lists[h], lists[h].y);
    // A listed cell lies wholly on its plane where it has one and no entry comes before it.
    const auto wholly = [&](std::size_t i) {
      return items[i].w == 0.0f && planes[i] != glm::vec4(0.0f);
    };
    seen.clear(), held.clear();
    for (std::size_t i = first; i < end; ++i) {
      if (!wholly(i)) continue;
      const std::size_t at =
          std::size_t(std::find(seen.begin(), seen.end(), planes[i]) - seen.begin());
      if (at == seen.size()) seen.push_back(planes[i]), held.push_back(0);
      ++held[at];
    }
    if (seen.empty()) continue;
    const glm::vec4 plane =
        seen[std::size_t(std::max_element(held.begin(), held.end()) - held.begin())];
    const auto onIt = [&](std::size_t i) { return wholly(i) && planes[i] == plane; };
    movedItems.clear(), movedPlanes.clear();
    for (std::size_t i = first; i < end; ++i)
      if (onIt(i)) movedItems.push_back(items[i]), movedPlanes.push_back(planes[i]);
    std::size_t to = first;
    for (std::size_t i = first; i < end; ++i)
      if (!onIt(i)) items[to] = items[i], planes[to] = planes[i], ++to;
    out[h].z = float(to - first);
    std::copy(movedItems.begin(), movedItems.end(), items.begin() + std::ptrdiff_t(to));
    std::copy(movedPlanes.begin(), movedPlanes.end(), planes.begin() + std::ptrdiff_t(to));
  }
  return out;
}

}  // namespace manylight
