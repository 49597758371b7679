// Street-network metrics (issue 18) on networks with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "urbanvec/core/error.hpp"
#include "urbanvec/streets/street_metrics.hpp"

using namespace urbanvec;
using namespace urbanvec::streets;

namespace {

/// n x n streets 100 m apart, each overhanging the last crossing by `overhang` metres.
std::vector<LineString> gridStreets(int n, double overhang) {
  std::vector<LineString> lines;
  const double lo = -overhang, hi = (n - 1) * 100.0 + overhang;
  for (int i = 0; i < n; ++i) {
    lines.push_back({{i * 100.0, lo}, {i * 100.0, hi}});
    lines.push_back({{lo, i * 100.0}, {hi, i * 100.0}});
  }
  return lines;
}

}  // namespace

TEST(StreetMetrics, PerfectGridHasEntropyLn4AndOrderOne) {
  const StreetMetrics m = measureStreets(gridStreets(6, 50.0), {});
  EXPECT_NEAR(m.orientationEntropy, std::log(4.0), 1e-12);
  EXPECT_NEAR(m.orientationOrder, 1.0, 1e-12);
  // 36 crossings (4-way) and 24 ends.
  EXPECT_EQ(m.nodes, 60u);
  EXPECT_NEAR(m.share4Way, 36.0 / 60.0, 1e-12);
  EXPECT_NEAR(m.shareDeadEnd, 24.0 / 60.0, 1e-12);
  EXPECT_EQ(m.share3Way, 0.0);
  // Edges: 6 streets x 5 inner blocks x 2 directions + 24 overhangs.
  EXPECT_EQ(m.edges, 84u);
  EXPECT_NEAR(m.averageDegree, 2.0 * 84 / 60, 1e-12);
  EXPECT_NEAR(m.circuity, 1.0, 1e-12);
  EXPECT_NEAR(m.medianEdgeLength, 100.0, 1e-9);
}

TEST(StreetMetrics, UniformBearingsHaveMaximalEntropyAndOrderZero) {
  // 360 separate spokes, one per degree (0.5, 1.5, ...): every 10-degree bin gets the same count.
  std::vector<LineString> lines;
  for (int i = 0; i < 360; ++i) {
    const double a = (i + 0.5) * M_PI / 180.0;
    const Vec2 c{(i % 20) * 1000.0, (i / 20) * 1000.0};
    lines.push_back({c, c + Vec2{std::sin(a), std::cos(a)} * 100.0});
  }
  const StreetMetrics m = measureStreets(lines, {});
  EXPECT_NEAR(m.orientationEntropy, std::log(36.0), 1e-12);
  EXPECT_NEAR(m.orientationOrder, 0.0, 1e-12);
  EXPECT_EQ(m.shareDeadEnd, 1.0);
}

TEST(StreetMetrics, HandGraphCounts) {
  // A street from (0,0) to (200,0) with a T-junction at x = 100 and a crossing at x = 150.
  const std::vector<LineString> lines = {{{0, 0}, {200, 0}}, {{100, 0}, {100, 100}}, {{150, -50}, {150, 50}}};
  const StreetMetrics m = measureStreets(lines, {});
  EXPECT_EQ(m.nodes, 7u);
  EXPECT_EQ(m.edges, 6u);
  EXPECT_NEAR(m.shareDeadEnd, 5.0 / 7.0, 1e-12);
  EXPECT_NEAR(m.share3Way, 1.0 / 7.0, 1e-12);
  EXPECT_NEAR(m.share4Way, 1.0 / 7.0, 1e-12);
  EXPECT_NEAR(m.averageDegree, 12.0 / 7.0, 1e-12);
  EXPECT_NEAR(m.medianEdgeLength, 50.0, 1e-12);
  EXPECT_NEAR(m.circuity, 1.0, 1e-12);
  // Convex hull of the nodes: (0,0) (150,-50) (200,0) (150,50) (100,100) = 15000 m^2; 2 intersections.
  EXPECT_NEAR(m.areaKm2, 0.015, 1e-12);
  EXPECT_NEAR(m.intersectionDensity, 2.0 / 0.015, 1e-9);
}

TEST(StreetMetrics, EdgesAreSimplifiedThroughDegreeTwoNodes) {
  // An L drawn as two features: one edge of 200 m between two dead ends, 141.4 m apart.
  const std::vector<LineString> lines = {{{0, 0}, {100, 0}}, {{100, 0}, {100, 100}}};
  const StreetMetrics m = measureStreets(lines, {});
  EXPECT_EQ(m.edges, 1u);
  EXPECT_EQ(m.nodes, 2u);
  EXPECT_NEAR(m.circuity, 200.0 / std::sqrt(2.0 * 100.0 * 100.0), 1e-12);
  EXPECT_NEAR(m.medianEdgeLength, 200.0, 1e-12);
  // One straight-line bearing and its reverse: two bins, ln 2.
  EXPECT_NEAR(m.orientationEntropy, std::log(2.0), 1e-12);
}

TEST(StreetMetrics, AreaKeepsWholeNetworkDegrees) {
  // Only the inner 3 x 3 crossings lie in the area: all 4-way although the streets go on outside.
  MultiPolygon area{{{{50, 50}, {350, 50}, {350, 350}, {50, 350}, {50, 50}}, {}}};
  const StreetMetrics m = measureStreets(gridStreets(6, 50.0), {}, area);
  EXPECT_EQ(m.nodes, 9u);
  EXPECT_EQ(m.share4Way, 1.0);
  EXPECT_EQ(m.shareDeadEnd, 0.0);
  EXPECT_EQ(m.edges, 12u);  // edges with both ends inside
  EXPECT_NEAR(m.areaKm2, 0.09, 1e-12);
  EXPECT_NEAR(m.intersectionDensity, 100.0, 1e-9);
}

TEST(StreetMetrics, BinsAreCentredOnMultiplesOfTenDegrees) {
  // 359.99 and 0.01 share the bin centred on 0; 4.99 too; 5.01 is in the next bin.
  EXPECT_NEAR(orientationEntropy({359.99, 0.01, 4.99}, 36), 0.0, 1e-12);
  EXPECT_NEAR(orientationEntropy({359.99, 5.01}, 36), std::log(2.0), 1e-12);
  EXPECT_NEAR(orientationOrder(std::log(4.0), 36), 1.0, 1e-12);
  EXPECT_NEAR(orientationOrder(std::log(36.0), 36), 0.0, 1e-12);
}

TEST(StreetMetrics, MinEdgeLengthDropsShortEdgesFromOrientationOnly) {
  // A 100 m east-west street and a 5 m north-south stub.
  const std::vector<LineString> lines = {{{0, 0}, {100, 0}}, {{200, 0}, {200, 5}}};
  StreetMetricOptions o;
  EXPECT_NEAR(measureStreets(lines, o).orientationEntropy, std::log(4.0), 1e-12);
  o.minEdgeLength = 10.0;
  const StreetMetrics m = measureStreets(lines, o);
  EXPECT_NEAR(m.orientationEntropy, std::log(2.0), 1e-12);
  EXPECT_EQ(m.edges, 2u);
}

TEST(StreetMetrics, EmptyNetworkIsAnError) {
  EXPECT_THROW(measureStreets({}, {}), Error);
  StreetMetricOptions o;
  o.minEdgeLength = -1;
  EXPECT_THROW(measureStreets({{{0, 0}, {1, 0}}}, o), Error);
}
