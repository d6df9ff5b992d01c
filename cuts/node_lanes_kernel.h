// The node bounds of cuts/node_lanes.h over lanes of type V, included twice by
// cuts/node_lanes.cpp: V = float, and V = __m256 under GCC's AVX2 target. It expects V,
// splat(float) → V, load(const float*) → V, store(float*, V), and vsqrt, vabs, vmin, vmax
// with std::min and std::max's semantics ((b < a) ? b : a and (a < b) ? b : a), and on the
// bits of floats: vexponent (a normal float's unbiased exponent, as a float), vmantissa (its
// mantissa with exponent 0, in [1, 2)) and vexp2Integer (2^k for integral k in [−126, 127]). The
// bounds are those glsl/lightcuts_walk.glsl's nodeBounds puts on a node at one point (a spot
// node's cone factor bounded above and below: spotConeLanes, its spotConeFactor), over a
// region of shading points instead (a box of positions, a cone of normals), and for specular
// lobes with a lower bound too, which the walk takes as 0 (as RegionTerms::walkBounds does).
// Every branch is taken by every lane and its results selected, so eight lanes and one give
// the same bits. No include guard: included once per lane type.

// libstdc++'s std::clamp: (v < lo) ? lo : (hi < v) ? hi : v.
MANYLIGHT_INLINE inline V clampLanes(V v, float lo, float hi) {
  return v < lo ? splat(lo) : (hi < v ? splat(hi) : v);
}

// The range window clamp(1 − (d²/range²)², 0, 1) (scene/shading_model.h): non-increasing in
// d² and in 1/range², so nodeBoundLanes' window(d⁻)/d⁻² with the largest range bounds a
// node's lights from above and window(d⁺)/d⁺² with the smallest range from below.
MANYLIGHT_INLINE inline V windowLanes(V d2, V invRange2) {
  const V x = d2 * invRange2;
  return clampLanes(1.0f - x * x, 0.0f, 1.0f);
}

MANYLIGHT_INLINE inline V maxOfLanes(const V v[3]) { return vmax(v[0], vmax(v[1], v[2])); }

using Mask = decltype(splat(0.0f) < splat(0.0f));

// The box [dMin, dMax] of vectors from the region's points to a node's box or a light (for
// a directional node: its directions), with its nearest and farthest squared lengths.
struct VectorBox {
  V dMin[3], dMax[3];
  V d2Min, d2Max;
};
MANYLIGHT_INLINE inline VectorBox vectorBox(const V dMin[3], const V dMax[3]) {
  const V zero = splat(0.0f);
  VectorBox b;
  V nearest[3], farthest[3];
  for (int c = 0; c < 3; ++c) {
    b.dMin[c] = dMin[c];
    b.dMax[c] = dMax[c];
    nearest[c] = vmin(vmax(zero, dMin[c]), dMax[c]);
    farthest[c] = vmax(vabs(dMin[c]), vabs(dMax[c]));
  }
  b.d2Min = nearest[0] * nearest[0] + nearest[1] * nearest[1] + nearest[2] * nearest[2];
  b.d2Max = farthest[0] * farthest[0] + farthest[1] * farthest[1] + farthest[2] * farthest[2];
  return b;
}

