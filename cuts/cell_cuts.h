#pragma once
// Shared cuts kept from frame to frame of a playback, per cell of the scene instead of per
// square of the screen (cuts/tile_cuts.h). No GL here.
//
// A square's shared cut holds for the shading points of that square in one frame: when the
// camera moves, every square sees other points and the CPU finds every cut again, most of a
// frame's time with many lights. The scene does not move, though. So in playback
// the pixels are grouped by where they are in the scene: a cell is a cube of space (edge
// cellSize(), about kCellPixels pixels of the first frame) and a bucket of normal directions
// (an octahedral map of kNormalBuckets² buckets, each about 8° wide), and its cut holds for
// a region (cuts/pixel_groups.h: a box of positions, a cone of normals) that contains every
// shading point the cell has had. A frame whose pixels lie in their cells' regions reuses the
// cuts as they are. A pixel outside its cell's region grows the region, and the cell's cut is
// found anew: the box joins the new points and, along an axis on which the points spread,
// widens by kGrow of the cube's edge (within the cube; a plane stays as thin as it is), and a
// cone that spreads widens by kConeGrow radians more than it must, so that regions soon stop
// growing. At kGrow = 1 the box spans the cube along such an axis at once: in a 90° orbit of
// the 65,536-light rooms, 26–38% fewer cuts are found than at ¼, with the same errors against
// the reference (docs/lightcuts.md). A cell's cut takes up to the rule's maximum (the
// finest squares' limit, not splitCut: CellCuts::cutCells says why), and a cell whose cut is
// full splits into eight cubes of half its edge, for good (kMaxCellLevel). Each pixel checks
// the rule for itself, with bounds that hold over its cell's region, which holds the pixel:
// the total rule's guarantee is kept.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "cuts/pixel_groups.h"
#include "cuts/tile_cuts.h"

namespace manylight {

inline constexpr int kCellPixels = 12;
// A cell whose cut is full is split into eight cubes of half its edge (each with its buckets),
// and those again, kMaxCellLevel times in all; the split is kept with the cells. The pixels of
// a full cell at the last level take cuts of squares of kFallbackTile pixels, as render's
// frames do (cuts/tile_cuts.h), found for that frame only.
inline constexpr int kMaxCellLevel = 2;
inline constexpr int kFallbackTile = 16;
inline constexpr int kNormalBuckets = 16;
inline constexpr float kGrow = 1.0f;
inline constexpr float kConeGrow = 0.05f;
// The kept cuts' entries stop at this many words (64 MiB): past it, the next frame starts
// without the cells the last frame did not use, so that a long playback's memory stays
// bounded (by this, or by one frame's cells when they alone hold more).
inline constexpr std::size_t kMaxKeptWords = std::size_t(16) << 20;

class CellCuts {
 public:
  // Cuts through `cutter`'s trees, which must outlive this; keeps about `maxWords` words of
  // entries at most (kMaxKeptWords).
  explicit CellCuts(const TileCutter& cutter, std::size_t maxWords = kMaxKeptWords)
      : cutter_(cutter), maxWords_(maxWords) {}

  // This frame's cuts, as TileCutter::cut gives them: those of its cells, found for cells that
  // are new or grew, on `threads` threads. TileCuts::made counts those cells (a split one
  // too) and the squares' cuts; TileCuts::kept, the cells whose cut was kept. The first frame fixes
  // the cells' size. Another rule than the last frame's starts over.
  TileCuts cut(const GBufferPixels& pixels, const CutRule& rule, int threads);

  float cellSize() const { return size_; }
  // Cells kept, used by the last frame or not.
  std::size_t cellCount() const { return cells_.size(); }
  // The last frame's cells' cuts (the squares' cuts are numbered after them), and the region
  // that the cut numbered `k` (cutOfPixel) holds for.
  std::size_t frameCellCuts() const { return frameCells_.size(); }
  const ShadingRegion& region(std::size_t k) const {
    return cells_[std::size_t(frameCells_[k])].region;
  }

 private:
  struct Cell {
    ShadingRegion region{};
    bool empty = true;      // no region yet
    bool perPixel = false;  // its cut is full
    bool split = false;     // full, and its pixels go to the cells of the next level
    RegionCut cut;
    std::vector<std::uint32_t> entries;
    long long lastUsed = -1;  // the last frame that used it
  };
  // The cell at `level` of position p and unit normal n: its cube (of edge cellSize() /
  // 2^level) and the normal's bucket.
  std::uint64_t keyOf(glm::vec3 p, glm::vec3 n, int level) const;
  // The edge of a cell's cube, and its corner of least coordinates.
  float edgeOf(std::uint64_t key) const;
  glm::vec3 cornerOf(std::uint64_t key) const;
  // Grows the region of each cell that has a pixel `outside` it (cellOfPixel names the
  // pixels' cells) to hold those pixels; returns those cells, in order.
  std::vector<int> grow(const GBufferPixels& px, const std::vector<int>& cellOfPixel,
                        const std::vector<std::uint8_t>& outside);
  // Finds the cuts of the cells `grown`, at `level`, on `threads` threads; returns how many,
  // how many filled up, and the node bounds evaluated.
  CutWork cutCells(const std::vector<int>& grown, const CutRule& rule, int threads, int level);
  // The frame's cuts into `out`: its cells' in the order the pixels first use them (cellOfPixel;
  // grownAll, the cells cut this frame), then squares' cuts for the pixels of full cells.
  void frameCuts(const GBufferPixels& px, const CutRule& rule, int threads,
                 const std::vector<int>& cellOfPixel, const std::vector<int>& grownAll,
                 TileCuts& out);
  void clear();
  // Drops the cells the last frame did not use.
  void dropUnused();

  const TileCutter& cutter_;
  std::size_t maxWords_;
  float size_ = 0.0f;
  CutRule rule_;
  std::unordered_map<std::uint64_t, int> index_;  // cell of a key
  std::vector<Cell> cells_;
  std::vector<std::uint64_t> keys_;  // key of a cell
  std::size_t words_ = 0;            // entry words the cells hold
  long long frame_ = 0;              // frames cut
  std::vector<int> frameCells_;      // the cell of each of the last frame's cells' cuts
};

}  // namespace manylight
