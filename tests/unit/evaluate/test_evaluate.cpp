// The evaluator's metrics on hand-made vectors with known answers (issue 2 §3).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include "urbanvec/core/error.hpp"
#include "urbanvec/evaluate/evaluate.hpp"
#include "urbanvec/evaluate/polygon_metrics.hpp"
#include "urbanvec/evaluate/report_format.hpp"
#include "urbanvec/evaluate/road_metrics.hpp"

// Inside the namespace, `evaluate(...)` names the function rather than the namespace.
namespace urbanvec::evaluate {
namespace {

Layer roadLayer(const std::vector<std::pair<LineString, std::string>>& roads) {
  Layer layer;
  layer.name = "roads";
  layer.geometryType = GeometryType::LineString;
  layer.fields = {{"road_class", FieldType::String}};
  for (const auto& [line, roadClass] : roads) layer.features.push_back({line, {roadClass}});
  return layer;
}

Polygon box(double x0, double y0, double x1, double y1) {
  return Polygon{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}}, {}};
}

Layer polygonLayer(const std::string& name, const std::vector<std::pair<Polygon, std::string>>& polygons) {
  Layer layer;
  layer.name = name;
  layer.geometryType = GeometryType::Polygon;
  layer.fields = {{"land_use", FieldType::String}};
  for (const auto& [polygon, use] : polygons) layer.features.push_back({polygon, {use}});
  return layer;
}

/// A staircase of unit steps from `from`, `steps` times right then up (dy = +1) or down (dy = -1).
LineString staircase(Vec2 from, int steps, double dy) {
  LineString line{from};
  for (int i = 0; i < steps; ++i) {
    from.x += 1.0;
    line.push_back(from);
    from.y += dy;
    line.push_back(from);
  }
  return line;
}

}  // namespace

TEST(RoadDistance, LineOffsetByHalfACellIsHalfACellBothWays) {
  EvaluationInput input;
  input.cellSize = 10.0;
  input.truth.roads = roadLayer({{{{0, 0}, {100, 0}}, "secondary"}});
  input.result.roads = roadLayer({{{{0, 5}, {100, 5}}, "secondary"}});
  const EvaluationReport report = evaluate(input);
  ASSERT_TRUE(report.roads.truthToResult && report.roads.resultToTruth);
  for (const DistanceSummary& d : {*report.roads.truthToResult, *report.roads.resultToTruth}) {
    EXPECT_DOUBLE_EQ(d.medianCells, 0.5);
    EXPECT_DOUBLE_EQ(d.p95Cells, 0.5);
    EXPECT_DOUBLE_EQ(d.medianMetres, 5.0);
    EXPECT_EQ(d.samples, 40u);  // 100 m every quarter of a 10 m cell
  }
  EXPECT_FALSE(report.roads.turningRatio.has_value()) << "two straight lines: the truth never turns";
}