// The bounding sphere of a VectorBox seen along `axis`: ψ (cosT, sinT) the angle from the
// axis to its centre, α (sinA, cosA) its angular radius; `inside` where it holds the origin.
// cos(ψ − α) is then the largest cosine to the axis over the sphere (where ψ ≥ α) and
// cos(ψ + α) the smallest.
struct SphereAngles {
  V cosT, sinT, sinA, cosA;
  Mask inside;
};
MANYLIGHT_INLINE inline SphereAngles sphereAngles(glm::vec3 axis, const VectorBox& b) {
  V centre[3], extent[3];
  for (int c = 0; c < 3; ++c) {
    centre[c] = 0.5f * (b.dMin[c] + b.dMax[c]);
    extent[c] = b.dMax[c] - b.dMin[c];
  }
  const V r2 = 0.25f * (extent[0] * extent[0] + extent[1] * extent[1] + extent[2] * extent[2]);
  const V d2Centre = centre[0] * centre[0] + centre[1] * centre[1] + centre[2] * centre[2];
  SphereAngles s;
  s.inside = d2Centre <= r2;
  s.cosT = (axis.x * centre[0] + axis.y * centre[1] + axis.z * centre[2]) / vsqrt(d2Centre);
  s.sinT = vsqrt(vmax(1.0f - s.cosT * s.cosT, splat(0.0f)));
  s.sinA = vsqrt(r2 / d2Centre);
  s.cosA = vsqrt(1.0f - s.sinA * s.sinA);
  return s;
}
// cos(ψ + α)⁺, 0 from inside: the smallest cosine over the sphere.
MANYLIGHT_INLINE inline V sphereLower(const SphereAngles& s) {
  const V zero = splat(0.0f);
  return s.inside ? zero : vmax(s.cosT * s.cosA - s.sinT * s.sinA, zero);
}

// The smallest cosine to `axis` over the box itself: (min of axis · v) / (farthest length),
// 0 where some vector of the box is at 90° or more.
MANYLIGHT_INLINE inline V boxLower(glm::vec3 axis, const VectorBox& b) {
  V m[3];
  for (int c = 0; c < 3; ++c) m[c] = vmin(axis[c] * b.dMin[c], axis[c] * b.dMax[c]);
  const V num = m[0] + m[1] + m[2];
  return num > 0.0f ? vmin(num / vsqrt(b.d2Max), splat(1.0f)) : splat(0.0f);
}

// cos(min(θ + γ, π/2))⁺ for θ = acos(c), γ the spread of the region's normals about their
// axis: the smallest cosine to any of them.
MANYLIGHT_INLINE inline V widenDown(V c, const ShadingRegion& g) {
  if (g.cosSpread <= 0.0f) return splat(0.0f);
  c = clampLanes(c, 0.0f, 1.0f);
  return vmax(c * g.cosSpread - vsqrt(1.0f - c * c) * g.sinSpread, splat(0.0f));
}

constexpr float kMinDistanceSquared = 1e-12f;  // glsl/shading.glsl

// The representative's shading at the region's centre per unit albedo and intensity (a
// spot's with its cone factor, as the shader sums it), unless its parent's is known
// (NodeLanes::knownUnit), for lanes [l, l + width of V).
MANYLIGHT_INLINE inline V unitLanes(const RegionTerms& r, const NodeLanes& in, int l,
                                    Mask directional, Mask spot) {
  constexpr float kPi = 3.14159265358979323846f;
  const ShadingRegion& g = r.g;
  const V zero = splat(0.0f);
  V rep[3], repAxis[3];
  for (int c = 0; c < 3; ++c) {
    rep[c] = load(in.repPoint[c] + l);
    repAxis[c] = load(in.repAxis[c] + l);
  }
  const V towards = vmax(g.axis.x * rep[0] + g.axis.y * rep[1] + g.axis.z * rep[2], zero);
  V v[3], dir[3];
  for (int c = 0; c < 3; ++c) v[c] = rep[c] - r.centre[c];
  const V d2Rep = vmax(v[0] * v[0] + v[1] * v[1] + v[2] * v[2], splat(kMinDistanceSquared));
  const V length = vsqrt(d2Rep);
  for (int c = 0; c < 3; ++c) dir[c] = v[c] / length;
  V atPoint = vmax(g.axis.x * dir[0] + g.axis.y * dir[1] + g.axis.z * dir[2], zero) *
              windowLanes(d2Rep, load(in.repInvRange2 + l)) / d2Rep;
  const V coneCos = repAxis[0] * -dir[0] + repAxis[1] * -dir[1] + repAxis[2] * -dir[2];
  const V t =
      clampLanes(coneCos * load(in.repConeScale + l) + load(in.repConeOffset + l), 0.0f, 1.0f);
  atPoint = spot ? atPoint * (t * t * (3.0f - 2.0f * t)) : atPoint;
  const V fresh = (directional ? towards : atPoint) / kPi;
  return load(in.knownUnit + l) != 0.0f ? load(in.unit + l) : fresh;
}

