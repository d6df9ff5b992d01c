
// The linkless octree of bake/linkless_octree.h: descends the per-level perfect hashes to
// the leaf holding a point, and reads the light index list.
uniform usamplerBuffer uOctreeNodes;    // RG32UI: per level, its hash table
uniform usamplerBuffer uOctreeOffsets;  // RGBA16UI: per level, its offset table
uniform usamplerBuffer uOctreeIndices;  // R32UI: the global list, then the leaves' lists
uniform vec3 uOctreeOrigin;
uniform float uOctreeInvLeaf;  // 1 / the deepest level's cell edge
uniform int uOctreeLevels;
uniform ivec3 uLevelDims[kMaxOctreeLevels];
uniform int uLevelNodeBase[kMaxOctreeLevels];
uniform int uLevelOffsetBase[kMaxOctreeLevels];
uniform int uLevelOffsetCount[kMaxOctreeLevels];

// The node texel of `key` at `level`.
uvec2 octreeNode(int level, uvec3 key) {
  uint slot = spatialHashSlot(key, uLevelDims[level], uLevelOffsetCount[level], uOctreeOffsets,
                              uLevelOffsetBase[level]);
  return texelFetch(uOctreeNodes, uLevelNodeBase[level] + int(slot)).xy;
}

// The leaf list at p: x its first index, y its length (0 where no ranged light reaches). A
// point outside the root takes the nearest cell's list, which is exact: no ranged light
// reaches it (the root holds every support met by geometry).
uvec2 octreeList(vec3 p) {
  int deepest = uOctreeLevels - 1;
  float cells = float(1 << deepest);
  uvec3 cell = uvec3(clamp(floor((p - uOctreeOrigin) * uOctreeInvLeaf), vec3(0.0), vec3(cells - 1.0)));
  uvec2 node = octreeNode(0, uvec3(0u));
  for (int level = 1; level <= deepest; ++level) {
    if ((node.y & kOctreeLeafBit) != 0u) break;
    uvec3 key = cell >> uint(deepest - level);
    uvec3 c = key & 1u;
    if ((node.y & (1u << (c.x + 2u * c.y + 4u * c.z))) == 0u) return uvec2(0u);
    node = octreeNode(level, key);
  }
  return uvec2(node.x, node.y & ~kOctreeLeafBit);
}
