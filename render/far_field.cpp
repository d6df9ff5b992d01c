#include "render/far_field.h"

#include <algorithm>
#include <cmath>

#include "bake/light_tree_layout.h"
#include "render/cpu_clones.h"

namespace manylight {
namespace {

void writeTexel(std::vector<std::uint32_t>& words, glm::dvec3 v) {
  for (int i = 0; i < 3; ++i) words.push_back(layout::wordOf(float(v[i])));
  words.push_back(0u);
}

// The slope of the cone's smoothstep σ(t) = t²(3 − 2t) at t in [0, 1].
double smoothstepSlope(double t) { return 6.0 * t * (1.0 - t); }

}  // namespace

void FarField::addDirectional(glm::vec3 towards, glm::vec3 intensity) {
  for (int c = 0; c < 3; ++c)
    channels_[std::size_t(c)].f += double(intensity[c]) * glm::dvec3(towards);
  ++count_;
}

void FarField::addPoint(glm::vec3 position, float invRange2, glm::vec3 intensity) {
  add(position, invRange2, nullptr, intensity);
}

void FarField::addSpot(glm::vec3 position, float invRange2, const Cone& cone, glm::vec3 intensity) {
  add(position, invRange2, &cone, intensity);
}

MANYLIGHT_AVX2_CLONES
void FarField::add(glm::vec3 position, float invRange2, const Cone* cone, glm::vec3 intensity) {
  // f(c) = W(s) v / r³ and Df(c) = −(2 W'(s) v vᵀ + W (I − 3 v vᵀ / r²)) / r³, v = p − c,
  // s = r² (far_field.h); W = (1 − x²)² with x = a·s, W' = −4a·x(1 − x²), both 0 for x ≥ 1.
  // So f = γ v and Df = α v vᵀ + β I, with γ = W/r³, α = (3W/s − 2W')/r³ and β = −W/r³.
  const glm::dvec3 v = glm::dvec3(position) - centre_;
  const double s = glm::dot(v, v);
  const double r = std::sqrt(s), invR3 = 1.0 / (s * r);
  const double a = invRange2, x = a * s;
  const double w = x < 1.0 ? (1.0 - x * x) * (1.0 - x * x) : 0.0;
  const double dw = x < 1.0 ? -4.0 * a * x * (1.0 - x * x) : 0.0;
  const double alpha = (3.0 * w / s - 2.0 * dw) * invR3, beta = -w * invR3;
  glm::dvec3 value = (w * invR3) * v;
  glm::dmat3 jacobian = glm::outerProduct(alpha * v, v);
  for (int i = 0; i < 3; ++i) jacobian[i][i] += beta;
  if (cone) {
    // S f with S = σ(t), t = clamp(k·(axis·u) + o, 0, 1), u = −v/r the way the light goes to
    // c, σ(t) = t²(3 − 2t): D(S f) = S Df + f ∇Sᵀ, ∇S = σ'(t)·k·(axis − (axis·u) u)/r, and
    // σ' = 6t(1 − t) is 0 where the clamp acts.
    const glm::dvec3 u = -v / r, axis(cone->axis);
    const double cosine = glm::dot(axis, u);
    const double tRaw = double(cone->scale) * cosine + double(cone->offset);
    const double t = std::clamp(tRaw, 0.0, 1.0);
    const double sigma = t * t * (3.0 - 2.0 * t);
    const double slope = tRaw > 0.0 && tRaw < 1.0 ? smoothstepSlope(t) : 0.0;
    const glm::dvec3 gradient = slope * double(cone->scale) * (axis - cosine * u) / r;
    jacobian = sigma * jacobian + glm::outerProduct(value, gradient);
    value *= sigma;
  }
  for (int c = 0; c < 3; ++c) {
    const double i = intensity[c];
    Channel& ch = channels_[std::size_t(c)];
    for (int k = 0; k < 3; ++k) ch.f[k] += i * value[k];
    for (int col = 0; col < 3; ++col) {
      for (int k = 0; k < 3; ++k) ch.j[col][k] += i * jacobian[col][k];
    }
  }
  ++count_;
}

FarField FarField::movedTo(glm::vec3 centre) const {
  FarField moved(*this);
  moved.centre_ = glm::dvec3(centre);
  const glm::dvec3 shift = moved.centre_ - centre_;
  for (Channel& ch : moved.channels_) ch.f += ch.j * shift;
  return moved;
}

glm::vec3 FarField::irradianceAtCentre(glm::vec3 n) const {
  const glm::dvec3 normal(n);
  return {float(glm::dot(normal, channels_[0].f)), float(glm::dot(normal, channels_[1].f)),
          float(glm::dot(normal, channels_[2].f))};
}

void FarField::write(std::vector<std::uint32_t>& words) const {
  writeTexel(words, centre_);
  for (const Channel& ch : channels_) writeTexel(words, ch.f);
  for (const Channel& ch : channels_) {
    for (int column = 0; column < 3; ++column) writeTexel(words, ch.j[column]);
  }
}

}  // namespace manylight
