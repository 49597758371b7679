// Road metrics of the evaluator (issue 2 §3, "road centreline distance" and "road smoothness"):
// centreline sampling, nearest-centreline distances through a GEOS STRtree, and turning per length.
#pragma once

#include <cstddef>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/layer.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/evaluate/evaluate.hpp"

namespace urbanvec::evaluate {

/// The centrelines of a road layer: multi-lines split into parts, features whose class is excluded
/// (options.excludedRoadClasses, compared case-insensitively) and lines of fewer than two points left
/// out. `featureCount` receives the number of road features kept.
std::vector<LineString> roadCentrelines(const Layer& roads, const EvaluateOptions& options,
                                        std::size_t* featureCount = nullptr);

/// Points along the lines, one at the middle of each of max(1, round(L / spacing)) equal pieces of a
/// line of length L, so every piece of road weighs the same and shared end points are not doubled.
std::vector<Vec2> samplePoints(const std::vector<LineString>& lines, double spacing);

/// Distance from each point to the nearest of the lines (any point of any segment).
std::vector<double> nearestDistances(const std::vector<Vec2>& points, const std::vector<LineString>& lines,
                                     const Progress& progress = {});

/// Linear-interpolated quantile (q in [0, 1]) of unsorted values, as numpy's default; values non-empty.
double quantile(std::vector<double> values, double q);

DistanceSummary summariseDistances(const std::vector<double>& distances, double cellSize);

/// Sum over the interior vertices of the absolute turning angle, in degrees (repeated points skipped).
double turningDegrees(const LineString& line);

/// Degrees of turning per km of lines whose coordinates are in metres; 0 for lines of no length.
double turningPerKm(const std::vector<LineString>& lines);

}  // namespace urbanvec::evaluate
