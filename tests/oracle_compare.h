#pragma once
// The GPU's image against the CPU oracle's (tests/oracle.h), with the thresholds every
// oracle test shares (tests/oracle_compare.cpp says why they are what they are).
#include <string>

#include "render/render_job.h"
#include "scene/scene.h"

namespace manylight::testing {

// Renders `request` on the GPU and with the oracle (using the scene's lights, or the rig the
// GPU used), expects them to agree at interior pixels, and returns the GPU outcome.
RenderOutcome expectMatchesOracle(const Scene& scene, const RenderRequest& request,
                                  const std::string& name);

}  // namespace manylight::testing
