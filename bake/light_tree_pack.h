#pragma once
// Packs light trees into the node texture (see bake/light_tree_layout.h).
#include <cstdint>
#include <vector>

#include "bake/light_tree.h"
#include "bake/node_colour.h"
#include "base/uninitialised.h"

namespace manylight {

struct PackedTrees {
  UninitialisedVector<std::uint32_t> words;  // a whole number of texels (4 words each)
  // Per light type (0 directional, 1 point, 2 spot): first word and leaf count (0: no tree).
  int base[3] = {0, 0, 0};
  int leaves[3] = {0, 0, 0};
  NodeColourCoder colour;  // how word 8 of each node codes its intensity, and the error
};

// Throws BakeError when the forest needs more than 2^31 words.
PackedTrees packLightTrees(const std::vector<LightTree>& trees,
                           NodeColourCoding coding = NodeColourCoding::Rgb9e5);

// The bake of a render's lights: their trees built with `options`, then packed. Whoever
// prepares a render calls it (or loads a baked file's trees); methods only upload.
PackedTrees bakeLightTrees(const std::vector<Light>& lights, const TreeOptions& options = {});

}  // namespace manylight
