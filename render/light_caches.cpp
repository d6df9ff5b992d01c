#include "render/light_caches.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <unordered_map>

#include "gl/context.h"
#include "render/lighting_inputs.h"
#include "render/rsm.h"

namespace manylight {

using namespace gl::api;

CacheGrid cacheGrid(glm::vec3 centre, float cell, int cascades, int resolution) {
  CacheGrid g;
  g.cascades = std::clamp(cascades, 1, kMaxCascades);
  g.resolution = resolution;
  g.centre = centre;
  for (int k = 0; k < g.cascades; ++k) {
    const float h = cell * float(1 << k);
    const glm::vec3 snapped = glm::floor(centre / h + 0.5f) * h;
    g.origin.push_back(snapped - float(resolution / 2) * h);
    g.cell.push_back(h);
    g.decision.push_back(float(resolution / 2 - 2) * h);
  }
  return g;
}

int cascadesToCover(glm::vec3 centre, float cell, const Bounds& bounds, int resolution) {
  if (bounds.empty) return 1;
  const glm::vec3 far = glm::max(glm::abs(bounds.min - centre), glm::abs(bounds.max - centre));
  const float reach = std::max({far.x, far.y, far.z});
  int cascades = 1;
  while (cascades < kMaxCascades &&
         float(resolution / 2 - 2) * cell * float(1 << (cascades - 1)) < reach)
    ++cascades;
  return cascades;
}

void setCascadeUniforms(const gl::Program& p, const CacheGrid& grid) {
  glUniform1i(p.uniform("uCascades"), grid.cascades);
  glUniform3fv(p.uniform("uCentre"), 1, glm::value_ptr(grid.centre));
  glUniform1fv(p.uniform("uCell"), grid.cascades, grid.cell.data());
  glUniform1fv(p.uniform("uDecision"), grid.cascades, grid.decision.data());
}

int cascadeOf(const CacheGrid& grid, glm::vec3 p, float* band) {
  const glm::vec3 d3 = glm::abs(p - grid.centre);
  const float d = std::max({d3.x, d3.y, d3.z});
  int k = 0;
  while (k < grid.cascades && d > grid.decision[std::size_t(k)]) ++k;
  if (band) {
    const float width = k < grid.cascades ? kBandCells * grid.cell[std::size_t(k)] : 1.0f;
    *band = k < grid.cascades
                ? std::max(0.0f, (d - (grid.decision[std::size_t(k)] - width)) / width)
                : 0.0f;
  }
  return k;
}

namespace {

// Marks the eight nodes around p in cascade k for a pixel of normal bin `bin` (normalBin),
// `corrected` where its normal lies within kCorrectionCosine of the bin's centre: a node gets
// a cache per bin of such pixels, listed from its CAV entry on, and one at least. (Every cache
// of a node has the same coefficients; the others' pixels read its first.) Returns whether
// every node holds what the pixel reads (not where kMaxCaches refused one).
bool markCell(const CacheGrid& g, int k, glm::ivec3 base, int bin, bool corrected,
              CacheAllocation& a) {
  bool complete = true;
  const int n = g.nodesPerAxis();
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 node =
        glm::clamp(base + glm::ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1),
                   glm::ivec3(0), glm::ivec3(g.resolution));
    const std::size_t at = std::size_t(((k * n + node.z) * n + node.y) * n + node.x);
    float& head = a.cav[at];
    bool listed = false;
    for (int c = int(head); c >= 0 && !listed; c = a.next[std::size_t(c)])
      listed = int(a.normals[std::size_t(c)].w) == bin;
    if (listed || (head >= 0.0f && !corrected)) continue;
    if (a.positions.size() >= kMaxCaches) {
      ++a.refused;
      complete = false;
      continue;
    }
    if (head < 0.0f) a.nodes.push_back(at);
    a.next.push_back(int(head));
    head = float(a.positions.size());
    a.positions.push_back(
        glm::vec4(g.origin[std::size_t(k)] + glm::vec3(node) * g.cell[std::size_t(k)],
                  g.cell[std::size_t(k)]));
    a.normals.push_back(glm::vec4(binNormal(bin), float(bin)));
  }
  return complete;
}

}  // namespace

int normalBin(glm::vec3 n) {
  const glm::vec3 m = glm::abs(n);
  const int axis = m.x >= m.y && m.x >= m.z ? 0 : m.y >= m.z ? 1 : 2;
  const int face = 2 * axis + (n[axis] < 0.0f ? 1 : 0);
  const float major = std::max(m[axis], 1e-20f);
  const float u = n[(axis + 1) % 3] / major, v = n[(axis + 2) % 3] / major;
  const auto cell = [](float t) {
    return std::clamp(int(std::floor((t + 1.0f) * (0.5f * float(kNormalBinGrid)))), 0,
                      kNormalBinGrid - 1);
  };
  return (face * kNormalBinGrid + cell(v)) * kNormalBinGrid + cell(u);
}

