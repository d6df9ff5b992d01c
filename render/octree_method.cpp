#include "render/octree_method.h"

#include <algorithm>

#include "bake/light_pack.h"
#include "gl/context.h"
#include "glsl/variants.h"
#include "render/lighting_inputs.h"

namespace manylight {

using namespace gl::api;

namespace {

template <typename T, typename Allocator>
gl::TextureBuffer upload(const std::vector<T, Allocator>& data, std::size_t perTexel, GLenum format,
                         const std::string& what) {
  static const T zeros[4] = {};  // an empty table: one texel keeps the sampler complete
  if (data.empty()) return gl::uploadTextureBuffer(zeros, 1, format, what);
  return gl::uploadTextureBuffer(data.data(), data.size() / perTexel, format, what);
}

}  // namespace

OctreeMethod::OctreeMethod(LinklessOctree octree, const std::vector<Light>& lights)
    : octree_(std::move(octree)) {
  uploadAll(lights);
}

void OctreeMethod::replace(const LinklessOctree& octree, const std::vector<Light>& lights) {
  octree_ = octree;
  uploadAll(lights);
}

void OctreeMethod::uploadAll(const std::vector<Light>& lights) {
  lights_.clear();
  for (int index : octree_.order) lights_.push_back(lights[std::size_t(index)]);
  lightTexture_ = upload(packLightTexels(lights, octree_.order), 4, GL_RGBA32F, "octree lights");
  nodes_ = upload(octree_.nodes, 2, GL_RG32UI, "light octree nodes");
  offsets_ = upload(octree_.offsets, 4, GL_RGBA16UI, "light octree hash offsets");
  indices_ = upload(octree_.indices, 1, GL_R32UI, "light octree lists");
}

int OctreeMethod::light(const GpuScene& scene, const GBuffer& gbuffer, const View& view,
                        int perPass) const {
  if (perPass <= 0 || perPass > layout::kOctreeEntriesPerPass)
    perPass = layout::kOctreeEntriesPerPass;
  glBindFramebuffer(GL_FRAMEBUFFER, gbuffer.lightingFramebuffer().id());
  const gl::Program& shader = gl::cachedProgram(
      "fullscreen.vert", "lighting_octree.frag",
      glsl::octreeDefines(scene.hasSpecular() ? glsl::kOctreeHasSpecular : 0u), {"oRadiance"});
  shader.use();
  bindLightingInputs(shader, gbuffer, scene, view);
  // The octree's own light texture, in its order, in place of the scene's.
  glActiveTexture(GL_TEXTURE4);
  glBindTexture(GL_TEXTURE_BUFFER, lightTexture_.texture.id());
  const gl::TextureBuffer* buffers[3] = {&nodes_, &offsets_, &indices_};
  const char* names[3] = {"uOctreeNodes", "uOctreeOffsets", "uOctreeIndices"};
  for (int i = 0; i < 3; ++i) {
    glActiveTexture(GL_TEXTURE5 + i);
    glBindTexture(GL_TEXTURE_BUFFER, buffers[i]->texture.id());
    glUniform1i(shader.uniform(names[i]), 5 + i);
  }
  const LinklessOctree& o = octree_;
  glUniform3fv(shader.uniform("uOctreeOrigin"), 1, &o.origin.x);
  glUniform1f(shader.uniform("uOctreeInvLeaf"), 1.0f / o.leafEdge);
  glUniform1i(shader.uniform("uOctreeLevels"), o.levels);
  std::vector<GLint> dims, nodeBase, offsetBase, offsetCount;
  for (const LinklessLevel& l : o.level) {
    dims.insert(dims.end(), {l.dims.x, l.dims.y, l.dims.z});
    nodeBase.push_back(l.nodeBase);
    offsetBase.push_back(l.offsetBase);
    offsetCount.push_back(l.offsetCount);
  }
  glUniform3iv(shader.uniform("uLevelDims"), o.levels, dims.data());
  glUniform1iv(shader.uniform("uLevelNodeBase"), o.levels, nodeBase.data());
  glUniform1iv(shader.uniform("uLevelOffsetBase"), o.levels, offsetBase.data());
  glUniform1iv(shader.uniform("uLevelOffsetCount"), o.levels, offsetCount.data());
  glUniform1i(shader.uniform("uGlobalCount"), int(o.globalCount));

  // Passes of kOctreeEntriesPerPass entries until the longest list ends.
  const long long longest = (long long)o.globalCount + o.maxLeafCount;
  int passes = 0;
  glUniform1i(shader.uniform("uEntriesPerPass"), perPass);
  for (long long first = 0; first < std::max(longest, 1ll); first += perPass) {
    glUniform1i(shader.uniform("uFirstEntry"), int(first));
    glDrawArrays(GL_TRIANGLES, 0, 3);
    ++passes;
  }
  glDisable(GL_BLEND);
  glActiveTexture(GL_TEXTURE0);
  return passes;
}

OctreeFrameStats OctreeMethod::frameStats(const GBuffer& gbuffer, bool bruteForce) const {
  const int w = gbuffer.width(), h = gbuffer.height();
  const std::vector<float> position = gbuffer.read(GBuffer::kPosition);
  const std::vector<float> normal = gbuffer.read(GBuffer::kNormal);
  OctreeFrameStats stats;
  long long entries = 0, evaluated = 0, reaching = 0, lit = 0;
  std::vector<char> listed(bruteForce ? lights_.size() : 0);
  for (std::size_t i = 0; i < std::size_t(w) * h; ++i) {
    if (normal[4 * i + 3] == 0.0f) continue;  // background
    const glm::vec3 p(position[4 * i], position[4 * i + 1], position[4 * i + 2]);
    const OctreeList list = linklessListAt(octree_, p);
    ++stats.pixels;
    entries += octree_.globalCount + list.count;
    for (std::uint32_t k = 0; k < octree_.globalCount + list.count; ++k) {
      const std::uint32_t at = k < octree_.globalCount ? k : list.first + (k - octree_.globalCount);
      const Light& light = lights_[octree_.indices[at]];
      const glm::vec3 d = light.position - p;
      const bool ranged = isRanged(light);
      // The shader's range test passes where the window is non-zero.
      const bool inRange = !ranged || glm::dot(d, d) < light.range * light.range;
      evaluated += inRange;
      reaching += inRange;
      lit += lightReaches(light, p);
      if (bruteForce) listed[octree_.indices[at]] = 1;
    }
    for (std::size_t slot = 0; slot < listed.size(); ++slot) {
      if (!listed[slot] && lightReaches(lights_[slot], p)) ++stats.missed;
      listed[slot] = 0;
    }
  }
  if (stats.pixels > 0) {
    stats.listEntries = double(entries) / double(stats.pixels);
    stats.lightEvaluations = double(evaluated) / double(stats.pixels);
    stats.lightsReaching = double(reaching) / double(stats.pixels);
    stats.lightsLit = double(lit) / double(stats.pixels);
  }
  return stats;
}

}  // namespace manylight
