// Real spherical harmonics for `--indirect caches` (render/light_caches.h): bands 0–1 (SH L1,
// 4 coefficients) or, with SH_L2, bands 0–2 (9), each an RGB coefficient stored in one
// texel's rgb. A cache projects the light arriving from its map texels; a pixel turns the
// coefficients into irradiance for its normal by the clamped cosine's convolution
// (Ramamoorthi and Hanrahan 2001): band l scaled by π, 2π/3, π/4.
#ifdef SH_L2
const int kShCoefficients = 9;
#else
const int kShCoefficients = 4;
#endif

// The basis functions at unit direction d.
void shBasis(vec3 d, out float y[9]) {
  y[0] = 0.282094792;
  y[1] = 0.488602512 * d.y;
  y[2] = 0.488602512 * d.z;
  y[3] = 0.488602512 * d.x;
  y[4] = 1.092548431 * d.x * d.y;
  y[5] = 1.092548431 * d.y * d.z;
  y[6] = 0.315391565 * (3.0 * d.z * d.z - 1.0);
  y[7] = 1.092548431 * d.x * d.z;
  y[8] = 0.546274215 * (d.x * d.x - d.y * d.y);
}

// The clamped cosine's convolution weight of coefficient k.
float shCosine(int k) { return k == 0 ? kPi : (k < 4 ? 2.0 * kPi / 3.0 : kPi / 4.0); }

// The weights that turn coefficients into irradiance for unit normal n (shIrradiance): the
// basis at n times the clamped cosine's convolution.
void shIrradianceWeights(vec3 n, out float w[9]) {
  shBasis(n, w);
  w[0] *= shCosine(0);
  for (int k = 1; k < 4; ++k) w[k] *= shCosine(1);
  for (int k = 4; k < 9; ++k) w[k] *= shCosine(4);
}

// Σ w[k] c[k] over the basis's coefficients.
vec3 shApply(vec3 c[9], float w[9]) {
  vec3 e = w[0] * c[0] + w[1] * c[1] + w[2] * c[2] + w[3] * c[3];
#ifdef SH_L2
  e += w[4] * c[4] + w[5] * c[5] + w[6] * c[6] + w[7] * c[7] + w[8] * c[8];
#endif
  return e;
}

// The irradiance coefficients `c` give unit normal n, through the clamped cosine's
// convolution; unclamped, so linear in c (a sum over parts of the light is the sum of theirs).
vec3 shIrradiance(vec3 c[9], vec3 n) {
  float w[9];
  shIrradianceWeights(n, w);
  return shApply(c, w);
}
