// Powers of lanes of floats for cuts/node_lanes_kernel.h (a Phong lobe's power of a
// cosine), from their bits: included by it once per lane type, with its V and operations
// (vexponent, vmantissa, vexp2Integer among them). No include guard.

// log₂ x for normal x > 0: x = 2^e · m with m in [√½, √2), and log₂ m = (2/ln 2) · atanh t
// for t = (m − 1)/(m + 1), |t| ≤ 0.172, by its series to t⁷ (truncated within 5e-8).
MANYLIGHT_INLINE inline V log2Lanes(V x) {
  V e = vexponent(x), m = vmantissa(x);
  const auto high = m > 1.41421356f;
  m = high ? m * 0.5f : m;
  e = high ? e + 1.0f : e;
  const V t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
  return e + t * (2.88539008f + t2 * (0.961796694f + t2 * (0.577078016f + t2 * 0.412198583f)));
}

// 2^y for y in [−126, 0]: 2^k · 2^f, k = y rounded to the nearest integer (adding and
// subtracting 1.5 · 2²³ rounds it so), f = y − k in [−½, ½], 2^f by the series of e^(f·ln 2) to
// its 7th power (truncated within 1e-8, relative).
MANYLIGHT_INLINE inline V exp2Lanes(V y) {
  const V k = (y + 12582912.0f) - 12582912.0f;
  const V f = (y - k) * 0.693147181f;
  const V p =
      1.0f + f * (1.0f + f * (0.5f + f * (0.166666672f +
                                          f * (0.0416666679f +
                                               f * (0.00833333377f +
                                                    f * (0.00138888892f + f * 0.000198412701f))))));
  return p * vexp2Integer(k);
}

// x^e for x in [0, 1] and e ≥ 1 (a Phong lobe's power of a cosine), as exp2(e · log₂ x):
// exactly 0 at x ≤ 0 and 1 at x ≥ 1. Its relative error is below 1e-6 + 2e-7 · (e − y),
// y = e · log₂ x, the log's error (about 1e-7, absolute) grown by e, the rest rounding:
// powUpperLanes widens it by that much up, powLowerLanes down, so that they bound the exact
// power (below 2⁻¹²⁶ the upper bound is 2⁻¹²⁶ and the lower 0). The tests compare them with
// std::pow in double.
constexpr float kSmallestNormal = 1.17549435e-38f;
MANYLIGHT_INLINE inline V powExponentLanes(V x, float e) {
  return e * log2Lanes(vmax(x, splat(kSmallestNormal)));
}
MANYLIGHT_INLINE inline V powSlackLanes(V y, float e) { return 1e-6f + 2e-7f * (e - y); }
MANYLIGHT_INLINE inline V powLanes(V x, float e) {
  const V p = exp2Lanes(vmax(powExponentLanes(x, e), splat(-126.0f)));
  return x <= 0.0f ? splat(0.0f) : (x >= 1.0f ? splat(1.0f) : p);
}
MANYLIGHT_INLINE inline V powUpperLanes(V x, float e) {
  const V y = vmax(powExponentLanes(x, e), splat(-126.0f));
  const V p = exp2Lanes(y) * (1.0f + powSlackLanes(y, e));
  return x <= 0.0f ? splat(0.0f) : (x >= 1.0f ? splat(1.0f) : p);
}
MANYLIGHT_INLINE inline V powLowerLanes(V x, float e) {
  const V y = powExponentLanes(x, e);
  const V p = exp2Lanes(vmax(y, splat(-126.0f))) * (1.0f - powSlackLanes(y, e));
  return x < kSmallestNormal || y < -126.0f ? splat(0.0f) : (x >= 1.0f ? splat(1.0f) : p);
}