#include "cuts/lane_powers.h"

// The largest cosine to the region's normals over the box of vectors `box` (dMin…dMax,
// nearest length `dist`) and its bounding sphere: the largest cosine to the axis, widened by
// the spread γ of the normals about it, cos(max(θ − γ, 0)).
MANYLIGHT_INLINE inline V cosUpLanes(const ShadingRegion& g, const V dMin[3], const V dMax[3],
                                     V dist, const SphereAngles& sphere) {
  const V zero = splat(0.0f), one = splat(1.0f);
  V sphereUpper =
      sphere.cosT >= sphere.cosA ? one : sphere.cosT * sphere.cosA + sphere.sinT * sphere.sinA;
  sphereUpper = sphere.inside ? one : sphereUpper;
  V m[3];
  for (int c = 0; c < 3; ++c) m[c] = vmax(g.axis[c] * dMin[c], g.axis[c] * dMax[c]);
  const V num = m[0] + m[1] + m[2];
  const V boxUpper = num <= 0.0f ? zero : (dist > 0.0f ? vmin(num / dist, one) : one);
  V cosUp = one;
  if (g.cosSpread > 0.0f) {
    const V c = clampLanes(vmin(boxUpper, sphereUpper), 0.0f, 1.0f);
    const V s = vsqrt(1.0f - c * c);
    cosUp = s <= g.sinSpread ? one : c * g.cosSpread + s * g.sinSpread;
  }
  return cosUp;
}

#include "cuts/lane_cones.h"

// The vectors from the region to a node (nodeBoundLanes): their box and nearest distance.
struct NodeVectors {
  const V* dMin;
  const V* dMax;
  const VectorBox& box;
  V dist;
};

// Where the region has specular lobes: BoundLanes' lobe terms for lanes [l, l + width of V),
// given which of them the node lights (`lit`), the largest and smallest cosines to the
// normals and the distance terms.
MANYLIGHT_INLINE inline void lobeLanes(const RegionTerms& r, const NodeLanes& in, int l,
                                       const NodeVectors& v, Mask lit, V cosUp, V cosLow, V gUp,
                                       V gLow, BoundLanes& out) {
  const SpecularLobes& lobes = r.g.lobes;
  const V zero = splat(0.0f);
  const VectorBox& box = v.box;
  const V upperScale = lit ? cosUp * gUp : zero;
  store(out.upperScale + l, upperScale);
  const V lowerScale = lit && gLow > 0.0f ? cosLow * gLow : zero;
  store(out.lowerScale + l, lowerScale);
  const SphereAngles mirrorSphere = sphereAngles(r.mirror.axis, box);
  const V cosR = clampLanes(cosUpLanes(r.mirror, v.dMin, v.dMax, v.dist, mirrorSphere), 0.0f, 1.0f);
  const V cosRLow =
      clampLanes(widenDown(vmax(boxLower(r.mirror.axis, box), sphereLower(mirrorSphere)), r.mirror),
                 0.0f, 1.0f);
  store(out.lobeTop + l, upperScale > 0.0f ? powUpperLanes(cosR, lobes.minExponent) : zero);
  const V bottom = lowerScale > 0.0f ? powLowerLanes(cosRLow, lobes.maxExponent) : zero;
  store(out.lobeBottom + l, r.walkBounds ? zero : bottom);
  // The representative's direction from the centre against the mirror axis.
  const auto directional = load(in.tree + l) == 0.0f;
  V towards[3];
  for (int c = 0; c < 3; ++c) {
    const V rep = load(in.repPoint[c] + l);
    towards[c] = directional ? rep : rep - r.centre[c];
  }
  const V length =
      vsqrt(towards[0] * towards[0] + towards[1] * towards[1] + towards[2] * towards[2]);
  const V along = lobes.axis.x * towards[0] + lobes.axis.y * towards[1] + lobes.axis.z * towards[2];
  const V c = length > 0.0f ? along / length : zero;
  store(out.lobeTowards + l, c > 0.0f ? powLanes(c, lobes.meanExponent) : zero);
}

