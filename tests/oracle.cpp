#include "tests/oracle.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "image/image.h"
#include "scene/shading_model.h"

namespace manylight::testing {
namespace {

struct Triangle {
  glm::dvec3 p[3], n[3];
  glm::dvec4 tangent[3];  // world-space xyz, w handedness (mirroring applied); 0 where absent
  glm::dvec2 uv[2][3];    // TEXCOORD_0, TEXCOORD_1
  glm::dvec4 colour[3];
  int material;
  int surface;
  bool mirrored;
  bool hasUv[2];
};

struct Hit {
  double t = std::numeric_limits<double>::infinity();
  const Triangle* tri = nullptr;
  double b1 = 0, b2 = 0;
  bool front = true;
};

// Möller–Trumbore, for hits beyond `after`; culls back faces of single-sided materials as
// the rasteriser does.
void intersect(const Triangle& tri, glm::dvec3 o, glm::dvec3 d, bool doubleSided, double after,
               Hit& hit) {
  const glm::dvec3 e1 = tri.p[1] - tri.p[0], e2 = tri.p[2] - tri.p[0];
  const glm::dvec3 pv = glm::cross(d, e2);
  const double det = glm::dot(e1, pv);
  if (det == 0.0) return;
  // Seen from the viewer, counter-clockwise is front (clockwise under a mirroring transform).
  const bool front = (glm::dot(glm::cross(e1, e2), d) < 0.0) != tri.mirrored;
  if (!front && !doubleSided) return;
  const double inv = 1.0 / det;
  const glm::dvec3 tv = o - tri.p[0];
  const double u = glm::dot(tv, pv) * inv;
  if (u < 0.0 || u > 1.0) return;
  const glm::dvec3 qv = glm::cross(tv, e1);
  const double v = glm::dot(d, qv) * inv;
  if (v < 0.0 || u + v > 1.0) return;
  const double t = glm::dot(e2, qv) * inv;
  if (t <= after || t >= hit.t) return;
  hit = {t, &tri, u, v, front};
}

// GL_LINEAR (or GL_NEAREST) sampling at level 0: texels decoded to linear (sRGB for colour
// textures, codes / 255 for data), then filtered.
glm::dvec4 sampleBilinear(const Texture& tex, glm::dvec2 uv) {
  auto wrap = [](int i, int n, bool repeat, bool mirror) {
    if (mirror) {
      const int period = 2 * n;
      int m = ((i % period) + period) % period;
      return m < n ? m : period - 1 - m;
    }
    if (repeat) return ((i % n) + n) % n;
    return std::clamp(i, 0, n - 1);
  };
  auto texel = [&](int x, int y) {
    x = wrap(x, tex.width, tex.repeatS, tex.mirrorS);
    y = wrap(y, tex.height, tex.repeatT, tex.mirrorT);
    const std::uint8_t* p = &tex.rgba[(std::size_t(y) * tex.width + x) * 4];
    auto decode = [&](std::uint8_t c) { return tex.srgb ? decodeSrgb8(c) : c / 255.0; };
    return glm::dvec4(decode(p[0]), decode(p[1]), decode(p[2]), p[3] / 255.0);
  };
  if (!tex.linearMag) {  // NEAREST
    return texel(int(std::floor(uv.x * tex.width)), int(std::floor(uv.y * tex.height)));
  }
  const double x = uv.x * tex.width - 0.5, y = uv.y * tex.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const int ix = int(fx), iy = int(fy);
  const double ax = x - fx, ay = y - fy;
  return glm::mix(glm::mix(texel(ix, iy), texel(ix + 1, iy), ax),
                  glm::mix(texel(ix, iy + 1), texel(ix + 1, iy + 1), ax), ay);
}

// The scene's triangles in world space; `centres` gets each surface's bounds centre (the
// order blended surfaces are composited in, as render/blend_pass.h does).
std::vector<Triangle> worldTriangles(const Scene& scene, std::vector<glm::dvec3>& centres) {
  std::vector<Triangle> tris;
  int surface = 0;
  for (const MeshInstance& inst : scene.instances) {
    const glm::dmat4 world(inst.world);
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(world)));
    const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
    for (const Primitive& prim : scene.meshes[inst.mesh].primitives) {
      if (prim.mode != PrimitiveMode::Triangles) continue;
      const std::vector<glm::vec2>* uvs[2] = {&prim.texcoords, &prim.texcoords1};
      for (std::size_t i = 0; i + 2 < prim.indices.size(); i += 3) {
        Triangle t;
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t v = prim.indices[i + k];
          t.p[k] = glm::dvec3(world * glm::dvec4(glm::dvec3(prim.positions[v]), 1.0));
          t.n[k] = normalMatrix * glm::dvec3(prim.normals[v]);
          const glm::dvec4 tan =
              prim.tangents.empty() ? glm::dvec4(0.0) : glm::dvec4(prim.tangents[v]);
          t.tangent[k] = glm::dvec4(glm::dmat3(world) * glm::dvec3(tan), mirrored ? -tan.w : tan.w);
          for (int set = 0; set < 2; ++set) {
            t.uv[set][k] = uvs[set]->empty() ? glm::dvec2(0.0) : glm::dvec2((*uvs[set])[v]);
          }
          t.colour[k] = prim.colours.empty() ? glm::dvec4(1.0) : glm::dvec4(prim.colours[v]);
        }
        t.material = prim.material;
        t.surface = surface;
        t.mirrored = mirrored;
        for (int set = 0; set < 2; ++set) t.hasUv[set] = !uvs[set]->empty();
        tris.push_back(t);
      }
      Bounds b;
      for (const glm::vec3& v : prim.positions) b.add(v);
      const glm::vec4 centre = inst.world * glm::vec4(0.5f * (b.min + b.max), 1.0f);
      centres.push_back(glm::dvec3(glm::vec3(centre)));
      ++surface;
    }
  }
  return tris;
}