TEST(RoadNetwork, IntersectionsDeadEndsAndComponentsOfTheNodedNetwork) {
  EvaluationInput input;
  input.cellSize = 10.0;
  // Truth: a crossroads drawn as two whole lines (noded where they cross) and a street apart.
  input.truth.roads = roadLayer({{{{0, 50}, {100, 50}}, "secondary"},
                                 {{{50, 0}, {50, 100}}, "secondary"},
                                 {{{200, 0}, {300, 0}}, "secondary"}});
  // Result: the same crossroads in four segments meeting at the node, one arm ending 0.05 m (well
  // within the snap of 0.01 cell = 0.1 m) short of it, and the separate street broken in two pieces
  // that meet exactly.
  input.result.roads = roadLayer({{{{0, 50}, {50, 50}}, "secondary"},
                                  {{{50, 50}, {100, 50}}, "secondary"},
                                  {{{50, 0}, {50, 49.95}}, "secondary"},
                                  {{{50, 50}, {50, 100}}, "secondary"},
                                  {{{200, 0}, {250, 0}}, "secondary"},
                                  {{{250, 0}, {300, 0}}, "secondary"},
                                  {{{200, 0}, {200, -100}}, "perimeter"}});
  const EvaluationReport report = evaluate(input);
  ASSERT_TRUE(report.roads.truthNetwork && report.roads.resultNetwork);
  for (const NetworkSummary& n : {*report.roads.truthNetwork, *report.roads.resultNetwork}) {
    EXPECT_EQ(n.intersections, 1u);
    EXPECT_EQ(n.deadEnds, 6u);  // four arms and the street's two ends; perimeter lines are not roads
    EXPECT_EQ(n.components, 2u);
  }
  // Without the snap the short arm is a piece of its own: the crossroads becomes a T.
  EvaluateOptions exact;
  exact.networkSnapCells = 0.0;
  const EvaluationReport apart = evaluate(input, exact);
  EXPECT_EQ(apart.roads.resultNetwork->intersections, 1u);
  EXPECT_EQ(apart.roads.resultNetwork->deadEnds, 7u);
  EXPECT_EQ(apart.roads.resultNetwork->components, 3u);
  const std::string table = formatReportTable(report, {"r.gpkg", "t.gpkg", "", "", "", "", "", ""});
  EXPECT_NE(
      table.find("roads: network result                   1 intersections, 6 dead ends, 2 components\n"),
      std::string::npos)
      << table;
}

TEST(RoadDistance, OneSidedDistancesDifferWhenTheResultMissesARoad) {
  // The result has only the first of two parallel roads 40 m apart: truth samples on the second are
  // 40 m (4 cells) from the result, while every result sample lies on the truth.
  EvaluationInput input;
  input.cellSize = 10.0;
  input.truth.roads = roadLayer({{{{0, 0}, {100, 0}}, "primary"}, {{{0, 40}, {100, 40}}, "secondary"}});
  input.result.roads = roadLayer({{{{0, 0}, {100, 0}}, "primary"}});
  const EvaluationReport report = evaluate(input);
  EXPECT_DOUBLE_EQ(report.roads.resultToTruth->p95Metres, 0.0);
  EXPECT_DOUBLE_EQ(report.roads.truthToResult->p95Cells, 4.0);
  EXPECT_EQ(report.roads.truthToResult->samples, 80u);
}

TEST(RoadDistance, PerimeterRoadsAreNotRoads) {
  EvaluationInput input;
  input.cellSize = 1.0;
  input.truth.roads = roadLayer({{{{0, 0}, {10, 0}}, "secondary"}, {{{0, 50}, {10, 50}}, "perimeter"}});
  input.result.roads = roadLayer({{{{0, 0}, {10, 0}}, "secondary"}, {{{0, -30}, {10, -30}}, "Perimeter"}});
  const EvaluationReport report = evaluate(input);
  EXPECT_EQ(*report.roads.truthLines, 1u);
  EXPECT_EQ(*report.roads.resultLines, 1u);
  EXPECT_DOUBLE_EQ(report.roads.truthToResult->p95Metres, 0.0);
  EXPECT_DOUBLE_EQ(report.roads.resultToTruth->p95Metres, 0.0);
  EXPECT_DOUBLE_EQ(*report.roads.truthLengthKm, 0.01);
}

