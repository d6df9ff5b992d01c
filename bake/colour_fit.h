#pragma once
// Power-law fits C = A·c^γ by least squares on log C = log A + γ·log c: the job the
// Lightcuts-in-UE4 work did by hand to match its light-tree path to the engine's
// point-light path. Here it picks the decode curve of compact node colours
// (bake/node_colour.h) and backs `manylight fit-gamma`. No GL.
#include <cstddef>
#include <string>
#include <vector>

#include "base/error.h"

namespace manylight {

// Thrown by bake/: data that cannot be fitted or packed.
class BakeError : public Error {
 public:
  using Error::Error;
};

struct FitPair {
  double in = 0.0, out = 0.0;  // both > 0
};

struct PowerFit {
  double gamma = 1.0;
  double a = 1.0;
  double log10A = 0.0;
  double r2 = 1.0;             // of the fit in log–log space
  double worstRelative = 0.0;  // max |A·in^γ − out| / out over the pairs
  std::size_t pairs = 0;

  double operator()(double in) const;
};

// Throws BakeError when a pair is not positive and finite, or fewer than two different
// inputs leave γ undetermined.
PowerFit fitPowerLaw(const std::vector<FitPair>& pairs);

// Reads in,out pairs, one per line; a header line "in,out" is allowed. Throws SceneError
// "PATH:LINE: problem".
std::vector<FitPair> readFitPairs(const std::string& path);

}  // namespace manylight
