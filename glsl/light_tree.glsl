// Reads light tree nodes; the layout is documented in bake/light_tree_layout.h.
uniform usamplerBuffer uNodes;
uniform ivec3 uTreeBase;    // first texel of the directional, point and spot trees
uniform ivec3 uTreeLeaves;  // their leaf counts (powers of two); 0: no such tree

struct Node {
  vec3 boxMin;
  int representative;  // light texture slot; −1: empty
  vec3 boxMax;
  float invRange2;     // 1/(largest range)², 0: some light has no range
  vec3 intensity;
  float w2;            // spot: cos Θ; point: 1/(smallest range)²
  vec3 axis;           // spot only
  float sinTheta;      // spot only
};

Node fetchNode(int tree, int i) {
  int t = uTreeBase[tree] + (tree == 2 ? 4 : 3) * i;
  uvec4 a = texelFetch(uNodes, t);
  uvec4 b = texelFetch(uNodes, t + 1);
  uvec4 c = texelFetch(uNodes, t + 2);
  Node n;
  n.boxMin = uintBitsToFloat(a.xyz);
  n.representative = int(a.w);
  n.boxMax = uintBitsToFloat(b.xyz);
  n.invRange2 = uintBitsToFloat(b.w);
  n.intensity = uintBitsToFloat(c.xyz);
  n.w2 = uintBitsToFloat(c.w);
  n.axis = vec3(0.0);
  n.sinTheta = 0.0;
  if (tree == 2) {
    uvec4 d = texelFetch(uNodes, t + 3);
    n.axis = uintBitsToFloat(d.xyz);
    n.sinTheta = uintBitsToFloat(d.w);
  }
  return n;
}
