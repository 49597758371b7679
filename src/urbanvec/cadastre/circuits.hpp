// Minimal circuits of a pre-block graph with the outline as entry 0, sub-blocks and courtyards
// (spec pueyo-urban-data.md §A.6.2, Figs. 16-17).
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/planar_graph.hpp"

namespace urbanvec::cadastre {

/// The circuits of a planar graph, per connected component: its outline (the circuit through the
/// lowest node, PlanarGraph::facesOutlineFirst) and its bounded circuits. A component lying inside a
/// bounded circuit of another (a closed ring inside a block, §A.6.2 "courtyards") is a hole of that
/// circuit: `parentFace` names the smallest such circuit, -1 for a top-level component.
struct Circuits {
  std::vector<Ring> outlines;      ///< per component, counter-clockwise
  std::vector<int> parentFace;     ///< per component
  std::vector<int> depth;          ///< per component: 0 top level, 1 inside a top-level circuit, ...
  std::vector<Polygon> faces;      ///< bounded circuits, holes = outlines of the components inside
  std::vector<int> faceComponent;  ///< per face
  std::size_t slivers = 0;         ///< bounded circuits under the minimum area, dropped
  std::size_t thinKept = 0;        ///< circuits thinner than the minimum width kept for a point inside
};

/// Circuits of `graph`; bounded circuits smaller than `minFaceArea` or thinner than `minWidth` (mean
/// width 2 area / perimeter) are slivers, dropped and counted — except a circuit thinner than
/// `minWidth` (but not smaller than `minFaceArea`) holding one of `keepThin` strictly inside (a thin
/// face a number-of-floors label marks as a building part), kept and counted in `thinKept`.
Circuits findCircuits(const PlanarGraph& graph, double minFaceArea, double minWidth = 0.0,
                      const std::vector<Vec2>& keepThin = {});

bool pointInRing(const Vec2& p, const Ring& ring);
/// Inside the outer ring and outside every hole.
bool pointInPolygon(const Vec2& p, const Polygon& polygon);
/// A point strictly inside the polygon (GEOS point on surface), or its first vertex when degenerate.
Vec2 interiorPoint(const Polygon& polygon);
/// The polygon as valid simple parts (GEOS MakeValid when it is not valid, e.g. a circuit walking a
/// bridge edge twice); tiny parts below `minArea` are dropped.
MultiPolygon validParts(const Polygon& polygon, double minArea);
/// Distance from p to the polygon's boundary (0 inside is not implied).
double distanceToBoundary(const Vec2& p, const Polygon& polygon);

}  // namespace urbanvec::cadastre