// A hit's interpolated attributes and its material's values there, as glsl/gbuffer.frag
// computes them.
struct SurfacePoint {
  glm::dvec4 base;  // base colour and alpha
  glm::dvec3 normal;
  shading::PhongMaterial phong;
  double occlusion;
  glm::dvec3 emissive;
};

SurfacePoint surfaceAt(const Scene& scene, const Material& m, const Hit& hit) {
  const Triangle& t = *hit.tri;
  const double b[3] = {1.0 - hit.b1 - hit.b2, hit.b1, hit.b2};
  auto lerp = [&](const auto& v) { return b[0] * v[0] + b[1] * v[1] + b[2] * v[2]; };
  auto sample = [&](const TextureRef& ref, glm::dvec4 none) {
    if (ref.texture < 0 || !t.hasUv[ref.texCoord]) return none;
    const glm::dvec2 uv = lerp(t.uv[ref.texCoord]);
    const glm::dvec3 moved = glm::dmat3(ref.transform) * glm::dvec3(uv, 1.0);
    return sampleBilinear(scene.textures[ref.texture], glm::dvec2(moved));
  };
  SurfacePoint s;
  s.base =
      glm::dvec4(m.baseColorFactor) * lerp(t.colour) * sample(m.baseColorTexture, glm::dvec4(1.0));
  const glm::dvec4 mr = sample(m.metallicRoughnessTexture, glm::dvec4(1.0));
  if (m.specularGlossiness) {
    const glm::dvec4 sg = glm::dvec4(glm::dvec3(m.specularFactor), m.glossiness) * mr;
    s.phong = shading::phongFromSpecularGlossiness(glm::dvec3(s.base), glm::dvec3(sg), sg.a);
  } else {
    s.phong = shading::phongFromMetallicRoughness(glm::dvec3(s.base), m.metallic * mr.b,
                                                  m.roughness * mr.g);
  }
  s.occlusion = 1.0 + m.occlusionStrength * (sample(m.occlusionTexture, glm::dvec4(1.0)).r - 1.0);
  s.emissive = glm::dvec3(m.emissive) * glm::dvec3(sample(m.emissiveTexture, glm::dvec4(1.0)));
  glm::dvec3 n = glm::normalize(lerp(t.n));
  const glm::dvec4 tangent = lerp(t.tangent);
  if (m.normalTexture.texture >= 0 && t.hasUv[m.normalTexture.texCoord] &&
      glm::dot(glm::dvec3(tangent), glm::dvec3(tangent)) > 0.0) {
    const glm::dvec3 tn =
        glm::normalize(glm::dvec3(tangent) - n * glm::dot(n, glm::dvec3(tangent)));
    const glm::dvec3 bn = glm::cross(n, tn) * (tangent.w < 0.0 ? -1.0 : 1.0);
    glm::dvec3 mapped =
        glm::dvec3(sample(m.normalTexture, glm::dvec4(0.5, 0.5, 1.0, 1.0))) * 2.0 - 1.0;
    mapped.x *= m.normalScale;
    mapped.y *= m.normalScale;
    const glm::dvec3 perturbed = glm::dmat3(tn, bn, n) * mapped;
    if (glm::dot(perturbed, perturbed) > 0.0) n = glm::normalize(perturbed);
  }
  s.normal = m.doubleSided && !hit.front ? -n : n;
  return s;
}

}  // namespace

