// The smallest cuts the total rule (docs/lightcuts.md) could take on a scene's light trees,
// whatever its bounds: at the points random pixels of the view show, each node's bounds are
// the tightest any bound on it can be, [I·min f, I·max f] with I its intensity and f its
// lights' shading per unit intensity at the point (the range of its estimate over the choice
// of representative, which holds its true value), found from every light. Leaves are exact.
// From the roots, the node with the widest interval is refined until the rule holds: the sum
// B of the widths within ε of the estimate less B (or within the absolute floor). A cut that
// keeps a representative's estimate can claim no less than half its width, so the same with
// half-widths is a floor under any method that bounds nodes of these trees by a light of
// theirs. The third figure takes, instead of a bound, each node's true error as if its
// lights all stood at their intensity-weighted centroid (centroidError): a floor under a
// second-order estimate's bounds, whatever they are.
//
// usage: manylight_cut_floor SCENE [--error E] [--samples N] [--seed S]
// Prints the cut sizes' spread over the samples and how many exceed --max-cut's default
// and the shared cuts' limit (cuts/tile_cuts.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <queue>
#include <random>
#include <string>
#include <vector>

#include "bake/light_pack.h"
#include "bake/light_tree.h"
#include "base/error.h"
#include "cuts/tile_cuts.h"
#include "render/lightcuts_method.h"
#include "scene/camera.h"
#include "scene/gltf_loader.h"
#include "scene/shading_model.h"