TEST(RoadSmoothness, StaircaseAgainstABentDiagonalHasAKnownTurningRatio) {
  // Truth: (0,0) -> (10,10) -> (20,0), one 90 degree turn over 20*sqrt(2) m.
  // Result: the same path as unit steps: 40 segments of 1 m, each of the 39 joints turning 90 degrees.
  LineString steps = staircase({0, 0}, 10, 1.0);
  const LineString down = staircase({10, 10}, 10, -1.0);
  steps.insert(steps.end(), down.begin() + 1, down.end());
  ASSERT_EQ(steps.size(), 41u);
  EXPECT_DOUBLE_EQ(turningDegrees(steps), 39 * 90.0);
  EvaluationInput input;
  input.cellSize = 1.0;
  input.truth.roads = roadLayer({{{{0, 0}, {10, 10}, {20, 0}}, "secondary"}});
  input.result.roads = roadLayer({{steps, "secondary"}});
  const EvaluationReport report = evaluate(input);
  const double truthPerKm = 90.0 / (20.0 * std::sqrt(2.0) / 1000.0);
  const double resultPerKm = 39 * 90.0 / (40.0 / 1000.0);
  EXPECT_NEAR(*report.roads.truthTurningPerKm, truthPerKm, 1e-9 * truthPerKm);
  EXPECT_NEAR(*report.roads.resultTurningPerKm, resultPerKm, 1e-9 * resultPerKm);
  EXPECT_NEAR(*report.roads.turningRatio, resultPerKm / truthPerKm, 1e-9);
  EXPECT_NEAR(*report.roads.turningRatio, 27.5772, 1e-4);
  // The staircase strays at most half a step diagonal from the diagonal it follows.
  EXPECT_LE(report.roads.resultToTruth->p95Metres, std::sqrt(0.5) + 1e-9);
}

TEST(RoadSmoothness, RepeatedPointsAndStraightRunsDoNotTurn) {
  EXPECT_DOUBLE_EQ(turningDegrees({{0, 0}, {1, 0}, {1, 0}, {2, 0}, {3, 0}}), 0.0);
  EXPECT_DOUBLE_EQ(turningDegrees({{0, 0}, {1, 0}, {1, 1}, {0, 1}}), 180.0);
  EXPECT_NEAR(turningDegrees({{0, 0}, {1, 0}, {2, 1}}), 45.0, 1e-12);
}

TEST(RoadSampling, EqualPiecesSampledAtTheirMiddles) {
  const std::vector<Vec2> points = samplePoints({{{0, 0}, {4, 0}, {4, 6}}}, 2.5);
  ASSERT_EQ(points.size(), 4u);  // 10 m in four pieces of 2.5 m
  EXPECT_DOUBLE_EQ(points[0].x, 1.25);
  EXPECT_DOUBLE_EQ(points[1].x, 3.75);
  EXPECT_DOUBLE_EQ(points[2].y, 2.25);
  EXPECT_DOUBLE_EQ(points[3].y, 4.75);
  EXPECT_EQ(samplePoints({{{0, 0}, {0.1, 0}}}, 2.5).size(), 1u) << "a short line still counts";
}

TEST(RoadSampling, QuantileInterpolatesLikeNumpy) {
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(quantile({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}, 0.95), 10.5);
  EXPECT_DOUBLE_EQ(quantile({7}, 0.95), 7.0);
}

TEST(BlockMatching, IoUOfOffsetSquares) {
  geos::Context ctx;
  const Layer truth = polygonLayer("blocks", {{box(0, 0, 10, 10), ""}, {box(100, 0, 110, 10), ""}});
  const Layer result = polygonLayer("blocks", {{box(5, 0, 15, 10), ""}, {box(101, 0, 111, 10), ""}});
  const PolygonLayer t(ctx, truth), r(ctx, result);
  const BlockMatching m = matchBlocks(ctx, t, r);
  EXPECT_NEAR(m.bestIoU[0], 50.0 / 150.0, 1e-12);  // half overlaps
  EXPECT_NEAR(m.bestIoU[1], 90.0 / 110.0, 1e-12);  // shifted by a tenth
  EXPECT_EQ(*m.bestResult[1], 1u);

  EvaluationInput input;
  input.cellSize = 1.0;
  input.truth.blocks = truth;
  input.result.blocks = result;
  const EvaluationReport report = evaluate(input);
  EXPECT_EQ(*report.blocks.matchedCount, 1u);
  EXPECT_DOUBLE_EQ(*report.blocks.matchedShare, 0.5);
  EXPECT_NEAR(*report.blocks.meanBestIoU, (1.0 / 3.0 + 9.0 / 11.0) / 2.0, 1e-12);
}

