// Stage F, curves drawn as curves (issue 20, beyond the documents; output only): after the output
// simplification a curved road is a polygon of a few vertices, each turning 20-40 degrees, where the
// road itself bends smoothly. Every piece of a segment whose two ends turn the same way (a run of a
// curve, not a zigzag or a lone kink, and not the first or last piece of the segment, whose end nodes
// have no turn of their own) is redrawn on the centripetal Catmull-Rom spline through the segment's
// vertices: the spline passes through every vertex, so the vertices of the simplified line stay where
// they are, and between them it follows the curve the vertices describe. It is flattened (points
// inserted by halving the piece) until every chord lies within `tolerance` pw of the spline.
#pragma once

#include <cstddef>
#include <cstdint>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/vectorize/roads/road_network.hpp"

namespace urbanvec::vectorize {

struct CurveDrawingOptions {
  /// [INFERENCE, beyond the documents] Largest distance (pw) between the drawn chords and the spline;
  /// 0 = the simplified polylines as they are. 0.02 pw (16 cm on an 8 m grid) draws a curve as a
  /// curve at any scale a map is read at; measured in docs/vectorize.md ("Curves drawn as curves, straight
  /// roads between ends off their line").
  double tolerance = 0.02;
  /// Halvings of a piece at most (2^6 = 64 chords per piece).
  int maxDepth = 6;
};

struct CurveDrawingStats {
  std::size_t segments = 0;  ///< segments with at least one piece redrawn
  std::size_t points = 0;    ///< spline points inserted
  std::size_t restored = 0;  ///< segments given back their polyline (a touch or an uncovered road cell)
};

/// `line` with its curved pieces (both ends turning the same way) redrawn on the centripetal
/// Catmull-Rom spline through its vertices, within `tolerance` pw; its vertices are kept.
LineString drawCurve(const LineString& line, const CurveDrawingOptions& options);

/// drawCurve on every primary and secondary segment of `network` (perimeters keep their lines). A
/// segment whose drawn line would touch another segment (anywhere but at a shared end node), or leave a
/// road cell of `landUse` (not kRemovedRoad in `cleaned`) farther than `coverDistance` pw from every
/// road that the polylines covered, keeps its polyline.
CurveDrawingStats drawCurves(RoadNetwork& network, const Grid<std::uint8_t>& landUse,
                             const Grid<std::uint8_t>& cleaned, const CurveDrawingOptions& options,
                             double coverDistance = 1.5);

}  // namespace urbanvec::vectorize
