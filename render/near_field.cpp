#include "render/near_field.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

#include "gl/context.h"
#include "render/lighting_inputs.h"
#include "render/near_grid.h"

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
  clusterEntries_ = 0;
  texels_.clear();
  clusters_.clear();
  binned_.clear();
}

void NearField::add(const std::vector<float>& position, const std::vector<float>& normal,
                    const std::vector<float>& flux, const RsmClusters& clusters, float radius) {
  binned_.clear();
  const int size = clusters.size * kRsmClusterEdge;
  for (int by = 0; by < clusters.size; ++by)
    for (int bx = 0; bx < clusters.size; ++bx) {
      const std::size_t at = std::size_t(by) * std::size_t(clusters.size) + std::size_t(bx);
      if (clusters.centre[at].w < 0.0f) continue;  // reflects nothing
      const glm::vec4 n = clusters.normal[at], f = clusters.flux[at];
      Entry e{clusters.centre[at],
              glm::vec4(glm::vec3(n), f.w),
              glm::vec4(glm::vec3(f), n.w > 0.0f ? radius : -radius),
              int(texels_.size()),
              0,
              int(clusters_.size())};
      for (int y = by * kRsmClusterEdge; y < (by + 1) * kRsmClusterEdge; ++y)
        for (int x = bx * kRsmClusterEdge; x < (bx + 1) * kRsmClusterEdge; ++x) {
          const std::size_t t = 4 * (std::size_t(y) * std::size_t(size) + std::size_t(x));
          if (flux[t + 3] == 0.0f) continue;
          texels_.push_back({glm::vec4(position[t], position[t + 1], position[t + 2], 0.0f),
                             glm::vec4(normal[t], normal[t + 1], normal[t + 2], flux[t + 3]),
                             glm::vec4(flux[t], flux[t + 1], flux[t + 2], 0.0f)});
          ++e.count;
        }
      clusters_.push_back(e);
    }
}

