// Stage C of shared/specs/sexton-vectorizer.md, "Road geometry creation" [DOC T §3.3; P §3.2.3]:
// curbs at a half-width from the centreline, pavement per segment (the triangle strip of its curb
// vertices), octagonal culs-de-sac at secondary dead ends, curb corners from the four candidates in
// clockwise winding order (with the parallel-pair case) and convex intersection polygons. Overlaps
// between pieces are resolved on one snap-rounded arrangement of all their boundaries on a fixed
// precision grid, so that pavement pieces never overlap and meet on exactly shared vertices (a polygon
// coverage): intersection and cul-de-sac pieces win, then primary segments, then secondary segments.
//
// All coordinates are in the internal frame of spec §0 (cells).
#pragma once

#include <geos_c.h>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/roads/road_network.hpp"

namespace urbanvec::vectorize {

/// Coordinates of every pavement, block and water polygon are snapped to this grid, in cells, and
/// overlay runs with this precision so that shared edges are exact and no slivers appear
/// ([INFERENCE]; spec §11 uses ε = 1e-6 pw). Every block stage defaults to it.
constexpr double kDefaultPrecisionGrid = 1e-6;

struct RoadGeometryOptions {
  /// Distance from a primary centreline to its curbs, in cells (spec §5.2: 1 pw, pavement 2 pw).
  double primaryHalfWidth = 1.0;
  /// Distance from a secondary centreline to its curbs, in cells (spec §5.2: 0.5 pw, pavement 1 pw).
  double secondaryHalfWidth = 0.5;
  /// Circumradius of the cul-de-sac octagon at secondary dead ends, in cells
  /// ([INFERENCE] spec §6: 1 pw = 2 x the secondary half-width; the documents give no size).
  double culDeSacCircumradius = 1.0;
  /// Two arms of an intersection count as (nearly) parallel when |sin(angle between them)| is below
  /// this (no unit) and get a connecting edge instead of a curb corner ([INFERENCE] spec §6: 0.05).
  double parallelSinEpsilon = 0.05;
  /// Longest miter at a curb vertex, and farthest curb corner from its node, as a multiple of the
  /// half-width (no unit) ([INFERENCE] spec §C / §6: 4).
  double miterClamp = 4.0;
  /// Radius of the curb returns that round the block corners at intersections, in cells
  /// ([INFERENCE], not in the documents: real curbs are rounded, and sharp 90° block corners are the
  /// signature of a raster outline; 0 gives the documents' sharp corners). The rounding is a separate
  /// `intersection` piece, so the intersection polygon itself stays the documented convex polygon.
  double curbReturnRadius = 0.5;
  /// Chords per curb return arc (no unit) ([INFERENCE]: 4 keeps every vertex turn under 25°).
  int curbReturnSegments = 4;
  /// Overlay precision grid, in cells (see kDefaultPrecisionGrid).
  double precisionGrid = kDefaultPrecisionGrid;
  /// Side of the squares, anchored at the frame's origin, whose pieces are resolved together
  /// (resolveOverlaps in road_geometry.cpp), in cells ([INFERENCE]: each square also nodes the pieces
  /// near its own, so small squares repeat work and large ones leave a core idle; any value gives the
  /// same pieces).
  double overlapRegion = 128.0;
  /// Worker threads of the overlap resolution; 0 = all cores. Does not change the output.
  int threads = 0;
};

enum class PavementKind : std::uint8_t { Segment, Intersection, CulDeSac };

std::string_view pavementKindName(PavementKind kind);
std::string_view roadClassName(RoadClass roadClass);

/// One pavement piece after overlap resolution. A piece can be empty when higher-priority pieces
/// cover it completely; such pieces are not returned.
struct PavementPiece {
  MultiPolygon shape;  ///< internal frame, snapped to the precision grid
  PavementKind kind = PavementKind::Segment;
  /// Primary when any road at the piece is primary.
  RoadClass roadClass = RoadClass::Secondary;
  int segment = -1;  ///< RoadNetwork::segments index for segment pieces, else -1
  int node = -1;     ///< RoadNetwork::nodes index for intersection and cul-de-sac pieces, else -1
};

struct RoadGeometry {
  std::vector<PavementPiece> pieces;
  /// Curb lines of every segment (left and right, untrimmed), for display and checks.
  MultiLineString curbs;
  /// Intersection polygons that came out non-convex from the corners and were replaced by their
  /// convex hull (spec Q12 asks to log them).
  int convexHullFallbacks = 0;
};

/// Stage C on the road and perimeter segments of `network`; perimeter segments get no pavement.
/// Throws urbanvec::Error (InvalidInput) for segments that reference missing nodes or have no points.
RoadGeometry buildRoadGeometry(const RoadNetwork& network, const RoadGeometryOptions& options,
                               const Progress& progress = {});

/// The curb corner of two clockwise-adjacent intersection arms A then B leaving the node `origin` in
/// the unit directions `dirA` and `dirB`: right curb of A intersected with left curb of B (spec §C
/// [INFERENCE], equal to the documented "candidate between the pair"). Returns false for a (nearly)
/// parallel pair, where the documents connect the two curb end vertices instead.
bool curbCorner(const Vec2& origin, const Vec2& dirA, double halfWidthA, const Vec2& dirB, double halfWidthB,
                double parallelSinEpsilon, Vec2& corner);

// ---- GEOS helpers shared by the block stages (C, D1-D5) ----

/// An STRtree over a fixed list of geometries; queries return indices in increasing order, so every
/// caller is deterministic. The geometries must outlive the index.
class GeometryIndex {
 public:
  GeometryIndex(const geos::Context& context, const std::vector<const GEOSGeometry*>& geometries);
  ~GeometryIndex();
  GeometryIndex(const GeometryIndex&) = delete;
  GeometryIndex& operator=(const GeometryIndex&) = delete;
  /// Indices of the geometries whose envelope intersects the envelope of `g`.
  std::vector<int> query(const GEOSGeometry* g) const;