bool OracleImage::interior(int x, int y) const {
  const int w = image.width, h = image.height;
  const int s = surface[std::size_t(y) * w + x];
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = std::clamp(x + dx, 0, w - 1), ny = std::clamp(y + dy, 0, h - 1);
      if (surface[std::size_t(ny) * w + nx] != s) return false;
    }
  }
  return true;
}

namespace {

// What one pixel's ray meets: the nearest hit among the triangles that `accept` takes that a
// MASK material's cutoff does not discard, its material and its values there.
struct Seen {
  Hit hit;
  SurfacePoint point;
  const Material* material = nullptr;
};

template <typename Accept>
Seen nearest(const Scene& scene, const std::vector<Triangle>& tris, glm::dvec3 origin,
             glm::dvec3 dir, const Accept& accept) {
  static const Material fallback = defaultMaterial();
  Seen seen;
  for (double after = 0.0;;) {
    seen.hit = Hit{};
    for (const Triangle& t : tris) {
      if (!accept(t)) continue;
      const bool doubleSided = t.material >= 0 && scene.materials[t.material].doubleSided;
      intersect(t, origin, dir, doubleSided, after, seen.hit);
    }
    if (!seen.hit.tri) return seen;
    seen.material =
        seen.hit.tri->material >= 0 ? &scene.materials[seen.hit.tri->material] : &fallback;
    seen.point = surfaceAt(scene, *seen.material, seen.hit);
    const Material& m = *seen.material;
    if (m.alphaMode != AlphaMode::Mask || seen.point.base.a >= m.alphaCutoff) return seen;
    after = seen.hit.t;
  }
}

// The radiance leaving what was seen towards the eye.
glm::dvec3 shade(const Seen& s, glm::dvec3 p, glm::dvec3 v, const std::vector<Light>& lights,
                 glm::dvec3 ambient) {
  const SurfacePoint& sp = s.point;
  if (s.material->unlit) return glm::dvec3(sp.base);
  const shading::PhongMaterial& phong = sp.phong;
  glm::dvec3 radiance = shading::ambientRadiance(phong, ambient, sp.occlusion) + sp.emissive;
  for (const Light& light : lights) {
    glm::dvec3 l;
    const glm::dvec3 e = shading::irradiance(light, p, sp.normal, l);
    radiance += shading::brdf(phong, sp.normal, l, v) * e;
  }
  return radiance;
}

bool blended(const Scene& scene, const Triangle& t) {
  return t.material >= 0 && scene.materials[t.material].alphaMode == AlphaMode::Blend;
}

}  // namespace

