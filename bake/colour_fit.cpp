#include "bake/colour_fit.h"

#include <algorithm>
#include <cmath>

#include "base/text_table.h"

namespace manylight {

double PowerFit::operator()(double in) const { return a * std::pow(in, gamma); }

PowerFit fitPowerLaw(const std::vector<FitPair>& pairs) {
  // Sums about the means, for accuracy when the logs are large.
  double smallest = HUGE_VAL, largest = -HUGE_VAL;
  double mx = 0.0, my = 0.0;
  for (const FitPair& p : pairs) {
    if (!(p.in > 0.0) || !(p.out > 0.0) || !std::isfinite(p.in) || !std::isfinite(p.out)) {
      throw BakeError("cannot fit the pair (" + std::to_string(p.in) + ", " +
                      std::to_string(p.out) + "): both values must be finite and > 0");
    }
    smallest = std::min(smallest, p.in);
    largest = std::max(largest, p.in);
    mx += std::log(p.in);
    my += std::log(p.out);
  }
  if (!(smallest < largest)) throw BakeError("a power-law fit needs at least two different inputs");
  const double n = double(pairs.size());
  mx /= n;
  my /= n;
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (const FitPair& p : pairs) {
    const double dx = std::log(p.in) - mx, dy = std::log(p.out) - my;
    sxx += dx * dx;
    sxy += dx * dy;
    syy += dy * dy;
  }
  PowerFit fit;
  fit.pairs = pairs.size();
  fit.gamma = sxy / sxx;
  const double logA = my - fit.gamma * mx;
  fit.a = std::exp(logA);
  fit.log10A = logA / std::log(10.0);
  double residual = 0.0;
  for (const FitPair& p : pairs) {
    const double r = std::log(p.out) - logA - fit.gamma * std::log(p.in);
    residual += r * r;
    fit.worstRelative = std::max(fit.worstRelative, std::abs(fit(p.in) - p.out) / p.out);
  }
  fit.r2 = syy > 0.0 ? 1.0 - residual / syy : 1.0;
  return fit;
}

std::vector<FitPair> readFitPairs(const std::string& path) {
  const std::string text = readTextFile(path, std::uintmax_t(1) << 30);
  const std::vector<TextLine> lines = contentLines(text);  // views into text
  std::vector<FitPair> pairs;
  for (const TextLine& line : lines) {
    const std::vector<std::string_view> f = splitFields(line.text);
    const std::string where = path + ":" + std::to_string(line.number) + ": ";
    if (&line == &lines.front() && f.size() == 2 && f[0] == "in" && f[1] == "out") continue;
    if (f.size() != 2)
      throw SceneError(where + "expected 2 fields (in,out), got " + std::to_string(f.size()));
    FitPair p;
    if (!parseNumber(f[0], p.in) || !parseNumber(f[1], p.out)) {
      throw SceneError(where + "expected two numbers, got '" + std::string(line.text) + "'");
    }
    if (!(p.in > 0.0) || !(p.out > 0.0))
      throw SceneError(where + "both values must be > 0 to be fitted in log space");
    pairs.push_back(p);
  }
  if (pairs.empty()) throw SceneError(path + ": no pairs");
  return pairs;
}

}  // namespace manylight
