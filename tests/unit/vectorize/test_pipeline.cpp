// The whole A1–B6 pipeline, its output layers, the topology checker, and loading rasters from files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "test_grids.hpp"
#include "urbanvec/app/grid_input.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/io/raster_io.hpp"
#include "urbanvec/vectorize/pipeline.hpp"
#include "urbanvec/vectorize/roads/road_checks.hpp"
#include "urbanvec/vectorize/roads/road_output.hpp"

using namespace urbanvec;
using namespace urbanvec::vectorize;
using namespace urbanvec::vectorize::testing;

namespace {

/// A small city: a primary avenue, a secondary grid, a diagonal street and a block on water.
std::vector<std::string> smallCity() {
  std::vector<std::string> rows = blank(40, 30);
  for (int r = 0; r < 30; ++r) rows[r][5] = rows[r][20] = 's';
  for (int c = 0; c < 40; ++c) rows[6][c] = rows[24][c] = 's';
  for (int k = 0; k < 12; ++k) {  // staircase diagonal from (21, 7) towards the south-east
    rows[7 + k][21 + k] = 's';
    rows[7 + k][22 + k] = 's';
  }
  for (int c = 0; c < 40; ++c) rows[14][c] = rows[15][c] = 'P';  // drawn over the secondary roads
  for (int r = 25; r < 30; ++r)
    for (int c = 30; c < 40; ++c) rows[r][c] = r > 27 ? 'w' : '.';
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 40; ++c) rows[r][c] = '.';
  for (int c = 0; c < 40; ++c) rows[2][c] = c % 7 == 0 ? '.' : 'c';
  return rows;
}

}  // namespace

TEST(Pipeline, SmallCityGivesCleanConnectedRoadsCoveringEveryRoadCell) {
  const VectorizeInput in = drawInput(smallCity());
  std::vector<double> seen;
  Progress progress = [&](double f, std::string_view) {
    seen.push_back(f);
    return true;
  };
  const VectorizeResult r = vectorize::vectorize(in, {}, progress);
  // Later stages add layers; roads and road_nodes come first.
  ASSERT_GE(r.layers.size(), 2u);
  const Layer& roads = r.layers[0];
  const Layer& nodes = r.layers[1];
  EXPECT_EQ(roads.name, "roads");
  EXPECT_EQ(nodes.name, "road_nodes");
  EXPECT_GT(roads.features.size(), 10u);
  // Progress never goes backwards and ends at exactly 1.
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
  // Topology contract.
  const RoadNetworkCheck check = checkRoadNetwork(roads, nodes);
  EXPECT_TRUE(check.ok()) << check.describe();
  // Every road cell that the pipeline kept lies within 1.5 cells (15 m) of a result road.
  std::vector<std::pair<Vec2, Vec2>> pieces;
  for (const Feature& f : roads.features) {
    const LineString& l = std::get<LineString>(f.geometry);
    for (size_t k = 0; k + 1 < l.size(); ++k) pieces.emplace_back(l[k], l[k + 1]);
  }
  int far = 0;
  for (int row = 0; row < in.spec.height; ++row)
    for (int col = 0; col < in.spec.width; ++col) {
      if (!isRoadCode(r.cells.at(col, row))) continue;
      const Vec2 centre = in.spec.cellCentre(col, row);
      double best = 1e9;
      for (const auto& [a, b] : pieces) best = std::min(best, distanceToSegment(centre, a, b));
      far += best > 15.0;
      if (best > 15.0)
        ADD_FAILURE() << "road cell " << col << "," << row << " is " << best / 10 << " cells away";
    }
  EXPECT_EQ(far, 0);
  // Fields and classes.
  const int cls = roads.fieldIndex("road_class");
  ASSERT_GE(cls, 0);
  std::set<std::string> classes;
  for (const Feature& f : roads.features) classes.insert(std::get<std::string>(f.values[cls]));
  EXPECT_TRUE(classes.count("primary"));
  EXPECT_TRUE(classes.count("secondary"));
  EXPECT_TRUE(classes.count("perimeter"));
  for (const char* field : {"road_id", "from_node", "to_node", "length"})
    EXPECT_GE(roads.fieldIndex(field), 0);
  for (const char* field : {"node_id", "kind", "degree"}) EXPECT_GE(nodes.fieldIndex(field), 0);
  // Per-stage reports for A2..B6 and the output.
  std::vector<std::string> ids;
  for (const StageReport& s : r.stages) ids.push_back(s.id);
  const std::vector<std::string> roadStages{"A2", "A3", "A4", "A4.8", "A5", "B1",
                                            "B2", "B3", "B4", "B5",   "B6"};
  ASSERT_GE(ids.size(), roadStages.size());
  EXPECT_EQ(std::vector<std::string>(ids.begin(), ids.begin() + roadStages.size()), roadStages);
}