TEST(BlockMatching, BestOfSeveralCandidatesAndNoneForAnIsolatedBlock) {
  geos::Context ctx;
  const Layer truth = polygonLayer("blocks", {{box(0, 0, 10, 10), ""}, {box(50, 50, 60, 60), ""}});
  const Layer result =
      polygonLayer("blocks", {{box(0, 0, 3, 10), ""}, {box(3, 0, 10, 10), ""}, {box(-5, -5, 15, 15), ""}});
  const PolygonLayer t(ctx, truth), r(ctx, result);
  const BlockMatching m = matchBlocks(ctx, t, r);
  EXPECT_EQ(*m.bestResult[0], 1u);
  EXPECT_NEAR(m.bestIoU[0], 0.7, 1e-12);
  EXPECT_FALSE(m.bestResult[1].has_value());
  EXPECT_DOUBLE_EQ(m.bestIoU[1], 0.0);
}

TEST(Parcels, KnownGapAndOverlapShares) {
  // Block of 100 m2; parcels [0,6]x[0,10] and [5,9]x[0,10]: 10 m2 uncovered, 10 m2 covered twice.
  EvaluationInput input;
  input.cellSize = 1.0;
  input.result.blocks = polygonLayer("blocks", {{box(0, 0, 10, 10), ""}, {box(20, 0, 30, 10), ""}});
  input.result.parcels = polygonLayer(
      "parcels",
      {{box(0, 0, 6, 10), "residential"}, {box(5, 0, 9, 10), "residential"}, {box(20, 0, 30, 10), "park"}});
  const EvaluationReport report = evaluate(input);
  EXPECT_NEAR(*report.parcels.gapShare, 10.0 / 200.0, 1e-12);
  EXPECT_NEAR(*report.parcels.overlapShare, 10.0 / 200.0, 1e-12);
  EXPECT_FALSE(report.parcels.countRatioMean.has_value()) << "no truth blocks to match";
  EXPECT_FALSE(report.blocks.matchedShare.has_value());
}

TEST(Parcels, ParcelSpillingOutOfItsBlockIsNotAnOverlap) {
  geos::Context ctx;
  const Layer blocks = polygonLayer("blocks", {{box(0, 0, 10, 10), ""}});
  const Layer parcels = polygonLayer("parcels", {{box(0, 0, 8, 10), ""}, {box(8, 0, 12, 10), ""}});
  const PolygonLayer b(ctx, blocks), p(ctx, parcels);
  const auto assignment = assignToBlocks(ctx, p, b);
  ASSERT_TRUE(assignment[0] && assignment[1]);
  const Coverage c = parcelCoverage(ctx, p, b, assignment);
  EXPECT_DOUBLE_EQ(c.gapArea, 0.0);
  EXPECT_DOUBLE_EQ(c.overlapArea, 0.0);
  EXPECT_DOUBLE_EQ(c.blockArea, 100.0);
}

TEST(Parcels, InvalidBowTieIsCounted) {
  EvaluationInput input;
  input.cellSize = 1.0;
  const Polygon bowTie{{{0, 0}, {10, 10}, {10, 0}, {0, 10}, {0, 0}}, {}};
  const Polygon spike{{{20, 0}, {21, 0}, {20, 0}, {20, 0}}, {}};  // too few corners to be a ring
  input.result.parcels = polygonLayer("parcels", {{bowTie, "residential"},
                                                  {box(30, 0, 40, 10), "residential"},
                                                  {box(40, 0, 50, 10), "park"},
                                                  {spike, "park"}});
  const EvaluationReport report = evaluate(input);
  EXPECT_EQ(*report.parcels.invalidCount, 2u);
  EXPECT_EQ(*report.parcels.resultCount, 4u);
  EXPECT_DOUBLE_EQ(*report.parcels.invalidShare, 0.5);
}