glm::vec3 binNormal(int bin) {
  constexpr int g = kNormalBinGrid;
  const int face = bin / (g * g), axis = face / 2;
  const auto centre = [](int i) { return (2.0f * float(i) + 1.0f) / float(g) - 1.0f; };
  const float u = centre(bin % g), v = centre(bin / g % g);
  glm::vec3 d(0.0f);
  d[axis] = face % 2 == 0 ? 1.0f : -1.0f;
  d[(axis + 1) % 3] = u;
  d[(axis + 2) % 3] = v;
  return glm::normalize(d);
}

CacheAllocation allocateCaches(const CacheGrid& grid, const std::vector<float>& position,
                               const std::vector<float>& normal) {
  CacheAllocation a;
  allocateCaches(grid, position, normal, a);
  return a;
}

void allocateCaches(const CacheGrid& grid, const std::vector<float>& position,
                    const std::vector<float>& normal, CacheAllocation& a) {
  const std::size_t n = std::size_t(grid.nodesPerAxis());
  const std::size_t nodes = n * n * n * std::size_t(grid.cascades);
  if (a.cav.size() == nodes) {
    // Only the last frame's nodes hold anything but −1.
    for (std::size_t node : a.nodes) a.cav[node] = -1.0f;
  } else {
    a.cav.assign(nodes, -1.0f);
  }
  a.positions.clear();
  a.normals.clear();
  a.next.clear();
  a.nodes.clear();
  a.refused = 0;
  // What the last pixel marked in each cascade: marking it again changes nothing, and most
  // pixels share their cell and normal bin with the one before.
  struct Marked {
    glm::ivec3 cell{-1};
    int bin = -1;
    bool corrected = false;
    bool complete = true;  // markCell's answer
  };
  std::vector<Marked> last(std::size_t(grid.cascades));
  const auto mark = [&](int k, glm::vec3 p, int bin, bool corrected) {
    const glm::ivec3 cell(
        glm::floor((p - grid.origin[std::size_t(k)]) / grid.cell[std::size_t(k)]));
    Marked& m = last[std::size_t(k)];
    if (cell == m.cell && bin == m.bin && corrected == m.corrected) return m.complete;
    m = {cell, bin, corrected, markCell(grid, k, cell, bin, corrected, a)};
    return m.complete;
  };
  // NaN, equal to no normal: the first pixel's bin is computed whatever its normal.
  glm::vec3 lastNormal(std::numeric_limits<float>::quiet_NaN());
  int bin = 0;
  bool corrected = false, centred = false;
  a.classes.assign(normal.size() / 4, 0);
  for (std::size_t i = 0; 4 * i + 3 < normal.size(); ++i) {
    if (normal[4 * i + 3] == 0.0f) continue;
    const glm::vec3 p(position[4 * i], position[4 * i + 1], position[4 * i + 2]);
    float band = 0.0f;
    const int k = cascadeOf(grid, p, &band);
    if (k == grid.cascades) continue;
    const glm::vec3 raw(normal[4 * i], normal[4 * i + 1], normal[4 * i + 2]);
    if (raw != lastNormal) {  // a flat surface's pixels share one normal
      lastNormal = raw;
      const glm::vec3 nrm = glm::normalize(raw);
      bin = normalBin(nrm);
      const float towards = glm::dot(nrm, binNormal(bin));
      corrected = towards > kCorrectionCosine;
      centred = towards >= kCentredCosine;
    }
    bool complete = mark(k, p, bin, corrected);
    const bool blended = band > 0.0f && k + 1 < grid.cascades;
    if (blended) complete = mark(k + 1, p, bin, corrected) && complete;
    // A centred pixel reads its bin's cache alone (glsl/cache_interpolate.frag): only where
    // every node around it holds one.
    const bool exact = centred && complete;
    a.classes[i] =
        std::uint8_t(kPixelCached | (exact ? kPixelCentred : 0) | (blended ? kPixelBand : 0));
  }
}

