#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "urbanvec/core/error.hpp"
#include "urbanvec/io/atomic_output.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/raster_io.hpp"
#include "urbanvec/io/vector_io.hpp"

using namespace urbanvec;
namespace fs = std::filesystem;

namespace {
fs::path freshDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("urbanvec_io_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST(AtomicOutput, RefusesExistingOutputWithoutOverwriteAndLeavesNothingOnFailure) {
  fs::path d = freshDir("atomic");
  const std::string target = (d / "out.gpkg").string();
  { std::ofstream(target) << "old"; }
  try {
    io::AtomicOutput out(target, false);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "output file '" + target + "' already exists; use -overwrite to replace it");
  }
  {
    io::AtomicOutput out(target, true);
    std::ofstream(out.tempPath()) << "new";
    // not committed: destructor removes the temporary, target untouched
  }
  std::ifstream in(target);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "old");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator{}), 1);
  {
    io::AtomicOutput out(target, true);
    std::ofstream(out.tempPath()) << "new";
    out.commit();
  }
  std::ifstream in2(target);
  in2 >> content;
  EXPECT_EQ(content, "new");
  EXPECT_THROW(io::AtomicOutput((d / "missing" / "x.gpkg").string(), false), Error);
  fs::remove_all(d);
}

TEST(RasterIo, WritesAndReadsBackGeoreferencedGrid) {
  fs::path d = freshDir("raster");
  GridSpec spec;
  spec.width = 4;
  spec.height = 3;
  spec.transform = GeoTransform{{500000, 12, 0, 4800000, 0, -12}};
  spec.crsWkt = io::crsToWkt("EPSG:32632", "-a_srs");
  Grid<std::uint8_t> g(4, 3, 0);
  g.at(2, 1) = 3;
  const std::string path = (d / "landuse.tif").string();
  io::writeRasterBand(path, spec, g, 255.0);
  io::RasterInfo info;
  Grid<std::uint8_t> back = io::readRasterBand<std::uint8_t>(path, "land-use raster", &info);
  EXPECT_EQ(back.at(2, 1), 3);
  EXPECT_EQ(info.dataType, "Byte");
  EXPECT_EQ(*info.nodata, 255.0);
  EXPECT_EQ(io::crsShortName(info.spec.crsWkt), "EPSG:32632");
  EXPECT_NO_THROW(io::requireSameGrid(spec, "a.tif", info.spec, path));
  GridSpec other = spec;
  other.width = 5;
  try {
    io::requireSameGrid(spec, "a.tif", other, "b.tif");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "'b.tif' and 'a.tif' differ in size (5x3 vs 4x3 cells)");
  }
  EXPECT_THROW(io::readRasterBand<std::uint8_t>((d / "nope.tif").string(), "land-use raster"), Error);
  fs::remove_all(d);
}

TEST(VectorIo, RoundTripsLayersWithStyles) {
  fs::path d = freshDir("vector");
  Layer parcels;
  parcels.name = "parcels";
  parcels.geometryType = GeometryType::Polygon;
  parcels.fields = {{"parcel_id", FieldType::Integer}, {"land_use", FieldType::String}, {"area", FieldType::Real}};
  parcels.features.push_back({Polygon{{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}}, {}},
                              {std::int64_t{7}, std::string("residential"), 100.0}});
  io::VectorWriteOptions options;
  options.crsWkt = io::crsToWkt("EPSG:32633", "-a_srs");
  const std::string path = (d / "city.gpkg").string();
  io::writeVectorDataset(path, {parcels}, options);
  auto names = io::listVectorLayers(path, "result");
  EXPECT_NE(std::find(names.begin(), names.end(), "layer_styles"), names.end());
  auto read = io::readVectorLayer(path, "parcels", "result");
  ASSERT_TRUE(read.has_value());
  ASSERT_EQ(read->layer.features.size(), 1u);
  EXPECT_EQ(std::get<std::string>(read->layer.features[0].values[1]), "residential");
  EXPECT_DOUBLE_EQ(area(std::get<Polygon>(read->layer.features[0].geometry)), 100.0);
  EXPECT_EQ(io::crsShortName(read->crsWkt), "EPSG:32633");
  auto styles = io::readVectorLayer(path, "layer_styles", "result");
  ASSERT_TRUE(styles.has_value());
  const int qml = styles->layer.fieldIndex("styleQML");
  ASSERT_GE(qml, 0);
  EXPECT_NE(std::get<std::string>(styles->layer.features[0].values[qml]).find("attr=\"land_use\""), std::string::npos);
  EXPECT_FALSE(io::readVectorLayer(path, "blocks", "result").has_value());
  fs::remove_all(d);
}
