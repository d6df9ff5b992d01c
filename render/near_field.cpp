#include "render/near_field.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

#include "gl/context.h"
#include "render/lighting_inputs.h"

namespace manylight {

using namespace gl::api;

float nearRadius(const std::vector<float>& flux) {
  std::vector<float> edges;
  for (std::size_t i = 3; i < flux.size(); i += 4) {
    if (flux[i] > 0.0f) edges.push_back(std::sqrt(flux[i]));
  }
  if (edges.empty()) return 0.0f;
  const auto middle = edges.begin() + std::ptrdiff_t(edges.size() / 2);
  std::nth_element(edges.begin(), middle, edges.end());
  return kNearTexelEdges * *middle;
}

void NearField::clear() {
  texels_.clear();
  binned_.clear();
}

void NearField::add(const std::vector<float>& position, const std::vector<float>& normal,
                    const std::vector<float>& flux, float radius) {
  binned_.clear();
  for (std::size_t i = 0; i + 3 < flux.size(); i += 4) {
    if (flux[i + 3] == 0.0f) continue;
    texels_.push_back({glm::vec4(position[i], position[i + 1], position[i + 2], radius),
                       glm::vec4(normal[i], normal[i + 1], normal[i + 2], flux[i + 3]),
                       glm::vec4(flux[i], flux[i + 1], flux[i + 2], 0.0f)});
  }
}

namespace {

constexpr int kTextureWidth = 1024;

void upload2d(const gl::Texture& t, const float* texels, int height) {
  glBindTexture(GL_TEXTURE_2D, t.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kTextureWidth, height, 0, GL_RGBA, GL_FLOAT, texels);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

void upload3d(const gl::Texture& t, glm::ivec3 size, const std::vector<glm::vec4>& texels) {
  glBindTexture(GL_TEXTURE_3D, t.id());
  glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA32F, size.x, size.y, size.z, 0, GL_RGBA, GL_FLOAT,
               texels.data());
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_3D, 0);
}

}  // namespace

// Per cell, the plane (unit normal, offset n·p) all its texels lie in within `tolerance`, or
// 0 where they do not share one: a pixel in that plane or behind it gets no light from them,
// since each sends its light only to the side it faces, so it skips the cell.
std::vector<glm::vec4> NearField::cellPlanes(const std::vector<Texel>& texels,
                                             const std::vector<float>& lists,
                                             const std::vector<glm::vec2>& ranges,
                                             float tolerance) {
  std::vector<glm::vec4> planes(ranges.size(), glm::vec4(0.0f));
  for (std::size_t c = 0; c < ranges.size(); ++c) {
    const std::size_t first = std::size_t(ranges[c].x), count = std::size_t(ranges[c].y);
    if (count == 0) continue;
    const Texel& t0 = texels[std::size_t(lists[first])];
    const glm::vec3 n = glm::normalize(glm::vec3(t0.normalArea));
    const float offset = glm::dot(n, glm::vec3(t0.positionRadius));
    bool shared = true;
    for (std::size_t j = first + 1; shared && j < first + count; ++j) {
      const Texel& t = texels[std::size_t(lists[j])];
      shared = glm::dot(glm::vec3(t.normalArea), n) > 0.9999f &&
               std::abs(glm::dot(n, glm::vec3(t.positionRadius)) - offset) <= tolerance;
    }
    if (shared) planes[c] = glm::vec4(n, offset);
  }
  return planes;
}