TEST(Pipeline, SameInputGivesIdenticalOutput) {
  const VectorizeInput in = drawInput(smallCity());
  const VectorizeResult a = vectorize::vectorize(in, {});
  const VectorizeResult b = vectorize::vectorize(in, {});
  ASSERT_EQ(a.layers[0].features.size(), b.layers[0].features.size());
  for (size_t k = 0; k < a.layers[0].features.size(); ++k)
    EXPECT_EQ(std::get<LineString>(a.layers[0].features[k].geometry),
              std::get<LineString>(b.layers[0].features[k].geometry));
}

TEST(Pipeline, BadGridsGiveWarningsOrClearErrorsNotCrashes) {
  // No road: valid empty layers and a warning.
  VectorizeResult none = vectorize::vectorize(drawInput({"rrr", "r.r"}), {});
  EXPECT_TRUE(none.layers[0].features.empty());
  EXPECT_TRUE(none.layers[1].features.empty());
  ASSERT_FALSE(none.warnings.empty());
  EXPECT_NE(none.warnings[0].find("no road cells"), std::string::npos);
  // All road: a warning, and a clean (tiny) network.
  VectorizeResult all = vectorize::vectorize(drawInput(blank(12, 9, 's')), {});
  ASSERT_FALSE(all.warnings.empty());
  EXPECT_NE(all.warnings[0].find("every cell"), std::string::npos);
  EXPECT_TRUE(checkRoadNetwork(all.layers[0], all.layers[1]).ok());
  // 1x1 grids of every class.
  for (const char* one : {"s", "P", "r", "."})
    EXPECT_NO_THROW(vectorize::vectorize(drawInput({one}), {})) << one;
  // Negative parcel ids.
  VectorizeInput neg = drawInput({"sss", "srs"});
  neg.parcelIds = Grid<std::int32_t>(3, 2, 0);
  neg.parcelIds.at(1, 1) = -4;
  try {
    vectorize::vectorize(neg, {});
    FAIL() << "negative id accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidInput);
    EXPECT_STREQ(
        e.what(),
        "the parcel grid holds negative parcel id -4 at column 1, row 1 (ids must be >= 0, 0 = no parcel)");
  }
}

namespace {

const Layer& layerNamed(const VectorizeResult& r, const std::string& name) {
  for (const Layer& l : r.layers)
    if (l.name == name) return l;
  throw std::runtime_error("no layer " + name);
}

double populationOf(const Layer& parcels) {
  const int field = parcels.fieldIndex("population");
  double sum = 0;
  for (const Feature& f : parcels.features) sum += std::get<double>(f.values[static_cast<size_t>(field)]);
  return sum;
}

}  // namespace

