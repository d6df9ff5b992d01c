#include "render/method_choice.h"

#include <cmath>
#include <cstdio>

#include "render/render_job.h"

namespace manylight {

double meanLeafList(const LinklessOctree& o) {
  double sum = 0.0;
  long long leaves = 0;
  for (std::size_t t = 0; t + 1 < o.nodes.size(); t += 2) {
    if (!(o.nodes[t + 1] & kOctreeLeafBit)) continue;
    const std::uint32_t count = o.nodes[t + 1] & ~kOctreeLeafBit;
    if (count == 0) continue;  // empty slots and empty leaves
    sum += double(count);
    ++leaves;
  }
  return leaves ? sum / double(leaves) : 0.0;
}

namespace {

std::string seconds(double evaluations) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g s", evaluations / kReferenceEvaluationsPerSecond);
  return text;
}

}  // namespace

MethodChoice chooseMethod(const Scene& scene, const std::vector<Light>& lights, int width,
                          int height, const OctreeOptions& options, const LinklessOctree* baked) {
  MethodChoice c;
  const double pixels = double(width) * double(height);
  const double reference = double(lights.size()) * pixels;
  const std::string count = std::to_string(lights.size()) + " lights";
  if (reference <= kAutoReferenceEvaluations) {
    c.reason = count + " × " + std::to_string(width) + "×" + std::to_string(height) +
               " pixels: the reference is exact and takes up to about " + seconds(reference);
    return c;
  }
  std::size_t ranged = 0;
  for (const Light& l : lights) ranged += isRanged(l);
  const double global = double(lights.size() - ranged);
  if (ranged > 0 && global <= kAutoOctreeEntries) {
    if (!baked) {
      c.octree = std::make_shared<LinklessOctree>(
          packLinklessOctree(buildLightOctree(lights, scene, options)));
      baked = c.octree.get();
    }
    const double entries = double(baked->globalCount) + meanLeafList(*baked);
    char text[160];
    std::snprintf(text, sizeof text,
                  ": the octree is exact and its lists hold about %.0f lights (at most %.0f for "
                  "it)",
                  entries, kAutoOctreeEntries);
    c.reason = count + text;
    if (entries <= kAutoOctreeEntries) {
      c.method = Method::Octree;
      return c;
    }
    c.octree = nullptr;
  } else {
    c.reason = count + ", " + std::to_string(lights.size() - ranged) +
               " without a range: the octree would evaluate those at every pixel";
  }
  c.method = Method::Lightcuts;
  c.reason += "; the reference would take up to about " + seconds(reference) +
              ", so lightcuts (approximate, within its documented error at --error)";
  return c;
}

}  // namespace manylight
