#pragma once
// Which lights get reflective shadow maps (render/rsm.h) in a frame of `--indirect`: the spot
// and directional lights that send the most flux into the view, weighed over a sample of the
// frame's covered pixels (measureLightFlux, on the CPU).
#include <glm/glm.hpp>
#include <vector>

#include "scene/scene.h"

namespace manylight {

// The lights given maps for one frame and what they cover.
struct RsmChoice {
  std::vector<int> lights;  // scene indices: those kept from the frame before, then by flux
  int candidates = 0;       // spot and directional lights
  int belowShare = 0;       // of the `count` largest, those passed over for their small share
};

// Pixels the choice wants, on a regular grid over the covered pixels: 256, or fewer (down to
// 32) where lights × samples would pass kRsmChoiceEvaluations. The grid's step is rounded
// down, so up to twice as many are taken.
inline constexpr int kRsmChoiceSamples = 256;
inline constexpr int kRsmChoiceMinSamples = 32;
inline constexpr double kRsmChoiceEvaluations = 1 << 22;

struct RsmSamples {
  std::vector<glm::vec3> position, normal;  // normals of unit length
};

// The samples for `lights` lights, from a G-buffer read back as RGBA floats (`position`,
// `normal`; normal.w 0 off the geometry).
RsmSamples sampleRsmChoice(const std::vector<float>& position, const std::vector<float>& normal,
                           std::size_t lights);

// The `count` spot and directional `lights` of the largest `flux` (per light, scene order: Σ
// over the samples of the luminance of its irradiance); ties go to the lower index. But the
// lights of the frame before's choice, `previous`, keep their places (in its order) while
// their flux is at least kRsmChoiceKeep × the weakest of the `count` largest: a playback
// whose view changes a little keeps its maps and caches, instead of trading lights whose
// flux differs by the sampling's noise. A light whose flux is under `leastShare` × Σ `flux`
// (every light's, points too) gets no map, whatever its rank (kRsmLeastShare), but a light of
// `previous` keeps its map down to kRsmChoiceKeep × that, so that a light about the least
// share does not gain and lose its map from frame to frame. Where Σ `flux` is 0 (a view the
// lights do not reach) every light has the share.
RsmChoice chooseRsmLights(const std::vector<Light>& lights, const std::vector<double>& flux,
                          int count, const std::vector<int>& previous = {},
                          double leastShare = 0.0);
inline constexpr double kRsmChoiceKeep = 0.5;
// The default least share (`--rsm-least-share`). A light's bounce is its flux reflected once:
// at most its albedo-weighted share of the light the view receives, spread over the surfaces
// it reaches. Under 0.1%, the maps' cost buys light no 8-bit image shows on average: among
// 65,536 lights of like power every light's share is about 1/65,536, and their maps would
// carry 0.002% of the view's light (the generated room: docs/indirect.md).
inline constexpr double kRsmLeastShare = 1e-3;

// The share of Σ `flux` that the `chosen` lights have; 1 where the sum is 0. Of the means
// RsmFluxHistory holds (a single frame's measureLightFlux in a single render), it is the
// chosen lights' share of the direct flux the view receives (of Σ over the sampled pixels of
// every light's irradiance, luminance), `--stats`'s rsm_flux_share.
double fluxShare(const std::vector<int>& chosen, const std::vector<double>& flux);

// The flux the frames so far measured, frame after frame of one renderer, as a weighted mean
// per light in which each frame's flux counts kRsmChoiceMemory^age: the choice
// (chooseRsmLights) ranks lights by what they sent into the last few views rather than into
// one. A light of small reach meets few of a frame's samples, or none, and one frame's
// measure ranks it by the samples' placement; a playback whose choice followed that would
// render new maps and caches every frame, and its indirect light would change with them. A light's
// mean starts again from its frame's flux when the light changes (moves, or changes colour,
// intensity, range or cone), and every light's when their count does: a light that changes every
// frame is ranked by its latest.
// A frame need not measure every light (due): each light is measured every kRsmChoiceStride
// frames in turn, and at once when it changes or has no mean; a light measured in turn
// weighs its mean kRsmChoiceMemory^kRsmChoiceStride, so the mean still holds about the last
// ten frames' views, and one not measured keeps its mean.
class RsmFluxHistory {
 public:
  // Per light of `lights`, whether this frame measures it (1) or keeps its mean (0).
  std::vector<char> due(const std::vector<Light>& lights) const;
  // Adds a frame's `flux` (per light of `lights`, scene order), of the lights `measured` says
  // (from due; null: every light, each frame's flux weighed kRsmChoiceMemory^age), and
  // returns the means.
  const std::vector<double>& add(const std::vector<Light>& lights, const std::vector<double>& flux,
                                 const std::vector<char>* measured = nullptr);

 private:
  std::vector<Light> lights_;
  std::vector<double> sum_, weight_, mean_;
  long long frames_ = 0;  // added since the lights' count last changed
};
// Weight of the frame before against this one's: the mean holds about the last ten frames.
inline constexpr double kRsmChoiceMemory = 0.9;
// A light measured in turn every this many frames: a frame of a playback evaluates a quarter
// of lights × samples, and a light's mean still follows the last ten or so views.
inline constexpr int kRsmChoiceStride = 4;

// Per light of `lights` (scene order): Σ over `samples` of the luminance of its irradiance
// (shading::irradiance's, in float, as the shaders evaluate it); 0 for a light `which` (if
// given) leaves out. A point or spot light of a range whose box holds under an eighth of the
// samples, binned in a grid over them, reads the samples of the cells its box overlaps only;
// the others read every sample.
std::vector<double> measureLightFlux(const std::vector<Light>& lights, const RsmSamples& samples,
                                     const std::vector<char>* which = nullptr);

}  // namespace manylight
