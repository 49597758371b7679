// Dimension estimates and regression, spec wijgerse-boundary.md §6.3-§6.5 (thesis Eqs. 4.1-4.13).
#include "urbanvec/shape/fractal_regression.hpp"

#include <algorithm>
#include <cmath>

#include "urbanvec/core/error.hpp"

namespace urbanvec::shape {

FractalRegression fractalRegression(const std::vector<double>& chordCounts,
                                    const std::vector<double>& meanChords,
                                    std::optional<double> evaluationLogChord) {
  if (chordCounts.size() != meanChords.size() || chordCounts.empty())
    throw invalidInput("the fractal regression needs one chord count per mean chord length");
  FractalRegression result;
  const double logCount0 = std::log(chordCounts[0]);
  for (size_t n = 1; n < chordCounts.size(); ++n) {
    const double logRatio = std::log(meanChords[n] / meanChords[0]);
    if (!(logRatio > 0.0) || !(chordCounts[n] > 0.0)) continue;
    result.logChord.push_back(std::log(meanChords[n]));
    result.dimensions.push_back((logCount0 - std::log(chordCounts[n])) / logRatio);
  }
  const size_t points = result.dimensions.size();
  if (points < 2) throw invalidInput("the fractal regression needs at least 2 usable chord lengths");
  double meanX = 0.0;
  double meanY = 0.0;
  for (size_t i = 0; i < points; ++i) {
    meanX += result.logChord[i];
    meanY += result.dimensions[i];
  }
  meanX /= points;
  meanY /= points;
  double sxx = 0.0;
  double sxy = 0.0;
  for (size_t i = 0; i < points; ++i) {
    sxx += (result.logChord[i] - meanX) * (result.logChord[i] - meanX);
    sxy += (result.logChord[i] - meanX) * (result.dimensions[i] - meanY);
  }
  result.slope = sxx > 0.0 ? sxy / sxx : 0.0;
  result.intercept = meanY - result.slope * meanX;
  double residual2 = 0.0;
  for (size_t i = 0; i < points; ++i) {
    const double d = result.dimensions[i] - (result.slope * result.logChord[i] + result.intercept);
    residual2 += d * d;
  }
  result.sigma = std::sqrt(residual2 / points);
  const auto [lo, hi] = std::minmax_element(result.logChord.begin(), result.logChord.end());
  result.logChordSpan = *hi - *lo;
  result.evaluationLogChord = evaluationLogChord.value_or(meanX);
  result.comparableDimension = result.slope * result.evaluationLogChord + result.intercept;
  return result;
}

}  // namespace urbanvec::shape
