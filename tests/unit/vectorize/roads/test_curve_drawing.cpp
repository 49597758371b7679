// Stage F, curves drawn as curves (issue 20): drawCurve and drawCurves on hand-made lines with known
// answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "urbanvec/vectorize/roads/curve_drawing.hpp"

using namespace urbanvec;
using namespace urbanvec::vectorize;

namespace {

/// Largest turn (degrees) at a vertex of the line.
double largestTurn(const LineString& l) {
  double worst = 0;
  for (std::size_t i = 1; i + 1 < l.size(); ++i) {
    const Vec2 a = l[i] - l[i - 1], b = l[i + 1] - l[i];
    worst = std::max(worst, std::atan2(std::fabs(cross(a, b)), dot(a, b)) * 180 / M_PI);
  }
  return worst;
}

/// `n` + 1 vertices on a circle of radius r from angle 0 to `degrees`.
LineString arc(double r, double degrees, int n) {
  LineString l;
  for (int k = 0; k <= n; ++k) {
    const double a = degrees * M_PI / 180 * k / n;
    l.push_back({r * std::cos(a), r * std::sin(a)});
  }
  return l;
}

}  // namespace

TEST(CurveDrawing, ArcDrawnWithFewVerticesBecomesSmoothAndKeepsItsVertices) {
  // A quarter circle of radius 6 pw drawn with 4 pieces: every inner vertex turns 22.5 degrees.
  const LineString coarse = arc(6, 90, 4);
  ASSERT_NEAR(largestTurn(coarse), 22.5, 1e-9);
  const LineString drawn = drawCurve(coarse, {});
  // Only the two inner pieces have a turning vertex at both ends; they gain points on the spline.
  EXPECT_GT(drawn.size(), coarse.size());
  std::size_t kept = 0;
  for (const Vec2& v : coarse)
    for (const Vec2& w : drawn) kept += v == w;
  EXPECT_EQ(kept, coarse.size());
  EXPECT_EQ(drawn.front(), coarse.front());
  EXPECT_EQ(drawn.back(), coarse.back());
  // The inserted points bulge outwards from the chords towards the circle, never past it by much.
  for (const Vec2& w : drawn) {
    EXPECT_GT(length(w), 6 * std::cos(M_PI / 16) - 1e-9);
    EXPECT_LT(length(w), 6.0 + 0.02);
  }
  // The sharpest vertex left turns at most 2/3 of the coarse line's (the end vertices keep theirs
  // partly: the first and last pieces have no turn at their node end).
  EXPECT_LT(largestTurn(drawn), 15.0);
}

TEST(CurveDrawing, ZigzagLoneKinkAndEndPiecesAreLeftAlone) {
  // Alternating turns: a zigzag is no curve.
  const LineString zigzag{{0, 0}, {1, 0.3}, {2.5, 0}, {3, 0.5}, {4.5, 0}, {5, 0.3}};
  EXPECT_EQ(drawCurve(zigzag, {}), zigzag);
  // One kink between straight runs: its pieces have a straight (turn-free) end.
  const LineString kink{{0, 0}, {1, 0}, {2, 0}, {3, 1}, {4, 2}, {5, 3}};
  EXPECT_EQ(drawCurve(kink, {}), kink);
  // Three vertices: the only pieces are end pieces.
  const LineString three = arc(5, 60, 2);
  EXPECT_EQ(drawCurve(three, {}), three);
  // Tolerance 0 draws the polyline.
  CurveDrawingOptions off;
  off.tolerance = 0;
  EXPECT_EQ(drawCurve(arc(6, 90, 4), off), arc(6, 90, 4));
}

TEST(CurveDrawing, FinerToleranceInsertsMorePoints) {
  const LineString coarse = arc(10, 120, 5);
  CurveDrawingOptions coarseTol, fineTol;
  coarseTol.tolerance = 0.1;
  fineTol.tolerance = 0.005;
  EXPECT_LT(drawCurve(coarse, coarseTol).size(), drawCurve(coarse, fineTol).size());
}

TEST(CurveDrawing, SegmentThatWouldTouchAnotherKeepsItsPolyline) {
  // Two roads: a coarse arc and a straight road touching the arc's outer side at the middle of an
  // inner piece's spline bulge; drawn, the arc would reach the straight road, so it stays a polyline.
  RoadNetwork net;
  const LineString coarse = arc(6, 90, 4);
  net.nodes = {{coarse.front(), NetworkNodeKind::DeadEnd, 1}, {coarse.back(), NetworkNodeKind::DeadEnd, 1}};
  NetworkSegment curved;
  curved.points = coarse;
  curved.fromNode = 0;
  curved.toNode = 1;
  net.segments.push_back(curved);
  const LineString drawn = drawCurve(coarse, {});
  // The inserted point of the drawn arc farthest from the centre, and a road just inside it there,
  // outside the polyline (whose vertices all lie nearer the centre along that direction).
  Vec2 far(0, 0);
  for (const Vec2& w : drawn)
    if (std::find(coarse.begin(), coarse.end(), w) == coarse.end() && length(w) > length(far)) far = w;
  const Vec2 out = far / length(far);
  const Vec2 along(-out.y, out.x);
  const Vec2 at = out * (length(far) - 0.001);
  net.nodes.push_back({at - along, NetworkNodeKind::DeadEnd, 1});
  net.nodes.push_back({at + along, NetworkNodeKind::DeadEnd, 1});
  NetworkSegment straight;
  straight.points = {at - along, at + along};
  straight.fromNode = 2;
  straight.toNode = 3;
  net.segments.push_back(straight);
  const Grid<std::uint8_t> none;
  RoadNetwork drawnNet = net;
  const CurveDrawingStats s = drawCurves(drawnNet, none, none, {});
  EXPECT_EQ(s.segments, 1u);
  EXPECT_EQ(s.restored, 1u);
  EXPECT_EQ(drawnNet.segments[0].points, coarse);
  // Without the other road the arc is drawn.
  net.segments.pop_back();
  net.nodes.resize(2);
  const CurveDrawingStats alone = drawCurves(net, none, none, {});
  EXPECT_EQ(alone.restored, 0u);
  EXPECT_EQ(net.segments[0].points, drawn);
}
