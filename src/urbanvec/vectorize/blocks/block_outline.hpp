// Stage D1 of shared/specs/sexton-vectorizer.md, "Block outlining" [DOC T §3.4; P §3.3.1]: the faces
// enclosed by curbs become internal blocks, the outer boundary of each road network is kept aside as
// the perimeter, and every block gets its PCA oriented bounding box and diagonal.
//
// The face walk of the curb linework is a walk of the pavement's boundary: stage C's pieces form a
// polygon coverage, so their union is the chain of the edges that only one piece has (coverageUnion;
// pavement that is not a coverage is unioned by GEOS overlay on the precision grid in a fixed grouping
// anchored to the frame, issue 22), and the holes of that union are exactly the
// bounded faces of the curb arrangement that contain no pavement (spec §3 D1 [INFERENCE] "a face is a block
// face iff it does not intersect the interior of any pavement polygon"). The exterior ring of each road
// component is its perimeter. Road networks lying inside another network's block are cut out of that block.
//
// All coordinates are in the internal frame of spec §0 (cells).
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/pavement/road_geometry.hpp"

namespace urbanvec::vectorize {

struct BlockOutlineOptions {
  /// Faces smaller than this are gaps between pavement pieces left by snap rounding, not blocks: they
  /// are handed back to the pavement, in cells² ([INFERENCE]; real slivers are 1e-13..1e-6 cells²).
  double minBlockArea = 0.1;
  /// Overlay precision grid, in cells (see kDefaultPrecisionGrid).
  double precisionGrid = kDefaultPrecisionGrid;
  /// Side of the squares, anchored at the frame's origin, that group the pavement pieces of the overlay
  /// union of pavement that is not a coverage (frameAnchoredUnion), in cells ([INFERENCE]: a square's pieces
  /// are united one after another, so small squares keep that short; on Monaco 2-8 cells cost what GEOS's
  /// cascaded union did, 16 cells 1.5 x, 64 cells 6 x). Any value gives a union that does not depend on the
  /// window.
  double unionSquare = 4.0;
  /// Worker threads of the union; 0 = all cores. Does not change the output.
  int threads = 0;
};

struct BlockOutline {
  /// Internal blocks: outer ring clockwise, holes counter-clockwise (spec: clockwise blocks).
  std::vector<Polygon> internalBlocks;
  /// The area inside the outer road perimeter of every top-level road network (pavement plus
  /// internal blocks), outer rings clockwise (spec D1 "save it as the perimeter").
  MultiPolygon perimeter;
  /// Faces below minBlockArea: they belong to the pavement (see absorbSlivers).
  MultiPolygon slivers;
};

BlockOutline outlineBlocks(const std::vector<PavementPiece>& pavement, const BlockOutlineOptions& options,
                           const Progress& progress = {});

/// Union of pavement pieces that form a polygon coverage (pieces meet only along edges with exactly
/// the same vertices, as stage C makes them), by walking the edges that are not shared between two
/// pieces: linear in the number of edges, no overlay. Outer rings clockwise, holes counter-clockwise;
/// where the union touches itself at a point, the rings are split there. Returns false (and `out` is
/// unusable) when the pieces are not a coverage: an edge met twice in the same direction (overlap) or
/// a boundary that does not close.
bool coverageUnion(const std::vector<PavementPiece>& pieces, MultiPolygon& out);
/// The same for polygons that form a coverage.
bool coverageUnion(const std::vector<const Polygon*>& polygons, MultiPolygon& out);

/// Merges every sliver into the pavement piece it touches that comes first by envelope (lower-left
/// corner, then upper-right, then area: an order that does not depend on the pieces' numbering), so
/// pavement and blocks still tile.
/// Returns how many found a piece.
/// The merges of different pieces are independent and run on `threads` workers (0 = all cores; the
/// result does not depend on it).
int absorbSlivers(std::vector<PavementPiece>& pavement, const MultiPolygon& slivers, double precisionGrid,
                  int threads = 1);

/// PCA oriented bounding box (spec D1): axes from the area-weighted second moments of the polygon,
/// extents from its outer ring projected on them.
struct OrientedBox {
  Vec2 centre;            ///< area centroid
  Vec2 axis;              ///< unit direction of the long side
  double length = 0.0;    ///< long extent, in the polygon's units
  double width = 0.0;     ///< short extent, in the polygon's units
  double aspect = 0.0;    ///< width / length in (0, 1]; 0 for a degenerate polygon
  double diagonal = 0.0;  ///< sqrt(width^2 + length^2): BBD of the E5 cost
};

OrientedBox orientedBoundingBox(const Polygon& polygon);

/// Makes the outer ring clockwise and the holes counter-clockwise (y-up frame).
void orientClockwise(Polygon& polygon);

}  // namespace urbanvec::vectorize
