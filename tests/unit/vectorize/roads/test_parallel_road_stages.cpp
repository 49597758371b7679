// The road stages that run on -threads (B2 and B6 averaging, B7 through roads: issue 21) give the
// graph of one thread, bit for bit, on the real sample grids: B7 runs its steps speculatively on
// each thread's copy of the graph and commits them in node order, running a step again when a node it
// read has moved since; Monaco's dense centre makes dozens of its steps run again (more with more threads).
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <string>

#include "urbanvec/core/planar_graph.hpp"
#include "urbanvec/io/raster_io.hpp"
#include "urbanvec/vectorize/pipeline.hpp"
#include "urbanvec/vectorize/roads/cycle_removal.hpp"

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

/// B4's bounded faces as the stage found them before issue 21 walked the adjacency lists directly: a
/// PlanarGraph of the road links with the graph's link order as rotation, its faces, the same area
/// filter, the links walked both ways dropped.
std::vector<std::vector<int>> planarGraphFaces(const RoadGraph& g) {
  PlanarGraph planar;
  for (const RoadNode& n : g.nodes) planar.addNode(n.p);
  auto roadNode = [&](std::size_t i) { return g.nodes[i].alive && g.nodes[i].type != NodeType::Perimeter; };
  std::map<std::pair<int, int>, int> edgeOf;
  for (std::size_t i = 0; i < g.nodes.size(); ++i)
    if (roadNode(i))
      for (int j : g.nodes[i].links)
        if (g.nodes[j].type != NodeType::Perimeter && static_cast<int>(i) < j)
          edgeOf[{static_cast<int>(i), j}] = planar.addEdge(static_cast<int>(i), j);
  for (std::size_t i = 0; i < g.nodes.size(); ++i) {
    if (!roadNode(i)) continue;
    std::vector<int> rotation;
    for (int j : g.nodes[i].links)
      if (g.nodes[j].type != NodeType::Perimeter)
        rotation.push_back(edgeOf.at({std::min(static_cast<int>(i), j), std::max(static_cast<int>(i), j)}));
    if (!rotation.empty()) planar.setRotation(static_cast<int>(i), rotation);
  }
  std::vector<std::vector<int>> out;
  std::vector<int> walked(planar.edgeCount(), 0);
  for (const PlanarGraph::Face& face : planar.faces()) {
    if (face.twiceSignedArea < -1e-9 || face.twiceSignedArea > 2e300) continue;
    for (int h : face.halfEdges) ++walked[PlanarGraph::edgeOf(h)];
    std::vector<int> cycle;
    for (int h : face.halfEdges)
      if (walked[PlanarGraph::edgeOf(h)] == 1) cycle.push_back(planar.origin(h));
    for (int h : face.halfEdges) walked[PlanarGraph::edgeOf(h)] = 0;
    if (cycle.size() >= 3) out.push_back(std::move(cycle));
  }
  return out;
}

// B4 (and F's loop removal) walk the faces on the adjacency lists (issue 21): the same faces, in the same
// order, from the same start node, as the PlanarGraph walk gave, on every graph stage of the samples.
TEST_P(ParallelRoadStages, FaceWalkOnTheAdjacencyEqualsThePlanarGraphWalk) {
  const VectorizeResult one = roadStages(GetParam(), 1);
  ASSERT_FALSE(one.stageGraphs.empty());
  std::size_t total = 0;
  for (const auto& [stage, graph] : one.stageGraphs) {
    const std::vector<std::vector<int>> faces = boundedRoadFaces(graph);
    EXPECT_EQ(faces, planarGraphFaces(graph)) << stage;
    total += faces.size();
  }
  EXPECT_GT(total, GetParam() == "monaco" ? 1000u : 20u);
}

INSTANTIATE_TEST_SUITE_P(Samples, ParallelRoadStages, ::testing::Values("monaco", "bubenec"));

}  // namespace
