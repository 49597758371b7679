// Spec §3 E1 (thesis §3.4.3, paper §3.4.1) with the inverted discard rule resolved as the spec's Q14
// explains: a tree with E ends joined to the boundary cuts a simply-connected block into E parcels, so
// "too many parcels" means E > N_sim.
#include "urbanvec/vectorize/parcels/spine_subdivision.hpp"

#include <algorithm>
#include <cmath>

namespace urbanvec::vectorize::parcels {

namespace {

/// Extra length past the boundary so the connector crosses it after noding, cells.
constexpr double kOvershoot = 1e-7;
/// Faces smaller than this share of the polygon are noding slivers (a cut that meets the boundary at a
/// vertex leaves a face of ~1e-20 cells², which collapses to repeated points in world coordinates).
constexpr double kSliverShare = 1e-9;
/// [INFERENCE] Grid of the snap-rounding fallback when plain noding fails, cells.
constexpr double kNodingFallbackGrid = 1e-9;

}  // namespace

MultiPolygon facesInside(const geos::Context& geos, const GEOSGeometry* polygon,
                         const MultiLineString& cuts) {
  GEOSContextHandle_t h = geos.handle();
  std::vector<geos::GeomPtr> parts;
  parts.push_back(geos.own(GEOSBoundary_r(h, polygon), "boundary"));
  for (const LineString& cut : cuts)
    if (cut.size() >= 2) parts.push_back(geos.lineString(cut));
  geos::GeomPtr all = geos.collection(GEOS_GEOMETRYCOLLECTION, std::move(parts));
  GEOSGeometry* nodedRaw = GEOSNode_r(h, all.get());
  if (!nodedRaw) {
    // Floating-point noding can fail to converge on near-coincident cuts; the snap-rounding union on
    // a grid far below the tiling tolerance always nodes.
    nodedRaw = GEOSUnaryUnionPrec_r(h, all.get(), kNodingFallbackGrid);
  }
  geos::GeomPtr noded = geos.own(nodedRaw, "node");
  const GEOSGeometry* lines[] = {noded.get()};
  geos::GeomPtr faces = geos.own(GEOSPolygonize_r(h, lines, 1), "polygonize");
  const GEOSPreparedGeometry* prepared = GEOSPrepare_r(h, polygon);
  double polygonArea = 0.0;
  GEOSArea_r(h, polygon, &polygonArea);
  MultiPolygon inside;
  const int n = GEOSGetNumGeometries_r(h, faces.get());
  for (int i = 0; i < n; ++i) {
    const GEOSGeometry* face = GEOSGetGeometryN_r(h, faces.get(), i);
    double a = 0.0;
    GEOSArea_r(h, face, &a);
    if (a <= kSliverShare * polygonArea) continue;
    geos::GeomPtr probe = geos.own(GEOSPointOnSurface_r(h, face), "pointOnSurface");
    if (GEOSPreparedContains_r(h, prepared, probe.get()) == 1) {
      MultiPolygon p = geos.toPolygons(face);
      inside.insert(inside.end(), p.begin(), p.end());
    }
  }
  GEOSPreparedGeom_destroy_r(h, prepared);
  return inside;
}

LineString endConnector(const geos::Context& geos, const GEOSGeometry* blockBoundary, const Vec2& end,
                        const Vec2& previous, const SpineSubdivisionOptions& options) {
  GEOSContextHandle_t h = geos.handle();
  geos::GeomPtr point = geos.point(end);
  GEOSCoordSequence* nearest = GEOSNearestPoints_r(h, blockBoundary, point.get());
  Vec2 target = end;
  if (nearest) {
    GEOSCoordSeq_getXY_r(h, nearest, 0, &target.x, &target.y);
    GEOSCoordSeq_destroy_r(h, nearest);
  }
  const double closest = distance(end, target);
  Vec2 dir = end - previous;
  if (length(dir) > 0.0) {
    dir = dir / length(dir);
    const double reach = std::max(closest * options.alongSpineFactor, 1e-9);
    geos::GeomPtr ray = geos.lineString({end, end + dir * reach});
    geos::GeomPtr hits = geos.own(GEOSIntersection_r(h, ray.get(), blockBoundary), "intersection");
    double best = 1e300;
    Vec2 hitPoint;
    const int n = GEOSGetNumGeometries_r(h, hits.get());
    for (int i = 0; i < n; ++i) {
      const GEOSGeometry* g = GEOSGetGeometryN_r(h, hits.get(), i);
      if (GEOSisEmpty_r(h, g)) continue;
      for (const Vec2& q : geos.coordinates(g)) {
        if (distance(q, end) < best) {
          best = distance(q, end);
          hitPoint = q;
        }
      }
    }
    if (best < 1e300) target = hitPoint;
  }
  Vec2 d = target - end;
  const double len = length(d);
  if (len > 0.0) target = target + d / len * kOvershoot;
  return {end, target};
}

SpineParcels spineSubdivision(const Polygon& block, const SpineGraph& spine, int simParcels,
                              double smallestSimParcel, const SpineSubdivisionOptions& options,
                              const geos::Context& geos) {
  SpineParcels result;
  if (spine.edges.empty()) return result;
  const std::vector<int> degree = spineDegrees(spine);
  std::vector<int> endIndex;
  for (size_t v = 0; v < degree.size(); ++v)
    if (degree[v] == 1) endIndex.push_back(static_cast<int>(v));
  result.ends = static_cast<int>(endIndex.size());
  const bool tooMany = options.literalDiscardRule ? simParcels > result.ends : result.ends > simParcels;
  if (tooMany || result.ends < 2) {
    result.discarded = true;
    return result;
  }
  geos::GeomPtr polygon = geos.polygon(block);
  geos::GeomPtr boundary = geos.own(GEOSBoundary_r(geos.handle(), polygon.get()), "boundary");
  MultiLineString cuts = spineBranches(spine);
  for (int v : endIndex) {
    int neighbour = -1;
    for (const auto& e : spine.edges)
      if (e[0] == v || e[1] == v) neighbour = e[0] == v ? e[1] : e[0];
    cuts.push_back(endConnector(geos, boundary.get(), spine.nodes[v], spine.nodes[neighbour], options));
  }
  result.parcels = facesInside(geos, polygon.get(), cuts);
  if (result.parcels.size() < 2) {
    result.discarded = true;
    result.parcels.clear();
    return result;
  }
  if (options.capacityCheck && smallestSimParcel > 0.0) {
    double capacity = 0.0;
    for (const Polygon& face : result.parcels) capacity += std::floor(area(face) / smallestSimParcel + 1e-9);
    if (capacity < simParcels) {
      result.discarded = true;
      result.parcels.clear();
      return result;
    }
  }
  result.used = true;
  return result;
}

}  // namespace urbanvec::vectorize::parcels
