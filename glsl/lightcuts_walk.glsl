// The lightcuts shader's first part (glsl/CMakeLists.txt puts glsl/lighting_lightcuts.frag
// after it): a pixel's own cut, walked in passes, and the stopping rules.
//
// Lightcuts (Walter et al. 2005) without visibility: per pixel, a cut through the light
// trees (one per light type). A node of the cut contributes its representative light's
// shading times the node's total intensity; a leaf is exact.
//
// Bounds of a node's contribution at a surface point p (no shadows, so conservative):
//   upper = I · (albedo/π + ks·(n+2)/(2π)·cosᵣ⁺ⁿ) · cos⁺ · window(d⁻)/d⁻²   [· a spot
//           node's cone factor's upper bound, 0 where its cone cannot reach p]
//   lower = I · albedo/π · cos⁻ · window⁻(d⁺)/d⁺²   [· a spot node's cone factor's lower
//           bound (spotConeFactor)]
// with d⁻, d⁺ the nearest and farthest distances from p to the node's box, cos⁺ ≥ the
// largest and cos⁻ ≤ the smallest cosine between the normal and a direction into the box
// (cosᵣ⁺ likewise about the mirror direction), window⁻ using the smallest range. The window
// clamp(1 − (d/range)⁴, 0, 1) is non-increasing in d and non-decreasing in range, and so is
// window/d² in d: over the box it is at most window(d⁻)/d⁻² with the largest range and at
// least window⁻(d⁺)/d⁺². p inside a box: the upper bound is unbounded, and the node is
// always refined. Directional trees use p = 0 and no distance term (their boxes hold
// directions). Both a node's estimate and its true contribution lie in [lower, upper], so
// its error is at most upper − lower.
// I is the node's decoded intensity Ĩ widened by the coding's slack (bake/node_colour.h):
// Ĩ + η·max(Ĩ) + ζ in the upper bound, Ĩ − η·max(Ĩ) − ζ in the lower, so the bounds hold
// for the exact intensity although the estimate uses Ĩ. Leaves use their light's exact colour.
//
// Stopping rules (uErrorMode):
//   0 "node", the paper's: every node of the cut has upper ≤ ε · max(estimate).
//   1 "total": with B = Σ (upper − lower) over the cut, max(B) ≤ ε · max(estimate − B) or
//     max(B) ≤ kAbsoluteFloor; then every channel's error is ≤ ε × the pixel's largest true
//     channel (or the floor).
// How the cut is found: the paper keeps the cut in a priority queue and refines the node
// with the largest bound first. On llvmpipe a per-pixel array costs time in proportion to
// its capacity on every dynamic access, so instead each pass walks the implicit tree
// depth first without any stack, refining every node whose measure exceeds a threshold;
// passes tighten the threshold until the rule holds (see nodeRuleCut and totalRuleCut).
// The end condition is the rule itself; only the order of refinement differs, which
// matters where a cut reaches uMaxCut (those pixels are counted).
// llvmpipe also caps a shader's loop iterations (see kIterationBudget).
// The DISTANCE variant is the cheaper, unguaranteed criterion of the Lightcuts-in-UE4 work:
// refine a node while p lies within its radius of influence: uInfluence × half its box
// diagonal, around its box centre.
uniform sampler2D uPosition;
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
uniform sampler2D uSpecular;
uniform vec3 uEye;
uniform vec3 uForward;
uniform bool uOrthographic;
uniform float uError;     // ε
uniform int uErrorMode;   // 0 node, 1 total
uniform int uMaxCut;      // most nodes in a cut
uniform float uInfluence; // DISTANCE: radius of influence per half diagonal
uniform vec2 uColourSlack;  // η and ζ of the node colour coding

layout(location = 0) out vec4 oRadiance;
// x: cut size, y: light evaluations, z: node bound evaluations, w: glsl/variants.h's
// CutStatsKind (0 stays on background pixels).
layout(location = 1) out vec4 oCutStats;

const float kUnbounded = 3.0e38;

Surface s;

float maxOf(vec3 v) { return max(v.x, max(v.y, v.z)); }
int lightEvaluations = 0;
int nodeEvaluations = 0;

// Shading of light slot `rep` of tree `tree` per unit intensity.
vec3 unitTerm(int tree, int rep) {
  ++lightEvaluations;
  vec3 l;
  float e = unitIrradiance(tree, rep, s.position, s.normal, l);
  if (e == 0.0) return vec3(0.0);
#ifdef HAS_SPECULAR
  return brdf(s, l) * e;
#else
  return s.albedo * (e / kPi);
#endif
}