namespace {

constexpr int kCacheTextureWidth = 1 << kCacheTextureShift;

void allocate2d(const gl::Texture& t, int w, int h, const float* data) {
  glBindTexture(GL_TEXTURE_2D, t.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, data);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

std::vector<std::string> basisDefines(bool shL2) {
  return shL2 ? std::vector<std::string>{"SH_L2"} : std::vector<std::string>{};
}

// The coefficient targets (seven; SH L1 fills three) and the exact irradiance, kCacheTargets.
const char* const kShNames[] = {"uSh0", "uSh1", "uSh2", "uSh3", "uSh4", "uSh5", "uSh6", "uExact"};
const std::vector<std::string> kShOutputs = {"oSh0", "oSh1", "oSh2", "oSh3",
                                             "oSh4", "oSh5", "oSh6", "oExact"};
constexpr std::size_t kCacheTargets = 8;

}  // namespace

namespace {

struct NodeKeyHash {
  std::size_t operator()(const std::array<std::int64_t, 5>& k) const {
    std::size_t h = 0;
    for (std::int64_t v : k) h = h * 0x9E3779B97F4A7C15ull + std::size_t(v);
    return h;
  }
};

std::int64_t bitsOf(float f) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof bits);
  return std::int64_t(bits);
}

// Node positions are whole multiples of their cell edge (cacheGrid snaps them), so rounding
// undoes the float arithmetic that made them; and the node's normal bin.
std::array<std::int64_t, 5> nodeKey(glm::vec4 node, glm::vec4 normal) {
  const double h = double(node.w);
  return {bitsOf(node.w), std::llround(double(node.x) / h), std::llround(double(node.y) / h),
          std::llround(double(node.z) / h), std::int64_t(normal.w)};
}

// Scissors the rows that hold caches `first` … `end` − 1.
void scissorCaches(int width, int height, int first, int end) {
  glEnable(GL_SCISSOR_TEST);
  const int y0 = first / width, y1 = std::min(height, (end + width - 1) / width);
  glScissor(0, y0, width, std::max(0, y1 - y0));
}

}  // namespace

void LightCaches::allocateTargets(Targets& t, int height) {
  const std::size_t targets = kCacheTargets;
  if (t.height == height && t.sh.size() == targets) return;
  t.sh.clear();
  t.sh.resize(targets);
  glBindFramebuffer(GL_FRAMEBUFFER, t.framebuffer.id());
  std::vector<GLenum> buffers;
  for (std::size_t i = 0; i < targets; ++i) {
    allocate2d(t.sh[i], width_, height, nullptr);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + GLenum(i), GL_TEXTURE_2D,
                           t.sh[i].id(), 0);
    buffers.push_back(GL_COLOR_ATTACHMENT0 + GLenum(i));
  }
  glDrawBuffers(GLsizei(buffers.size()), buffers.data());
  t.height = height;
}

