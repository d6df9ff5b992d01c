// Spot nodes' cones over a region for cuts/node_lanes_kernel.h: whether a node's light may
// reach it, and bounds on its cone factor. Included by it once per lane type, with its V,
// operations and helpers. No include guard.

// Whether some light of a spot node may shine on some point of the region: its cone (axis,
// cos θ in w2, sin θ) widened by the angular radius of the node's and the region's bounding
// spheres together.
MANYLIGHT_INLINE inline Mask spotReachesLanes(const RegionTerms& r, const NodeLanes& in, int l) {
  const V zero = splat(0.0f);
  V boxCentre[3], boxExtent[3], toP[3];
  for (int c = 0; c < 3; ++c) {
    const V bMin = load(in.boxMin[c] + l), bMax = load(in.boxMax[c] + l);
    boxCentre[c] = 0.5f * (bMin + bMax);
    boxExtent[c] = bMax - bMin;
    toP[c] = r.centre[c] - boxCentre[c];
  }
  const V reach = 0.5f * vsqrt(boxExtent[0] * boxExtent[0] + boxExtent[1] * boxExtent[1] +
                               boxExtent[2] * boxExtent[2]) +
                  r.halfDiagonal;
  const V d = vsqrt(toP[0] * toP[0] + toP[1] * toP[1] + toP[2] * toP[2]);
  const V spotCos = load(in.w2 + l), spotSin = load(in.sinTheta + l);
  const V sinR = reach / d;
  const V cosR = vsqrt(vmax(1.0f - sinR * sinR, zero));
  const V sinSum = spotSin * cosR + spotCos * sinR;
  const V cosSum = spotCos * cosR - spotSin * sinR;
  V axis[3];
  for (int c = 0; c < 3; ++c) axis[c] = load(in.axis[c] + l);
  return d <= reach || sinSum < 0.0f ||
         (axis[0] * toP[0] + axis[1] * toP[1] + axis[2] * toP[2]) / d >= cosSum;
}

// A spot node's cone factor over the region: bounds on smoothstep(clamp(cos · scale +
// offset)) of any of its lights at any point of the region, cos the cosine between the
// light's axis and its direction to the point. The angle between the node's axis and a
// direction from its box to the region is within α of the angle φ to the region's centre,
// α the angular radius of both boxes' bounding spheres together (spotReachesLanes), and a
// light's axis within the spread σ of the node's; so the cosine lies in
// [cos min(φ + α + σ, π), cos max(φ − α − σ, 0)]. The widest cone's terms at the largest
// cosine bound every light's factor from above (it is non-increasing in the outer and inner
// cosines), the narrowest's at the smallest from below (TileCutter::SpotCone).
struct ConeFactor {
  V up, low;
};
MANYLIGHT_INLINE inline ConeFactor spotConeLanes(const RegionTerms& r, const NodeLanes& in, int l) {
  const V zero = splat(0.0f), one = splat(1.0f);
  V toP[3], extent[3], axis[3];
  for (int c = 0; c < 3; ++c) {
    const V bMin = load(in.boxMin[c] + l), bMax = load(in.boxMax[c] + l);
    toP[c] = r.centre[c] - 0.5f * (bMin + bMax);
    extent[c] = bMax - bMin;
    axis[c] = load(in.axis[c] + l);
  }
  const V reach =
      0.5f * vsqrt(extent[0] * extent[0] + extent[1] * extent[1] + extent[2] * extent[2]) +
      r.halfDiagonal;
  const V d = vsqrt(toP[0] * toP[0] + toP[1] * toP[1] + toP[2] * toP[2]);
  // Within kSpotReachSlack · reach the angular radius is taken as 90°: beyond it cos α ≥ 0.014, and
  // its float error (about 1e-7 / cos α) stays within kSpotCosineMargin, added below.
  const auto inside = d <= reach * kSpotReachSlack;
  const V sinA = vmin(reach / d, one), cosA = vsqrt(vmax(1.0f - sinA * sinA, zero));
  const V cosS = load(in.spreadCos + l), sinS = vsqrt(vmax(1.0f - cosS * cosS, zero));
  // β = α + σ; past π where its sine is negative.
  const V cosB = cosA * cosS - sinA * sinS, sinB = sinA * cosS + cosA * sinS;
  const V cosF =
      clampLanes((axis[0] * toP[0] + axis[1] * toP[1] + axis[2] * toP[2]) / d, -1.0f, 1.0f);
  const V sinF = vsqrt(vmax(1.0f - cosF * cosF, zero));
  const auto wide = inside || sinB < 0.0f;
  V top = cosF * cosB + sinF * sinB, bottom = cosF * cosB - sinF * sinB;
  top = wide || cosF >= cosB ? one : vmin(top + kSpotCosineMargin, one);
  bottom = wide || cosB <= -cosF ? splat(-1.0f) : vmax(bottom - kSpotCosineMargin, splat(-1.0f));
  const V tUp = clampLanes(top * load(in.upScale + l) + load(in.upOffset + l), 0.0f, 1.0f);
  const V tLow = clampLanes(bottom * load(in.lowScale + l) + load(in.lowOffset + l), 0.0f, 1.0f);
  return {tUp * tUp * (3.0f - 2.0f * tUp), tLow * tLow * (3.0f - 2.0f * tLow)};
}