// Upper and lower bounds of node n's contribution (see the top of this file); the lower one
// only when `wantLower` (the node rule needs none). Returns false when the upper bound is
// unbounded (p inside the box).
// A spot node's cones, found by the CPU (cuts/tile_cuts.h, TileCutter::spotConeTexels): per
// internal node of the spot tree two texels, (cos of its lights' axes' spread about its axis, the
// widest cone's smoothstep scale and offset, the narrowest's scale), (the narrowest's offset,
// the largest 1/range², 0, 0).
uniform samplerBuffer uSpotCones;

// Bounds on the cone factor smoothstep(clamp(cos · scale + offset)) of any light of spot
// node n (node i of the spot tree) at p: above (.x) and below (.y), and the largest 1/range²
// of its lights (.z). cuts/lane_cones.h's spotConeLanes for a region of one point, which
// says why they hold: the cosine between a light's axis and its direction to p lies within
// [cos min(φ + α + σ, π), cos max(φ − α − σ, 0)], φ the angle between the node's axis and
// the direction from its box's centre to p, α the box's angular radius from p, σ the spread.
vec3 spotConeFactor(Node n, int i, vec3 p) {
  vec4 a = texelFetch(uSpotCones, 2 * i);
  vec4 b = texelFetch(uSpotCones, 2 * i + 1);
  vec3 toP = p - 0.5 * (n.boxMin + n.boxMax);
  float reach = 0.5 * length(n.boxMax - n.boxMin);
  float d = length(toP);
  // Within kSpotReachSlack · reach the angular radius is taken as 90° (spotConeLanes says why).
  bool inside = d <= reach * kSpotReachSlack;
  float sinA = min(reach / max(d, 1e-30), 1.0);
  float cosA = sqrt(max(1.0 - sinA * sinA, 0.0));
  float cosS = a.x;
  float sinS = sqrt(max(1.0 - cosS * cosS, 0.0));
  float cosB = cosA * cosS - sinA * sinS;  // β = α + σ; past π where its sine is negative
  float sinB = sinA * cosS + cosA * sinS;
  float cosF = clamp(dot(n.axis, toP) / max(d, 1e-30), -1.0, 1.0);
  float sinF = sqrt(max(1.0 - cosF * cosF, 0.0));
  bool wide = inside || sinB < 0.0;
  float top = wide || cosF >= cosB ? 1.0 : min(cosF * cosB + sinF * sinB + kSpotCosineMargin, 1.0);
  float bottom =
      wide || cosB <= -cosF ? -1.0 : max(cosF * cosB - sinF * sinB - kSpotCosineMargin, -1.0);
  float up = clamp(top * a.y + a.z, 0.0, 1.0);
  float low = clamp(bottom * a.w + b.x, 0.0, 1.0);
  return vec3(up * up * (3.0 - 2.0 * up), low * low * (3.0 - 2.0 * low), b.y);
}

bool nodeBounds(int tree, int i, Node n, bool wantLower, out vec3 upper, out vec3 lower) {
  ++nodeEvaluations;
  upper = vec3(0.0);
  lower = vec3(0.0);
  vec3 p = tree == 0 ? vec3(0.0) : s.position;
  vec3 nearest = clamp(p, n.boxMin, n.boxMax) - p;
  float d2Min = dot(nearest, nearest);
  if (tree != 0 && d2Min == 0.0) return false;
  vec3 farthest = max(abs(n.boxMin - p), abs(n.boxMax - p));
  float d2Max = dot(farthest, farthest);
  float dMin = sqrt(d2Min);
  vec2 sphere = sphereCosines(s.normal, p, n);
  float cosUp = min(cosineUpper(s.normal, p, n, dMin), sphere.x);
  if (cosUp <= 0.0) return true;
  float gUp = 1.0, gLow = wantLower ? 1.0 : 0.0;
  if (tree != 0) {
    gUp = window(d2Min, n.invRange2) / max(d2Min, kMinDistanceSquared);
    gLow = !wantLower ? 0.0 : window(d2Max, n.w2) / max(d2Max, kMinDistanceSquared);
    if (tree == 2) {  // a spot node's w2 is its cone's cos Θ, not a range
      if (!spotMayReach(n, p)) return true;
      vec3 cone = spotConeFactor(n, i, p);
      gUp *= cone.x;
      gLow = !wantLower ? 0.0 : cone.y * window(d2Max, cone.z) / max(d2Max, kMinDistanceSquared);
    }
  }
  vec3 m = s.albedo / kPi;
#ifdef HAS_SPECULAR
  if (s.specular != vec3(0.0)) {
    vec3 mirror = reflect(-s.view, s.normal);
    // Clamped: the sphere's cosine may be negative, and pow of a negative base is NaN.
    float rUp = clamp(min(cosineUpper(mirror, p, n, dMin), sphereCosines(mirror, p, n).x), 0.0, 1.0);
    m += s.specular * ((s.exponent + 2.0) / (2.0 * kPi) * pow(rUp, s.exponent));
  }
#endif
  float slack = uColourSlack.x * maxOf(n.intensity) + uColourSlack.y;
  upper = (n.intensity + slack) * m * (cosUp * gUp);
  // A bound that overflowed or went NaN bounds nothing (and max() would hide a NaN).
  if (any(isnan(upper)) || any(isinf(upper))) return false;
  if (gLow > 0.0) {
    float cosLow = max(cosineLower(s.normal, p, n, sqrt(d2Max)), sphere.y);
    lower = max(n.intensity - slack, 0.0) * (s.albedo / kPi) * (cosLow * gLow);
  }
  return true;
}