void LightCaches::upload(const CacheGrid& grid, CacheAllocation& a, bool shL2) {
  const bool keep = shL2 == shL2_ && count_ > 0;
  grid_ = grid;
  shL2_ = shL2;
  const std::size_t count = a.positions.size();
  // Per cache of `a`, its slot at the last upload (−1: none), and its slot now: kept first.
  std::vector<int> before(count, -1), slot(count);
  if (keep) {
    std::unordered_map<NodeKey, int, NodeKeyHash> slots;
    slots.reserve(keys_.size());
    for (std::size_t i = 0; i < keys_.size(); ++i) slots.emplace(keys_[i], int(i));
    for (std::size_t c = 0; c < count; ++c) {
      const auto it = slots.find(nodeKey(a.positions[c], a.normals[c]));
      if (it != slots.end()) before[c] = it->second;
    }
  }
  int next = 0;
  for (std::size_t c = 0; c < count; ++c)
    if (before[c] >= 0) slot[c] = next++;
  kept_ = next;
  for (std::size_t c = 0; c < count; ++c)
    if (before[c] < 0) slot[c] = next++;
  count_ = int(count);
  for (std::size_t node : a.nodes) a.cav[node] = float(slot[std::size_t(a.cav[node])]);
  const int n = grid.nodesPerAxis();
  const glm::ivec3 size(n, n, n * grid.cascades);
  // Per cascade, the slices holding nodes now, and with the last upload's, those that changed
  // (a range per cascade: the slices between two cascades' nodes hold none).
  const std::size_t slice = std::size_t(n) * std::size_t(n);
  std::vector<glm::ivec2> slices(std::size_t(grid.cascades), glm::ivec2(size.z, -1));
  for (std::size_t node : a.nodes) {
    const int z = int(node / slice);
    glm::ivec2& s = slices[std::size_t(z / n)];
    s = glm::ivec2(std::min(s.x, z), std::max(s.y, z));
  }
  glBindTexture(GL_TEXTURE_3D, cav_.id());
  if (size == cavSize_) {  // into the texture's memory, not new memory
    for (std::size_t k = 0; k < slices.size(); ++k) {
      const glm::ivec2 last = k < cavSlices_.size() ? cavSlices_[k] : glm::ivec2(size.z, -1);
      const glm::ivec2 changed(std::min(slices[k].x, last.x), std::max(slices[k].y, last.y));
      if (changed.y >= changed.x)
        glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, changed.x, n, n, changed.y - changed.x + 1, GL_RED,
                        GL_FLOAT, a.cav.data() + std::size_t(changed.x) * slice);
    }
  } else {
    glTexImage3D(GL_TEXTURE_3D, 0, GL_R32F, n, n, size.z, 0, GL_RED, GL_FLOAT, a.cav.data());
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    cavSize_ = size;
  }
  cavSlices_ = std::move(slices);
  glBindTexture(GL_TEXTURE_3D, 0);
  width_ = kCacheTextureWidth;
  height_ = std::max(1, (count_ + width_ - 1) / width_);
  std::vector<float> texels(std::size_t(width_) * std::size_t(height_) * 4, 0.0f),
      normals(texels.size(), 0.0f), links(texels.size(), 0.0f), previous(texels.size(), 0.0f);
  keys_.assign(count, NodeKey{});
  for (std::size_t c = 0; c < count; ++c) {
    const std::size_t s = std::size_t(slot[c]);
    std::copy_n(glm::value_ptr(a.positions[c]), 4, &texels[4 * s]);
    std::copy_n(glm::value_ptr(a.normals[c]), 4, &normals[4 * s]);
    links[4 * s] = a.next[c] >= 0 ? float(slot[std::size_t(a.next[c])]) : -1.0f;
    links[4 * s + 1] = a.normals[c].w;  // its bin, beside the link: one read a step of a walk
    previous[4 * s] = float(before[c]);
    keys_[s] = nodeKey(a.positions[c], a.normals[c]);
  }
  allocate2d(positions_, width_, height_, texels.data());
  allocate2d(normals_, width_, height_, normals.data());
  allocate2d(links_, width_, height_, links.data());
  allocate2d(previous_, width_, height_, previous.data());
  glBindTexture(GL_TEXTURE_2D, 0);
  ++uploads_;
  keptEverywhere_ = true;
  gathered_ = 0;
}

void LightCaches::clearTargets(const Targets& t) {
  glBindFramebuffer(GL_FRAMEBUFFER, t.framebuffer.id());
  const float zero[4] = {0, 0, 0, 0};
  for (std::size_t i = 0; i < t.sh.size(); ++i) glClearBufferfv(GL_COLOR, GLint(i), zero);
}

void LightCaches::copyKept(const Targets& from, const Targets& to) {
  const gl::Program& p =
      gl::cachedProgram("fullscreen.vert", "cache_copy.frag", basisDefines(shL2_), kShOutputs);
  p.use();
  glBindFramebuffer(GL_FRAMEBUFFER, to.framebuffer.id());
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  bindSampler(p, "uPrevious", GL_TEXTURE_2D, previous_.id(), 0);
  for (std::size_t i = 0; i < kCacheTargets; ++i)
    bindSampler(p, kShNames[i], GL_TEXTURE_2D, from.sh[i].id(), 1 + int(i));
  glUniform1i(p.uniform("uKept"), kept_);
  scissorCaches(width_, height_, 0, kept_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_SCISSOR_TEST);
  glActiveTexture(GL_TEXTURE0);
}

void LightCaches::startLayer(int layer, std::vector<long long> maps) {
  if (std::size_t(layer) >= layers_.size()) layers_.resize(std::size_t(layer) + 1);
  Layer& l = layers_[std::size_t(layer)];
  std::sort(maps.begin(), maps.end());
  l.keep = kept_ > 0 && l.maps == maps && l.upload == uploads_ - 1;
  keptEverywhere_ = keptEverywhere_ && l.keep;
  l.maps = std::move(maps);
  l.upload = uploads_;
  Targets& out = l.keep ? scratch_ : l.targets;
  allocateTargets(out, height_);
  clearTargets(out);
  if (l.keep) {
    copyKept(l.targets, scratch_);
    std::swap(l.targets, scratch_);
  }
}