OracleImage renderOracle(const Scene& scene, const Camera& camera, const std::vector<Light>& lights,
                         int width, int height, glm::dvec3 ambient) {
  const View view = makeView(camera, width, height);
  const glm::dmat4 inverseViewProjection =
      glm::inverse(glm::dmat4(view.projection) * glm::dmat4(view.view));
  const glm::dvec3 eye(view.eye), forward = glm::normalize(glm::dvec3(view.forward));
  std::vector<glm::dvec3> centres;
  const std::vector<Triangle> tris = worldTriangles(scene, centres);
  // Blended surfaces, farthest first by their centres.
  std::vector<int> blendOrder;
  for (const Triangle& t : tris) {
    if (blended(scene, t) && (blendOrder.empty() || blendOrder.back() != t.surface))
      blendOrder.push_back(t.surface);
  }
  auto depth = [&](int s) {
    const glm::dvec3 c = centres[std::size_t(s)];
    return view.orthographic ? glm::dot(c - eye, forward) : glm::length(c - eye);
  };
  std::stable_sort(blendOrder.begin(), blendOrder.end(),
                   [&](int a, int b) { return depth(a) > depth(b); });

  OracleImage out;
  out.image.width = width;
  out.image.height = height;
  out.image.rgba.assign(std::size_t(width) * height * 4, 0.0f);
  out.surface.assign(std::size_t(width) * height, -1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      // Pixel centre in normalised device coordinates (image row 0 is GL's top row).
      const glm::dvec2 ndc((x + 0.5) / width * 2.0 - 1.0,
                           (height - 1 - y + 0.5) / height * 2.0 - 1.0);
      auto unproject = [&](double z) {
        const glm::dvec4 p = inverseViewProjection * glm::dvec4(ndc, z, 1.0);
        return glm::dvec3(p) / p.w;
      };
      glm::dvec3 origin, dir;
      if (view.orthographic) {
        origin = unproject(-1.0);
        dir = forward;
      } else {
        origin = eye;
        dir = glm::normalize(unproject(0.0) - eye);
      }
      auto viewOf = [&](glm::dvec3 p) {
        return view.orthographic ? -forward : glm::normalize(eye - p);
      };
      const Seen opaque =
          nearest(scene, tris, origin, dir, [&](const Triangle& t) { return !blended(scene, t); });
      glm::dvec4 c(0.0);  // premultiplied radiance and coverage
      int id = -1;
      if (opaque.hit.tri) {
        const glm::dvec3 p = origin + opaque.hit.t * dir;
        c = glm::dvec4(shade(opaque, p, viewOf(p), lights, ambient), 1.0);
        id = opaque.hit.tri->surface;
      }
      // Each blended surface in front of it, farthest first: its nearest hit, composited over.
      for (int s : blendOrder) {
        const Seen layer =
            nearest(scene, tris, origin, dir, [&](const Triangle& t) { return t.surface == s; });
        if (!layer.hit.tri || (opaque.hit.tri && layer.hit.t >= opaque.hit.t)) continue;
        const glm::dvec3 p = origin + layer.hit.t * dir;
        const double a = std::clamp(layer.point.base.a, 0.0, 1.0);
        c = glm::dvec4(shade(layer, p, viewOf(p), lights, ambient) * a, a) + c * (1.0 - a);
        id = id * 31 + s + 1;
      }
      if (id == -1) continue;
      float* px = out.image.pixel(x, y);
      for (int ch = 0; ch < 4; ++ch) px[ch] = float(c[ch]);
      out.surface[std::size_t(y) * width + x] = id;
    }
  }
  return out;
}

}  // namespace manylight::testing