// Appends to `lists` the indices of `texels` ordered by their cell in the grid of `cells`
// cells of edge `cell` from `lo`; returns per cell its first entry in lists and its count.
std::vector<glm::vec2> NearField::binTexels(const std::vector<Texel>& texels, glm::vec3 lo,
                                            float cell, glm::ivec3 cells,
                                            std::vector<float>& lists) {
  const std::size_t n = texels.size();
  std::vector<int> home(n);
  std::vector<glm::vec2> r(std::size_t(cells.x * cells.y * cells.z), glm::vec2(0.0f));
  for (std::size_t i = 0; i < n; ++i) {
    const glm::ivec3 c =
        glm::clamp(glm::ivec3(glm::floor((glm::vec3(texels[i].positionRadius) - lo) / cell)),
                   glm::ivec3(0), cells - 1);
    home[i] = (c.z * cells.y + c.y) * cells.x + c.x;
    r[std::size_t(home[i])].y += 1.0f;
  }
  float first = float(lists.size());
  for (glm::vec2& range : r) {
    range.x = first;
    first += range.y;
  }
  lists.resize(lists.size() + n);
  std::vector<float> next(r.size());
  for (std::size_t c = 0; c < r.size(); ++c) next[c] = r[c].x;
  for (std::size_t i = 0; i < n; ++i) lists[std::size_t(next[std::size_t(home[i])]++)] = float(i);
  return r;
}

// Bins `texels` (from `lo` to `hi`) as binTexels does in cells of edge `reach`, or of half
// that where cells of `reach` would hold more than kNearTexelsPerCell texels on average.
// Returns the ranges, and the cells' edge and count per axis.
std::vector<glm::vec2> NearField::binCascade(const std::vector<Texel>& texels, glm::vec3 lo,
                                             glm::vec3 hi, float reach, std::vector<float>& lists,
                                             float& cell, glm::ivec3& cells) {
  const float extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  const std::size_t listed = lists.size();
  std::vector<glm::vec2> r;
  for (float perReach : {1.0f, 2.0f}) {
    lists.resize(listed);
    cell = std::max({reach / perReach, extent / float(kNearGridCells - 1), 1e-6f});
    cells = glm::clamp(glm::ivec3(glm::floor((hi - lo) / cell)) + 1, glm::ivec3(1),
                       glm::ivec3(kNearGridCells));
    r = binTexels(texels, lo, cell, cells, lists);
    std::size_t occupied = 0;
    for (const glm::vec2& range : r) occupied += range.y > 0.0f;
    if (texels.size() <= kNearTexelsPerCell * occupied) break;
  }
  return r;
}

// Per cascade's cell, stacked in z in volumes of `size`: its first texel and their count
// (grid_), and cellPlanes (planes_).
void NearField::uploadGrids(glm::ivec3 size, const std::vector<std::vector<glm::vec2>>& ranges,
                            const std::vector<std::vector<glm::vec4>>& planes) {
  std::vector<glm::vec4> volume(std::size_t(size.x) * std::size_t(size.y) * std::size_t(size.z),
                                glm::vec4(0.0f)),
      planeVolume(volume.size(), glm::vec4(0.0f));
  for (std::size_t k = 0; k < ranges.size(); ++k) {
    const glm::ivec3 cells = cells_[k];
    for (int z = 0; z < cells.z; ++z)
      for (int y = 0; y < cells.y; ++y)
        for (int x = 0; x < cells.x; ++x) {
          const std::size_t at =
              (std::size_t(firstZ_[k] + z) * std::size_t(size.y) + std::size_t(y)) *
                  std::size_t(size.x) +
              std::size_t(x);
          const std::size_t c = std::size_t((z * cells.y + y) * cells.x + x);
          volume[at] = glm::vec4(ranges[k][c], 0.0f, 0.0f);
          planeVolume[at] = planes[k][c];
        }
  }
  upload3d(grid_, size, volume);
  upload3d(planes_, size, planeVolume);
}

