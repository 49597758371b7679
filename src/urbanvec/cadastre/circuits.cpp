// Minimal circuits, sub-blocks and courtyards (spec pueyo-urban-data.md §A.6.2). See circuits.hpp.
#include "urbanvec/cadastre/circuits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "urbanvec/cadastre/linework.hpp"
#include "urbanvec/core/geos.hpp"

namespace urbanvec::cadastre {

bool pointInRing(const Vec2& p, const Ring& r) {
  bool inside = false;
  for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
    const Vec2& a = r[i];
    const Vec2& b = r[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
  }
  return inside;
}

bool pointInPolygon(const Vec2& p, const Polygon& poly) {
  if (!pointInRing(p, poly.outer)) return false;
  for (const Ring& h : poly.holes)
    if (pointInRing(p, h)) return false;
  return true;
}

double distanceToBoundary(const Vec2& p, const Polygon& poly) {
  double best = std::numeric_limits<double>::infinity();
  auto ring = [&](const Ring& r) {
    for (size_t i = 1; i < r.size(); ++i) best = std::min(best, distanceToSegment(p, r[i - 1], r[i]));
  };
  ring(poly.outer);
  for (const Ring& h : poly.holes) ring(h);
  return best;
}

Vec2 interiorPoint(const Polygon& polygon) {
  thread_local geos::Context ctx;
  const geos::GeomPtr g = ctx.polygon(polygon);
  GEOSGeometry* pt = GEOSPointOnSurface_r(ctx.handle(), g.get());
  if (!pt) return polygon.outer.empty() ? Vec2{} : polygon.outer.front();
  const geos::GeomPtr owned = ctx.own(pt, "point on surface");
  double x = 0, y = 0;
  if (GEOSisEmpty_r(ctx.handle(), pt) || !GEOSGeomGetX_r(ctx.handle(), pt, &x) ||
      !GEOSGeomGetY_r(ctx.handle(), pt, &y))
    return polygon.outer.empty() ? Vec2{} : polygon.outer.front();
  return {x, y};
}

MultiPolygon validParts(const Polygon& polygon, double minArea) {
  thread_local geos::Context ctx;
  MultiPolygon parts;
  if (polygon.outer.size() < 4) return parts;
  const geos::GeomPtr g = ctx.polygon(polygon);
  if (GEOSisValid_r(ctx.handle(), g.get()) == 1) {
    parts.push_back(polygon);
  } else {
    GEOSGeometry* fixed = GEOSMakeValid_r(ctx.handle(), g.get());
    if (!fixed) return parts;
    const geos::GeomPtr owned = ctx.own(fixed, "make valid");
    parts = ctx.toPolygons(fixed);
  }
  parts.erase(std::remove_if(parts.begin(), parts.end(), [&](const Polygon& p) { return area(p) < minArea; }),
              parts.end());
  return parts;
}

Circuits findCircuits(const PlanarGraph& g, double minFaceArea, double minWidth,
                      const std::vector<Vec2>& keepThin) {
  Circuits c;
  // The points that keep a thin circuit, in a grid (looked up for thin circuits only).
  CellGrid keepGrid(8.0);
  for (std::size_t i = 0; i < keepThin.size(); ++i) keepGrid.insert(keepThin[i], static_cast<int>(i));
  auto holdsKeepPoint = [&](const Ring& ring) {
    const Box b = boxOf(ring);
    bool found = false;
    keepGrid.query(b.x0, b.y0, b.x1, b.y1, [&](int i) {
      const Vec2& p = keepThin[static_cast<std::size_t>(i)];
      if (!found && b.contains(p) && pointInRing(p, ring)) found = true;
    });
    return found;
  };
  int componentCount = 0;
  const std::vector<int> component = g.components(&componentCount);
  c.outlines.assign(static_cast<size_t>(componentCount), {});
  c.parentFace.assign(static_cast<size_t>(componentCount), -1);
  c.depth.assign(static_cast<size_t>(componentCount), 0);
  std::vector<char> hasOutline(static_cast<size_t>(componentCount), 0);
  for (const PlanarGraph::Face& f : g.facesOutlineFirst()) {
    if (f.halfEdges.empty()) continue;
    const int comp = component[static_cast<size_t>(g.origin(f.halfEdges.front()))];
    Ring ring = g.faceRing(f);
    if (!hasOutline[static_cast<size_t>(comp)]) {
      // Entry 0 of each component: its outline, walked clockwise; stored counter-clockwise.
      hasOutline[static_cast<size_t>(comp)] = 1;
      std::reverse(ring.begin(), ring.end());
      c.outlines[static_cast<size_t>(comp)] = std::move(ring);
      continue;
    }
    if (f.twiceSignedArea <= 0.0)
      continue;  // another non-bounded walk (should not happen after fringe removal)
    if (f.twiceSignedArea / 2.0 < minFaceArea) {
      ++c.slivers;
      continue;
    }
    if (f.twiceSignedArea / std::max(length(ring), 1e-300) < minWidth) {
      if (keepThin.empty() || !holdsKeepPoint(ring)) {
        ++c.slivers;
        continue;
      }
      ++c.thinKept;
    }
    c.faces.push_back({std::move(ring), {}});
    c.faceComponent.push_back(comp);
  }
  // Nesting: the smallest bounded circuit of another component around each component's outline.
  double cell = 1.0;
  if (!c.faces.empty()) {
    double total = 0.0;
    for (const Polygon& p : c.faces) total += std::abs(signedArea(p.outer));
    cell = std::max(1.0, std::sqrt(total / static_cast<double>(c.faces.size())) * 2.0);
  }
  CellGrid grid(cell);
  std::vector<double> faceArea(c.faces.size());
  for (size_t i = 0; i < c.faces.size(); ++i) {
    grid.insertBox(boxOf(c.faces[i].outer), static_cast<int>(i));
    faceArea[i] = std::abs(signedArea(c.faces[i].outer));
  }
  for (size_t k = 0; k < c.outlines.size(); ++k) {
    if (c.outlines[k].empty()) continue;
    const Vec2 p = c.outlines[k].front();
    int best = -1;
    grid.query(p.x, p.y, p.x, p.y, [&](int f) {
      if (c.faceComponent[static_cast<size_t>(f)] == static_cast<int>(k)) return;
      if (best >= 0 &&
          (faceArea[static_cast<size_t>(f)] > faceArea[static_cast<size_t>(best)] ||
           (faceArea[static_cast<size_t>(f)] == faceArea[static_cast<size_t>(best)] && f >= best)))
        return;
      if (pointInRing(p, c.faces[static_cast<size_t>(f)].outer)) best = f;
    });
    c.parentFace[k] = best;
    if (best >= 0) {
      Ring hole = c.outlines[k];
      std::reverse(hole.begin(), hole.end());
      c.faces[static_cast<size_t>(best)].holes.push_back(std::move(hole));
    }
  }
  // Depth by following parents (components nest as a forest).
  for (size_t k = 0; k < c.outlines.size(); ++k) {
    int d = 0;
    for (int f = c.parentFace[k]; f >= 0 && d <= static_cast<int>(c.outlines.size());
         f = c.parentFace[static_cast<size_t>(c.faceComponent[static_cast<size_t>(f)])])
      ++d;
    c.depth[k] = d;
  }
  return c;
}

}  // namespace urbanvec::cadastre