// Lanes [l, l + width of V) of `out`.
MANYLIGHT_INLINE inline void nodeBoundLanes(const RegionTerms& r, const NodeLanes& in, int l,
                                            BoundLanes& out) {
  constexpr float kPi = 3.14159265358979323846f;
  const ShadingRegion& g = r.g;
  const V zero = splat(0.0f), one = splat(1.0f);
  const V tree = load(in.tree + l);
  const auto directional = tree == 0.0f, spot = tree == 2.0f;
  const auto leaf = load(in.leaf + l) != 0.0f;
  V intensity[3];
  for (int c = 0; c < 3; ++c) intensity[c] = load(in.intensity[c] + l);
  const V unit = unitLanes(r, in, l, directional, spot);
  store(out.unit + l, unit);
  for (int c = 0; c < 3; ++c) store(out.estimate[c] + l, intensity[c] * unit);

  // The vectors from the region's points to the node's box (directional: its directions).
  V dMin[3], dMax[3];
  for (int c = 0; c < 3; ++c) {
    const V bMin = load(in.boxMin[c] + l), bMax = load(in.boxMax[c] + l);
    dMin[c] = directional ? bMin : bMin - g.pMax[c];
    dMax[c] = directional ? bMax : bMax - g.pMin[c];
  }
  const VectorBox box = vectorBox(dMin, dMax);
  const V d2Min = box.d2Min, d2Max = box.d2Max;
  const auto touching = !directional && d2Min == 0.0f;  // unbounded
  const V dist = vsqrt(d2Min);

  const SphereAngles sphere = sphereAngles(g.axis, box);
  const V cosUp = cosUpLanes(g, dMin, dMax, dist, sphere);
  const auto lit = cosUp > 0.0f && (!spot || spotReachesLanes(r, in, l));

  // The node's upper (and under the total rule lower) bound per unit albedo; a spot's times
  // its cone factor's bounds.
  const V invRange2 = load(in.invRange2 + l), w2 = load(in.w2 + l);
  const ConeFactor cone = spotConeLanes(r, in, l);
  V gUp =
      directional ? one : windowLanes(d2Min, invRange2) / vmax(d2Min, splat(kMinDistanceSquared));
  gUp = spot ? gUp * cone.up : gUp;
  const V gLow = directional ? one
                 : spot      ? cone.low * windowLanes(d2Max, load(in.lowInvRange2 + l)) /
                              vmax(d2Max, splat(kMinDistanceSquared))
                        : windowLanes(d2Max, w2) / vmax(d2Max, splat(kMinDistanceSquared));
  const V slack = r.slackRate * maxOfLanes(intensity) + r.slackFloor;
  const V upperScale = cosUp * gUp / kPi;
  V upper[3], lower[3] = {zero, zero, zero};
  for (int c = 0; c < 3; ++c) upper[c] = lit ? (intensity[c] + slack) * upperScale : zero;
  const auto unbounded = touching || (lit && !(vabs(maxOfLanes(upper)) <= 3.40282347e+38f));
  // The smallest cosine over the box (or its sphere), narrowed by the normals' spread: the
  // total rule's lower bounds and the lobes' need it.
  const V cosLow =
      r.total || g.lobes.on ? widenDown(vmax(boxLower(g.axis, box), sphereLower(sphere)), g) : zero;
  if (r.total) {
    const V lowerScale = cosLow * gLow / kPi;
    const auto on = lit && gLow > 0.0f;
    for (int c = 0; c < 3; ++c)
      lower[c] = on ? vmax(intensity[c] - slack, zero) * lowerScale : zero;
  }
  if (g.lobes.on) lobeLanes(r, in, l, {dMin, dMax, box, dist}, lit, cosUp, cosLow, gUp, gLow, out);
  store(out.dark + l, !unbounded && maxOfLanes(upper) <= 0.0f ? one : zero);
  V error[3];
  for (int c = 0; c < 3; ++c) error[c] = r.total ? upper[c] - lower[c] : upper[c];
  const V measure = unbounded ? splat(__builtin_inff()) : maxOfLanes(error);
  store(out.measure + l, leaf ? splat(-1.0f) : measure);
  for (int c = 0; c < 3; ++c) store(out.error[c] + l, leaf || unbounded ? zero : error[c]);
}

