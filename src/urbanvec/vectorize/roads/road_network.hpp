// The plain road-network interface between vectorizer part 1 (stages A1-A5, B1-B6 of
// shared/specs/sexton-vectorizer.md: raster -> smoothed road graph) and part 2 (stages C, D1-D5:
// pavement and blocks). Part 1 fills these structs after B6; part 2 reads nothing else.
//
// Every position is in the spec's internal frame (§0): cell units, x = col (east-positive),
// y = H - row (north-positive), so cell (c, r) covers [c, c+1] x [H-r-1, H-r]. World coordinates
// are spec.transform.pixelToWorld(x, H - y) for the grid's GridSpec.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/landuse.hpp"

namespace urbanvec::vectorize {

/// The class of a road segment (CONVENTIONS.md `roads.road_class`).
enum class RoadClass : std::uint8_t {
  Primary,    ///< 2 cells wide
  Secondary,  ///< 1 cell wide
  Perimeter   ///< an external block boundary line (A4.8): no pavement, bounds external blocks
};

/// The kind of a graph node (CONVENTIONS.md `road_nodes.kind`).
enum class NetworkNodeKind : std::uint8_t {
  Intersection,  ///< more than two links
  DeadEnd,       ///< one link
  Connection,    ///< where a primary and a secondary road meet with two links
  Road           ///< an ordinary node inside a segment
};

struct NetworkNode {
  Vec2 position;  ///< internal frame (cells)
  NetworkNodeKind kind = NetworkNodeKind::Road;
  int degree = 0;  ///< number of links at the node, perimeter links included
};

/// A chain of links between two nodes that are intersections, dead ends or connections.
struct NetworkSegment {
  /// Node positions from `fromNode` to `toNode` inclusive (at least two points), internal frame.
  LineString points;
  RoadClass roadClass = RoadClass::Secondary;
  int fromNode = -1;  ///< index into RoadNetwork::nodes
  int toNode = -1;    ///< index into RoadNetwork::nodes; equals fromNode for a closed loop
};

/// The road graph after B6 plus the external perimeter lines of A4.8 (class Perimeter segments).
struct RoadNetwork {
  std::vector<NetworkNode> nodes;
  std::vector<NetworkSegment> segments;
};

/// A grid cell, (col, row) as in the rasters (row 0 = north).
struct GridCell {
  std::int32_t col = 0;
  std::int32_t row = 0;
};

/// A simulated block of A2: a 4-connected region of non-road cells.
struct SimulatedBlock {
  int id = 0;
  bool internal = true;  ///< enclosed by roads (does not touch the grid border)
  std::vector<GridCell> cells;
  Vec2 centre;                 ///< mean of the cell centres, internal frame
  std::vector<int> parcelIds;  ///< SimulatedParcel::id of the parcels attached in A5
};

/// A simulated parcel of A5 (one ownership id).
struct SimulatedParcel {
  int id = 0;
  LandUse landUse = LandUse::Unused;
  std::vector<GridCell> cells;
  Vec2 centre;  ///< mean of the cell centres, internal frame
};

/// The raster-side data part 2 needs: land use (for water and cell ownership tests) and the
/// simulated blocks and parcels.
struct SimulatedCity {
  Grid<LandUse> grid;  ///< the land-use grid after A3 (water cells are LandUse::Water)
  std::vector<SimulatedBlock> blocks;
  std::vector<SimulatedParcel> parcels;
};

/// Calls f(col, row, distance) for every cell of a w x h grid whose centre (col + 0.5, h - row - 0.5)
/// lies within r of segment ab (internal frame; a centre at r up to rounding counts as within). Scans
/// row by row only the columns the capsule around ab can reach, so the cost is about the capsule's
/// area in cells. With a frame offset (dx, dy) (Grid::frameDx/frameDy of a window) the centres are
/// (dx + col + 0.5, dy + h - row - 0.5): the whole raster's frame, the same numbers in any window.
template <class F>
void forEachCellNearSegment(int w, int h, int dx, int dy, const Vec2& a, const Vec2& b, double r, F f) {
  const double r2 = (r + 1e-9) * (r + 1e-9);
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  const double yLo = std::min(a.y, b.y) - r, yHi = std::max(a.y, b.y) + r;
  const int top = dy + h;  // the frame's y of the grid's first row's top edge
  const int rowFirst = std::max(0, static_cast<int>(std::ceil(top - 0.5 - yHi - 1e-9)));
  const int rowLast = std::min(h - 1, static_cast<int>(std::floor(top - 0.5 - yLo + 1e-9)));
  for (int row = rowFirst; row <= rowLast; ++row) {
    const double yc = top - row - 0.5;
    // The part of ab within r of this row's centre line, widened by r, bounds the columns.
    double t0 = 0, t1 = 1;
    if (ab.y != 0) {
      t0 = (yc - r - a.y) / ab.y;
      t1 = (yc + r - a.y) / ab.y;
      if (t0 > t1) std::swap(t0, t1);
      t0 = std::max(0.0, t0);
      t1 = std::min(1.0, t1);
      if (t0 > t1) continue;
    }
    const double x0 = a.x + ab.x * t0, x1 = a.x + ab.x * t1;
    const int colFirst = std::max(0, static_cast<int>(std::ceil(std::min(x0, x1) - r - 0.5 - 1e-9)) - dx);
    const int colLast = std::min(w - 1, static_cast<int>(std::floor(std::max(x0, x1) + r - 0.5 + 1e-9)) - dx);
    for (int col = colFirst; col <= colLast; ++col) {
      const Vec2 p(dx + col + 0.5, yc);
      const double t = len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
      const Vec2 d = p - (a + ab * t);
      const double d2 = dot(d, d);
      if (d2 <= r2) f(col, row, std::sqrt(d2));
    }
  }
}

template <class F>
void forEachCellNearSegment(int w, int h, const Vec2& a, const Vec2& b, double r, F f) {
  forEachCellNearSegment(w, h, 0, 0, a, b, r, f);
}

/// forEachCellNearSegment over the cells of `grid` (a window keeps the whole raster's frame).
template <class T, class F>
void forEachCellNearSegment(const Grid<T>& grid, const Vec2& a, const Vec2& b, double r, F f) {
  forEachCellNearSegment(grid.width, grid.height, grid.frameDx, grid.frameDy, a, b, r, f);
}

/// Internal frame (x = col, y = H - row, pw) to world coordinates through the geotransform; correct
/// for north-up, south-up and rotated transforms alike.
inline Vec2 toWorld(const Vec2& internal, const GridSpec& spec) {
  // A window's transform and frame are the whole raster's (GridSpec::frameHeight, issue 22).
  return spec.transform.pixelToWorld(internal.x,
                                     (spec.frameHeight > 0 ? spec.frameHeight : spec.height) - internal.y);
}

}  // namespace urbanvec::vectorize
