#include "cuts/cell_cuts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cuts/threads.h"

namespace manylight {

namespace {

constexpr float kPi = 3.14159265358979323846f;

// Pixel i's normal, of unit length.
glm::vec3 unitNormalAt(const GBufferPixels& px, std::size_t i) {
  return glm::normalize(normalAt(px, i));
}

// A cell's key: the level (2 bits), then each coordinate of the cube's corner in edges (18
// bits each: cells beyond ±131,072 edges from the origin share keys with nearer ones, which
// only makes their regions larger), then the normals' bucket (8 bits).
constexpr int kLevelShift = 62;
constexpr std::uint64_t kCoordMask = 0x3ffffu;
constexpr std::int64_t kCoordOrigin = std::int64_t(1) << 17;
constexpr int coordShift(int axis) { return 8 + 18 * (2 - axis); }
static_assert(kNormalBuckets * kNormalBuckets <= 256 && kMaxCellLevel < 4);

// The bucket of unit vector `n` in an octahedral map of kNormalBuckets² buckets.
int bucketOf(glm::vec3 n) {
  n /= std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  glm::vec2 p(n.x, n.y);
  if (n.z < 0.0f) {
    p = {(1.0f - std::abs(n.y)) * (n.x >= 0.0f ? 1.0f : -1.0f),
         (1.0f - std::abs(n.x)) * (n.y >= 0.0f ? 1.0f : -1.0f)};
  }
  const int u = std::clamp(int((p.x + 1.0f) * 0.5f * kNormalBuckets), 0, kNormalBuckets - 1);
  const int v = std::clamp(int((p.y + 1.0f) * 0.5f * kNormalBuckets), 0, kNormalBuckets - 1);
  return v * kNormalBuckets + u;
}

// kCellPixels times the median distance between horizontal neighbours on one surface (normals
// within 8°), over every fourth row; 0 when no two such neighbours exist.
float cellSizeOf(const GBufferPixels& px) {
  std::vector<float> steps;
  for (int y = 0; y < px.height; y += 4) {
    for (int x = 0; x + 1 < px.width; ++x) {
      const std::size_t i = std::size_t(y) * px.width + x;
      if (px.normal[4 * i + 3] == 0.0f || px.normal[4 * i + 7] == 0.0f) continue;
      const glm::vec3 a = normalAt(px, i), b = normalAt(px, i + 1);
      if (glm::dot(a, b) < 0.99f * std::sqrt(glm::dot(a, a) * glm::dot(b, b))) continue;
      const float d = glm::length(positionAt(px, i + 1) - positionAt(px, i));
      if (std::isfinite(d) && d > 0.0f) steps.push_back(d);
    }
  }
  if (steps.empty()) return 0.0f;
  std::nth_element(steps.begin(), steps.begin() + std::ptrdiff_t(steps.size() / 2), steps.end());
  return kCellPixels * steps[steps.size() / 2];
}

// Whether the region holds position p and unit normal n.
bool holds(const ShadingRegion& g, glm::vec3 p, glm::vec3 n) {
  return p.x >= g.pMin.x && p.y >= g.pMin.y && p.z >= g.pMin.z && p.x <= g.pMax.x &&
         p.y <= g.pMax.y && p.z <= g.pMax.z && glm::dot(n, g.axis) >= g.cosSpread;
}

// Sets the region's box to the points' box lo…hi, widened by kGrow of the cube's edge (within
// the cube of that edge at `corner`) along each axis on which the points spread, and padded
// for round-off.
void setBox(ShadingRegion& r, glm::vec3 lo, glm::vec3 hi, float edge, glm::vec3 corner) {
  for (int a = 0; a < 3; ++a) {
    if (hi[a] - lo[a] > 0.02f * edge) {
      lo[a] = std::max(lo[a] - kGrow * edge, std::min(lo[a], corner[a]));
      hi[a] = std::min(hi[a] + kGrow * edge, std::max(hi[a], corner[a] + edge));
    }
    const float pad = 1e-3f * edge + 1e-6f * std::max(std::abs(lo[a]), std::abs(hi[a]));
    lo[a] -= pad;
    hi[a] += pad;
  }
  r.pMin = lo;
  r.pMax = hi;
}

}  // namespace

std::uint64_t CellCuts::keyOf(glm::vec3 p, glm::vec3 n, int level) const {
  std::uint64_t key = std::uint64_t(level) << kLevelShift | std::uint64_t(bucketOf(n));
  const float edge = size_ / float(1 << level);
  for (int a = 0; a < 3; ++a) {
    const float q = std::floor(p[a] / edge);
    const std::int64_t c = std::isfinite(q) ? std::int64_t(std::clamp(q, -1e9f, 1e9f)) : 0;
    key |= (std::uint64_t(c + kCoordOrigin) & kCoordMask) << coordShift(a);
  }
  return key;
}

float CellCuts::edgeOf(std::uint64_t key) const {
  return size_ / float(1 << int(key >> kLevelShift));
}

glm::vec3 CellCuts::cornerOf(std::uint64_t key) const {
  glm::vec3 corner;
  for (int a = 0; a < 3; ++a) {
    const std::int64_t c = std::int64_t((key >> coordShift(a)) & kCoordMask) - kCoordOrigin;
    corner[a] = float(c) * edgeOf(key);
  }
  return corner;
}

void CellCuts::clear() {
  index_.clear();
  cells_.clear();
  keys_.clear();
  words_ = 0;
}

void CellCuts::dropUnused() {
  std::vector<Cell> cells;
  std::vector<std::uint64_t> keys;
  index_.clear();
  words_ = 0;
  for (std::size_t c = 0; c < cells_.size(); ++c) {
    if (cells_[c].lastUsed < frame_ - 1) continue;
    index_.emplace(keys_[c], int(cells.size()));
    words_ += cells_[c].entries.size();
    cells.push_back(std::move(cells_[c]));
    keys.push_back(keys_[c]);
  }
  cells_ = std::move(cells);
  keys_ = std::move(keys);
}

std::vector<int> CellCuts::grow(const GBufferPixels& px, const std::vector<int>& cellOfPixel,
                                const std::vector<std::uint8_t>& outside) {
  struct Growth {
    glm::vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
    glm::vec3 normals{0.0f};
    float lowest = 1.0f;  // smallest cosine to the new axis
  };
  std::vector<int> growthOf(cells_.size(), -1), grown;
  std::vector<Growth> growth;
  for (std::size_t i = 0; i < outside.size(); ++i) {
    if (!outside[i]) continue;
    const int c = cellOfPixel[i];
    if (growthOf[std::size_t(c)] < 0) {
      growthOf[std::size_t(c)] = int(growth.size());
      growth.emplace_back();
      grown.push_back(c);
    }
    Growth& g = growth[std::size_t(growthOf[std::size_t(c)])];
    const glm::vec3 p = positionAt(px, i);
    g.lo = glm::min(g.lo, p);
    g.hi = glm::max(g.hi, p);
    g.normals += unitNormalAt(px, i);
  }
  // The new cones' axes: the old axis and the new normals' mean, halfway; the cone then holds
  // the old one and every new normal.
  for (std::size_t k = 0; k < grown.size(); ++k) {
    Cell& cell = cells_[std::size_t(grown[k])];
    Growth& g = growth[k];
    // Normals that cancel out leave no axis; any will do, the spread below covers them.
    glm::vec3 axis = glm::dot(g.normals, g.normals) > 1e-12f ? glm::normalize(g.normals)
                                                             : glm::vec3(0.0f, 0.0f, 1.0f);
    if (!cell.empty) {
      const glm::vec3 mid = cell.region.axis + axis;
      axis = glm::dot(mid, mid) > 1e-12f ? glm::normalize(mid) : cell.region.axis;
      const float c = std::clamp(glm::dot(axis, cell.region.axis), -1.0f, 1.0f);
      const float angle = std::acos(c) + std::acos(std::clamp(cell.region.cosSpread, -1.0f, 1.0f));
      g.lowest = angle >= kPi ? -1.0f : std::cos(angle);
    }
    cell.region.axis = axis;
  }
  for (std::size_t i = 0; i < outside.size(); ++i) {
    if (!outside[i]) continue;
    const int c = cellOfPixel[i];
    Growth& g = growth[std::size_t(growthOf[std::size_t(c)])];
    g.lowest =
        std::min(g.lowest, glm::dot(unitNormalAt(px, i), cells_[std::size_t(c)].region.axis));
  }
  for (std::size_t k = 0; k < grown.size(); ++k) {
    Cell& cell = cells_[std::size_t(grown[k])];
    const Growth& g = growth[k];
    ShadingRegion& r = cell.region;
    const float angle = std::acos(std::clamp(g.lowest, -1.0f, 1.0f));
    // A flat surface's normals differ only in their last bits: round-off, as shadingRegion.
    r.cosSpread = angle > 1e-3f ? std::cos(std::min(angle + kConeGrow, kPi))
                                : std::max(g.lowest - 1e-6f, -1.0f);
    r.sinSpread = std::sqrt(std::max(1.0f - r.cosSpread * r.cosSpread, 0.0f));
    glm::vec3 lo = g.lo, hi = g.hi;
    if (!cell.empty) {
      lo = glm::min(lo, r.pMin);
      hi = glm::max(hi, r.pMax);
    }
    const std::uint64_t key = keys_[std::size_t(grown[k])];
    setBox(r, lo, hi, edgeOf(key), cornerOf(key));
    cell.empty = false;
  }
  std::sort(grown.begin(), grown.end());
  return grown;
}

TileCuts CellCuts::cut(const GBufferPixels& px, const CutRule& rule, int threads) {
  TileCuts out;
  const std::size_t n = std::size_t(px.width) * px.height;
  out.cutOfPixel.assign(n, kNoSharedCut);
  if (rule.error != rule_.error || rule.total != rule_.total || rule.maxCut != rule_.maxCut) {
    clear();
    rule_ = rule;
  }
  if (words_ > maxWords_) dropUnused();
  if (size_ <= 0.0f) size_ = cellSizeOf(px);
  frameCells_.clear();
  if (!(size_ > 0.0f) || !std::isfinite(size_)) {
    size_ = 0.0f;  // nothing on screen to size cells by: every pixel cuts for itself
    return out;
  }

  // Level by level: each pending pixel's cell, whether the cell's region holds it, then the
  // cuts of the cells that are new or grew. A full cell below the last level splits: its
  // pixels go on to the next level's cells.
  std::vector<int> cellOfPixel(n, -1), grownAll;
  std::vector<std::uint8_t> outside(n, 0);
  std::vector<std::size_t> pending, later;
  for (std::size_t i = 0; i < n; ++i) {
    // Specular pixels' lobes depend on the view, which moves: they take this frame's
    // squares' cuts (frameCuts).
    if (sharesCuts(px, i) && !isSpecular(px, i) &&
        glm::dot(normalAt(px, i), normalAt(px, i)) > 0.0f)
      pending.push_back(i);
  }
  for (int level = 0; level <= kMaxCellLevel && !pending.empty(); ++level) {
    std::uint64_t lastKey = ~std::uint64_t(0);
    int last = -1;
    later.clear();
    for (const std::size_t i : pending) {
      const glm::vec3 p = positionAt(px, i), n = unitNormalAt(px, i);
      const std::uint64_t key = keyOf(p, n, level);
      if (key != lastKey) {
        const auto [it, added] = index_.try_emplace(key, int(cells_.size()));
        if (added) {
          cells_.emplace_back();
          keys_.push_back(key);
        }
        lastKey = key;
        last = it->second;
        cells_[std::size_t(last)].lastUsed = frame_;
      }
      const Cell& cell = cells_[std::size_t(last)];
      if (cell.split) {
        later.push_back(i);
        continue;
      }
      cellOfPixel[i] = last;
      outside[i] = cell.empty || !holds(cell.region, p, n);
    }
    const std::vector<int> grown = grow(px, cellOfPixel, outside);
    for (const std::size_t i : pending) outside[i] = 0;
    out.work[std::size_t(CutKind::Cell)].add(cutCells(grown, rule, threads, level));
    grownAll.insert(grownAll.end(), grown.begin(), grown.end());
    for (const std::size_t i : pending) {
      const int c = cellOfPixel[i];
      if (c >= 0 && cells_[std::size_t(c)].split) {
        cellOfPixel[i] = -1;
        later.push_back(i);
      }
    }
    std::sort(later.begin(), later.end());
    pending.swap(later);
  }
  frameCuts(px, rule, threads, cellOfPixel, grownAll, out);
  return out;
}

CutWork CellCuts::cutCells(const std::vector<int>& grown, const CutRule& rule, int threads,
                           int level) {
  // Cells split (or fall back to the frame's squares) only where their cut fills up, or past
  // half of it still far from the rule (cut_region::kHopeless), under either rule; the
  // frame's squares split under the node rule past splitCut (kSplitCut says why). A square's
  // quarters are cut for one frame, while a cell keeps its cut, and the frame that splits it
  // finds the cuts of its eight cells, and of theirs, at once (docs/lightcuts.md measures
  // both).
  CutRule cellRule = rule;
  cellRule.shareFull = false;
  const int workers = std::clamp(threads, 1, std::max(int(grown.size()), 1));
  std::vector<CutWork> made(static_cast<std::size_t>(workers));
  auto work = [&](int t) {
    CutWorkspace workspace;
    for (std::size_t k = std::size_t(t); k < grown.size(); k += std::size_t(workers)) {
      Cell& cell = cells_[std::size_t(grown[k])];
      cell.entries.clear();
      cell.cut = cutter_.cutRegion(workspace, cell.region, cellRule, true, cell.entries);
      cell.perPixel = cell.cut.perPixel;
      cell.split = cell.perPixel && level < kMaxCellLevel;
      if (cell.perPixel) cell.entries.clear();
      cell.entries.shrink_to_fit();
      made[std::size_t(t)].add(cell.cut.bounds, cell.perPixel);
    }
  };
  for (const int c : grown) words_ -= cells_[std::size_t(c)].entries.size();
  onThreads(workers, work);
  for (const int c : grown) words_ += cells_[std::size_t(c)].entries.size();
  CutWork sum;
  for (const CutWork& w : made) sum.add(w);
  return sum;
}

void CellCuts::frameCuts(const GBufferPixels& px, const CutRule& rule, int threads,
                         const std::vector<int>& cellOfPixel, const std::vector<int>& grownAll,
                         TileCuts& out) {
  const std::size_t n = cellOfPixel.size();
  // The frame's cuts: its cells' in the order the pixels first use them, then, for the
  // pixels of cells whose cut is full and for specular pixels, squares' cuts as
  // TileCutter::cut finds them (split by surface and into quarters as needed), this frame
  // only.
  std::vector<std::uint8_t> made(cells_.size(), 0), full(n, 0);
  for (const int c : grownAll) made[std::size_t(c)] = 1;
  std::vector<int> frameCut(cells_.size(), -2);
  bool anyFull = false;
  for (std::size_t i = 0; i < n; ++i) {
    const int c = cellOfPixel[i];
    if (c < 0) {
      if (sharesCuts(px, i) && isSpecular(px, i)) full[i] = 1, anyFull = true;
      continue;
    }
    int& f = frameCut[std::size_t(c)];
    if (f == -2) {
      const Cell& cell = cells_[std::size_t(c)];
      if (!made[std::size_t(c)]) ++out.kept;
      f = cell.perPixel ? -1 : int(frameCells_.size());
      if (f >= 0) frameCells_.push_back(c);
    }
    if (f >= 0) {
      out.cutOfPixel[i] = std::uint32_t(f);
    } else {
      full[i] = 1;
      anyFull = true;
    }
  }
  TileCuts squares = anyFull ? cutter_.cut(px, kFallbackTile, rule, threads, &full) : TileCuts{};
  const std::size_t cuts = frameCells_.size() + std::size_t(squares.sharedCuts);
  std::size_t cellTexels = 0;
  for (const int c : frameCells_) cellTexels += cells_[std::size_t(c)].entries.size() / 4;
  ++frame_;
  // The head: every header, then the cells' entries; the squares' entries follow as they
  // are (their head holds only their headers).
  const std::size_t squareHeads = 2 * std::size_t(squares.sharedCuts);
  std::vector<std::uint32_t>& head = out.texels.head;
  head.assign((2 * cuts + cellTexels) * 4, 0u);
  std::size_t next = 2 * cuts;
  for (std::size_t u = 0; u < frameCells_.size(); ++u) {
    const Cell& cell = cells_[std::size_t(frameCells_[u])];
    cell.cut.writeTexels(u, cell.entries.data(), cell.entries.size() / 4, next, head.data());
  }
  // The squares' headers, their first entries moved past the cells' entries.
  std::uint32_t* h = head.data() + 8 * frameCells_.size();
  for (std::size_t k = 0; k < std::size_t(squares.sharedCuts); ++k, h += 8) {
    std::copy_n(squares.texels.head.data() + 8 * k, 8, h);
    h[0] = std::uint32_t(h[0] - squareHeads + next);
  }
  out.texels.takePieces(std::move(squares.texels));
  for (std::size_t i = 0; i < n; ++i) {
    if (squares.cutOfPixel.empty() || squares.cutOfPixel[i] == kNoSharedCut) continue;
    out.cutOfPixel[i] = std::uint32_t(frameCells_.size()) + squares.cutOfPixel[i];
  }
  out.sharedCuts = int(cuts);
  out.exactCuts = squares.exactCuts;
  out.perPixelGroups = squares.perPixelGroups;
  out.surfaceSplits = squares.surfaceSplits;
  addWorks(out.work, squares.work);
  out.made = int(grownAll.size()) + squares.made;
}

}  // namespace manylight
