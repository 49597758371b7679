// Realism of a boundary: structured-walk fractal dimension and enclosed-area ratio with the thesis's
// validity rules, for any closed ring (spec wijgerse-boundary.md §8, thesis §4.4.1).
#pragma once

#include <optional>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/shape/enclosed_area.hpp"
#include "urbanvec/shape/fractal_regression.hpp"
#include "urbanvec/shape/structured_walk.hpp"

namespace urbanvec::shape {

struct ShapeMetricOptions {
  StructuredWalkOptions walk;
  /// R, the natural log of the chord length (ring units) at which the regression line is read to give
  /// D_R. The thesis's 2.5696 is the mean ln r_n of its 512-pixel hulls, i.e. in pixel units; empty =
  /// the mean ln r_n of the shape itself, the same rule applied to any unit.
  std::optional<double> evaluationLogChord = 2.5696;
  /// Scales whose mean number of chords N_n (leftover included) falls below this are left out of the
  /// regression: the chord is then comparable to the shape itself and says nothing about its detail.
  /// The thesis's hulls never come near it (Table 4.1: N_11 = 25.6) [INF].
  double minimumChordCount = 3.0;
  /// Realistic D_R lies strictly between these (Batty & Longley's cities: 1.18 < D_R < 1.28, Eq. 4.10).
  double minimumDimension = 1.18;
  double maximumDimension = 1.28;
  /// Largest |a| for a "constant" dimension: 0.10 / 3.429, the mean ln r span of the thesis (Eq. 4.11).
  double maximumSlope = 0.02916;
  /// Largest scatter sigma of the D_n around the regression line (thesis: 0.02).
  double maximumSigma = 0.02;
  /// Smallest realistic enclosed-area ratio: a 200 m x 4 km village gives 0.0635 (Eq. 2.20).
  double minimumEnclosedAreaRatio = 0.0635;
};

struct ShapeMetrics {
  StructuredWalk walk;
  /// Empty when fewer than 2 chord lengths were usable (the shape is too small for the chords).
  std::optional<FractalRegression> regression;
  EnclosedArea enclosed;
  bool dimensionRealistic = false;  ///< D_R in range, |a| and sigma small enough
  bool areaRealistic = false;       ///< enclosed-area ratio large enough
  bool realistic() const { return dimensionRealistic && areaRealistic; }
};

/// Measures one closed ring. Throws InvalidInput for fewer than 3 distinct vertices.
ShapeMetrics measureShape(const Ring& ring, const ShapeMetricOptions& options);

}  // namespace urbanvec::shape