// A spot's cone over the region: the lowest and highest cosine between its axis and a
// direction from the light to the region's bounding sphere (−1 and 1 from inside it), then
// far_field.h's variation: the smoothstep's values t0, t1 there, its slope and curvature
// where it varies, the largest sine to its axis there; a hard edge where its scale is not
// finite.
struct ConeVariation {
  V scale, t0, t1, slope, curvature, sine;
  Mask varies, hardEdge;
};
MANYLIGHT_INLINE inline ConeVariation coneVariation(const RegionTerms& r, const FoldLanes& in,
                                                    int l, const V rep[3], const V axis[3]) {
  const V zero = splat(0.0f), one = splat(1.0f);
  V w[3];
  for (int c = 0; c < 3; ++c) w[c] = r.centre[c] - rep[c];
  const V d = vsqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  const auto insideCone = d <= r.halfDiagonal;
  const V cosW = (axis[0] * w[0] + axis[1] * w[1] + axis[2] * w[2]) / d;
  const V sinW = vsqrt(vmax(1.0f - cosW * cosW, zero));
  const V sinB = r.halfDiagonal / d, cosB = vsqrt(vmax(1.0f - sinB * sinB, zero));
  V low = sinW * cosB + cosW * sinB < 0.0f ? splat(-1.0f) : cosW * cosB - sinW * sinB;
  V high = cosW >= cosB ? one : cosW * cosB + sinW * sinB;
  low = insideCone ? splat(-1.0f) : low;
  high = insideCone ? one : high;
  ConeVariation v;
  v.scale = load(in.coneScale + l);
  const V offset = load(in.coneOffset + l);
  v.t0 = clampLanes(v.scale * low + offset, 0.0f, 1.0f);
  v.t1 = clampLanes(v.scale * high + offset, 0.0f, 1.0f);
  v.varies = !(v.t1 <= 0.0f || v.t0 >= 1.0f);
  v.slope = v.t0 <= 0.5f && v.t1 >= 0.5f
                ? splat(1.5f)
                : vmax(6.0f * v.t0 * (1.0f - v.t0), 6.0f * v.t1 * (1.0f - v.t1));
  v.curvature = vmax(vabs(6.0f - 12.0f * v.t0), vabs(6.0f - 12.0f * v.t1));
  const V cosine = vmax(low, load(in.repCos + l));
  v.sine = cosine > 0.0f ? vsqrt(1.0f - cosine * cosine) : one;
  v.hardEdge = !(vabs(v.scale) <= 3.40282347e+38f);
  return v;
}