 private:
  const geos::Context& context_;
  GEOSSTRtree* tree_ = nullptr;
  std::vector<int> ids_;
};

/// Worker threads with one GEOS context each, for the independent per-item loops of the block stages.
/// Geometries made on a worker's context stay valid as long as the pool does.
class GeosWorkers {
 public:
  /// `threads` workers; 0 = all cores.
  explicit GeosWorkers(int threads);
  GeosWorkers(const GeosWorkers&) = delete;
  GeosWorkers& operator=(const GeosWorkers&) = delete;
  size_t size() const { return contexts_.size(); }
  /// Runs body(i, worker, context) for every i in [0, n): `worker` in [0, size()) names the thread
  /// (for per-thread scratch space) and `context` is its GEOS context. Items are claimed in increasing
  /// order; the calling thread is worker 0. `tick`, when set, runs on the calling thread only, with the
  /// number of items finished since its previous call (for progress; it may throw Cancelled). The exception
  /// of the lowest failing item is rethrown once every worker has stopped. When body(i) writes only
  /// item i's own slot, the result does not depend on the thread count.
  void run(size_t n, const std::function<void(size_t, size_t, const geos::Context&)>& body,
           const std::function<void(size_t)>& tick = {}) const;

 private:
  std::vector<std::unique_ptr<geos::Context>> contexts_;
};

/// Unary union of `parts` on the precision grid; an empty input gives an empty collection.
geos::GeomPtr unionOnGrid(const geos::Context& context, std::vector<geos::GeomPtr> parts, double grid);

/// Union of all parts by GEOS's floating overlay (OverlayNG with floating noding, which retries with
/// snapping noders on its own), without snap rounding; snap-rounded on `grid` only when GEOS fails.
geos::GeomPtr floatingUnion(const geos::Context& context, std::vector<geos::GeomPtr> parts, double grid);
/// a − b by the floating overlay, snap-rounded on `grid` only when GEOS fails. The water stages use
/// these two; C's overlap resolution and D1's union stay snap-rounded, whose floating versions broke
/// the tiled = single equality and left invalid polygons (docs/performance.md, issue 21 round 4).
geos::GeomPtr floatingDifference(const geos::Context& context, const GEOSGeometry* a, const GEOSGeometry* b,
                                 double grid);
/// Union of the polygonal `parts` on the precision grid whose vertices near a point depend only on
/// the parts near that point, not on the rest of the input (issue 22: a window of the raster and the
/// whole raster give the same union wherever both hold the same parts). GEOS's cascaded union groups
/// its inputs by an STRtree over all of them, and every grouping snap-rounds the shared edges
/// differently; here the grouping is fixed by the frame instead. Each part goes to the square of
/// `squareSize` cells (anchored at the frame's origin) that holds the lower-left corner of its
/// envelope; a square's parts are unioned one after another in the order of their envelopes; then
/// neighbouring squares are merged pairwise, along x, then along y, level by level, by one fixed binary
/// tree over the frame. The merges of a level are independent and run on `workers`.
geos::GeomPtr frameAnchoredUnion(const geos::Context& context, const GeosWorkers& workers,
                                 std::vector<geos::GeomPtr> parts, double grid, double squareSize);
/// Polygonal area of a geometry (0 for empty or non-polygonal).
double geosArea(const geos::Context& context, const GEOSGeometry* g);
/// A geometry's place in an order that does not depend on input numbering (issue 22): its envelope
/// (x min, y min, x max, y max), then its area.
std::array<double, 5> envelopeKey(const geos::Context& context, const GEOSGeometry* g);

}  // namespace urbanvec::vectorize