TEST(Pipeline, AGridOfDevelopedLandWithoutRoadsIsOneBlockWithItsParcelsAndPeople) {
  // Issue 15: 12 x 10 residential cells, four parcels of 6 x 5 cells, 2 people per cell.
  VectorizeInput in = drawInput(blank(12, 10));
  in.parcelIds = Grid<std::int32_t>(12, 10, 0);
  for (int r = 0; r < 10; ++r)
    for (int c = 0; c < 12; ++c) in.parcelIds.at(c, r) = 1 + (r / 5) * 2 + c / 6;
  in.density = Grid<float>(12, 10, 2.0f);
  const VectorizeResult r = vectorize::vectorize(in, {});
  const Layer& blocks = layerNamed(r, "blocks");
  const Layer& parcels = layerNamed(r, "parcels");
  ASSERT_EQ(blocks.features.size(), 1u);
  EXPECT_EQ(parcels.features.size(), 4u);
  EXPECT_NEAR(populationOf(parcels), 240.0, 1e-9);
  EXPECT_EQ(r.warnings,
            (std::vector<std::string>{
                "the land-use grid has no road cells (codes 2 and 3): the road layers are empty",
                "1 closed boundary between undeveloped land and external blocks meets no road and got "
                "no perimeter line (islands become blocks of their own outline)"}));
  // Without a parcels grid the density has no parcel to go to, and the warning says so.
  in.parcelIds = {};
  const VectorizeResult n = vectorize::vectorize(in, {});
  ASSERT_EQ(layerNamed(n, "parcels").features.size(), 1u);
  EXPECT_EQ(populationOf(layerNamed(n, "parcels")), 0.0);
  ASSERT_EQ(n.warnings.size(), 3u);
  EXPECT_EQ(
      n.warnings[2],
      "the density grid holds 240 people, but without a parcels grid (-parcels) there are no input parcels "
      "to carry them: each block is one undeveloped parcel with population 0");
  // Density on cells without a parcel (and no table) is reported too.
  in.parcelIds = Grid<std::int32_t>(12, 10, 1);
  in.parcelIds.at(0, 0) = 0;
  const VectorizeResult hole = vectorize::vectorize(in, {});
  EXPECT_NEAR(populationOf(layerNamed(hole, "parcels")), 238.0, 1e-9);
  ASSERT_EQ(hole.warnings.size(), 3u);
  EXPECT_EQ(hole.warnings[2],
            "2 people of the density grid lie on 1 cell without a parcel (id 0) and reach no parcel of the "
            "parcels layer");
}

TEST(Output, WorldCoordinatesFollowAnyGeotransform) {
  GridSpec spec;
  spec.width = 10;
  spec.height = 8;
  // North-up: internal (x, y) = (col, H - row).
  spec.transform.c = {500.0, 2.0, 0.0, 900.0, 0.0, -2.0};
  Vec2 w = toWorld(patchCentre(3, 1, spec.height), spec);
  EXPECT_EQ(w, spec.cellCentre(3, 1));
  // South-up (row 0 is the southern row).
  spec.transform.c = {500.0, 2.0, 0.0, 100.0, 0.0, 2.0};
  w = toWorld(patchCentre(3, 1, spec.height), spec);
  EXPECT_EQ(w, spec.cellCentre(3, 1));
  EXPECT_DOUBLE_EQ(w.y, 103.0);
  // Rotated by 30 degrees.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  spec.transform.c = {500.0, 2 * c, -2 * s, 900.0, -2 * s, -2 * c};
  w = toWorld(patchCentre(3, 1, spec.height), spec);
  const Vec2 expect = spec.cellCentre(3, 1);
  EXPECT_NEAR(w.x, expect.x, 1e-9);
  EXPECT_NEAR(w.y, expect.y, 1e-9);
}

TEST(Output, SegmentsRunBetweenIntersectionsAndDeadEndsAndShareTheirNodes) {
  RoadGraph g;
  // A T: west arm of 3 nodes, east arm of 2, south arm of 2 primary nodes.
  const int x = g.addNode({5, 5}, NodeType::Secondary);
  int prev = x;
  for (int k = 1; k <= 3; ++k) {
    const int n = g.addNode({5.0 - k, 5}, NodeType::Secondary);
    g.link(prev, n);
    prev = n;
  }
  const int e1 = g.addNode({6, 5}, NodeType::Secondary), e2 = g.addNode({7, 5}, NodeType::Secondary);
  g.link(x, e1);
  g.link(e1, e2);
  const int s1 = g.addNode({5, 4}, NodeType::Primary), s2 = g.addNode({5, 3}, NodeType::Primary);
  g.link(x, s1);
  g.link(s1, s2);
  GridSpec spec;
  spec.width = spec.height = 10;
  const std::vector<Layer> layers = roadLayers(buildRoadNetwork(g), spec);
  ASSERT_EQ(layers[0].features.size(), 4u);  // west, east, x-s1 (secondary class), s1-s2 (primary)
  EXPECT_EQ(layers[1].features.size(), 5u);  // intersection, 3 dead ends, 1 connection
  EXPECT_TRUE(checkRoadNetwork(layers[0], layers[1]).ok());
}