namespace {

constexpr int kTextureWidth = 1 << kNearTextureShift;

// `texels` padded with zeros to whole rows of kTextureWidth, at least one.
void upload2d(const gl::Texture& t, std::vector<glm::vec4>& texels) {
  const int height = std::max(int((texels.size() + kTextureWidth - 1) / kTextureWidth), 1);
  texels.resize(std::size_t(height) * kTextureWidth, glm::vec4(0.0f));
  glBindTexture(GL_TEXTURE_2D, t.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kTextureWidth, height, 0, GL_RGBA, GL_FLOAT,
               glm::value_ptr(texels[0]));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

}  // namespace

// The entries of cascade k (cells of edge `cell`): each cluster, or where its radius passes
// kNearClusterSpread · r, each of its texels alone.
std::vector<NearField::Entry> NearField::cascadeEntries(float cell) const {
  std::vector<Entry> out;
  for (const Entry& c : clusters_) {
    const float r = std::max(c.mapRadius(), kNearCells * cell);
    if (c.centreRadius.w <= kNearClusterSpread * r) {
      out.push_back(c);
      continue;
    }
    for (int i = c.first; i < c.first + c.count; ++i) {
      const Texel& t = texels_[std::size_t(i)];
      out.push_back({glm::vec4(glm::vec3(t.position), 0.0f), t.normalArea,
                     glm::vec4(glm::vec3(t.flux), c.mapRadius()), i, 1, c.cluster});
    }
  }
  return out;
}

// The passes of one cascade (`entries` binned by `list` into `ranges` over `cells`, a pixel
// reading the cells within `m` of its own): per pass the first entry of a pixel's cells in
// their order, and the count. Where no pixel's cells cost more than kNearTexelsPerPass loop
// iterations (an entry's one, and a cluster's texels where it is summed texel by texel), one
// pass reads them all; else each pass reads as many entries as cost that at most.
void NearField::cascadePasses(const std::vector<Entry>& entries, const std::vector<int>& list,
                              const std::vector<glm::vec2>& ranges, glm::ivec3 cells, int m,
                              std::vector<int>& first, std::vector<int>& count) {
  constexpr long long kMostPerEntry = 1 + kRsmClusterEdge * kRsmClusterEdge;
  std::vector<long long> cost(ranges.size(), 0), held(ranges.size(), 0);
  for (std::size_t c = 0; c < ranges.size(); ++c) {
    held[c] = (long long)ranges[c].y;
    for (std::size_t j = std::size_t(ranges[c].x); j < std::size_t(ranges[c].x + ranges[c].y); ++j)
      cost[c] += entries[std::size_t(list[j])].centreRadius.w > 0.0f ? kMostPerEntry : 1;
  }
  const std::vector<long long> entriesNear = windowSums(held, cells, m);
  if (largest(windowSums(cost, cells, m)) <= kNearTexelsPerPass) {
    first.push_back(0);
    count.push_back(int(entries.size()));
    return;
  }
  const long long perPass = kNearTexelsPerPass / kMostPerEntry;
  const long long most = largest(entriesNear);
  for (long long f = 0; f < most; f += perPass) {
    first.push_back(int(f));
    count.push_back(int(perPass));
  }
}

std::vector<glm::vec4> NearField::cellPlanes(const std::vector<Entry>& entries,
                                             std::vector<int>& list,
                                             const std::vector<glm::vec2>& ranges, float tolerance,
                                             std::vector<float>& before) const {
  std::vector<glm::vec4> planes(ranges.size(), glm::vec4(0.0f));
  before.assign(ranges.size(), 0.0f);
  // Whether every texel of entry `e` lies on the plane (n, offset).
  const auto onPlane = [&](const Entry& e, glm::vec3 n, float offset) {
    for (int i = e.first; i < e.first + e.count; ++i) {
      const Texel& t = texels_[std::size_t(i)];
      // Accepted, not rejected: a plane of NaN (a texel without a normal) holds no texel.
      const bool on = glm::dot(glm::vec3(t.normalArea), n) > 0.9999f &&
                      std::abs(glm::dot(n, glm::vec3(t.position)) - offset) <= tolerance;
      if (!on) return false;
    }
    return true;
  };
  for (std::size_t c = 0; c < ranges.size(); ++c) {
    const std::size_t first = std::size_t(ranges[c].x), count = std::size_t(ranges[c].y);
    if (count == 0) continue;
    // Candidates: the planes of the first texels of the cell's first kPlaneCandidates
    // entries; the one the most texels lie on wins.
    glm::vec4 best(0.0f);
    long long bestTexels = 0;
    for (std::size_t j = first; j < first + std::min(count, kPlaneCandidates); ++j) {
      const Texel& t0 = texels_[std::size_t(entries[std::size_t(list[j])].first)];
      const glm::vec3 n = glm::normalize(glm::vec3(t0.normalArea));
      const float offset = glm::dot(n, glm::vec3(t0.position));
      long long texels = 0;
      for (std::size_t i = first; i < first + count; ++i) {
        const Entry& e = entries[std::size_t(list[i])];
        if (onPlane(e, n, offset)) texels += e.count;
      }
      if (texels > bestTexels) best = glm::vec4(n, offset), bestTexels = texels;
    }
    if (bestTexels == 0) continue;
    // The entries off the plane first, then those on it (the tail a pixel in or behind the
    // plane leaves out), each part in its order.
    const auto begin = list.begin() + std::ptrdiff_t(first);
    const auto off = std::stable_partition(begin, begin + std::ptrdiff_t(count), [&](int e) {
      return !onPlane(entries[std::size_t(e)], glm::vec3(best), best.w);
    });
    planes[c] = best;
    before[c] = float(off - begin);
  }
  return planes;
}

// Per cascade's cell, stacked in z in a volume of `size`: its list's count, first, and count
// before the cells on its plane (homePlanes; grid_).
void NearField::uploadGrids(glm::ivec3 size, const std::vector<std::vector<glm::vec3>>& lists) {
  std::vector<glm::vec3> volume(std::size_t(size.x) * std::size_t(size.y) * std::size_t(size.z),
                                glm::vec3(0.0f));
  for (std::size_t k = 0; k < lists.size(); ++k) {
    const glm::ivec3 cells = cells_[k];
    for (int z = 0; z < cells.z; ++z)
      for (int y = 0; y < cells.y; ++y)
        for (int x = 0; x < cells.x; ++x) {
          const std::size_t at =
              (std::size_t(firstZ_[k] + z) * std::size_t(size.y) + std::size_t(y)) *
                  std::size_t(size.x) +
              std::size_t(x);
          const std::size_t c = std::size_t((z * cells.y + y) * cells.x + x);
          volume[at] = glm::vec3(lists[k][c].y, lists[k][c].x, lists[k][c].z);
        }
  }
  glBindTexture(GL_TEXTURE_3D, grid_.id());
  glTexImage3D(GL_TEXTURE_3D, 0, GL_RGB32F, size.x, size.y, size.z, 0, GL_RGB, GL_FLOAT,
               glm::value_ptr(volume[0]));
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_3D, 0);
}

