// Reads light tree nodes, and bounds the geometry of a node's box as seen from a point; the
// layout is documented in bake/light_tree_layout.h, the colour codings in
// bake/node_colour.h, the bounds in glsl/lightcuts_walk.glsl.
uniform usamplerBuffer uNodes;
uniform ivec3 uTreeBase;    // first word of the directional, point and spot trees
uniform ivec3 uTreeLeaves;  // their leaf counts (powers of two); 0: no such tree
#ifdef FITTED_COLOUR
uniform vec2 uColourFit;     // A, γ of the fitted power law
#else
uniform float uColourScale;  // RGB9_E5: stored = intensity / scale
#endif

struct Node {
  vec3 boxMin;
  int representative;  // light texture slot; −1: empty
  vec3 boxMax;
  float invRange2;     // 1/(largest range)², 0: some light has no range
  vec3 intensity;      // internal nodes: decoded, within the coding's slack; leaves: exact
  float w2;            // spot: cos Θ; point: 1/(smallest range)²
  vec3 axis;           // spot only
  float sinTheta;      // spot only
};

vec3 decodeIntensity(uint w) {
#ifdef FITTED_COLOUR
  vec3 code = vec3(uvec3(w, w >> 8u, w >> 16u) & uvec3(255u));
  // pow(0, γ) is left undefined by GLSL: code 0 is 0 by the coding's definition.
  vec3 c = mix(vec3(0.0), pow(max(code, vec3(1.0)), vec3(uColourFit.y)), greaterThan(code, vec3(0.0)));
  return c * (exp2(float(int(w >> 24u) - 128)) * uColourFit.x);  // 2^−128 is below float's normal range
#else
  vec3 m = vec3(uvec3(w, w >> 9u, w >> 18u) & uvec3(511u));
  // 2^(e − 15 − 9) built from its bits (e − 24 + 127 in the float's exponent): exact, and
  // cheaper than exp2 on llvmpipe.
  return m * (uintBitsToFloat(((w >> 27u) + 103u) << 23u) * uColourScale);
#endif
}

Node fetchNode(int tree, int i) {
  int word = uTreeBase[tree] + (tree == 2 ? kSpotNodeWords : kNodeWords) * i;
  int t = word >> 2;
  uvec4 a = texelFetch(uNodes, t);
  uvec4 b = texelFetch(uNodes, t + 1);
  uvec4 c = texelFetch(uNodes, t + 2);
  if ((word & 2) != 0) {  // the node starts at word 2 of its first texel
    a = uvec4(a.zw, b.xy);
    b = uvec4(b.zw, c.xy);
    c.xy = c.zw;
  }
  Node n;
  n.boxMin = uintBitsToFloat(a.xyz);
  n.representative = int(a.w);
  n.invRange2 = uintBitsToFloat(b.w);
  if (i < uTreeLeaves[tree] - 1) {
    n.boxMax = uintBitsToFloat(b.xyz);
    n.intensity = decodeIntensity(c.x);
  } else {  // a leaf: a point box, and its light's exact intensity
    n.boxMax = n.boxMin;
    n.intensity = uintBitsToFloat(b.xyz);
  }
  n.w2 = uintBitsToFloat(c.y);
  n.axis = vec3(0.0);
  n.sinTheta = 0.0;
  if (tree == 2) {
    uvec4 d = texelFetch(uNodes, t + 3);
    uvec4 spot = (word & 2) != 0 ? d : uvec4(c.zw, d.xy);  // words 10–13
    n.axis = uintBitsToFloat(spot.xyz);
    n.sinTheta = uintBitsToFloat(spot.w);
  }
  return n;
}

// Largest of u·(x − p)/|x − p| over the box, bounded through the largest numerator over the
// nearest distance dMin.
float cosineUpper(vec3 u, vec3 p, Node n, float dMin) {
  vec3 m = max(u * (n.boxMin - p), u * (n.boxMax - p));
  float num = m.x + m.y + m.z;
  if (num <= 0.0) return 0.0;
  return dMin > 0.0 ? min(num / dMin, 1.0) : 1.0;
}

// Smallest cosine over the box: the smallest numerator over the farthest distance dMax.
float cosineLower(vec3 u, vec3 p, Node n, float dMax) {
  vec3 m = min(u * (n.boxMin - p), u * (n.boxMax - p));
  float num = m.x + m.y + m.z;
  return num > 0.0 ? min(num / dMax, 1.0) : 0.0;
}

// Tighter where the box is small and far: the cone around the direction u·… to the box's
// bounding sphere (centre c, radius r). Returns cos(max(θ − α, 0)) in .x and
// cos(min(θ + α, π/2))⁺ in .y, θ the angle between u and the centre, α the sphere's angular
// radius; (1, 0) when p is inside the sphere.
vec2 sphereCosines(vec3 u, vec3 p, Node n) {
  vec3 c = 0.5 * (n.boxMin + n.boxMax) - p;
  float r2 = 0.25 * dot(n.boxMax - n.boxMin, n.boxMax - n.boxMin);
  float d2 = dot(c, c);
  if (d2 <= r2) return vec2(1.0, 0.0);
  float cosT = dot(u, c) * inversesqrt(d2);
  float sinT = sqrt(max(1.0 - cosT * cosT, 0.0));
  float sinA = sqrt(r2 / d2);
  float cosA = sqrt(1.0 - sinA * sinA);
  float upper = cosT >= cosA ? 1.0 : cosT * cosA + sinT * sinA;
  float lower = max(cosT * cosA - sinT * sinA, 0.0);
  return vec2(upper, lower);
}

// The range window clamp(1 − (d²/range²)², 0, 1) (scene/shading_model.h).
float window(float d2, float invRange2) {
  float x = d2 * invRange2;
  return clamp(1.0 - x * x, 0.0, 1.0);
}

// Whether some light of spot node n may shine on p: some direction from its box to p lies
// within Θ of the axis (the box seen as its bounding sphere).
bool spotMayReach(Node n, vec3 p) {
  vec3 c = 0.5 * (n.boxMin + n.boxMax);
  float r = 0.5 * length(n.boxMax - n.boxMin);
  vec3 toP = p - c;
  float d = length(toP);
  if (d <= r) return true;
  float sinA = r / d;
  float cosA = sqrt(max(1.0 - sinA * sinA, 0.0));
  float cosT = n.w2;
  float sinSum = n.sinTheta * cosA + cosT * sinA;  // sin(Θ + α)
  if (sinSum < 0.0) return true;                   // Θ + α beyond π
  float cosSum = cosT * cosA - n.sinTheta * sinA;  // cos(Θ + α)
  return dot(n.axis, toP) / d >= cosSum;
}