TEST(Parcels, CountRatioAndLandUseShareErrorPerMatchedBlock) {
  // Truth block: residential 50 + park 50 in 2 parcels. Result block: 3 residential parcels of 25 and
  // one park of 25: twice the parcels, shares 0.75/0.25 against 0.5/0.5, so L1 = 0.5.
  EvaluationInput input;
  input.cellSize = 1.0;
  input.truth.blocks = polygonLayer("blocks", {{box(0, 0, 10, 10), ""}});
  input.truth.parcels =
      polygonLayer("parcels", {{box(0, 0, 5, 10), "residential"}, {box(5, 0, 10, 10), "park"}});
  input.result.blocks = polygonLayer("blocks", {{box(0, 0, 10, 10), ""}});
  input.result.parcels = polygonLayer("parcels", {{box(0, 0, 2.5, 10), "Residential"},
                                                  {box(2.5, 0, 5, 10), "residential"},
                                                  {box(5, 0, 7.5, 10), "residential"},
                                                  {box(7.5, 0, 10, 10), "park"}});
  const EvaluationReport report = evaluate(input);
  EXPECT_EQ(*report.parcels.comparedBlocks, 1u);
  EXPECT_DOUBLE_EQ(*report.parcels.countRatioMean, 2.0);
  EXPECT_DOUBLE_EQ(*report.parcels.countRatioMedian, 2.0);
  EXPECT_DOUBLE_EQ(*report.parcels.landUseErrorMean, 0.5);
  EXPECT_DOUBLE_EQ(*report.parcels.gapShare, 0.0);
}

TEST(Parcels, LandUseCodesAndNamesAgree) {
  EXPECT_EQ(landUseKey(FieldValue{std::int64_t{4}}), "residential");
  EXPECT_EQ(landUseKey(FieldValue{std::string("Residential")}), "residential");
  EXPECT_EQ(landUseKey(FieldValue{std::int64_t{7}}), "park");
  // The vectorizer's parcels without a use compare with the grid's unused land.
  EXPECT_EQ(landUseKey(FieldValue{std::string("Undeveloped")}), "unused");
  EXPECT_EQ(landUseKey(FieldValue{std::int64_t{0}}), "unused");
  EXPECT_EQ(landUseKey(FieldValue{std::string("gardens")}), "gardens");
  EXPECT_EQ(landUseKey(FieldValue{}), "");
  EXPECT_DOUBLE_EQ(landUseShareError({{"residential", 3}, {"park", 1}}, {{"residential", 1}, {"park", 1}}),
                   0.5);
  EXPECT_DOUBLE_EQ(landUseShareError({{"park", 1}}, {{"industrial", 5}}), 2.0);
  EXPECT_DOUBLE_EQ(landUseShareError({}, {{"industrial", 5}}), 1.0);
}