// A pass that fills the cut stops refining wherever the depth-first walk happens to be,
// leaving the rest of the tree coarse; the previous pass, complete at a looser threshold,
// is the better answer then. Both are counted as at the maximum.
vec3 keptEstimate;
int keptCut;
bool keptComplete = false;  // until the first pass is kept
float keptLargest;

// The result of one pass over the trees.
vec3 estimateSum;  // Σ of the cut's estimates (leaves exact)
vec3 errorSum;     // Σ of the cut's error bounds (upper − lower), bounded nodes only
int cutSize;
int unboundedNodes;  // nodes kept in the cut although unbounded (only when the cut is full)
float largestMeasure;  // the largest measure among the cut's bounded nodes
bool atMax;          // the cut could not be refined further for want of room

// Most recently computed representative term, reused when the next node shares it (a
// left child has its parent's representative half of the time).
int lastRepresentative = -1;
int lastTree = -1;
vec3 lastTerm;

vec3 representativeTerm(int tree, int rep) {
  if (rep != lastRepresentative || tree != lastTree) {
    lastTerm = unitTerm(tree, rep);
    lastRepresentative = rep;
    lastTree = tree;
  }
  return lastTerm;
}

// llvmpipe ends every loop of a shader invocation once all loops together have run 65,535
// iterations, silently (kIterationBudget, cuts/tile_cuts.h). A pass visits at most
// 2·uMaxCut nodes, one iteration each, so a pass starts only while the budget holds a full
// one; a pixel that runs out keeps its last complete pass and is counted as at the maximum.
int iterationsLeft = kIterationBudget;

bool passFits() { return iterationsLeft >= 2 * uMaxCut + 8; }

// One cut through every tree, depth first and without a stack (the implicit layout gives
// child and next node by arithmetic): a node is refined when `measure` of it exceeds tau and
// the cut has room (uMaxCut), otherwise it joins the cut with its estimate.
// measure: 0 the upper bound (node rule), 1 upper − lower (total rule), 2 the distance
// criterion (refine inside the radius of influence; tau unused).
void cutPass(float tau, int measure) {
  estimateSum = vec3(0.0);
  errorSum = vec3(0.0);
  cutSize = 0;
  unboundedNodes = 0;
  largestMeasure = 0.0;
  atMax = false;
  for (int tree = 0; tree < 3; ++tree) {
    int leaves = uTreeLeaves[tree];
    if (leaves == 0) continue;
    // Nodes are numbered h = i + 1 here: children 2h and 2h + 1, the root 1.
    int h = 1;
    int pending = 0;  // right siblings still to visit: nodes already promised to the cut
    while (true) {
      --iterationsLeft;
      int i = h - 1;
      Node n = fetchNode(tree, i);
      bool refine = false;
      if (n.representative >= 0 && i < leaves - 1) {
        bool wanted;
        vec3 error = vec3(0.0);
        bool bounded = true;
        if (measure == 2) {
          ++nodeEvaluations;
          vec3 p = tree == 0 ? vec3(0.0) : s.position;
          float radius = 0.5 * length(n.boxMax - n.boxMin) * uInfluence;
          vec3 toCentre = 0.5 * (n.boxMin + n.boxMax) - p;
          wanted = dot(toCentre, toCentre) < radius * radius;
        } else {
          vec3 upper, lower;
          bounded = nodeBounds(tree, i, n, measure == 1, upper, lower);
          error = measure == 0 ? upper : upper - lower;
          wanted = !bounded || maxOf(error) > tau;
        }
        if (wanted && cutSize + pending + 2 <= uMaxCut) {
          refine = true;
        } else {
          atMax = atMax || wanted;
          // Once a complete pass is kept, one that fills the cut is given up at once: its
          // pixel falls back on the kept pass (fallBackIfFull), so the rest would be thrown away.
          if (atMax && keptComplete) return;
          if (bounded) {
            errorSum += error;
            largestMeasure = max(largestMeasure, maxOf(error));
          } else {
            ++unboundedNodes;
          }
        }
      }
      if (refine) {
        h *= 2;
        ++pending;
        continue;
      }
      if (n.representative >= 0) {
        ++cutSize;
        estimateSum += representativeTerm(tree, n.representative) * n.intensity;
      }
      // Next: up past every level where this is a right child (h's trailing ones), then
      // across to the right sibling: (h + 1) with its trailing zeros shifted out. Back at
      // the root means the tree is done.
      int next = h + 1;
      h = next / (next & -next);
      if (h == 1) break;
      --pending;
    }
  }
}

