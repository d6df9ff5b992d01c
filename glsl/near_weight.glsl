// The split of a map texel's light between the caches and the pixels (render/near_field.h):
// arriving at distance d from a texel of near radius r, the caches take w(d) of it, the
// pixel itself 1 − w(d), so the two add up to `--indirect exact` wherever w is sampled at the
// point that receives the light.
float farWeight(float d, float r) { return smoothstep(r, 2.0 * r, d); }
