// core/planar_graph: every query checked against answers worked out by hand on small graphs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "urbanvec/core/planar_graph.hpp"

using namespace urbanvec;

namespace {

/// A (cols+1) x (rows+1) lattice of unit squares; node id = row * (cols + 1) + col.
PlanarGraph lattice(int cols, int rows) {
  PlanarGraph g;
  for (int r = 0; r <= rows; ++r)
    for (int c = 0; c <= cols; ++c) g.addNode({static_cast<double>(c), static_cast<double>(r)});
  auto id = [&](int c, int r) { return r * (cols + 1) + c; };
  for (int r = 0; r <= rows; ++r)
    for (int c = 0; c <= cols; ++c) {
      if (c < cols) g.addEdge(id(c, r), id(c + 1, r));
      if (r < rows) g.addEdge(id(c, r), id(c, r + 1));
    }
  g.sortRotations();
  return g;
}

double pathCost(const PlanarGraph& g, const std::vector<int>& path, const std::function<double(int)>& cost) {
  double total = 0.0;
  for (int e : path) total += cost(e);
  return total;
}

}  // namespace

TEST(PlanarGraph, LatticeHasOneBoundedFacePerSquareAndOneOuterFace) {
  const PlanarGraph g = lattice(3, 2);
  const std::vector<PlanarGraph::Face> all = g.faces();
  ASSERT_EQ(all.size(), 7u);  // 6 squares + the outer face: Euler V - E + F = 12 - 17 + 7 = 2
  int outer = 0;
  double bounded = 0.0;
  for (const PlanarGraph::Face& f : all) {
    if (f.twiceSignedArea < 0) {
      ++outer;
      EXPECT_DOUBLE_EQ(f.twiceSignedArea, -12.0);  // the 3 x 2 rectangle, clockwise
      EXPECT_EQ(f.halfEdges.size(), 10u);
    } else {
      bounded += f.twiceSignedArea;
      EXPECT_DOUBLE_EQ(f.twiceSignedArea, 2.0);  // a unit square, counter-clockwise
      EXPECT_EQ(g.faceNodes(f).size(), 4u);
    }
  }
  EXPECT_EQ(outer, 1);
  EXPECT_DOUBLE_EQ(bounded, 12.0);
  EXPECT_EQ(g.boundedFaces().size(), 6u);
  // Every half-edge lies on exactly one face.
  std::size_t halfEdges = 0;
  for (const PlanarGraph::Face& f : all) halfEdges += f.halfEdges.size();
  EXPECT_EQ(halfEdges, 2 * g.edgeCount());
}

TEST(PlanarGraph, FaceWalkKeepsTheFaceOnTheLeftAndItsRingIsClosed) {
  const PlanarGraph g = lattice(1, 1);
  const std::vector<PlanarGraph::Face> bounded = g.boundedFaces();
  ASSERT_EQ(bounded.size(), 1u);
  const Ring ring = g.faceRing(bounded[0]);
  ASSERT_EQ(ring.size(), 5u);
  EXPECT_EQ(ring.front(), ring.back());
  EXPECT_DOUBLE_EQ(signedArea(ring), 1.0);
  // The outer face is found first: node 0's first edge clockwise from north is the one to (0, 1),
  // and the face on the left of 0 -> (0, 1) is outside the square.
  EXPECT_LT(g.faces().front().twiceSignedArea, 0.0);
}

TEST(PlanarGraph, PolylineEdgesCountInTheFaceArea) {
  PlanarGraph g;
  const int a = g.addNode({0, 0}), b = g.addNode({2, 0}), c = g.addNode({2, 2}), d = g.addNode({0, 2});
  g.addEdge(a, b, {{0, 0}, {1, -1}, {2, 0}});  // a bump of area 1 below the square
  g.addEdge(b, c);
  g.addEdge(c, d);
  g.addEdge(d, a);
  g.sortRotations();
  const std::vector<PlanarGraph::Face> bounded = g.boundedFaces();
  ASSERT_EQ(bounded.size(), 1u);
  EXPECT_DOUBLE_EQ(bounded[0].twiceSignedArea, 2.0 * 5.0);
  EXPECT_EQ(g.faceRing(bounded[0]).size(), 6u);
}