// The entries of every cascade, in their cells' order, then the texels of the clusters as
// records of their own, kRsmClusterEdge² a cluster.
void NearField::uploadEntries(const std::vector<Entry>& ordered) {
  constexpr int kSlots = kRsmClusterEdge * kRsmClusterEdge;
  // Records are numbered in float texels: exact up to 2^24.
  const std::size_t records = ordered.size() + clusters_.size() * kSlots;
  if (records > kMostRecords)
    throw gl::GlError("the near field needs " + std::to_string(records) +
                      " records, past 16,777,216: use fewer or smaller maps (--rsm-lights, "
                      "--rsm-size)");
  std::vector<glm::vec4> centres, normals, fluxes;
  for (const Entry& e : ordered) {
    centres.push_back(e.centreRadius);
    const bool cluster = e.centreRadius.w > 0.0f;
    const float firstRecord = float(ordered.size() + std::size_t(e.cluster) * kSlots);
    normals.push_back(glm::vec4(glm::vec3(e.normalArea), cluster ? firstRecord : e.normalArea.w));
    fluxes.push_back(e.fluxRadius);
  }
  for (const Entry& c : clusters_) {
    for (int i = c.first; i < c.first + c.count; ++i) {
      const Texel& t = texels_[std::size_t(i)];
      centres.push_back(glm::vec4(glm::vec3(t.position), 0.0f));
      normals.push_back(t.normalArea);
      fluxes.push_back(glm::vec4(glm::vec3(t.flux), c.mapRadius()));
    }
    for (int i = c.count; i < kSlots; ++i) {
      centres.push_back(glm::vec4(0.0f));
      normals.push_back(glm::vec4(0.0f, 0.0f, 1.0f, 0.0f));
      fluxes.push_back(glm::vec4(0.0f, 0.0f, 0.0f, c.mapRadius()));
    }
  }
  upload2d(centres_, centres);
  upload2d(normals_, normals);
  upload2d(fluxes_, fluxes);
  glBindTexture(GL_TEXTURE_2D, 0);
}

