// The road stages that run on -threads (B2 and B6 averaging, B7 through roads: issue 21) give the
// graph of one thread, bit for bit, on the real sample grids: B7 runs its steps speculatively on
// each thread's copy of the graph and commits them in node order, running a step again when a node it
// read has moved since; Monaco's dense centre makes dozens of its steps run again (more with more threads).
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "urbanvec/io/raster_io.hpp"
#include "urbanvec/vectorize/pipeline.hpp"

using namespace urbanvec;
using namespace urbanvec::vectorize;

namespace {

VectorizeResult roadStages(const std::string& sample, int threads) {
  io::RasterInfo info;
  VectorizeInput input;
  input.landUse = io::readRasterBand<std::uint8_t>(
      std::string(URBANVEC_SOURCE_DIR) + "/sample_data/" + sample + "/landuse.tif", "land-use raster", &info);
  input.spec = info.spec;
  VectorizeOptions options;
  options.roadsOnly = true;
  options.keepStageGraphs = true;
  options.city.parcels.threads = threads;
  return urbanvec::vectorize::vectorize(input, options);
}

bool samePoint(const Vec2& a, const Vec2& b) {
  return std::memcmp(&a.x, &b.x, sizeof(double)) == 0 && std::memcmp(&a.y, &b.y, sizeof(double)) == 0;
}

/// The first difference between two graphs (positions bit for bit, links, liveness), or "".
std::string firstDifference(const RoadGraph& a, const RoadGraph& b) {
  if (a.nodes.size() != b.nodes.size()) return "node count";
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const RoadNode& m = a.nodes[i];
    const RoadNode& n = b.nodes[i];
    if (!samePoint(m.p, n.p) || m.alive != n.alive || m.links != n.links) return "node " + std::to_string(i);
  }
  return "";
}

class ParallelRoadStages : public ::testing::TestWithParam<std::string> {};

TEST_P(ParallelRoadStages, EveryGraphStageAndTheNetworkEqualOneThreadsBitForBit) {
  const VectorizeResult one = roadStages(GetParam(), 1);
  ASSERT_FALSE(one.stageGraphs.empty());
  for (int threads : {2, 3, 8}) {
    const VectorizeResult many = roadStages(GetParam(), threads);
    ASSERT_EQ(many.stageGraphs.size(), one.stageGraphs.size());
    for (std::size_t s = 0; s < one.stageGraphs.size(); ++s)
      EXPECT_EQ(firstDifference(one.stageGraphs[s].second, many.stageGraphs[s].second), "")
          << one.stageGraphs[s].first << ", " << threads << " threads";
    ASSERT_EQ(many.network.segments.size(), one.network.segments.size()) << threads << " threads";
    for (std::size_t s = 0; s < one.network.segments.size(); ++s) {
      const LineString& a = one.network.segments[s].points;
      const LineString& b = many.network.segments[s].points;
      bool same = a.size() == b.size();
      for (std::size_t k = 0; same && k < a.size(); ++k) same = samePoint(a[k], b[k]);
      EXPECT_TRUE(same) << "road segment " << s << ", " << threads << " threads";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Samples, ParallelRoadStages, ::testing::Values("monaco", "bubenec"));

}  // namespace