namespace {

using namespace manylight;

struct Sample {
  glm::dvec3 p, n;
};

struct Triangle {
  glm::dvec3 a, b, c;
};

std::vector<Triangle> worldTriangles(const Scene& scene) {
  std::vector<Triangle> triangles;
  for (const MeshInstance& inst : scene.instances) {
    const glm::dmat4 world(inst.world);
    for (const Primitive& prim : scene.meshes[std::size_t(inst.mesh)].primitives) {
      if (prim.mode != PrimitiveMode::Triangles) continue;
      const auto corner = [&](std::size_t k) {
        return glm::dvec3(world * glm::dvec4(glm::dvec3(prim.positions[prim.indices[k]]), 1.0));
      };
      for (std::size_t t = 0; t + 2 < prim.indices.size(); t += 3)
        triangles.push_back({corner(t), corner(t + 1), corner(t + 2)});
    }
  }
  return triangles;
}

// Where the ray o + t·d first meets a triangle (Möller–Trumbore): t, or a negative number.
double hit(const Triangle& tri, glm::dvec3 o, glm::dvec3 d) {
  const glm::dvec3 e1 = tri.b - tri.a, e2 = tri.c - tri.a, q = glm::cross(d, e2);
  const double det = glm::dot(e1, q);
  if (std::abs(det) < 1e-12) return -1.0;
  const glm::dvec3 s = o - tri.a;
  const double u = glm::dot(s, q) / det;
  const glm::dvec3 r = glm::cross(s, e1);
  const double v = glm::dot(d, r) / det;
  if (u < 0.0 || v < 0.0 || u + v > 1.0) return -1.0;
  return glm::dot(e2, r) / det;
}

// The points that random pixels of a 640×480 view show (the scene's first perspective
// camera, else the view `render` frames), each with its triangle's normal turned towards
// the camera.
std::vector<Sample> visiblePoints(const Scene& scene, int count, std::uint64_t seed) {
  const std::vector<Triangle> triangles = worldTriangles(scene);
  const bool own = !scene.cameras.empty() && !scene.cameras.front().orthographic;
  const Camera camera = own ? scene.cameras.front() : frameBounds(scene.bounds(), 640, 480);
  const glm::dmat4 world(camera.world);
  const glm::dvec3 eye(world[3]);
  const double h = std::tan(0.5 * double(camera.yfov)), w = h * 640.0 / 480.0;
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Sample> samples;
  for (int tries = 0; int(samples.size()) < count && tries < 100 * count; ++tries) {
    const glm::dvec3 d = glm::normalize(
        glm::dvec3(world * glm::dvec4(unit(random) * w, unit(random) * h, -1.0, 0.0)));
    double nearest = 1e300;
    const Triangle* seen = nullptr;
    for (const Triangle& tri : triangles) {
      const double t = hit(tri, eye, d);
      if (t > 1e-6 && t < nearest) nearest = t, seen = &tri;
    }
    if (!seen) continue;
    glm::dvec3 n = glm::normalize(glm::cross(seen->b - seen->a, seen->c - seen->a));
    if (glm::dot(n, d) > 0.0) n = -n;
    samples.push_back({eye + nearest * d, n});
  }
  if (samples.empty()) throw Error(scene.name + ": the view shows no surface");
  return samples;
}

double maxOf(glm::dvec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

// Per tree, per node: an error per channel (0 for leaves).
using NodeErrors = std::vector<std::vector<glm::dvec3>>;

// The total rule's cut from the roots, refining the node of the largest error (times `share`)
// first until the errors' sum B is within ε of total − B in every channel, or within the
// absolute floor.
int floorCut(const std::vector<LightTree>& trees, const NodeErrors& errors, double share,
             glm::dvec3 total, double error) {
  using Entry = std::pair<double, std::pair<int, int>>;  // largest channel of an error; node
  std::priority_queue<Entry> open;
  glm::dvec3 bound(0.0);
  int size = 0;
  auto add = [&](int t, int i) {
    if (trees[std::size_t(t)].nodes[std::size_t(i)].empty()) return;
    const glm::dvec3 e = share * errors[std::size_t(t)][std::size_t(i)];
    ++size;
    bound += e;
    if (maxOf(e) > 0.0) open.push({maxOf(e), {t, i}});
  };
  for (int t = 0; t < int(trees.size()); ++t) add(t, 0);
  while (!open.empty() && maxOf(bound) > double(kAbsoluteFloor) &&
         maxOf(bound) > error * maxOf(total - bound)) {
    const auto [t, i] = open.top().second;
    open.pop();
    --size;
    bound -= share * errors[std::size_t(t)][std::size_t(i)];
    add(t, 2 * i + 1);
    add(t, 2 * i + 2);
  }
  return size;
}

// What a node of a tree sums from its lights, bottom-up.
struct NodeSums {
  double lo = 1e300, hi = -1e300;  // the lights' shading per unit intensity
  glm::dvec3 intensity{0.0}, exact{0.0};
  glm::dmat3 moment{0.0};     // column c: Σ intensity_c · position (directional: direction)
  glm::dvec3 perRange4{0.0};  // Σ intensity / range⁴ over the lights with ranges
  double minRange = 1e300;    // the smallest of those ranges
  void add(const NodeSums& o) {
    lo = std::min(lo, o.lo), hi = std::max(hi, o.hi);
    intensity += o.intensity, exact += o.exact, moment += o.moment;
    perRange4 += o.perRange4, minRange = std::min(minRange, o.minRange);
  }
};

// A node's error estimated as if all its lights were at their intensity-weighted centroid
// (per channel): point lights so, their range windows Σ I·(1 − d⁴/range⁴) where no light's
// range is below the distance d (else half the width); directional lights by the weighted sum
// of their directions (exact where all are in front); spots by half the width.
glm::dvec3 centroidError(LightType type, const NodeSums& n, const Sample& s) {
  const glm::dvec3 width = n.intensity * (n.hi - n.lo);
  if (type == LightType::Spot) return 0.5 * width;
  glm::dvec3 e(0.0);
  for (int c = 0; c < 3; ++c) {
    if (!(n.intensity[c] > 0.0)) continue;
    double estimate;
    if (type == LightType::Directional) {
      estimate = std::max(glm::dot(s.n, -n.moment[c]), 0.0);
    } else {
      const glm::dvec3 v = n.moment[c] / n.intensity[c] - s.p;
      const double d2 = std::max(glm::dot(v, v), shading::kMinDistanceSquared);
      if (d2 > n.minRange * n.minRange) return 0.5 * width;
      const double windowed = n.intensity[c] - d2 * d2 * n.perRange4[c];
      estimate = windowed * std::max(glm::dot(s.n, v), 0.0) / (d2 * std::sqrt(d2));
    }
    e[c] = std::abs(n.exact[c] - estimate);
  }
  return e;
}

struct Floors {
  int widths, halfWidths, centroids;
};

Floors floorsAt(const std::vector<LightTree>& trees, const std::vector<Light>& lights,
                const LightOrder& order, const Sample& s, double error) {
  glm::dvec3 total(0.0);
  NodeErrors widths, centroids;
  for (const LightTree& tree : trees) {
    const std::size_t count = tree.nodes.size();
    std::vector<NodeSums> sums(count);
    widths.emplace_back(count, glm::dvec3(0.0));
    centroids.emplace_back(count, glm::dvec3(0.0));
    for (std::size_t i = count; i-- > 0;) {
      const LightTreeNode& node = tree.nodes[i];
      NodeSums& n = sums[i];
      if (node.empty()) continue;
      if (int(i) >= tree.firstLeaf()) {
        const Light& light = lights[std::size_t(order.scene[std::size_t(node.representative)])];
        glm::dvec3 l;
        n.exact = shading::irradiance(light, s.p, s.n, l);
        n.intensity = glm::dvec3(light.colour) * double(light.intensity);
        n.lo = n.hi = maxOf(n.intensity) > 0.0 ? maxOf(n.exact) / maxOf(n.intensity) : 0.0;
        const glm::dvec3 at = light.type == LightType::Directional
                                  ? glm::normalize(glm::dvec3(light.direction))
                                  : glm::dvec3(light.position);
        for (int c = 0; c < 3; ++c) n.moment[c] = n.intensity[c] * at;
        if (isRanged(light)) {
          const double r2 = double(light.range) * double(light.range);
          n.perRange4 = n.intensity / (r2 * r2);
          n.minRange = double(light.range);
        }
        total += n.exact;
        continue;
      }
      n.add(sums[2 * i + 1]);
      n.add(sums[2 * i + 2]);
      widths.back()[i] = n.intensity * (n.hi - n.lo);
      centroids.back()[i] = centroidError(tree.type, n, s);
    }
  }
  return {floorCut(trees, widths, 1.0, total, error), floorCut(trees, widths, 0.5, total, error),
          floorCut(trees, centroids, 1.0, total, error)};
}

void report(const char* what, std::vector<int> sizes, int maxCut) {
  std::sort(sizes.begin(), sizes.end());
  const auto at = [&](double q) { return sizes[std::size_t(q * double(sizes.size() - 1))]; };
  const auto over = [&](int limit) {
    return std::count_if(sizes.begin(), sizes.end(), [&](int s) { return s > limit; });
  };
  std::printf("%s: min %d, median %d, 90th percentile %d, max %d; over %d: %ld, over %d: %ld\n",
              what, sizes.front(), at(0.5), at(0.9), sizes.back(), maxCut, long(over(maxCut)),
              kSharedCutLimit, long(over(kSharedCutLimit)));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') {
    std::fprintf(stderr, "usage: manylight_cut_floor SCENE [--error E] [--samples N] [--seed S]\n");
    return 2;
  }
  double error = 0.02;
  int samples = 64;
  std::uint64_t seed = 1;
  for (int i = 2; i < argc; i += 2) {
    const std::string a = argv[i];
    char* end = nullptr;
    const char* value = i + 1 < argc ? argv[i + 1] : "";
    if (a == "--error")
      error = std::strtod(value, &end);
    else if (a == "--samples")
      samples = int(std::strtol(value, &end, 10));
    else if (a == "--seed")
      seed = std::strtoull(value, &end, 10);
    else {
      std::fprintf(stderr, "manylight_cut_floor: unknown option %s\n", argv[i]);
      return 2;
    }
    if (end == value || *end != '\0' || !(error > 0.0 && error <= 1.0) || samples < 1) {
      std::fprintf(stderr,
                   "manylight_cut_floor: %s needs a value (--error in (0, 1], "
                   "--samples of at least 1)\n",
                   argv[i]);
      return 2;
    }
  }
  try {
    const Scene scene = loadGltf(argv[1]);
    if (scene.lights.empty()) throw Error(scene.name + ": no lights");
    const std::vector<LightTree> trees = buildLightTrees(scene.lights);
    const LightOrder order = lightOrder(scene.lights);
    std::vector<int> widths, halves, centroids;
    for (const Sample& s : visiblePoints(scene, samples, seed)) {
      const Floors f = floorsAt(trees, scene.lights, order, s, error);
      widths.push_back(f.widths);
      halves.push_back(f.halfWidths);
      centroids.push_back(f.centroids);
    }
    std::printf("%s: %zu lights, %zu points, total rule at error %g\n", argv[1],
                scene.lights.size(), widths.size(), error);
    const int maxCut = LightcutsSettings{}.maxCut;
    report("cut with the tightest bounds", widths, maxCut);
    report("cut with half of them", halves, maxCut);
    report("cut with errors at the centroids", centroids, maxCut);
  } catch (const Error& e) {
    std::fprintf(stderr, "manylight_cut_floor: %s\n", e.what());
    return 1;
  }
  return 0;
}
