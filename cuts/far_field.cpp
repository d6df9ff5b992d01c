#include "cuts/far_field.h"

#include "bake/light_tree_layout.h"
#include "cuts/node_lanes.h"

namespace manylight {
namespace {

void writeTexel(std::vector<std::uint32_t>& words, glm::dvec3 v) {
  for (int i = 0; i < 3; ++i) words.push_back(layout::wordOf(float(v[i])));
  words.push_back(0u);
}

}  // namespace

void FarField::addDirectional(glm::vec3 towards, glm::vec3 intensity) {
  for (int c = 0; c < 3; ++c)
    channels_[std::size_t(c)].f += double(intensity[c]) * glm::dvec3(towards);
  ++count_;
}

void FarField::addPoint(glm::vec3 position, float invRange2, glm::vec3 intensity) {
  addOne(position, invRange2, nullptr, intensity);
}

void FarField::addSpot(glm::vec3 position, float invRange2, const Cone& cone, glm::vec3 intensity) {
  addOne(position, invRange2, &cone, intensity);
}

void FarField::addOne(glm::vec3 position, float invRange2, const Cone* cone, glm::vec3 intensity) {
  FarLanes in{};
  for (int c = 0; c < 3; ++c) {
    in.position[c][0] = position[c];
    in.intensity[c][0] = intensity[c];
    if (cone) in.coneAxis[c][0] = cone->axis[c];
  }
  in.invRange2[0] = invRange2;
  if (cone) {
    in.spot[0] = 1.0f;
    in.coneScale[0] = cone->scale;
    in.coneOffset[0] = cone->offset;
  }
  FarSums sums{};
  addFarField(centre(), in, 1, sums, false);
  add(sums, 1);
}

void FarField::add(const FarSums& sums, int entries) {
  for (int c = 0; c < 3; ++c) {
    Channel& ch = channels_[std::size_t(c)];
    for (int k = 0; k < 3; ++k) {
      for (int l = 0; l < kLanes; ++l) ch.f[k] += double(sums.f[c][k][l]);
    }
    for (int col = 0; col < 3; ++col) {
      for (int row = 0; row < 3; ++row) {
        for (int l = 0; l < kLanes; ++l) ch.j[col][row] += double(sums.j[c][3 * col + row][l]);
      }
    }
  }
  count_ += entries;
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