void NearField::upload(const CacheGrid& grid) {
  cascades_ = grid;
  // The bins depend on the texels and the cascades' cells only, not on where the camera is.
  if (texels_.empty() || binned_ == grid.cell) return;
  binned_ = grid.cell;
  // Over the texels, which hold every cluster's centre: a texel alone is an entry too.
  glm::vec3 lo(texels_[0].position), hi = lo;
  for (const Texel& t : texels_) {
    lo = glm::min(lo, glm::vec3(t.position));
    hi = glm::max(hi, glm::vec3(t.position));
  }
  float mapRadius = 0.0f;
  for (const Entry& c : clusters_) mapRadius = std::max(mapRadius, c.mapRadius());
  origin_ = lo;
  clusterEntries_ = 0;
  std::vector<Entry> ordered;                 // every cascade's entries in its cells' order
  std::vector<std::vector<glm::vec3>> lists;  // per cascade, per cell: its list (homePlanes)
  std::vector<glm::vec4> neighbours, planes;  // every cascade's listedCells
  cell_.clear(), reach_.clear(), spread_.clear(), cells_.clear(), firstZ_.clear();
  std::vector<std::vector<int>> first, count;  // per cascade, per pass
  glm::ivec3 size(1, 1, 0);
  for (int k = 0; k < grid.cascades; ++k) {
    const std::vector<Entry> entries = cascadeEntries(grid.cell[std::size_t(k)]);
    std::vector<glm::vec4> spheres;  // each entry's centre and radius: its texels' reach
    float spread = 0.0f;
    for (const Entry& e : entries) {
      spheres.push_back(e.centreRadius);
      spread = std::max(spread, e.centreRadius.w);
    }
    const float reach = 2.0f * std::max(mapRadius, kNearCells * grid.cell[std::size_t(k)]) + spread;
    float cell = 0.0f;
    glm::ivec3 cells;
    std::vector<int> list;
    std::vector<glm::vec2> r = binCascade(spheres, lo, hi, reach, list, cell, cells);
    std::vector<float> before;
    const std::vector<glm::vec4> cellPlane =
        cellPlanes(entries, list, r, kPlaneTolerance * cell, before);
    for (const Entry& e : entries) clusterEntries_ += e.centreRadius.w > 0.0f;
    first.emplace_back(), count.emplace_back();
    // A pixel's cells lie within m of its own on each axis.
    const int m = int(std::ceil(reach / cell)) + 1;
    cascadePasses(entries, list, r, cells, m, first.back(), count.back());
    const std::size_t listed = neighbours.size();
    const std::vector<glm::vec2> homes = neighbourLists(r, texelBounds(spheres, list, r, lo), cells,
                                                        cell, reach - spread, m, neighbours);
    for (glm::vec2& range : r) range.x += float(ordered.size());
    listedCells(r, cellPlane, before, cells, listed, neighbours, planes);
    lists.push_back(homePlanes(homes, neighbours, planes));
    for (int i : list) ordered.push_back(entries[std::size_t(i)]);
    cell_.push_back(cell), reach_.push_back(reach), spread_.push_back(spread);
    cells_.push_back(cells);
    firstZ_.push_back(size.z);
    size = glm::ivec3(std::max(size.x, cells.x), std::max(size.y, cells.y), size.z + cells.z);
  }
  std::size_t passes = 0;
  for (const std::vector<int>& f : first) passes = std::max(passes, f.size());
  passFirst_.assign(passes, std::vector<int>(std::size_t(grid.cascades), 0));
  passCount_ = passFirst_;
  for (std::size_t k = 0; k < first.size(); ++k)
    for (std::size_t p = 0; p < first[k].size(); ++p) {
      passFirst_[p][k] = first[k][p];
      passCount_[p][k] = count[k][p];
    }
  uploadEntries(ordered);
  upload2d(neighbours_, neighbours);
  upload2d(neighbourPlanes_, planes);
  uploadGrids(size, lists);
}

int NearField::draw(const GBuffer& camera, const PixelClasses& classes) {
  if (texels_.empty() || passFirst_.empty()) return 0;
  const gl::Program& p = gl::cachedProgram("fullscreen.vert", "cache_near.frag", {}, {"oRadiance"});
  p.use();
  classes.bind(p, camera, kPixelCached, kPixelCached);
  bindSampler(p, "uEntryCentre", GL_TEXTURE_2D, centres_.id(), 3);
  bindSampler(p, "uEntryNormal", GL_TEXTURE_2D, normals_.id(), 4);
  bindSampler(p, "uEntryFlux", GL_TEXTURE_2D, fluxes_.id(), 5);
  bindSampler(p, "uGrid", GL_TEXTURE_3D, grid_.id(), 6);
  bindSampler(p, "uNeighbours", GL_TEXTURE_2D, neighbours_.id(), 7);
  bindSampler(p, "uNeighbourPlanes", GL_TEXTURE_2D, neighbourPlanes_.id(), 8);
  setCascadeUniforms(p, cascades_);
  const int k = std::min(cascades_.cascades, int(cell_.size()));
  glUniform3fv(p.uniform("uGridOrigin"), 1, glm::value_ptr(origin_));
  glUniform1fv(p.uniform("uGridCell"), k, cell_.data());
  glUniform1fv(p.uniform("uGridReach"), k, reach_.data());
  glUniform1fv(p.uniform("uGridSpread"), k, spread_.data());
  glUniform3iv(p.uniform("uGridCells"), k, glm::value_ptr(cells_[0]));
  glUniform1iv(p.uniform("uGridFirstZ"), k, firstZ_.data());
  for (std::size_t pass = 0; pass < passFirst_.size(); ++pass) {
    glUniform1iv(p.uniform("uFirst"), k, passFirst_[pass].data());
    glUniform1iv(p.uniform("uCount"), k, passCount_[pass].data());
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  PixelClasses::done();
  glDisable(GL_BLEND);
  glActiveTexture(GL_TEXTURE0);
  return int(passFirst_.size());
}

}  // namespace manylight
