// Geometric adjustment of the cleaned linework (beyond the thesis, issue 17): once the topology is
// known, every vertex is placed by a least-squares fit to all the drawn copies of its segment ends
// instead of their plain mean, with soft constraints for straight lines and right angles.
#pragma once

#include <cstddef>
#include <vector>

#include "urbanvec/cadastre/linework.hpp"

namespace urbanvec::cadastre {

struct AdjustmentOptions {
  /// A vertex whose two segments make an angle within this many degrees of 180 lies on one straight
  /// line (a split line, a T-junction, the edges of neighbouring parcels and buildings continuing
  /// each other): kept on the line of its two neighbours by a soft constraint. 0 disables.
  double straightAngle = 10.0;
  /// Two segments at a vertex making an angle within this many degrees of 90 are held square by a
  /// soft constraint (cadastral buildings are mostly rectilinear); other angles are left alone. 0
  /// disables.
  double rightAngle = 10.0;
  /// Either constraint is set only where the noise explains the departure from the ideal shape: the
  /// middle vertex within `reach` noise units of the line of its neighbours, the end of the shorter
  /// arm within `reach` noise units of square.
  double reach = 1.0;
  /// Standard deviation (m) of a straight vertex off the line of its neighbours, and of the end of
  /// the shorter arm of a near-right angle off square: how strongly the constraints hold against the
  /// drawn copies.
  double straightSigma = 0.03;
  double rightSigma = 0.06;
  /// Huber threshold, in noise units, on a copy's residual along its own segment (over- and
  /// undershoots move an end along its line, not across it).
  double huber = 1.5;
  /// Reweighted least-squares rounds (2 to 5 give the same scores on the sample within 0.004).
  int iterations = 2;
  /// A vertex moving farther than this (m) from its mean keeps the mean (a safeguard).
  double maxShift = 0.5;
};

struct AdjustmentStats {
  double noise = 0.0;  ///< estimated standard deviation of a drawn copy across its segment (m)
  std::size_t straightConstraints = 0, rightConstraints = 0;
  std::size_t verticesMoved = 0;  ///< vertices moved by more than 1 mm
  std::size_t shiftsRefused = 0;  ///< vertices kept at their mean by maxShift
};

/// The drawing's noise (m): the robust standard deviation of the drawn copies across their own segments
/// around their vertex (1.4826 times the median residual, scaled for the copies that made the mean);
/// under 1 mm when the copies coincide (a clean drawing).
double copyNoise(const Linework& linework);

/// Below this noise estimate (m) the drawing is clean (its copies coincide).
constexpr double kCleanNoise = 1e-3;

/// The positions of `linework.vertices` at the least-squares fit of `linework.copies`: each copy observes its
/// vertex across its own segment with full weight and along it with a Huber weight (an over- or
/// undershot end is off along its line only), plus the soft straight and right-angle constraints
/// chosen on the vertices' initial positions. Observations are weighted by the drawing's noise
/// estimated from the copies' spread across their segments; a clean drawing (estimate under 1 mm:
/// most copies coincide) is returned unchanged. Deterministic; does nothing without copies.
std::vector<Vec2> adjustedVertices(const Linework& linework, const AdjustmentOptions& options,
                                   AdjustmentStats& stats);

}  // namespace urbanvec::cadastre
