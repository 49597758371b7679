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

/// The absolute turning angle at each interior vertex, in degrees (repeated points skipped), in order.
std::vector<double> vertexTurns(const LineString& line);

/// Turning per km split by the size of each vertex's turn (issue 20): entry i holds the degrees of the
/// turns of at least edges[i-1] and less than edges[i] degrees (entry 0 from 0, the last entry
/// without an upper edge), per km of all the lines; `edges` ascending. All zero for lines of no length.
std::vector<double> turningPerKmByBend(const std::vector<LineString>& lines,
                                       const std::vector<double>& edges);

}  // namespace urbanvec::evaluate
