// The committed sample grids obey the road rules the vectorizer relies on, and the grid CRS is chosen
// as issue 2 §2 says (UTM of the data's centre for geographic input, else the input CRS).
#include <gtest/gtest.h>

#include "urbanvec/app/city_source.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/gridify/road_raster.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/raster_io.hpp"

using namespace urbanvec;

class SampleGrid : public ::testing::TestWithParam<std::string> {};

TEST_P(SampleGrid, RoadsAreFourConnectedOneAndTwoCellsWide) {
  const std::string path = std::string(URBANVEC_SOURCE_DIR) + "/sample_data/" + GetParam() + "/landuse.tif";
  io::RasterInfo info;
  const Grid<std::uint8_t> grid = io::readRasterBand<std::uint8_t>(path, "land-use raster", &info);
  EXPECT_TRUE(io::isProjectedInMetres(info.spec.crsWkt)) << path;
  std::size_t roads = 0;
  for (std::uint8_t v : grid.cells) roads += (v == 2 || v == 3);
  EXPECT_GT(roads, 500u);
  const gridify::RoadWidthReport report = gridify::checkRoadWidths(grid);
  EXPECT_EQ(report.secondaryBlocks2x2, 0u);
  EXPECT_EQ(report.primaryOutside2x2, 0u);
  EXPECT_EQ(report.primaryBlocks3x3, 0u);
  EXPECT_EQ(report.diagonalOnlyLinks, 0u);
}

INSTANTIATE_TEST_SUITE_P(Samples, SampleGrid, ::testing::Values("monaco", "bubenec"));

TEST(GridCrs, GeographicInputGetsTheUtmZoneOfItsCentre) {
  const std::string wgs84 = io::crsToWkt("EPSG:4326", "test");
  EXPECT_EQ(io::crsShortName(app::chooseGridCrs(wgs84, 7.42, 43.74, "")), "EPSG:32632");
  EXPECT_EQ(io::crsShortName(app::chooseGridCrs(wgs84, -58.4, -34.6, "")), "EPSG:32721");
}

TEST(GridCrs, ProjectedInputKeepsItsCrsAndUserTargetWins) {
  const std::string utm33 = io::crsToWkt("EPSG:32633", "test");
  EXPECT_EQ(io::crsShortName(app::chooseGridCrs(utm33, 460000, 5550000, "")), "EPSG:32633");
  EXPECT_EQ(io::crsShortName(app::chooseGridCrs(utm33, 460000, 5550000, "EPSG:3035")), "EPSG:3035");
}

TEST(GridCrs, GeographicUserTargetIsRefused) {
  const std::string utm33 = io::crsToWkt("EPSG:32633", "test");
  EXPECT_THROW(app::chooseGridCrs(utm33, 460000, 5550000, "EPSG:4326"), Error);
}
