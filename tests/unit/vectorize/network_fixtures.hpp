// Hand-made road networks and simulated cities with exact answers for the unit tests of stages C
// (pavement) and D1-D5 (blocks): shared by tests/unit/vectorize/pavement and .../blocks.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <set>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/vectorize/blocks/blocks_pipeline.hpp"

using namespace urbanvec;
using namespace urbanvec::vectorize;

namespace {

/// Builds a RoadNetwork from chains of node positions: each chain is cut into one segment per pair of
/// consecutive listed nodes, with extra points every cell in between (part 1 leaves nodes <= 2 cells
/// apart).
struct NetworkBuilder {
  RoadNetwork net;

  int node(const Vec2& p) {
    for (size_t i = 0; i < net.nodes.size(); ++i)
      if (distance(net.nodes[i].position, p) < 1e-9) return static_cast<int>(i);
    net.nodes.push_back({p, NetworkNodeKind::Road, 0});
    return static_cast<int>(net.nodes.size()) - 1;
  }
  void chain(const std::vector<Vec2>& nodes, RoadClass cls) {
    for (size_t i = 0; i + 1 < nodes.size(); ++i) {
      NetworkSegment seg;
      seg.roadClass = cls;
      seg.fromNode = node(nodes[i]);
      seg.toNode = node(nodes[i + 1]);
      const int steps = std::max(1, static_cast<int>(std::ceil(distance(nodes[i], nodes[i + 1]))));
      for (int k = 0; k <= steps; ++k)
        seg.points.push_back(nodes[i] + (nodes[i + 1] - nodes[i]) * (double(k) / steps));
      net.segments.push_back(seg);
    }
  }
  /// A raw polyline segment between its first and last point.
  void polyline(const LineString& points, RoadClass cls) {
    NetworkSegment seg;
    seg.roadClass = cls;
    seg.fromNode = node(points.front());
    seg.toNode = node(points.back());
    seg.points = points;
    net.segments.push_back(seg);
  }
  RoadNetwork finish() {
    for (auto& n : net.nodes) n.degree = 0;
    for (const auto& s : net.segments) {
      ++net.nodes[s.fromNode].degree;
      ++net.nodes[s.toNode].degree;
    }
    for (auto& n : net.nodes)
      n.kind = n.degree == 1  ? NetworkNodeKind::DeadEnd
               : n.degree > 2 ? NetworkNodeKind::Intersection
                              : NetworkNodeKind::Road;
    return net;
  }
};

const PavementPiece* pieceAtNode(const RoadGeometry& g, int node, PavementKind kind) {
  for (const PavementPiece& p : g.pieces)
    if (p.node == node && p.kind == kind) return &p;
  return nullptr;
}

std::set<std::pair<long, long>> vertexSet(const Ring& ring) {
  std::set<std::pair<long, long>> out;
  for (const Vec2& p : ring) out.emplace(std::lround(p.x * 1000), std::lround(p.y * 1000));
  return out;
}

/// The closed ring without the vertices that lie on the straight line between their neighbours: stage
/// C's pieces carry the vertices of the pieces they meet (a coverage, issue 21), the shapes' corners
/// are the rest.
Ring withoutStraightVertices(const Ring& ring) {
  std::vector<Vec2> open(ring.begin(), ring.end() - 1);
  Ring out;
  for (size_t i = 0; i < open.size(); ++i) {
    const Vec2& a = open[(i + open.size() - 1) % open.size()];
    const Vec2& b = open[i];
    const Vec2& c = open[(i + 1) % open.size()];
    if (std::fabs(cross(b - a, c - b)) > 1e-5 * length(b - a) * length(c - b)) out.push_back(b);
  }
  if (!out.empty()) out.push_back(out.front());
  return out;
}

std::set<std::pair<long, long>> cornerSet(const Ring& ring) {
  return vertexSet(withoutStraightVertices(ring));
}

double unionArea(const std::vector<PavementPiece>& pieces, const Polygon* clip = nullptr) {
  geos::Context ctx;
  std::vector<geos::GeomPtr> parts;
  for (const PavementPiece& p : pieces) parts.push_back(ctx.multiPolygon(p.shape));
  geos::GeomPtr u = unionOnGrid(ctx, std::move(parts), 1e-9);
  if (clip) {
    geos::GeomPtr c = ctx.polygon(*clip);
    u = ctx.own(GEOSIntersection_r(ctx.handle(), u.get(), c.get()), "intersection");
  }
  return geosArea(ctx, u.get());
}

Polygon box(double x0, double y0, double x1, double y1) {
  return Polygon{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}}, {}};
}

/// A city on a W x H grid with the land use `use(col, row)`: simulated blocks are the 4-connected
/// components of developed cells, internal iff their non-road region does not touch the grid border
/// (spec A2), with one parcel per block.
struct TestCity {
  SimulatedCity city;
  GridSpec spec;
};

TestCity makeCity(int w, int h, const std::function<LandUse(int, int)>& use, double cellSize = 12.0) {
  TestCity t;
  t.city.grid = Grid<LandUse>(w, h, LandUse::Unused);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) t.city.grid.at(c, r) = use(c, r);
  t.spec.width = w;
  t.spec.height = h;
  t.spec.transform.c = {500000.0, cellSize, 0.0, 4000000.0, 0.0, -cellSize};
  const int dc[4] = {1, -1, 0, 0}, dr[4] = {0, 0, 1, -1};
  auto flood = [&](int c0, int r0, Grid<int>& label, int id, const std::function<bool(LandUse)>& member) {
    std::vector<GridCell> cells{{c0, r0}}, stack{{c0, r0}};
    label.at(c0, r0) = id;
    while (!stack.empty()) {
      const GridCell cell = stack.back();
      stack.pop_back();
      for (int k = 0; k < 4; ++k) {
        const int nc = cell.col + dc[k], nr = cell.row + dr[k];
        if (!t.city.grid.inside(nc, nr) || label.at(nc, nr) >= 0 || !member(t.city.grid.at(nc, nr))) continue;
        label.at(nc, nr) = id;
        stack.push_back({nc, nr});
        cells.push_back({nc, nr});
      }
    }
    return cells;
  };
  Grid<int> region(w, h, -1);
  std::vector<bool> regionTouchesBorder;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      if (region.at(c, r) >= 0 || isRoad(t.city.grid.at(c, r))) continue;
      bool border = false;
      for (const GridCell& cell :
           flood(c, r, region, int(regionTouchesBorder.size()), [](LandUse u) { return !isRoad(u); }))
        border = border || cell.col == 0 || cell.row == 0 || cell.col == w - 1 || cell.row == h - 1;
      regionTouchesBorder.push_back(border);
    }
  Grid<int> label(w, h, -1);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      if (label.at(c, r) >= 0 || !isDeveloped(t.city.grid.at(c, r))) continue;
      SimulatedBlock b;
      b.id = static_cast<int>(t.city.blocks.size()) + 100;
      b.cells = flood(c, r, label, int(t.city.blocks.size()), [](LandUse u) { return isDeveloped(u); });
      b.internal = !regionTouchesBorder[region.at(c, r)];
      Vec2 sum;
      for (const GridCell& cell : b.cells) sum += cellCentre(cell, h);
      b.centre = sum / double(b.cells.size());
      SimulatedParcel parcel{b.id * 10, LandUse::Residential, b.cells, b.centre};
      b.parcelIds.push_back(parcel.id);
      t.city.parcels.push_back(parcel);
      t.city.blocks.push_back(b);
    }
  return t;
}

}  // namespace