TEST(Evaluate, AbsentLayersGiveAbsentMetricsNeverZero) {
  EvaluationInput input;
  input.cellSize = 5.0;
  input.truth.roads = roadLayer({{{{0, 0}, {10, 0}, {10, 10}}, "secondary"}});
  input.truth.blocks = polygonLayer("blocks", {{box(0, 0, 10, 10), ""}});
  const EvaluationReport report = evaluate(input);
  EXPECT_TRUE(report.roads.truthTurningPerKm.has_value());
  EXPECT_FALSE(report.roads.resultTurningPerKm.has_value());
  EXPECT_FALSE(report.roads.turningRatio.has_value());
  EXPECT_FALSE(report.roads.truthToResult.has_value());
  EXPECT_FALSE(report.blocks.matchedShare.has_value());
  EXPECT_FALSE(report.parcels.invalidShare.has_value());
  EXPECT_FALSE(report.parcels.gapShare.has_value());
  const std::string table =
      formatReportTable(report, {"r.gpkg", "t.gpkg", "", "", "", "'roads' of 't.gpkg'", "", ""});
  EXPECT_NE(table.find("roads: turning ratio result/truth       absent\n"), std::string::npos) << table;
  EXPECT_NE(table.find("roads: lines truth / result             1 / absent\n"), std::string::npos) << table;
  EXPECT_NE(table.find("result roads                            absent\n"), std::string::npos) << table;
  ReportInputs inputs;
  inputs.result = "r.gpkg";
  inputs.truth = "t.gpkg";
  const nlohmann::json j = nlohmann::json::parse(formatReportJson(report, inputs));
  EXPECT_TRUE(j["roads"]["turning_ratio"].is_null());
  EXPECT_TRUE(j["roads"]["distance_truth_to_result"].is_null());
  EXPECT_TRUE(j["blocks"]["matched_share"].is_null());
  EXPECT_TRUE(j["parcels"]["gap_share"].is_null());
  EXPECT_TRUE(j["layers"]["result_roads"].is_null());
  EXPECT_DOUBLE_EQ(j["roads"]["truth_length_km"].get<double>(), 0.02);
  EXPECT_DOUBLE_EQ(j["cell_size_m"].get<double>(), 5.0);
}

TEST(Evaluate, StraightTruthLeavesTheRatioUndefinedNotInfinite) {
  EvaluationInput input;
  input.cellSize = 1.0;
  input.truth.roads = roadLayer({{{{0, 0}, {10, 0}}, "secondary"}});
  input.result.roads = roadLayer({{staircase({0, 0}, 5, 1.0), "secondary"}});
  const EvaluationReport report = evaluate(input);
  EXPECT_FALSE(report.roads.turningRatio.has_value());
  EXPECT_GT(*report.roads.resultTurningPerKm, 0.0);
  const std::string table = formatReportTable(report, {});
  EXPECT_NE(table.find("undefined (the truth roads never turn)"), std::string::npos);
}

TEST(Evaluate, BadOptionsAreInvalidOptionErrors) {
  EvaluationInput input;
  input.cellSize = 0.0;
  try {
    evaluate(input);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidOption);
    EXPECT_STREQ(e.what(), "the cell size must be a positive number of metres, got 0.000000");
  }
  input.cellSize = 1.0;
  EvaluateOptions options;
  options.blockMatchIoU = 1.5;
  EXPECT_THROW(evaluate(input, options), Error);
}

TEST(Evaluate, ProgressIsMonotonicEndsAtOneAndCancels) {
  EvaluationInput input;
  input.cellSize = 1.0;
  input.truth.roads = roadLayer({{{{0, 0}, {100, 0}}, "secondary"}});
  input.result.roads = roadLayer({{{{0, 1}, {100, 1}}, "secondary"}});
  input.truth.blocks = polygonLayer("blocks", {{box(0, 0, 10, 10), ""}});
  input.result.blocks = input.truth.blocks;
  std::vector<double> seen;
  evaluate(input, {}, [&](double f, std::string_view) {
    seen.push_back(f);
    return true;
  });
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
  EXPECT_THROW(evaluate(input, {}, [](double f, std::string_view) { return f < 0.3; }), Cancelled);
}

