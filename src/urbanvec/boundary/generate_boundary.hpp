// A realistic city boundary from two-dimensional Perlin noise, after Wijgerse (2007): noise, radial
// transformation, threshold method 4, contour trace, realism test, regenerate until realistic
// (spec wijgerse-boundary.md §1 and §9.6).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "urbanvec/boundary/contour_trace.hpp"
#include "urbanvec/boundary/fill_threshold.hpp"
#include "urbanvec/boundary/perlin_noise.hpp"
#include "urbanvec/boundary/radial_transform.hpp"
#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/shape/shape_metrics.hpp"

namespace urbanvec::boundary {

struct BoundaryOptions {
  PerlinOptions noise;
  RadialTransformOptions transform;
  FillThresholdOptions threshold;
  ContourTraceOptions trace;
  /// Realism test in pixel units: evaluation point R = 2.5696 and the thesis's bounds.
  shape::ShapeMetricOptions realism;
  /// Seed of the first try; later tries use seeds derived from it (thesis seeds are 32-bit).
  PerlinSeed seed = 1;
  /// Bitmaps to generate at most: a threshold below the rim (method 4) or, with `validate`, an
  /// unrealistic hull starts over with new noise. The thesis recommends 3 (0.27^3 < 2 % all fail).
  int maxTries = 3;
  /// Regenerate unrealistic hulls (thesis §7.2); without it only threshold failures regenerate.
  bool validate = true;
  /// Also keep the other islands of at least this many pixels as suburbs; 0 = only the city (thesis).
  double suburbMinimumPixels = 0.0;
};

/// One bitmap: everything the thesis's work result records, and the hull when there is one.
struct BoundaryAttempt {
  PerlinSeed seed = 0;
  FillThreshold threshold;
  double fillRatio = 0.0;    ///< filled pixels / all pixels after thresholding (all islands)
  Grid<std::uint8_t> mask;   ///< the thresholded bitmap: 1 filled
  std::vector<Pixel> chain;  ///< the longest trace; empty when the threshold failed
  std::optional<shape::ShapeMetrics> metrics;  ///< realism of the chain, in pixel units
  bool hasHull() const { return !chain.empty(); }
  bool realistic() const { return metrics && metrics->realistic(); }
};

/// Generates and measures one bitmap from `seed` (no regeneration): the unit of the thesis's experiment.
BoundaryAttempt attemptBoundary(const BoundaryOptions& options, PerlinSeed seed);

/// The chain as a closed ring through pixel centres (pixel (c, r) covers [c, c+1] x [r, r+1]), without
/// the vertices inside straight runs: the geometry is unchanged, but the mean segment length l0 (the
/// structured walk's base chord) becomes about 1.6 pixels as in the thesis's Table 4.1 (l0 = 1.582,
/// impossible for a raw 8-connected chain whose steps are 1 or 1.414; spec §5.5). This is the ring
/// the realism metrics measure; docs/boundary.md gives the measurement.
Ring ringThroughCentres(const std::vector<Pixel>& chain);

/// Seed of try `index` (0-based) of a run: the run seed itself first, then derived seeds.
PerlinSeed trySeed(PerlinSeed runSeed, int index);

struct BoundaryResult {
  BoundaryAttempt attempt;  ///< the bitmap kept: the first realistic one, else the last with a hull
  int tries = 0;            ///< bitmaps generated
  /// The chain as a ring through pixel centres (what the realism metrics measured), in the pixel
  /// frame: x to the right, y downwards, pixel (c, r) covering [c, c+1] x [r, r+1]. Closed.
  Ring ring;
  /// The city as one valid polygon in the same frame: the outline of its pixels (cell_outline.hpp).
  Polygon city;
  /// Outlines of the other islands kept as suburbs, largest first.
  std::vector<Polygon> suburbs;
};

/// Runs the generator. Throws InvalidOption when the options are out of range and InvalidInput when
/// no try produced a hull (every threshold fell below the rim).
BoundaryResult generateBoundary(const BoundaryOptions& options, const Progress& progress = {});

}  // namespace urbanvec::boundary
