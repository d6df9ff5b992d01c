#include "tests/oracle.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/image.h"
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

std::vector<Triangle> worldTriangles(const Scene& scene) {
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
  double metallic, roughness, occlusion;
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
  s.metallic = m.metallic * mr.b;
  s.roughness = m.roughness * mr.g;
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

OracleImage renderOracle(const Scene& scene, const Camera& camera, const std::vector<Light>& lights,
                         int width, int height, glm::dvec3 ambient) {
  const View view = makeView(camera, width, height);
  const glm::dmat4 inverseViewProjection =
      glm::inverse(glm::dmat4(view.projection) * glm::dmat4(view.view));
  const glm::dvec3 eye(view.eye), forward = glm::normalize(glm::dvec3(view.forward));
  const std::vector<Triangle> tris = worldTriangles(scene);
  const Material fallback = defaultMaterial();

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
      // The nearest hit that a MASK material's cutoff does not discard.
      Hit hit;
      SurfacePoint sp;
      const Material* m = nullptr;
      for (double after = 0.0;;) {
        hit = Hit{};
        for (const Triangle& t : tris) {
          const bool doubleSided = t.material >= 0 && scene.materials[t.material].doubleSided;
          intersect(t, origin, dir, doubleSided, after, hit);
        }
        if (!hit.tri) break;
        m = hit.tri->material >= 0 ? &scene.materials[hit.tri->material] : &fallback;
        sp = surfaceAt(scene, *m, hit);
        if (m->alphaMode != AlphaMode::Mask || sp.base.a >= m->alphaCutoff) break;
        after = hit.t;
      }
      if (!hit.tri) continue;
      const glm::dvec3 p = origin + hit.t * dir;
      glm::dvec3 radiance = glm::dvec3(sp.base);
      if (!m->unlit) {
        const shading::PhongMaterial phong =
            shading::phongFromMetallicRoughness(glm::dvec3(sp.base), sp.metallic, sp.roughness);
        const glm::dvec3 v = view.orthographic ? -forward : glm::normalize(eye - p);
        radiance = shading::ambientRadiance(phong, ambient, sp.occlusion) + sp.emissive;
        for (const Light& light : lights) {
          glm::dvec3 l;
          const glm::dvec3 e = shading::irradiance(light, p, sp.normal, l);
          radiance += shading::brdf(phong, sp.normal, l, v) * e;
        }
      }
      float* px = out.image.pixel(x, y);
      px[0] = float(radiance.r), px[1] = float(radiance.g), px[2] = float(radiance.b), px[3] = 1.0f;
      out.surface[std::size_t(y) * width + x] = hit.tri->surface;
    }
  }
  return out;
}

}  // namespace manylight::testing