TEST(Evaluate, ThousandsOfBlocksStayFast) {
  // A 60 x 60 grid of 3600 blocks with 4 parcels each and 120 roads of 6 km (2 x 288,000 distance
  // samples): a few seconds with the STRtrees; comparing all pairs would take hours.
  EvaluationInput input;
  input.cellSize = 10.0;
  std::vector<std::pair<Polygon, std::string>> blocks, parcels;
  std::vector<std::pair<LineString, std::string>> roads;
  for (int i = 0; i < 60; ++i) {
    roads.push_back({{{i * 100.0, 0}, {i * 100.0, 6000}}, "secondary"});
    roads.push_back({{{0, i * 100.0}, {6000, i * 100.0}}, "secondary"});
    for (int j = 0; j < 60; ++j) {
      const double x = i * 100.0 + 5, y = j * 100.0 + 5;
      blocks.push_back({box(x, y, x + 90, y + 90), ""});
      for (int k = 0; k < 4; ++k)
        parcels.push_back({box(x + k * 22.5, y, x + (k + 1) * 22.5, y + 90), "residential"});
    }
  }
  input.truth.roads = roadLayer(roads);
  input.truth.blocks = polygonLayer("blocks", blocks);
  input.truth.parcels = polygonLayer("parcels", parcels);
  input.result = input.truth;
  const auto start = std::chrono::steady_clock::now();
  const EvaluationReport report = evaluate(input);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_DOUBLE_EQ(*report.blocks.matchedShare, 1.0);
  EXPECT_EQ(*report.parcels.comparedBlocks, 3600u);
  EXPECT_DOUBLE_EQ(*report.parcels.countRatioMean, 1.0);
  EXPECT_NEAR(*report.parcels.gapShare, 0.0, 1e-12);
  EXPECT_NEAR(report.roads.truthToResult->p95Metres, 0.0, 1e-9);
  EXPECT_LT(seconds, 30.0);
  std::printf("evaluated 3600 blocks, 14400 parcels, 720 km of road in %.2f s\n", seconds);
}

}  // namespace urbanvec::evaluate

