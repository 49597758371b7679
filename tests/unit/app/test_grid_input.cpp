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