TEST(Checker, FindsCrossingsZeroLengthPiecesDuplicatesAndLoneEnds) {
  Layer roads;
  roads.name = "roads";
  roads.geometryType = GeometryType::LineString;
  Layer nodes;
  nodes.name = "road_nodes";
  nodes.geometryType = GeometryType::Point;
  auto line = [&](LineString l) { roads.features.push_back({std::move(l), {}}); };
  auto node = [&](Vec2 p) { nodes.features.push_back({p, {}}); };
  line({{0, 0}, {10, 10}});
  line({{0, 10}, {10, 0}});  // crosses the first without a node
  line({{10, 10}, {20, 10}});
  for (Vec2 p : {Vec2(0, 0), Vec2(10, 10), Vec2(0, 10), Vec2(10, 0), Vec2(20, 10)}) node(p);
  RoadNetworkCheck c = checkRoadNetwork(roads, nodes);
  EXPECT_EQ(c.crossings, 1u);
  EXPECT_EQ(c.zeroLengthPieces, 0u);
  EXPECT_EQ(c.loneEnds, 0u);
  // A line touching another's interior (T without a node), a zero-length piece, a duplicate node.
  line({{5, 5}, {5, 20}, {5, 20}});
  node(Vec2(5, 20));
  node(Vec2(5, 20));
  c = checkRoadNetwork(roads, nodes);
  EXPECT_EQ(c.crossings, 1u + 2u);  // touches both diagonals at their crossing point
  EXPECT_EQ(c.zeroLengthPieces, 1u);
  EXPECT_EQ(c.duplicateNodes, 1u);
  EXPECT_EQ(c.loneEnds, 1u);  // (5, 5) has no node
  EXPECT_FALSE(c.ok());
}

TEST(GridInput, RastersMustShareTheGridAndHoldClassCodes) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "urbanvec_vectorize_unit";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  GridSpec spec;
  spec.width = 4;
  spec.height = 3;
  spec.transform.c = {1000.0, 10.0, 0.0, 2000.0, 0.0, -10.0};
  Grid<std::uint8_t> lu(4, 3, 4);
  lu.at(1, 1) = 2;
  lu.at(3, 2) = 255;
  const std::string luPath = (dir / "landuse.tif").string();
  io::writeRasterBand(luPath, spec, lu, 255.0);
  vectorize::VectorizeInput in = app::loadGridInput({luPath, "", "", "", ""});
  EXPECT_EQ(in.landUse.at(1, 1), 2);
  EXPECT_EQ(in.landUse.at(3, 2), 0);  // nodata = unused

  GridSpec shifted = spec;
  shifted.transform.c[0] += 5;
  const std::string densityPath = (dir / "density.tif").string();
  io::writeRasterBand(densityPath, shifted, Grid<float>(4, 3, 1.0f), std::nullopt);
  try {
    app::loadGridInput({luPath, densityPath, "", "", ""});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("differ in geotransform"), std::string::npos) << e.what();
  }

  Grid<float> notCodes(4, 3, 0.5f);
  const std::string floatPath = (dir / "float.tif").string();
  io::writeRasterBand(floatPath, spec, notCodes, std::nullopt);
  try {
    app::loadGridInput({floatPath, "", "", "", ""});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "land-use raster '" + floatPath +
            "' (Float32) holds value 0.5 at column 0, row 0, which is not a land-use class code (0..8, 255 = "
            "nodata); map its values to classes with -classes <csv>");
  }
  // The same raster mapped through -classes.
  const std::string classesPath = (dir / "classes.csv").string();
  std::ofstream(classesPath) << "value,class_name\n0.5,park\n";
  in = app::loadGridInput({floatPath, "", "", "", classesPath});
  EXPECT_EQ(in.landUse.at(2, 2), static_cast<std::uint8_t>(LandUse::Park));

  // Parcel table naming an id that is not in the raster.
  Grid<std::int32_t> ids(4, 3, 0);
  ids.at(0, 0) = 3;
  const std::string idsPath = (dir / "parcels.tif").string();
  io::writeRasterBand(idsPath, spec, ids, std::nullopt);
  const std::string tablePath = (dir / "parcels.csv").string();
  std::ofstream(tablePath) << "parcel_id,land_use,population,cells\n3,residential,10,1\n8,commercial,0,2\n";
  try {
    app::loadGridInput({luPath, "", idsPath, tablePath, ""});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "parcel table '" + tablePath +
                                         "' line 3 names parcel id 8, which is not in the "
                                         "parcels raster '" +
                                         idsPath + "'");
  }
  std::filesystem::remove_all(dir);
}