TEST(PlanarGraph, TreeHasOnlyItsOuterFaceOfZeroArea) {
  PlanarGraph g;
  const int centre = g.addNode({0, 0});
  for (const Vec2& p : {Vec2(1, 0), Vec2(0, 1), Vec2(-1, 0), Vec2(0, -1)}) g.addEdge(centre, g.addNode(p));
  g.sortRotations();
  const std::vector<PlanarGraph::Face> all = g.faces();
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].halfEdges.size(), 8u);
  EXPECT_DOUBLE_EQ(all[0].twiceSignedArea, 0.0);
  EXPECT_TRUE(g.boundedFaces().empty());
  EXPECT_EQ(g.degree(centre), 4);
  // Clockwise from north: (0, 1), (1, 0), (0, -1), (-1, 0).
  std::vector<Vec2> order;
  for (int e : g.node(centre).edges) order.push_back(g.node(g.otherEnd(e, centre)).p);
  EXPECT_EQ(order, (std::vector<Vec2>{{0, 1}, {1, 0}, {0, -1}, {-1, 0}}));
}

TEST(PlanarGraph, ComponentsAreNumberedByTheirLowestNode) {
  PlanarGraph g;
  for (int i = 0; i < 7; ++i) g.addNode({static_cast<double>(i), 0.0});
  g.addEdge(0, 3);
  g.addEdge(3, 5);
  g.addEdge(1, 2);
  g.addEdge(4, 6);
  int count = 0;
  EXPECT_EQ(g.components(&count), (std::vector<int>{0, 1, 1, 0, 2, 0, 2}));
  EXPECT_EQ(count, 3);
  PlanarGraph isolated;
  isolated.addNode({0, 0});
  isolated.addNode({1, 0});
  EXPECT_EQ(isolated.components(&count), (std::vector<int>{0, 1}));
  EXPECT_EQ(count, 2);
}

TEST(PlanarGraph, ShortestPathFindsTheCheapestRouteWithOrWithoutHeuristic) {
  const PlanarGraph g = lattice(4, 4);
  auto id = [](int c, int r) { return r * 5 + c; };
  // Edges touching column 2 below row 4 are expensive: the cheap route goes over the top row.
  auto cost = [&](int e) {
    const PlanarGraph::Edge& edge = g.edge(e);
    const bool wall = (g.node(edge.a).p.x == 2.0 || g.node(edge.b).p.x == 2.0) && g.node(edge.a).p.y < 4.0 &&
                      g.node(edge.b).p.y < 4.0;
    return wall ? 100.0 : g.edgeLength(e);
  };
  const auto dijkstra = g.shortestPath(id(0, 0), id(4, 0), cost);
  const auto astar = g.shortestPath(id(0, 0), id(4, 0), cost, g.euclideanHeuristic(id(4, 0)));
  ASSERT_TRUE(dijkstra && astar);
  EXPECT_DOUBLE_EQ(pathCost(g, *dijkstra, cost), 12.0);  // up 4, across 4, down 4
  EXPECT_DOUBLE_EQ(pathCost(g, *astar, cost), 12.0);
  EXPECT_EQ(dijkstra->size(), 12u);
  // The path is connected from start to goal.
  int at = id(0, 0);
  for (int e : *astar) at = g.otherEnd(e, at);
  EXPECT_EQ(at, id(4, 0));
  // Plain lengths: 4 steps straight along the bottom.
  const auto straight = g.shortestPath(id(0, 0), id(4, 0), [&](int e) { return g.edgeLength(e); });
  EXPECT_EQ(straight->size(), 4u);
  EXPECT_EQ(g.shortestPath(id(3, 3), id(3, 3), cost)->size(), 0u);
  PlanarGraph apart;
  apart.addNode({0, 0});
  apart.addNode({1, 0});
  EXPECT_FALSE(apart.shortestPath(0, 1, [](int) { return 1.0; }).has_value());
}