void NearField::upload(const CacheGrid& grid) {
  cascades_ = grid;
  uploaded_ = int(texels_.size());
  // The bins depend on the texels and the cascades' cells only, not on where the camera is.
  if (texels_.empty() || binned_ == grid.cell) return;
  binned_ = grid.cell;
  glm::vec3 lo(texels_[0].positionRadius), hi = lo;
  float mapRadius = 0.0f;
  for (const Texel& t : texels_) {
    lo = glm::min(lo, glm::vec3(t.positionRadius));
    hi = glm::max(hi, glm::vec3(t.positionRadius));
    mapRadius = std::max(mapRadius, t.positionRadius.w);
  }
  origin_ = lo;
  std::vector<float> lists;                    // per cascade, the texel indices ordered by cell
  std::vector<std::vector<glm::vec2>> ranges;  // per cascade, per cell: first in lists, count
  std::vector<std::vector<glm::vec4>> planes;  // per cascade, per cell: cellPlanes
  cell_.clear();
  reach_.clear();
  cells_.clear();
  firstZ_.clear();
  glm::ivec3 size(1, 1, 0);
  for (int k = 0; k < grid.cascades; ++k) {
    const float radius = std::max(mapRadius, kNearCells * grid.cell[std::size_t(k)]);
    float cell = 0.0f;
    glm::ivec3 cells;
    std::vector<glm::vec2> r = binCascade(texels_, lo, hi, 2.0f * radius, lists, cell, cells);
    planes.push_back(cellPlanes(texels_, lists, r, kPlaneTolerance * cell));
    cell_.push_back(cell);
    reach_.push_back(2.0f * radius);
    cells_.push_back(cells);
    firstZ_.push_back(size.z);
    size = glm::ivec3(std::max(size.x, cells.x), std::max(size.y, cells.y), size.z + cells.z);
    ranges.push_back(std::move(r));
  }
  // The texels themselves in the lists' order, so a pixel reads a cell's texels in a row.
  const int height = int((lists.size() + kTextureWidth - 1) / kTextureWidth);
  std::vector<glm::vec4> a(std::size_t(height) * kTextureWidth), b(a.size()), c(a.size());
  for (std::size_t l = 0; l < lists.size(); ++l) {
    const Texel& t = texels_[std::size_t(lists[l])];
    a[l] = t.positionRadius;
    b[l] = t.normalArea;
    c[l] = t.flux;
  }
  upload2d(positions_, glm::value_ptr(a[0]), height);
  upload2d(normals_, glm::value_ptr(b[0]), height);
  upload2d(fluxes_, glm::value_ptr(c[0]), height);
  glBindTexture(GL_TEXTURE_2D, 0);
  uploadGrids(size, ranges, planes);
}

int NearField::draw(const GBuffer& camera) {
  if (uploaded_ == 0) return 0;
  const gl::Program& p = gl::cachedProgram("fullscreen.vert", "cache_near.frag", {}, {"oRadiance"});
  p.use();
  bindIndirectInputs(p, camera);
  bindSampler(p, "uTexelPosition", GL_TEXTURE_2D, positions_.id(), 3);
  bindSampler(p, "uTexelNormal", GL_TEXTURE_2D, normals_.id(), 4);
  bindSampler(p, "uTexelFlux", GL_TEXTURE_2D, fluxes_.id(), 5);
  bindSampler(p, "uGrid", GL_TEXTURE_3D, grid_.id(), 6);
  bindSampler(p, "uPlanes", GL_TEXTURE_3D, planes_.id(), 7);
  setCascadeUniforms(p, cascades_);
  const int k = cascades_.cascades;
  glUniform3fv(p.uniform("uGridOrigin"), 1, glm::value_ptr(origin_));
  glUniform1fv(p.uniform("uGridCell"), k, cell_.data());
  glUniform1fv(p.uniform("uGridReach"), k, reach_.data());
  glUniform3iv(p.uniform("uGridCells"), k, glm::value_ptr(cells_[0]));
  glUniform1iv(p.uniform("uGridFirstZ"), k, firstZ_.data());
  int passes = 0;
  for (int first = 0; first < uploaded_; first += kNearTexelsPerPass, ++passes) {
    glUniform1i(p.uniform("uFirst"), first);
    glUniform1i(p.uniform("uCount"), kNearTexelsPerPass);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glDisable(GL_BLEND);
  glActiveTexture(GL_TEXTURE0);
  return passes;
}

}  // namespace manylight