TEST(Output, SimplificationThatUncoversARoadCellIsUndoneOnlyAsFarAsNeeded) {
  // One segment bending up to (5.5, 7) with two small wiggles on a 12 x 12 grid; simplified to its
  // chord at y = 5.5 it leaves the road cell centred at (5.5, 8.5) 3 cells away. Half the tolerance
  // keeps the bend and still drops the wiggles.
  RoadNetwork exact;
  exact.nodes = {{{0.5, 5.5}, NetworkNodeKind::DeadEnd, 1}, {{10.5, 5.5}, NetworkNodeKind::DeadEnd, 1}};
  NetworkSegment s;
  s.points = {{0.5, 5.5}, {3.0, 6.4}, {5.5, 7.0}, {8.0, 6.4}, {10.5, 5.5}};
  s.fromNode = 0;
  s.toNode = 1;
  exact.segments = {s};
  RoadNetwork simplified = exact;
  simplified.segments[0].points = {{0.5, 5.5}, {10.5, 5.5}};
  Grid<std::uint8_t> landUse(12, 12, 0);
  landUse.at(5, 3) = 2;  // centre (5.5, 8.5)
  EXPECT_EQ(restoreUncoveringSegments(simplified, exact, landUse, Grid<std::uint8_t>(), 2.0), 1u);
  const LineString expected = {{0.5, 5.5}, {5.5, 7.0}, {10.5, 5.5}};
  EXPECT_EQ(simplified.segments[0].points, expected);
  // A cell the chord still covers changes nothing.
  RoadNetwork chord = exact;
  chord.segments[0].points = {{0.5, 5.5}, {10.5, 5.5}};
  Grid<std::uint8_t> near(12, 12, 0);
  near.at(5, 5) = 2;  // centre (5.5, 6.5)
  EXPECT_EQ(restoreUncoveringSegments(chord, exact, near, Grid<std::uint8_t>(), 2.0), 0u);
  EXPECT_EQ(chord.segments[0].points.size(), 2u);
}

TEST(Checker, CoverageExcusesCellsOfRemovedDeadEndsAndCountsThemApart) {
  // One road cell at (5, 5) on a 10 x 10 grid and no road: far, unless a removed link passes by.
  Grid<std::uint8_t> landUse(10, 10, 0);
  landUse.at(5, 5) = 2;  // centre (5.5, 4.5)
  const RoadNetwork none;
  EXPECT_EQ(checkRoadCoverage(landUse, Grid<std::uint8_t>(), none, {}).far, 1u);
  const std::array<Vec2, 2> link = {Vec2(4.5, 4.5), Vec2(6.5, 4.5)};
  const RoadCoverageCheck deadEnd = checkRoadCoverage(landUse, Grid<std::uint8_t>(), none, {}, {link});
  EXPECT_EQ(deadEnd.far, 0u);
  EXPECT_EQ(deadEnd.farRemovedDeadEnds, 1u);
  EXPECT_EQ(deadEnd.removedOnPurpose(), 1u);
  EXPECT_NE(deadEnd.describe().find("1 dead ends (B5)"), std::string::npos) << deadEnd.describe();
}