// The far field's linearisation bound T per unit albedo and intensity (cuts/far_field.h)
// for lanes [l, l + width of V) of `in`, or −1 where the entry does not fold: a directional
// or point light that does not light every point of the region from in front, a light whose
// range sphere cuts the region (its window has a kink there), a spot with a hard edge, or a
// bound that overflows.
MANYLIGHT_INLINE inline void foldBoundLanes(const RegionTerms& r, const FoldLanes& in, int l,
                                            float* out) {
  constexpr float kPi = 3.14159265358979323846f;
  const ShadingRegion& g = r.g;
  const V zero = splat(0.0f);
  const V tree = load(in.tree + l);
  const auto directional = tree == 0.0f, spot = tree == 2.0f;
  V rep[3], axis[3];
  for (int c = 0; c < 3; ++c) {
    rep[c] = load(in.repPoint[c] + l);
    axis[c] = load(in.repAxis[c] + l);
  }
  // A directional light: in front of every normal.
  const auto directionalFront =
      widenDown(g.axis.x * rep[0] + g.axis.y * rep[1] + g.axis.z * rep[2], g) > 0.0f;

  // A point or spot light: in front of every point (the smallest cosine over the box of
  // vectors from the region to the light, as in nodeBoundLanes).
  V dMin[3], dMax[3];
  for (int c = 0; c < 3; ++c) {
    dMin[c] = rep[c] - g.pMax[c];
    dMax[c] = rep[c] - g.pMin[c];
  }
  const VectorBox box = vectorBox(dMin, dMax);
  const V d2Min = box.d2Min, d2Max = box.d2Max;
  const SphereAngles sphere = sphereAngles(g.axis, box);
  const auto pointFront =
      d2Min > 0.0f && widenDown(vmax(boxLower(g.axis, box), sphereLower(sphere)), g) > 0.0f;

  const ConeVariation cone = coneVariation(r, in, l, rep, axis);
  const V scale = cone.scale, t0 = cone.t0, t1 = cone.t1, slope = cone.slope;
  const V curvature = cone.curvature, sine = cone.sine;
  const auto varies = cone.varies, hardEdge = cone.hardEdge;

  // ‖D²f‖ (far_field.h), then T; the bound holds only where the whole region is within the
  // range (a·d⁺² < 1: no point of it beyond the window's kink).
  const V a = load(in.repInvRange2 + l);
  const auto withinRange = a == 0.0f || a * d2Max < 1.0f;
  const V rMin4 = d2Min * d2Min;
  V second = 6.0f / rMin4 + 2.0f * a * a;
  const V q = scale * sine;
  const V coneTerm = (1.415f * slope * scale + 4.0f * slope * q + curvature * q * q) / rMin4 +
                     4.0f * slope * q * a / d2Min;
  second = spot && varies ? second + coneTerm : second;
  const V bound = 0.5f * second * r.h2 / kPi;
  const auto folds =
      pointFront && withinRange && !(spot && hardEdge) && vabs(bound) <= 3.40282347e+38f;

  // Entries that give nothing at any point of the region (kZeroEntry): the light behind every
  // normal (its direction at least 90° + γ from the axis: the box's sphere seen from it, for a
  // point or spot), out of range of the nearest point, or a spot whose cone (smoothstep) is 0
  // towards the whole region; and spots whose cone is 1 towards all of it (kFullCone).
  const auto directionalBehind =
      g.cosSpread > 0.0f &&
      g.axis.x * rep[0] + g.axis.y * rep[1] + g.axis.z * rep[2] <= -g.sinSpread;
  const auto behind = g.cosSpread > 0.0f && !sphere.inside && d2Min > 0.0f &&
                      sphere.cosT * sphere.cosA + sphere.sinT * sphere.sinA <= -g.sinSpread;
  const auto outOfRange = a > 0.0f && d2Min * a >= 1.0f;
  const auto dark = spot && !hardEdge && t1 <= 0.0f;
  const auto fullCone = spot && !hardEdge && t0 >= 1.0f;
  const V result = directional                      ? (directionalFront    ? zero
                                                       : directionalBehind ? splat(kZeroEntry)
                                                                           : splat(-1.0f))
                   : (behind || outOfRange || dark) ? splat(kZeroEntry)
                   : folds                          ? bound
                   : fullCone                       ? splat(kFullCone)
                                                    : splat(-1.0f);
  store(out + l, result);
}

