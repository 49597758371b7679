#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

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
    EXPECT_EQ(std::string(e.what()),
              "output file '" + target + "' already exists; use -overwrite to replace it");
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
  parcels.fields = {
      {"parcel_id", FieldType::Integer}, {"land_use", FieldType::String}, {"area", FieldType::Real}};
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
  EXPECT_NE(std::get<std::string>(styles->layer.features[0].values[qml]).find("attr=\"land_use\""),
            std::string::npos);
  EXPECT_FALSE(io::readVectorLayer(path, "blocks", "result").has_value());
  fs::remove_all(d);
}

namespace {
// Layers big enough that a background writer is still busy when the next one arrives.
std::vector<Layer> streamLayers() {
  Layer roads{
      "roads", GeometryType::LineString, {{"road_id", FieldType::Integer}, {"kind", FieldType::String}}, {}};
  Layer nodes{"road_nodes", GeometryType::Point, {{"node_id", FieldType::Integer}}, {}};
  Layer parcels{
      "parcels", GeometryType::Polygon, {{"parcel_id", FieldType::Integer}, {"area", FieldType::Real}}, {}};
  for (int i = 0; i < 3000; ++i) {
    const double x = (i * 37) % 1000, y = (i * 91) % 1000;
    roads.features.push_back(
        {LineString{{x, y}, {x + 5, y + 3}, {x + 9, y}}, {std::int64_t{i}, std::string("road")}});
    nodes.features.push_back({Vec2{x, y}, {std::int64_t{i}}});
    parcels.features.push_back(
        {Polygon{{{x, y}, {x + 4, y}, {x + 4, y + 4}, {x, y + 4}, {x, y}}, {}}, {std::int64_t{i}, 16.0}});
  }
  return {roads, nodes, parcels};
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
}  // namespace

TEST(VectorIo, LayerStreamWritesTheSameFileOnItsOwnThreadAsInline) {
  fs::path d = freshDir("stream");
  const std::vector<std::string> names = {"roads", "road_nodes", "parcels"};
  io::VectorWriteOptions options;
  const std::string crs = io::crsToWkt("EPSG:32633", "-a_srs");
  std::string bytes[2];
  for (int background = 0; background < 2; ++background) {
    const std::string path = (d / ("city" + std::to_string(background) + ".gpkg")).string();
    io::VectorOutput out(path, options, names, io::OutputRules{});
    {
      io::LayerStream stream(out, crs, background == 1);
      for (Layer& layer : streamLayers()) stream.add(std::move(layer));
      stream.finish();
    }
    out.commit();
    bytes[background] = fileBytes(path);
    EXPECT_EQ(io::listVectorLayers(path, "result"),
              (std::vector<std::string>{"roads", "road_nodes", "parcels", "layer_styles"}));
    auto parcels = io::readVectorLayer(path, "parcels", "result");
    ASSERT_TRUE(parcels.has_value());
    EXPECT_EQ(parcels->layer.features.size(), 3000u);
    EXPECT_EQ(io::crsShortName(parcels->crsWkt), "EPSG:32633");
  }
  EXPECT_FALSE(bytes[0].empty());
  EXPECT_TRUE(bytes[0] == bytes[1]) << "the background writer made another file than the inline one";
  fs::remove_all(d);
}

TEST(VectorIo, LayerStreamDestroyedUnfinishedStopsAtOnceAndLeavesNoOutput) {
  fs::path d = freshDir("stream_cancel");
  const std::string path = (d / "city.gpkg").string();
  for (int background = 0; background < 2; ++background) {
    // Each layer waits 3 s before it is written (the test hook of the data-safety tests), so a
    // writer that did not stop when the run fails would hold the run for 6 s.
    if (background) ::setenv("URBANVEC_FAULT", "write-delay-ms=3000", 1);
    const auto t0 = std::chrono::steady_clock::now();
    {
      io::VectorOutput out(path, io::VectorWriteOptions{}, {"roads", "road_nodes", "parcels"},
                           io::OutputRules{});
      io::LayerStream stream(out, {}, background == 1);
      std::vector<Layer> layers = streamLayers();
      stream.add(std::move(layers[0]));
      stream.add(std::move(layers[1]));
      std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the writer is inside the first layer
      // The run fails here: the stream goes first (stopping its thread), then the output's staging.
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ::unsetenv("URBANVEC_FAULT");
    if (background) EXPECT_LT(seconds, 2.5);
    EXPECT_FALSE(fs::exists(path));
    EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator{}), 0);
  }
  fs::remove_all(d);
}