void keepPass() {
  keptEstimate = estimateSum;
  keptCut = cutSize;
  keptComplete = !atMax;
  keptLargest = largestMeasure;
}

void fallBackIfFull() {
  if (atMax && keptComplete) {
    estimateSum = keptEstimate;
    cutSize = keptCut;
  }
}

// The stopping rule (uErrorMode) for a cut with estimate `estimate`: node, `largest` (the
// largest upper bound of its nodes) ≤ ε · max(estimate); total, with B = errorSum (the sum
// of its nodes' upper − lower), max(B) ≤ ε · max(estimate − B) or ≤ the absolute floor.
bool ruleHolds(float largest, vec3 errorSum, vec3 estimate) {
  if (uErrorMode == 0) return largest <= uError * maxOf(estimate);
  float b = maxOf(errorSum);
  return b <= uError * maxOf(estimate - errorSum) || b <= kAbsoluteFloor;
}

// Thresholds fall by at most kStep per pass, so the cut grows from its largest bounds
// down, much as the paper's priority order would grow it, and a pass that fills the cut
// falls back to a balanced one.
const float kStep = 32.0;

// Under the node rule, a pass at threshold `full` filled the cut. The kept pass, complete,
// may be up to kStep times coarser: narrowing in between, kNarrowPasses passes at the
// geometric mean of the finest complete threshold and the coarsest full one end within
// kStep^(1/2^kNarrowPasses) (2.4×) of the finest threshold whose cut fits. A pass among them
// that meets the rule ends the pixel's cut there, not at the maximum. Otherwise the pixel
// keeps the finest complete pass and stays counted as at the maximum. Not under the total
// rule: on 65,536 street lights, whose walks mostly reach the maximum (137,196 of 234,846
// pixels at 640×480, ε = 0.02), it took the frame from 9.1 to 20.3 s (the reference's 26 s).
const int kNarrowPasses = 2;
void narrowIfFull(float full) {
  float coarse = keptLargest;
  for (int k = 0; k < kNarrowPasses && keptComplete && full < coarse && passFits(); ++k) {
    float tau = sqrt(full * coarse);
    cutPass(tau, 0);
    if (atMax) {
      full = tau;
      continue;
    }
    if (ruleHolds(largestMeasure, errorSum, estimateSum)) return;
    keepPass();
    coarse = min(tau, largestMeasure);
  }
  atMax = true;
  fallBackIfFull();
}

// The node rule: every node of the cut has an upper bound ≤ ε × the pixel's estimate. Each
// pass refines against max(kUndershoot · ε × the previous estimate, the previous threshold
// / kStep) and stops once the largest upper bound in its cut is ≤ ε × its own estimate.
// Refining to ε × the previous estimate exactly, the rule often failed by a little against
// the pass's own estimate and a further pass of full size followed; undershooting to 0.8 ε
// trades slightly larger cuts for fewer passes (the least node bounds over 0.6 to 1.0).
const float kUndershoot = 0.8;
void nodeRuleCut() {
  cutPass(kUnbounded * 0.5, 0);  // the roots (and unbounded nodes below them)
  keepPass();
  float tau = largestMeasure;
  while (passFits()) {
    tau = max(kUndershoot * uError * maxOf(keptEstimate), tau / kStep);
    cutPass(tau, 0);
    if (atMax) {
      narrowIfFull(tau);
      return;
    }
    // The rule is about the cut's own bounds, which may all be below the threshold.
    if (ruleHolds(largestMeasure, errorSum, estimateSum)) return;
    keepPass();
  }
  atMax = true;  // out of loop iterations before the rule held
}

// The total rule: Σ (upper − lower) ≤ ε · (estimate − Σ (upper − lower)), or ≤ the absolute
// floor. Passes lower a common threshold on each node's error until the sum holds.
void totalRuleCut() {
  cutPass(kUnbounded * 0.5, 1);
  keepPass();
  float tau = largestMeasure;
  while (passFits()) {
    float b = maxOf(errorSum);
    float allowed = uError * maxOf(estimateSum - errorSum);
    tau *= clamp(0.5 * allowed / max(b, 1e-30), 1.0 / kStep, 0.5);
    cutPass(tau, 1);
    if (atMax) {
      fallBackIfFull();
      return;
    }
    if (unboundedNodes == 0 && ruleHolds(0.0, errorSum, estimateSum)) return;
    keepPass();
  }
  atMax = true;  // out of loop iterations before the rule held
}
