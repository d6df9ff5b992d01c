#pragma once
// The far field of a shared tile cut (cuts/tile_cuts.h): the cut's directional, point and
// spot entries that light every pixel of the tile from in front and from within their range,
// folded into one function of the pixel that is linear in its position and normal, so a
// pixel evaluates them all at the cost of about six entries.
//
// A Lambert pixel at x with normal n gets from a point entry of intensity I (RGB) at p
//   I · max(n·(p − x), 0) · W(|p − x|²) / |p − x|³,   W the range window
// (scene/shading_model.h) as a function of s = |p − x|²: W(s) = clamp(1 − a²s², 0, 1) with
// a = 1/range² (0: none).
// Where n·(p − x) > 0 for every pixel of the tile the clamp never acts, and the sum over
// such entries is n · Σ I f(x) with f(x) = W(|p − x|²)(p − x)/|p − x|³. The far field keeps
// that sum to first order about the tile's centre c: per channel, F = Σ I f(c) and the
// Jacobian J = Σ I Df(c), and a pixel takes n · (F + J (x − c)). A directional entry adds
// I · l to F exactly (its term n·l does not depend on x).
//
// The first-order remainder is at most ½ sup‖D²f‖ |x − c|² along the segment from c to x,
// inside the tile's box, provided f is twice differentiable in the box. It is not at
// s = 1/a: W/d² has a kink at d = range (its slope jumps from −4/range³ to 0), so an entry
// whose range sphere cuts the box never folds, and one beyond its range from the whole box
// gives nothing (kZeroEntry). One whose range holds the whole box (a·s < 1 at its farthest
// point) has W = 1 − a²s² all over it, and with v = p − x, ρ = |v|:
//   f = (1 − a²ρ⁴) v/ρ³ = v/ρ³ − a² ρ v.
// ‖D²(v/ρ³)‖ ≤ 6/ρ⁴ (v/ρ³ is minus the gradient of 1/ρ; its second derivative is the third
// of 1/ρ). Along a unit direction d, with c = v·d/ρ, D(ρ v)·d = c v + ρ d and
// D²(ρ v)[d, d] = ((1 − c²)/ρ) v + 2c d, of length √(1 + 6c² − 3c⁴) ≤ 2. With r the distance
// from p to the box (ρ ≥ r):
//   ‖D²f‖ ≤ 6/r⁴ + 2·a².
// So the entry's error grows by
//   T = I · ½ (6/r⁴ + 2·a²) · h² / π   per unit albedo,
// h the half-diagonal of the tile's box, and the tile's bounds (U, B) take T in with the
// node's own bound: the total rule's guarantee is kept.
//
// A spot entry is S f, S = σ(t) its cone, t = clamp(k·(axis·u) + o, 0, 1) with u the unit
// vector from the light to x, σ(t) = t²(3 − 2t): C¹ (σ' is 0 where the clamp acts) with
// |σ| ≤ 1, and S is constant where the clamp acts, so only points between the inner and
// outer cone count: there t lies in [t₀, t₁], the range over the box, with |σ'| = 6t(1 − t)
// ≤ σ'₁ (1.5 at most) and |σ''| = |6 − 12t| ≤ σ''₁ (6 at most), at an angle ψ from the axis
// whose sine is ≤ sin θ (θ the smaller of the outer angle and the box's farthest angle, up
// to π/2). Along a direction d, |D(axis·u)·d| ≤ sin ψ/r ≤ sin θ/r, and the second
// derivative of axis·u is −c·β² − 2s·γ·αβ over r² (d = α u + β w, axis = c u + s e,
// γ = e·w), at most √2/r². With |f| ≤ W/ρ² ≤ 1/r², |Df·d| ≤ 2/ρ³ + 2a²ρ ≤ 2/r³ + 2·a/r
// (|D(ρ v)·d| ≤ 2ρ, and a²ρ ≤ a/ρ where aρ² < 1) and q = k·sin θ:
//   ‖D²(S f)‖ ≤ |D²S| |f| + 2 |DS| |Df| + ‖D²f‖
//            ≤ (6 + 1.415·σ'₁·k + 4·σ'₁·q + σ''₁·q²)/r⁴ + 4·σ'₁·q·a/r² + 2·a².
// Where the cone is constant over the whole tile (all its light through, or none), S f
// has the point light's bound; a spot with a hard edge (k infinite) does not fold.
// T is computed, in single precision, by foldBounds (cuts/node_lanes.h), which also says
// which entries light every point of the group from in front and within their range.
//
// Texels (4 words, float bits), kFarFieldTexels of them: c; F per channel R, G, B; then
// per channel the three columns of J.
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace manylight {

struct FarSums;

inline constexpr int kFarFieldTexels = 13;

class FarField {
 public:
  explicit FarField(glm::vec3 centre) : centre_(centre) {}
  // A directional entry: unit vector towards the light, intensity (lux, RGB).
  void addDirectional(glm::vec3 towards, glm::vec3 intensity);
  // A point entry at `position` with 1/range² (0: none) and intensity (candela, RGB).
  void addPoint(glm::vec3 position, float invRange2, glm::vec3 intensity);
  // A spot's cone as the light texture holds it: smoothstep(clamp(cos · scale + offset)),
  // cos to the axis (the way it shines).
  struct Cone {
    glm::vec3 axis;
    float scale, offset;
  };
  // A spot entry: a point entry times its cone.
  void addSpot(glm::vec3 position, float invRange2, const Cone& cone, glm::vec3 intensity);
  // Entries summed per lane by addFarField (cuts/node_lanes.h) about centre().
  void add(const FarSums& sums, int entries);
  glm::vec3 centre() const { return glm::vec3(centre_); }
  // The same linear function about another centre (exact: F + J (centre − c), J).
  FarField movedTo(glm::vec3 centre) const;
  // Its irradiance at its centre for unit normal n, per channel: n · F.
  glm::vec3 irradianceAtCentre(glm::vec3 n) const;
  // The folded entries' Phong lobes, per unit specular colour: a constant over the group,
  // their sum at its centre (cuts/cut_region.cpp bounds it); moved as it is.
  void addSpecular(glm::vec3 radiance) { specular_ += glm::dvec3(radiance); }
  glm::vec3 specular() const { return glm::vec3(specular_); }
  bool empty() const { return count_ == 0; }
  int count() const { return count_; }
  // Appends the kFarFieldTexels texels.
  void write(std::vector<std::uint32_t>& words) const;

 private:
  void addOne(glm::vec3 position, float invRange2, const Cone* cone, glm::vec3 intensity);

  glm::dvec3 centre_;
  struct Channel {
    glm::dvec3 f{0.0};
    glm::dmat3 j{0.0};
  };
  std::array<Channel, 3> channels_{};  // R, G, B
  glm::dvec3 specular_{0.0};
  int count_ = 0;
};

}  // namespace manylight