// Lanes [l, l + width of V) of `in`'s point and spot entries, those below `count`, added to
// `sums`: per channel, the entry's f(c) and Df(c) times its intensity (cuts/far_field.h).
MANYLIGHT_INLINE inline void farFieldLanes(glm::vec3 centre, const FarLanes& in, int count, int l,
                                           FarSums& sums) {
  const V zero = splat(0.0f);
  V lane;  // each lane's index
  {
    float index[kLanes];
    for (int k = 0; k < kLanes; ++k) index[k] = float(k);
    lane = load(index + l);
  }
  const auto active = lane < float(count);
  // f = γ v, Df = α v vᵀ + β I: v = p − c, s = |v|², W = 1 − x², x = a·s, W' = dW/ds = −2a·x
  // (W and W' 0 for x ≥ 1), γ = W/r³, α = (3W/s − 2W')/r³, β = −W/r³.
  V v[3];
  for (int c = 0; c < 3; ++c) v[c] = load(in.position[c] + l) - centre[c];
  const V s = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const V r = vsqrt(s), invR3 = 1.0f / (s * r);
  const V a = load(in.invRange2 + l), x = a * s;
  const auto inRange = x < 1.0f;
  const V w = inRange ? 1.0f - x * x : zero;
  const V dw = inRange ? -2.0f * a * x : zero;
  const V alpha = (3.0f * w / s - 2.0f * dw) * invR3, beta = -w * invR3;
  V value[3], jacobian[3][3];  // jacobian[column][row]
  for (int c = 0; c < 3; ++c) value[c] = w * invR3 * v[c];
  for (int col = 0; col < 3; ++col) {
    for (int row = 0; row < 3; ++row) jacobian[col][row] = alpha * v[row] * v[col];
    jacobian[col][col] = jacobian[col][col] + beta;
  }
  // A spot: S f with S = σ(t), t = clamp(k·(axis·u) + o, 0, 1), u = −v/r, σ(t) = t²(3 − 2t):
  // D(S f) = S Df + f ∇Sᵀ, ∇S = σ'(t)·k·(axis − (axis·u) u)/r, σ' = 6t(1 − t) (0 where the
  // clamp acts).
  const auto spot = load(in.spot + l) != 0.0f;
  V u[3], axis[3];
  for (int c = 0; c < 3; ++c) {
    u[c] = -v[c] / r;
    axis[c] = load(in.coneAxis[c] + l);
  }
  const V cosine = axis[0] * u[0] + axis[1] * u[1] + axis[2] * u[2];
  const V scale = load(in.coneScale + l);
  const V tRaw = scale * cosine + load(in.coneOffset + l);
  const V t = clampLanes(tRaw, 0.0f, 1.0f);
  const V sigma = spot ? t * t * (3.0f - 2.0f * t) : splat(1.0f);
  const V slope = spot && tRaw > 0.0f && tRaw < 1.0f ? 6.0f * t * (1.0f - t) : zero;
  V gradient[3];
  for (int c = 0; c < 3; ++c) gradient[c] = slope * scale * (axis[c] - cosine * u[c]) / r;
  for (int col = 0; col < 3; ++col) {
    for (int row = 0; row < 3; ++row)
      jacobian[col][row] = sigma * jacobian[col][row] + value[row] * gradient[col];
  }
  for (int c = 0; c < 3; ++c) value[c] = sigma * value[c];
  for (int ch = 0; ch < 3; ++ch) {
    const V i = active ? load(in.intensity[ch] + l) : zero;
    for (int k = 0; k < 3; ++k) {
      const V term = active ? i * value[k] : zero;
      store(sums.f[ch][k] + l, load(sums.f[ch][k] + l) + term);
    }
    for (int col = 0; col < 3; ++col) {
      for (int row = 0; row < 3; ++row) {
        const V term = active ? i * jacobian[col][row] : zero;
        float* sum = sums.j[ch][3 * col + row] + l;
        store(sum, load(sum) + term);
      }
    }
  }
}
