#include "tests/oracle.h"

#include <cmath>
#include <limits>

#include "render/image.h"
#include "scene/shading_model.h"

namespace manylight::testing {
namespace {

struct Triangle {
  glm::dvec3 p[3], n[3];
  glm::dvec2 uv[3];
  glm::dvec4 colour[3];
  int material;
  int surface;
  bool mirrored;
  bool textured;
};

struct Hit {
  double t = std::numeric_limits<double>::infinity();
  const Triangle* tri = nullptr;
  double b1 = 0, b2 = 0;
  bool front = true;
};

// Möller–Trumbore; culls back faces of single-sided materials as the rasteriser does.
void intersect(const Triangle& tri, glm::dvec3 o, glm::dvec3 d, bool doubleSided, Hit& hit) {
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
  if (t <= 0.0 || t >= hit.t) return;
  hit = {t, &tri, u, v, front};
}

// GL_LINEAR sampling of an sRGB texture at level 0: texels decoded to linear, then filtered.
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
    return glm::dvec4(decodeSrgb8(p[0]), decodeSrgb8(p[1]), decodeSrgb8(p[2]), p[3] / 255.0);
  };
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
      const Material m = prim.material >= 0 ? scene.materials[prim.material] : defaultMaterial();
      for (std::size_t i = 0; i + 2 < prim.indices.size(); i += 3) {
        Triangle t;
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t v = prim.indices[i + k];
          t.p[k] = glm::dvec3(world * glm::dvec4(glm::dvec3(prim.positions[v]), 1.0));
          t.n[k] = normalMatrix * glm::dvec3(prim.normals[v]);
          t.uv[k] = prim.texcoords.empty() ? glm::dvec2(0.0) : glm::dvec2(prim.texcoords[v]);
          t.colour[k] = prim.colours.empty() ? glm::dvec4(1.0) : glm::dvec4(prim.colours[v]);
        }
        t.material = prim.material;
        t.surface = surface;
        t.mirrored = mirrored;
        t.textured = m.baseColorTexture >= 0 && !prim.texcoords.empty();
        tris.push_back(t);
      }
      ++surface;
    }
  }
  return tris;
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
      Hit hit;
      for (const Triangle& t : tris) {
        const bool doubleSided = t.material >= 0 && scene.materials[t.material].doubleSided;
        intersect(t, origin, dir, doubleSided, hit);
      }
      if (!hit.tri) continue;
      const Triangle& t = *hit.tri;
      const double b0 = 1.0 - hit.b1 - hit.b2;
      const glm::dvec3 p = origin + hit.t * dir;
      glm::dvec3 n = glm::normalize(b0 * t.n[0] + hit.b1 * t.n[1] + hit.b2 * t.n[2]);
      const Material& m = t.material >= 0 ? scene.materials[t.material] : fallback;
      if (m.doubleSided && !hit.front) n = -n;
      glm::dvec4 base = glm::dvec4(m.baseColorFactor) *
                        (b0 * t.colour[0] + hit.b1 * t.colour[1] + hit.b2 * t.colour[2]);
      if (t.textured) {
        base *= sampleBilinear(scene.textures[m.baseColorTexture],
                               b0 * t.uv[0] + hit.b1 * t.uv[1] + hit.b2 * t.uv[2]);
      }
      const shading::PhongMaterial phong =
          shading::phongFromMetallicRoughness(glm::dvec3(base), m.metallic, m.roughness);
      const glm::dvec3 v = view.orthographic ? -forward : glm::normalize(eye - p);
      glm::dvec3 radiance = ambient * phong.albedo + glm::dvec3(m.emissive);
      for (const Light& light : lights) {
        glm::dvec3 l;
        const glm::dvec3 e = shading::irradiance(light, p, n, l);
        radiance += shading::brdf(phong, n, l, v) * e;
      }
      float* px = out.image.pixel(x, y);
      px[0] = float(radiance.r), px[1] = float(radiance.g), px[2] = float(radiance.b), px[3] = 1.0f;
      out.surface[std::size_t(y) * width + x] = t.surface;
    }
  }
  return out;
}

}  // namespace manylight::testing
