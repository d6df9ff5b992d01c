#pragma once
// Constants of `--indirect` that C++ and GLSL share (glsl/variants.cpp writes them
// into every shader's prelude). No GL.
namespace manylight {

// Cells (of the smaller cascade) across a transition band: two, not the document's one, so
// a camera moving a given distance a frame moves the blend half as far.
inline constexpr float kBandCells = 2.0f;
// A texel's near radius (render/near_field.h) is at least this many cells of the cascade
// whose caches receive its light, so the far part is smooth between caches.
inline constexpr float kNearCells = 2.0f;

// The near field's texels lie in one plane when within this × the near grid's cell of it
// (and their normals within a cosine of 0.9999 of one another); a pixel as close to the plane,
// or behind it, skips them (NearField::cellPlanes), missing the light they would still send
// it. That light grows with the pixel's height over the plane, and a surface meeting the
// plane holds pixels at every height, so the tolerance only absorbs the rounding of positions
// on the plane: at 10⁻³ cells a wall's pixel 3 × 10⁻⁵ m over the floor (cells of 0.4 m)
// misses 12% of its near light (NearField.PixelsOnAPlaneReadTheCellsOtherTexels).
inline constexpr float kPlaneTolerance = 1e-5f;

// A cache holds, beside its coefficients, the exact far irradiance for one normal (its normal
// bin's centre, render/light_caches.h) as a correction to them; a pixel takes all of it at
// that normal, none beyond this cosine to it (11°, under the least angle from a bin's centre
// to its edge), and a smooth part between (glsl/cache_interpolate.frag).
inline constexpr float kCorrectionCosine = 0.981f;
// Normal bins a cube face's side (odd, so that the axis is a bin's centre).
inline constexpr int kNormalBinGrid = 3;

// Textures addressed by a record's index i hold it at texel (i mod w, i / w), for a width w
// of 2^shift: a shader finds it as (i & (w − 1), i >> shift), since llvmpipe has no vector
// integer division and runs i % w and i / w lane by lane (a third of the near field's time).
// The caches' textures (render/light_caches.h):
inline constexpr int kCacheTextureShift = 9;
// The near field's entries and texel records (render/near_field.h):
inline constexpr int kNearTextureShift = 10;

}  // namespace manylight
