// Realism test, spec wijgerse-boundary.md §8 (thesis §4.4.1, Eqs. 4.10-4.11, 2.20).
#include "urbanvec/shape/shape_metrics.hpp"

#include <cmath>

#include "urbanvec/core/error.hpp"

namespace urbanvec::shape {

ShapeMetrics measureShape(const Ring& ring, const ShapeMetricOptions& options) {
  ShapeMetrics metrics;
  metrics.walk = structuredWalk(ring, options.walk);
  std::vector<double> counts;
  std::vector<double> means;
  for (const WalkScale& s : metrics.walk.scales) {
    if (s.chordCount < options.minimumChordCount) break;
    counts.push_back(s.chordCount);
    means.push_back(s.meanChord);
  }
  if (counts.size() >= 3) {
    try {
      metrics.regression = fractalRegression(counts, means, options.evaluationLogChord);
    } catch (const Error&) {
      metrics.regression.reset();  // degenerate scales: no dimension, reported as missing
    }
  }
  if (metrics.regression) {
    const FractalRegression& r = *metrics.regression;
    metrics.dimensionRealistic = r.comparableDimension > options.minimumDimension &&
                                 r.comparableDimension < options.maximumDimension &&
                                 std::abs(r.slope) <= options.maximumSlope && r.sigma <= options.maximumSigma;
  }
  metrics.enclosed = enclosedArea(ring);
  metrics.areaRealistic = metrics.enclosed.ratio >= options.minimumEnclosedAreaRatio;
  return metrics;
}

}  // namespace urbanvec::shape