TEST(PlanarGraph, ChainsMergeLinesThroughDegreeTwoNodes) {
  // A T: a horizontal street of 4 edges (nodes 0-1-2-3-4) and a stem 2-5-6 of 2 edges.
  PlanarGraph g;
  for (int i = 0; i < 5; ++i) g.addNode({static_cast<double>(i), 0.0});
  g.addNode({2.0, -1.0});
  g.addNode({2.0, -2.0});
  g.addEdge(0, 1);
  g.addEdge(2, 1);  // reversed on purpose: the merged line still runs end to end
  g.addEdge(2, 3);
  g.addEdge(3, 4);
  g.addEdge(2, 5);
  g.addEdge(6, 5);
  g.sortRotations();
  const std::vector<std::vector<int>> chains = g.chains();
  ASSERT_EQ(chains.size(), 3u);
  EXPECT_EQ(chains[0], (std::vector<int>{0, 1}));
  EXPECT_EQ(g.chainLine(chains[0]), (LineString{{0, 0}, {1, 0}, {2, 0}}));
  EXPECT_EQ(chains[1], (std::vector<int>{2, 3}));
  EXPECT_EQ(g.chainLine(chains[2]), (LineString{{2, 0}, {2, -1}, {2, -2}}));
  // A node the caller keeps (a change of road class) ends the chain there.
  EXPECT_EQ(g.chains([](int n) { return n == 3; }).size(), 4u);
}

TEST(PlanarGraph, ARingOfDegreeTwoNodesIsOneClosedChain) {
  const PlanarGraph g = lattice(1, 1);
  const std::vector<std::vector<int>> chains = g.chains();
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_EQ(chains[0].size(), 4u);
  const LineString line = g.chainLine(chains[0]);
  EXPECT_EQ(line.size(), 5u);
  EXPECT_EQ(line.front(), line.back());
  EXPECT_DOUBLE_EQ(length(line), 4.0);
}

TEST(PlanarGraph, ATwoEdgeRingChainStartsAtTheNodeItHangsFrom) {
  // A ring of two edges between node 1 (a junction: the ring and a stem to node 2) and node 0 (its tip,
  // degree 2). Both ring edges run 0 -> 1, so the first edge's free end is ambiguous.
  PlanarGraph g;
  g.addNode({1, 0});
  g.addNode({0, 0});
  g.addNode({-1, 0});
  g.addEdge(0, 1, {{1, 0}, {0.5, 1}, {0, 0}});
  g.addEdge(0, 1, {{1, 0}, {0.5, -1}, {0, 0}});
  g.addEdge(1, 2);
  g.sortRotations();
  std::vector<int> ring;
  for (const std::vector<int>& chain : g.chains())
    if (chain.size() == 2) ring = chain;
  ASSERT_EQ(ring.size(), 2u);
  EXPECT_EQ(g.chainNodes(ring), (std::vector<int>{1, 0, 1}));
  const LineString line = g.chainLine(ring);
  EXPECT_EQ(line.front(), Vec2(0, 0));
  EXPECT_EQ(line.back(), Vec2(0, 0));
  EXPECT_EQ(line.size(), 5u);

  // Without the stem both nodes have degree 2: a node the caller keeps is where the ring starts...
  PlanarGraph loop;
  loop.addNode({1, 0});
  loop.addNode({0, 0});
  loop.addEdge(0, 1, {{1, 0}, {0.5, 1}, {0, 0}});
  loop.addEdge(0, 1, {{1, 0}, {0.5, -1}, {0, 0}});
  loop.sortRotations();
  const auto keepOne = [](int n) { return n == 1; };
  const std::vector<std::vector<int>> kept = loop.chains(keepOne);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(loop.chainNodes(kept[0], keepOne), (std::vector<int>{1, 0, 1}));
  // ...and a closed ring of degree-2 nodes starts at its first edge's first node.
  const std::vector<std::vector<int>> closed = loop.chains();
  ASSERT_EQ(closed.size(), 1u);
  EXPECT_EQ(loop.chainNodes(closed[0]), (std::vector<int>{0, 1, 0}));
}

