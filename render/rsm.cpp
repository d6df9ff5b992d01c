#include "render/rsm.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "gl/context.h"

namespace manylight {

RsmView rsmView(const Light& light, const Bounds& bounds, int size) {
  const glm::vec3 centre = bounds.empty ? glm::vec3(0.0f) : 0.5f * (bounds.min + bounds.max);
  const float radius =
      bounds.empty ? 1.0f : std::max(0.5f * glm::length(bounds.max - bounds.min), 1e-6f);
  const glm::vec3 axis = glm::normalize(light.direction);
  const glm::vec3 up = std::abs(axis.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  RsmView r;
  r.view.forward = axis;
  if (light.type == LightType::Directional) {
    r.view.eye = centre - axis * (2.0f * radius);
    r.view.view = glm::lookAt(r.view.eye, centre, up);
    r.view.projection = glm::ortho(-radius, radius, -radius, radius, 0.0f, 4.0f * radius);
    r.view.orthographic = true;
    const float texel = 2.0f * radius / float(size);
    r.texelScale = texel * texel;
    return r;
  }
  const float half = std::clamp(light.outerConeAngle, 1e-3f, kMaxRsmHalfAngle);
  const float farSide = glm::length(centre - light.position) + radius;
  const float far = light.range > 0.0f ? std::min(light.range, farSide) : farSide;
  r.view.eye = light.position;
  r.view.view = glm::lookAt(light.position, light.position + axis, up);
  r.view.projection = glm::perspective(2.0f * half, 1.0f, 1e-3f * far, far);
  const float texel = 2.0f * std::tan(half) / float(size);
  r.texelScale = texel * texel;
  return r;
}

using namespace gl::api;

int drawRsmRowPasses(const gl::Program& program, const GBuffer& rsm, int firstUnit, int rowAlign,
                     double iterationsPerTexel) {
  const GBuffer::Target targets[] = {GBuffer::kPosition, GBuffer::kNormal, GBuffer::kRadiance};
  const char* names[] = {"uRsmPosition", "uRsmNormal", "uRsmFlux"};
  for (int i = 0; i < 3; ++i) {
    glActiveTexture(GLenum(GL_TEXTURE0 + firstUnit + i));
    glBindTexture(GL_TEXTURE_2D, rsm.target(targets[i]).id());
    glUniform1i(program.uniform(names[i]), firstUnit + i);
  }
  glUniform1i(program.uniform("uRsmSize"), rsm.width());
  const int fit = int(65000.0 / (double(std::max(rsm.width(), 1)) * iterationsPerTexel)) - 1;
  const int rows = std::max(rowAlign, fit / rowAlign * rowAlign);
  int passes = 0;
  for (int first = 0; first < rsm.height(); first += rows, ++passes) {
    glUniform1i(program.uniform("uFirstRow"), first);
    glUniform1i(program.uniform("uRows"), std::min(rows, rsm.height() - first));
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glActiveTexture(GL_TEXTURE0);
  return passes;
}

void RsmClusterTextures::upload(const RsmClusters& clusters, const std::vector<float>& mapPosition,
                                const std::vector<float>& mapNormal,
                                const std::vector<float>& mapFlux) {
  constexpr int kSlots = kRsmClusterEdge * kRsmClusterEdge;
  // Cluster (bx, by) at (s · (by mod kSlots) + bx, by / kSlots): kSlots rows of clusters a
  // row of texels; then its texels from row clusterRows on.
  const int s = clusters.size, width = kSlots * s, clusterRows = (s + kSlots - 1) / kSlots,
            height = clusterRows + s;
  std::vector<glm::vec4> data[3];
  for (std::vector<glm::vec4>& d : data)
    d.assign(std::size_t(width) * std::size_t(height), glm::vec4(0.0f));
  const std::vector<float>* texels[] = {&mapPosition, &mapNormal, &mapFlux};
  const std::vector<glm::vec4>* records[] = {&clusters.centre, &clusters.normal, &clusters.flux};
  for (int by = 0; by < s; ++by) {
    for (int bx = 0; bx < s; ++bx) {
      const std::size_t cluster = std::size_t(by * s + bx);
      for (int i = 0; i < 3; ++i) {
        data[i][std::size_t((by / kSlots) * width + s * (by % kSlots) + bx)] =
            (*records[i])[cluster];
        for (int j = 0; j < kSlots; ++j) {
          // Texel j of the block, as glsl/cache_gather.frag numbers it.
          const std::size_t t =
              std::size_t((kRsmClusterEdge * by + j / kRsmClusterEdge) * kRsmClusterEdge * s +
                          kRsmClusterEdge * bx + j % kRsmClusterEdge);
          data[i][std::size_t((clusterRows + by) * width + kSlots * bx + j)] =
              glm::vec4((*texels[i])[4 * t], (*texels[i])[4 * t + 1], (*texels[i])[4 * t + 2],
                        (*texels[i])[4 * t + 3]);
        }
      }
    }
  }
  const gl::Texture* textures[] = {&centre, &normal, &flux};
  for (int i = 0; i < 3; ++i) {
    glBindTexture(GL_TEXTURE_2D, textures[i]->id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, data[i].data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  glBindTexture(GL_TEXTURE_2D, 0);
}

}  // namespace manylight
