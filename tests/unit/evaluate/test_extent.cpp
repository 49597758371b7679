// Result and truth that do not overlap (issue 15): the report says so, so distances of thousands of
// cells are not taken for a measure of the result.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "urbanvec/evaluate/evaluate.hpp"
#include "urbanvec/evaluate/report_format.hpp"

namespace urbanvec::evaluate {
namespace {

Layer roads(double dx, double dy) {
  Layer layer;
  layer.name = "roads";
  layer.geometryType = GeometryType::LineString;
  layer.features.push_back({LineString{{dx, dy}, {dx + 100, dy}}, {}});
  layer.features.push_back({LineString{{dx + 50, dy - 20}, {dx + 50, dy + 30}}, {}});
  return layer;
}

Layer blocks(double dx, double dy) {
  Layer layer;
  layer.name = "blocks";
  layer.geometryType = GeometryType::Polygon;
  layer.features.push_back(
      {Polygon{{{dx, dy}, {dx + 40, dy}, {dx + 40, dy + 60}, {dx, dy + 60}, {dx, dy}}, {}}, {}});
  return layer;
}

TEST(Extent, CoversEveryLayerAndDetectsDisjointCities) {
  CityLayers city;
  EXPECT_FALSE(cityExtent(city));
  city.roads = roads(1000, 2000);
  city.blocks = blocks(990, 2010);
  const std::optional<Extent> e = cityExtent(city);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->minX, 990);
  EXPECT_EQ(e->minY, 1980);
  EXPECT_EQ(e->maxX, 1100);
  EXPECT_EQ(e->maxY, 2070);
  EXPECT_TRUE(extentsOverlap(*e, Extent{1100, 2070, 1200, 2100}));  // touching corners
  EXPECT_FALSE(extentsOverlap(*e, Extent{1100.5, 1900, 1200, 2100}));
  EXPECT_FALSE(extentsOverlap(*e, Extent{990, 2070.5, 1100, 2100}));
}

TEST(Extent, EvaluateReportsLayersThatDoNotOverlap) {
  EvaluationInput input;
  input.cellSize = 10;
  input.truth.roads = roads(1000, 2000);
  input.result.roads = roads(1000, 2000);
  EvaluationReport report = evaluate(input);
  EXPECT_TRUE(report.layersOverlap);
  EXPECT_TRUE(nlohmann::json::parse(formatReportJson(report, {}))["extent"]["overlap"].get<bool>());

  input.result.roads = roads(601000, 2000);  // 600 km east: another UTM zone's label
  report = evaluate(input);
  EXPECT_FALSE(report.layersOverlap);
  ASSERT_TRUE(report.resultExtent && report.truthExtent);
  EXPECT_EQ(formatExtent(*report.resultExtent), "x 601000 to 601100, y 1980 to 2030");
  EXPECT_EQ(formatExtent(*report.truthExtent), "x 1000 to 1100, y 1980 to 2030");
  const nlohmann::json j = nlohmann::json::parse(formatReportJson(report, {}));
  EXPECT_FALSE(j["extent"]["overlap"].get<bool>());
  EXPECT_EQ(j["extent"]["result"]["min_x"].get<double>(), 601000);
  EXPECT_EQ(j["extent"]["truth"]["max_y"].get<double>(), 2030);

  // A side with no layer has no extent: nothing to compare, no claim of disjointness.
  input.result.roads.reset();
  report = evaluate(input);
  EXPECT_TRUE(report.layersOverlap);
  EXPECT_TRUE(nlohmann::json::parse(formatReportJson(report, {}))["extent"]["result"].is_null());
}

}  // namespace
}  // namespace urbanvec::evaluate