int LightCaches::gather(int layer, const GBuffer& rsm, const RsmClusterTextures& clusters,
                        float nearRadius) {
  const Layer& l = layers_.at(std::size_t(layer));
  const bool keep = l.keep;
  const int first = keep ? kept_ : 0;
  gathered_ += count_ - first;
  if (first == count_) return 0;
  const gl::Program& p =
      gl::cachedProgram("fullscreen.vert", "cache_gather.frag", basisDefines(shL2_), kShOutputs);
  p.use();
  glBindFramebuffer(GL_FRAMEBUFFER, l.targets.framebuffer.id());
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  bindSampler(p, "uCachePosition", GL_TEXTURE_2D, positions_.id(), 0);
  bindSampler(p, "uCacheNormal", GL_TEXTURE_2D, normals_.id(), 7);
  glUniform1i(p.uniform("uFirstCache"), first);
  glUniform1i(p.uniform("uCacheCount"), count_);
  glUniform1f(p.uniform("uNearRadius"), nearRadius);
  bindSampler(p, "uClusterCentre", GL_TEXTURE_2D, clusters.centre.id(), 4);
  bindSampler(p, "uClusterNormal", GL_TEXTURE_2D, clusters.normal.id(), 5);
  bindSampler(p, "uClusterFlux", GL_TEXTURE_2D, clusters.flux.id(), 6);
  scissorCaches(width_, height_, first, count_);
  // At most one iteration per cluster besides one per texel.
  const int passes = drawRsmRowPasses(p, rsm, 1, kRsmClusterEdge,
                                      1.0 + 1.0 / double(kRsmClusterEdge * kRsmClusterEdge));
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  return passes;
}

void LightCaches::sum(const std::vector<int>& layers) {
  allocateTargets(sum_, height_);
  clearTargets(sum_);
  std::vector<std::string> defines = basisDefines(shL2_);
  defines.push_back("CACHE_SUM");
  const gl::Program& p =
      gl::cachedProgram("fullscreen.vert", "cache_copy.frag", defines, kShOutputs);
  p.use();
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  glUniform1i(p.uniform("uKept"), count_);
  for (int layer : layers) {
    const Targets& t = layers_[std::size_t(layer)].targets;
    for (std::size_t i = 0; i < kCacheTargets; ++i)
      bindSampler(p, kShNames[i], GL_TEXTURE_2D, t.sh[i].id(), 1 + int(i));
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glDisable(GL_BLEND);
  glActiveTexture(GL_TEXTURE0);
}

void LightCaches::interpolate(const GBuffer& camera, const PixelClasses& classes,
                              const std::vector<int>& layers) {
  if (layers.empty()) return;
  if (layers.size() > 1) sum(layers);
  const std::vector<gl::Texture>& sh =
      layers.size() > 1 ? sum_.sh : layers_[std::size_t(layers[0])].targets.sh;
  // Pixels whose normal is their bin's centre, and the others; each their own cascade's share,
  // then the next one's in the bands (glsl/cache_interpolate.frag). The programs are compiled
  // before the stencil is bound, so that a failure leaves no stencil test on.
  const gl::Program* programs[2][2];  // [next][centred]
  for (int next = 0; next < 2; ++next)
    for (int centred = 0; centred < 2; ++centred) {
      std::vector<std::string> defines = basisDefines(shL2_);
      if (centred) defines.push_back("CENTRED_NORMALS");
      if (next) defines.push_back("NEXT_CASCADE");
      programs[next][centred] =
          &gl::cachedProgram("fullscreen.vert", "cache_interpolate.frag", defines, {"oRadiance"});
    }
  for (int next = 0; next < 2; ++next) {
    for (int centred = 0; centred < 2; ++centred) {
      const gl::Program& p = *programs[next][centred];
      p.use();
      // The band bit is tested only for the next cascade's share: the own share takes both.
      const unsigned mask = kPixelCached | kPixelCentred | (next ? kPixelBand : 0);
      const unsigned bits = kPixelCached | (centred ? kPixelCentred : 0) | (next ? kPixelBand : 0);
      classes.bind(p, camera, bits, mask);
      bindSampler(p, "uCav", GL_TEXTURE_3D, cav_.id(), 3);
      for (std::size_t i = 0; i < kCacheTargets; ++i)
        bindSampler(p, kShNames[i], GL_TEXTURE_2D, sh[i].id(), 4 + int(i));
      bindSampler(p, "uCacheNext", GL_TEXTURE_2D, links_.id(), 4 + int(kCacheTargets));
      setCascadeUniforms(p, grid_);
      glUniform1i(p.uniform("uResolution"), grid_.resolution);
      glUniform3fv(p.uniform("uOrigin"), grid_.cascades, glm::value_ptr(grid_.origin[0]));
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
  PixelClasses::done();
  glDisable(GL_BLEND);
  glActiveTexture(GL_TEXTURE0);
}

}  // namespace manylight
