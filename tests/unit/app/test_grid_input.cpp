// Inputs that used to give silently wrong output (issue 15): grids in degrees or feet, densities that
// are negative or not finite, parcel and class tables separated by semicolons or tabs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

#include "urbanvec/app/grid_input.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/raster_io.hpp"
#include "urbanvec/vectorize/roads/road_network.hpp"

using namespace urbanvec;
namespace fs = std::filesystem;

namespace {

fs::path freshDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("urbanvec_input_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// A 4 x 3 grid of 10 m cells in `crs` with its top-left corner at (x0, y0), cells of `cell` units.
GridSpec frame(const std::string& crs, double x0, double y0, double cell) {
  GridSpec spec;
  spec.width = 4;
  spec.height = 3;
  spec.transform.c = {x0, cell, 0.0, y0, 0.0, -cell};
  spec.crsWkt = crs.empty() ? "" : io::crsToWkt(crs, "test");
  return spec;
}

/// The frame of the Monaco sample (EPSG:32632, 10 m cells).
GridSpec metricFrame() {
  return frame("EPSG:32632", 371576, 4845656, 10);
}

/// A residential land-use raster on metricFrame() in `dir`; returns its path.
std::string writeResidential(const fs::path& dir) {
  const std::string path = (dir / "landuse.tif").string();
  io::writeRasterBand(path, metricFrame(), Grid<std::uint8_t>(4, 3, 4), std::nullopt);
  return path;
}

std::string message(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(Crs, NonMetricUnitNamesDegreesAndFeet) {
  EXPECT_EQ(io::nonMetricUnit(io::crsToWkt("EPSG:4326", "t")), "degrees");
  EXPECT_EQ(io::nonMetricUnit(io::crsToWkt("EPSG:2263", "t")), "US survey feet");
  EXPECT_EQ(io::nonMetricUnit(io::crsToWkt("EPSG:2227", "t")), "US survey feet");
  EXPECT_EQ(io::nonMetricUnit(io::crsToWkt("EPSG:32632", "t")), "");
  EXPECT_EQ(io::nonMetricUnit(""), "");
}

TEST(Crs, UtmZoneOfAPointInAnyCrs) {
  EXPECT_EQ(io::utmEpsgAt(io::crsToWkt("EPSG:4326", "t"), 7.42, 43.73), 32632);   // Monaco
  EXPECT_EQ(io::utmEpsgAt(io::crsToWkt("EPSG:4326", "t"), -43.2, -22.9), 32723);  // Rio
  EXPECT_EQ(io::utmEpsgAt(io::crsToWkt("EPSG:32632", "t"), 371576, 4845656), 32632);
  EXPECT_EQ(io::utmEpsgAt(io::crsToWkt("EPSG:2263", "t"), 985000, 203000), 32618);  // Manhattan
  EXPECT_EQ(io::utmEpsgAt("", 0, 0), 0);
}

TEST(GridInput, RefusesALandUseGridInDegreesOrFeetSuggestingItsUtmZone) {
  const fs::path d = freshDir("crs");
  const Grid<std::uint8_t> lu(4, 3, 4);
  const std::string degrees = (d / "degrees.tif").string();
  io::writeRasterBand(degrees, frame("EPSG:4326", 7.42, 43.74, 0.0001), lu, std::nullopt);
  EXPECT_EQ(message([&] {
              app::loadGridInput({degrees, "", "", "", ""});
            }),
            "land-use raster '" + degrees +
                "' is in EPSG:4326; vectorize needs a projected CRS in metres (the grid is in degrees); "
                "reproject it with gdalwarp -t_srs EPSG:32632");
  const std::string feet = (d / "feet.tif").string();
  io::writeRasterBand(feet, frame("EPSG:2263", 985000, 203000, 30), lu, std::nullopt);
  EXPECT_EQ(
      message([&] {
        app::loadGridInput({feet, "", "", "", ""});
      }),
      "land-use raster '" + feet +
          "' is in EPSG:2263; vectorize needs a projected CRS in metres (the grid is in US survey feet); "
          "reproject it with gdalwarp -t_srs EPSG:32618");
  // Metres and no CRS at all (a warning elsewhere) are read.
  const std::string metres = (d / "metres.tif").string();
  io::writeRasterBand(metres, metricFrame(), lu, std::nullopt);
  EXPECT_NO_THROW(app::loadGridInput({metres, "", "", "", ""}));
  const std::string none = (d / "none.tif").string();
  io::writeRasterBand(none, frame("", 0, 30, 10), lu, std::nullopt);
  EXPECT_NO_THROW(app::loadGridInput({none, "", "", "", ""}));
  fs::remove_all(d);
}

TEST(GridInput, RefusesNegativeOrNonFiniteDensitiesButReadsNodataAsZero) {
  const fs::path d = freshDir("density");
  const GridSpec spec = metricFrame();
  const std::string lu = writeResidential(d);
  const std::string density = (d / "density.tif").string();
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (const auto& [value, shown] : std::vector<std::pair<float, std::string>>{
           {-0.5f, "-0.5"}, {nan, "nan"}, {inf, "inf"}, {-inf, "-inf"}}) {
    Grid<float> g(4, 3, 1.0f);
    g.at(2, 1) = value;
    io::writeRasterBand(density, spec, g, std::nullopt);
    EXPECT_EQ(message([&] {
                app::loadGridInput({lu, density, "", "", ""});
              }),
              "density raster '" + density + "' holds value " + shown +
                  " at column 2, row 1, which is not a population per cell (a finite number >= 0; only "
                  "nodata cells count as 0)");
  }
  for (const float nodata : {-9999.0f, nan}) {
    Grid<float> g(4, 3, 1.5f);
    g.at(2, 1) = nodata;
    io::writeRasterBand(density, spec, g, static_cast<double>(nodata));
    const vectorize::VectorizeInput in = app::loadGridInput({lu, density, "", "", ""});
    EXPECT_EQ(in.density.at(2, 1), 0.0f);
    EXPECT_EQ(in.density.at(1, 2), 1.5f);
  }
  fs::remove_all(d);
}

TEST(GridInput, ReadsParcelTablesSeparatedByCommasSemicolonsOrTabs) {
  const fs::path d = freshDir("table");
  const GridSpec spec = metricFrame();
  const std::string lu = writeResidential(d);
  Grid<std::int32_t> ids(4, 3, 1);
  ids.at(3, 2) = 2;
  const std::string idsPath = (d / "parcels.tif").string();
  io::writeRasterBand(idsPath, spec, ids, std::nullopt);
  const std::string table = (d / "parcels.csv").string();
  for (const std::string& text :
       {std::string("parcel_id,land_use,population,cells\n1,residential,12.5,11\n2,park,0,1\n"),
        std::string("parcel_id;land_use;population;cells\n1;residential;12,5;11\n2;park;0;1\n"),
        std::string("parcel_id\tland_use\tpopulation\tcells\n1\tresidential\t12.5\t11\n2\tpark\t0\t1\n")}) {
    std::ofstream(table) << text;
    const vectorize::VectorizeInput in = app::loadGridInput({lu, "", idsPath, table, ""});
    ASSERT_EQ(in.parcelTable.size(), 2u) << text;
    EXPECT_EQ(in.parcelTable[0].id, 1);
    EXPECT_EQ(in.parcelTable[0].use, LandUse::Residential);
    EXPECT_EQ(in.parcelTable[0].population, 12.5) << text;
    EXPECT_EQ(in.parcelTable[0].cells, 11);
    EXPECT_EQ(in.parcelTable[1].use, LandUse::Park);
  }
  std::ofstream(table) << "parcel_id;land_use;population;cells\n1,residential,1,11\n";
  EXPECT_EQ(message([&] {
              app::loadGridInput({lu, "", idsPath, table, ""});
            }),
            "parcel table '" + table +
                "' line 2 has too few columns (the header separates columns with semicolons, this line seems "
                "to use commas)");
  std::ofstream(table) << "id\tuse\tpopulation\tcells\n1\tresidential\t1\t11\n";
  EXPECT_EQ(
      message([&] {
        app::loadGridInput({lu, "", idsPath, table, ""});
      }),
      "parcel table '" + table +
          "' has no column 'parcel_id' (expected parcel_id,land_use,population,cells, separated by tabs)");
  // A comma table keeps its message.
  std::ofstream(table) << "id,use,population,cells\n1,residential,1,11\n";
  EXPECT_EQ(message([&] {
              app::loadGridInput({lu, "", idsPath, table, ""});
            }),
            "parcel table '" + table +
                "' has no column 'parcel_id' (expected parcel_id,land_use,population,cells)");
  fs::remove_all(d);
}

TEST(GridInput, ReadsClassTablesSeparatedBySemicolons) {
  const fs::path d = freshDir("classes");
  const std::string classes = (d / "classes.csv").string();
  std::ofstream(classes) << "# from a spreadsheet\nvalue;class_name\n0,5;park\n12;water\n";
  const auto table = app::readClassTable(classes);
  ASSERT_EQ(table.size(), 2u);
  EXPECT_EQ(table[0].first, 0.5);
  EXPECT_EQ(table[0].second, LandUse::Park);
  EXPECT_EQ(table[1].first, 12.0);
  EXPECT_EQ(table[1].second, LandUse::Water);
  fs::remove_all(d);
}

// Issue 22: `-srcwin` reads only a window of every raster, georeferenced at its place; rows of the
// parcel table outside it are skipped; positions in messages are whole-raster cells.
TEST(GridInput, ReadsOnlyTheWindowGeoreferencedAtItsPlace) {
  const fs::path d = freshDir("window");
  const GridSpec spec = metricFrame();
  Grid<std::uint8_t> lu(4, 3, 4);
  Grid<float> density(4, 3, 0.0f);
  Grid<std::int32_t> ids(4, 3, 0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      lu.at(c, r) = static_cast<std::uint8_t>((c + r) % 8 + 1);
      density.at(c, r) = static_cast<float>(10 * r + c);
      ids.at(c, r) = 1 + c;  // one parcel per column
    }
  const std::string luPath = (d / "landuse.tif").string(), dPath = (d / "density.tif").string(),
                    pPath = (d / "parcels.tif").string(), table = (d / "parcels.csv").string();
  io::writeRasterBand(luPath, spec, lu, std::nullopt);
  io::writeRasterBand(dPath, spec, density, std::nullopt);
  io::writeRasterBand(pPath, spec, ids, std::nullopt);
  std::ofstream(table) << "parcel_id,land_use,population,cells\n1,residential,1,3\n2,park,2,3\n3,park,3,3\n"
                          "4,commercial,4,3\n";
  app::GridInputPaths paths{luPath, dPath, pPath, table, ""};
  paths.window = io::RasterWindow{1, 1, 2, 2};
  const vectorize::VectorizeInput in = app::loadGridInput(paths);
  EXPECT_EQ(in.spec.width, 2);
  EXPECT_EQ(in.spec.height, 2);
  // The window keeps the whole raster's transform and frame (issue 22): its first cell's top-left
  // corner is internal (frameDx, frameDy + height), which is world (371576 + 10, 4845656 - 10).
  EXPECT_DOUBLE_EQ(in.spec.transform.c[0], 371576);
  EXPECT_DOUBLE_EQ(in.spec.transform.c[3], 4845656);
  EXPECT_EQ(in.spec.frameCol, 1);
  EXPECT_EQ(in.spec.frameRow, 1);
  EXPECT_EQ(in.spec.frameHeight, 3);
  EXPECT_EQ(in.landUse.frameDx, 1);
  EXPECT_EQ(in.landUse.frameDy, 0);  // 3 rows - row 1 - 2 rows: the window's bottom is the raster's
  const Vec2 corner =
      vectorize::toWorld(Vec2(in.landUse.frameDx, in.landUse.frameDy + in.landUse.height), in.spec);
  EXPECT_DOUBLE_EQ(corner.x, 371576 + 10);
  EXPECT_DOUBLE_EQ(corner.y, 4845656 - 10);
  EXPECT_EQ(in.originCol, 1);
  EXPECT_EQ(in.originRow, 1);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) {
      EXPECT_EQ(in.landUse.at(c, r), lu.at(c + 1, r + 1));
      EXPECT_EQ(in.density.at(c, r), density.at(c + 1, r + 1));
      EXPECT_EQ(in.parcelIds.at(c, r), ids.at(c + 1, r + 1));
    }
  // Parcels 1 and 4 lie outside the window: their rows are skipped, not refused.
  ASSERT_EQ(in.parcelTable.size(), 2u);
  EXPECT_EQ(in.parcelTable[0].id, 2);
  EXPECT_EQ(in.parcelTable[1].id, 3);
  // The open-regions raster is read through the window and holds 0 or 1 only.
  Grid<std::uint8_t> open(4, 3, 0);
  open.at(2, 1) = 1;
  const std::string oPath = (d / "open.tif").string();
  io::writeRasterBand(oPath, spec, open, std::nullopt);
  paths.openRegions = oPath;
  const vectorize::VectorizeInput withOpen = app::loadGridInput(paths);
  ASSERT_EQ(withOpen.openRegions.width, 2);
  EXPECT_EQ(withOpen.openRegions.at(1, 0), 1);
  EXPECT_EQ(withOpen.openRegions.at(0, 0), 0);
  open.at(1, 1) = 2;
  io::writeRasterBand(oPath, spec, open, std::nullopt);
  EXPECT_EQ(message([&] { app::loadGridInput(paths); }),
            "open-regions raster '" + oPath +
                "' holds value 2 at column 1, row 1, which is not 0 (enclosed region) or 1 (region reaching "
                "the grid's edge)");
  paths.openRegions.clear();
  // A window reaching past the grid is refused, naming the raster's size.
  paths.window = io::RasterWindow{3, 2, 2, 2};
  EXPECT_EQ(message([&] { app::loadGridInput(paths); }),
            "-srcwin 3 2 2 2 is not inside land-use raster '" + luPath +
                "' (4 x 3 cells; the window must lie within columns 0..3 and rows 0..2)");
  paths.window = io::RasterWindow{0, 0, 0, 2};
  EXPECT_EQ(message([&] { app::loadGridInput(paths); }),
            "-srcwin 0 0 0 2: the window size must be at least 1 x 1 cells");
  // A bad value inside the window is reported at its whole-raster cell.
  density.at(2, 2) = -1.0f;
  io::writeRasterBand(dPath, spec, density, std::nullopt);
  paths.window = io::RasterWindow{1, 1, 2, 2};
  EXPECT_NE(message([&] { app::loadGridInput(paths); }).find("at column 2, row 2"), std::string::npos);
  // The rasters must still be one grid as wholes: a density raster of another size is refused.
  io::writeRasterBand(dPath, spec, Grid<float>(3, 3, 0.0f), std::nullopt);
  EXPECT_NE(message([&] { app::loadGridInput(paths); }).find("differ in size"), std::string::npos);
  fs::remove_all(d);
}