TEST(PlanarGraph, FromLinesNodesCrossingsAndSnapsNearEnds) {
  const PlanarGraph cross = PlanarGraph::fromLines({{{0, 0}, {2, 2}}, {{0, 2}, {2, 0}}});
  EXPECT_EQ(cross.nodeCount(), 5u);
  EXPECT_EQ(cross.edgeCount(), 4u);
  int centre = -1;
  for (std::size_t n = 0; n < cross.nodeCount(); ++n)
    if (cross.node(static_cast<int>(n)).p == Vec2(1, 1)) centre = static_cast<int>(n);
  ASSERT_GE(centre, 0);
  EXPECT_EQ(cross.degree(centre), 4);
  // Nodes are numbered by (x, y): (0,0), (0,2), (1,1), (2,0), (2,2).
  EXPECT_EQ(cross.node(0).p, Vec2(0, 0));
  EXPECT_EQ(cross.node(4).p, Vec2(2, 2));

  // Two streets whose ends miss by 0.04: exact noding keeps them apart, a 0.1 grid joins them.
  const std::vector<LineString> soup = {{{0, 0}, {1, 0}}, {{1.04, 0}, {2, 0}}, {{1, 0}, {2, 0}}};
  EXPECT_EQ(PlanarGraph::fromLines({soup[0], soup[1]}).nodeCount(), 4u);
  const PlanarGraph snapped = PlanarGraph::fromLines({soup[0], soup[1]}, 0.1);
  EXPECT_EQ(snapped.nodeCount(), 3u);
  EXPECT_EQ(snapped.chains().size(), 1u);
  // A repeated street is dissolved into one edge.
  EXPECT_EQ(PlanarGraph::fromLines({soup[2], soup[2]}).edgeCount(), 1u);
  // A closed ring becomes two edges, so that no edge is a loop, and one bounded face.
  const PlanarGraph ring = PlanarGraph::fromLines({{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}}});
  EXPECT_EQ(ring.boundedFaces().size(), 1u);
  EXPECT_DOUBLE_EQ(ring.boundedFaces()[0].twiceSignedArea, 2.0);
}

TEST(PlanarGraph, OutlineComesFirstEvenThroughACutVertex) {
  // Two unit squares touching at one corner (a figure eight), nodes numbered so that the plain walk
  // would meet a square's inside first.
  PlanarGraph g;
  const int a1 = g.addNode({2, 1});  // node 0: its first edge (north) has square A on its left
  const int c = g.addNode({1, 1});   // the cut vertex
  const int a2 = g.addNode({2, 2}), a3 = g.addNode({1, 2});
  const int b1 = g.addNode({0, 1}), b2 = g.addNode({0, 0}), b3 = g.addNode({1, 0});
  for (auto [u, v] : {std::pair{c, a1}, {a1, a2}, {a2, a3}, {a3, c}, {c, b1}, {b1, b2}, {b2, b3}, {b3, c}})
    g.addEdge(u, v);
  g.sortRotations();
  EXPECT_GT(g.faces().front().twiceSignedArea, 0.0) << "the plain walk starts inside a square here";
  const std::vector<PlanarGraph::Face> faces = g.facesOutlineFirst();
  ASSERT_EQ(faces.size(), 3u);
  // Entry 0 is the whole outline, both squares in one walk through the cut vertex.
  EXPECT_EQ(faces[0].halfEdges.size(), 8u);
  EXPECT_DOUBLE_EQ(faces[0].twiceSignedArea, -4.0);
  EXPECT_DOUBLE_EQ(faces[1].twiceSignedArea, 2.0);
  EXPECT_DOUBLE_EQ(faces[2].twiceSignedArea, 2.0);
  // Every edge is used exactly twice, once in each direction.
  std::vector<int> uses(2 * g.edgeCount(), 0);
  for (const PlanarGraph::Face& f : faces)
    for (int h : f.halfEdges) ++uses[static_cast<std::size_t>(h)];
  EXPECT_EQ(uses, std::vector<int>(2 * g.edgeCount(), 1));
  // Two components: each outline before any inner face.
  PlanarGraph two = lattice(1, 1);
  const int o = static_cast<int>(two.nodeCount());
  for (const Vec2& p : {Vec2(5, 0), Vec2(6, 0), Vec2(6, 1), Vec2(5, 1)}) two.addNode(p);
  for (int k = 0; k < 4; ++k) two.addEdge(o + k, o + (k + 1) % 4);
  two.sortRotations();
  const std::vector<PlanarGraph::Face> both = two.facesOutlineFirst();
  ASSERT_EQ(both.size(), 4u);
  EXPECT_LT(both[0].twiceSignedArea, 0.0);
  EXPECT_LT(both[1].twiceSignedArea, 0.0);
  EXPECT_GT(both[2].twiceSignedArea, 0.0);
}