namespace urbanvec::evaluate {
namespace {

/// A polyline from the origin that walks `step` metres, then turns by each angle (degrees, left) and
/// walks again.
LineString turningLine(const std::vector<double>& turns, double step) {
  LineString line{{0, 0}};
  double heading = 0.0;
  line.push_back({step, 0});
  for (double t : turns) {
    heading += t * M_PI / 180.0;
    const Vec2 last = line.back();
    line.push_back({last.x + step * std::cos(heading), last.y + step * std::sin(heading)});
  }
  return line;
}

}  // namespace

TEST(RoadTurning, TurningPerKmIsSplitByTheSizeOfEachBend) {
  // 1 km in 10 pieces of 100 m with turns of 3, 6, 10, 21, 30 and 90 degrees.
  const LineString line = turningLine({3, 6, 10, 21, 30, 90, 0, 0, 0}, 100.0);
  ASSERT_NEAR(length(line), 1000.0, 1e-9);
  const std::vector<double> byBend = turningPerKmByBend({line}, {5, 20, 45});
  ASSERT_EQ(byBend.size(), 4u);
  EXPECT_NEAR(byBend[0], 3.0, 1e-9);
  EXPECT_NEAR(byBend[1], 16.0, 1e-9);
  EXPECT_NEAR(byBend[2], 51.0, 1e-9);
  EXPECT_NEAR(byBend[3], 90.0, 1e-9);
  EXPECT_NEAR(byBend[0] + byBend[1] + byBend[2] + byBend[3], turningPerKm({line}), 1e-9);
}

TEST(RoadTurning, ReportGivesBendClassesAndTheSharpTurningRatio) {
  EvaluationInput input;
  input.cellSize = 10.0;
  // Truth: one 40-degree bend over 1 km. Result: the same bend drawn as a 25- and a 15-degree bend,
  // a zigzag of 10-degree jogs (below the sharp class) and a 60-degree hook and back.
  input.truth.roads = roadLayer({{turningLine({40, 0, 0, 0, 0, 0, 0, 0, 0}, 100.0), "secondary"}});
  input.result.roads = roadLayer({{turningLine({25, 15, 10, -10, 60, -60, 0, 0, 0}, 100.0), "secondary"}});
  const EvaluationReport report = evaluate(input);
  const RoadReport& r = report.roads;
  ASSERT_TRUE(r.truthTurningByBend && r.resultTurningByBend);
  EXPECT_NEAR((*r.truthTurningByBend)[2], 40.0, 1e-9);
  EXPECT_NEAR((*r.resultTurningByBend)[1], 35.0, 1e-9);
  EXPECT_NEAR((*r.resultTurningByBend)[2], 25.0, 1e-9);
  EXPECT_NEAR((*r.resultTurningByBend)[3], 120.0, 1e-9);
  ASSERT_TRUE(r.sharpTurningRatio);
  EXPECT_NEAR(*r.sharpTurningRatio, 145.0 / 40.0, 1e-9);
  EXPECT_NEAR(*r.turningRatio, 180.0 / 40.0, 1e-9);
  const auto json = nlohmann::json::parse(formatReportJson(report, {}));
  EXPECT_NEAR(json["roads"]["result_turning_by_bend_deg_per_km"][3].get<double>(), 120.0, 1e-9);
  EXPECT_NEAR(json["roads"]["sharp_turning_ratio"].get<double>(), 145.0 / 40.0, 1e-9);
  const std::string table = formatReportTable(report, {});
  const std::size_t row = table.find("roads: turning >=45 deg truth/result");
  ASSERT_NE(row, std::string::npos) << table;
  const std::string line = table.substr(row, table.find('\n', row) - row);
  EXPECT_NE(line.find(" 0.0 / 120.0 deg/km"), std::string::npos) << line;
}

TEST(BlockMatching, MatchableShareLeavesOutBlocksMostlyOnRoadCells) {
  // A 10 x 4 grid of 10 m cells, north-up from (0, 40): columns 0-3 land, column 4 road, columns 5-9
  // road too in rows 0-1, land in rows 2-3.
  LandUseCells cells;
  cells.spec.width = 10;
  cells.spec.height = 4;
  cells.spec.transform.c = {0, 10, 0, 40, 0, -10};
  cells.codes = Grid<std::uint8_t>(10, 4, 4);
  for (int row = 0; row < 4; ++row) cells.codes.at(4, row) = 2;
  for (int row = 0; row < 2; ++row)
    for (int col = 5; col < 10; ++col) cells.codes.at(col, row) = 2;
  EXPECT_NEAR(landShare(box(0, 0, 40, 40), cells, 4), 1.0, 1e-12);
  EXPECT_NEAR(landShare(box(50, 0, 100, 40), cells, 4), 0.5, 1e-12);
  EXPECT_NEAR(landShare(box(30, 0, 50, 40), cells, 4), 0.5, 1e-12);  // half on the road column

  EvaluationInput input;
  input.cellSize = 10.0;
  input.landUse = cells;
  input.truth.blocks = polygonLayer("blocks", {{box(0, 0, 40, 40), "a"}, {box(50, 0, 100, 40), "b"}});
  input.result.blocks = polygonLayer("blocks", {{box(0, 0, 40, 40), "a"}});
  const EvaluationReport report = evaluate(input);
  ASSERT_TRUE(report.blocks.matchedShare && report.blocks.matchableMatchedShare);
  EXPECT_DOUBLE_EQ(*report.blocks.matchedShare, 0.5);
  EXPECT_EQ(*report.blocks.matchableTruthCount, 1u);
  EXPECT_EQ(*report.blocks.matchableMatchedCount, 1u);
  EXPECT_DOUBLE_EQ(*report.blocks.matchableMatchedShare, 1.0);

  EvaluateOptions loose;
  loose.matchableLandShare = 0.5;  // now the half-road block counts and is not matched
  const EvaluationReport both = evaluate(input, loose);
  EXPECT_EQ(*both.blocks.matchableTruthCount, 2u);
  EXPECT_DOUBLE_EQ(*both.blocks.matchableMatchedShare, 0.5);

  input.landUse.reset();
  EXPECT_FALSE(evaluate(input).blocks.matchableMatchedShare.has_value()) << "absent without the grid";
}

}  // namespace urbanvec::evaluate
