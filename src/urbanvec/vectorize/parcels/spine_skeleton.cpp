// Spec §3 D6, the better-thinning variant the thesis could not reach (§8.2): inner bisectors of
// CGAL's interior straight skeleton. Kept in one translation unit because CGAL is slow to compile.
#include "urbanvec/vectorize/parcels/spine_skeleton.hpp"

// GCC 12 warns that CGAL's empty Epick traits object "may be used uninitialized" when toCgalRing's
// is_simple() takes it by reference: a false positive (the object has no state).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/create_straight_skeleton_from_polygon_with_holes_2.h>

#include <cmath>
#include <map>
#include <optional>

namespace urbanvec::vectorize::parcels {

namespace {

// Both kernels have exact predicates. The inexact-construction one builds a block's skeleton about
// 14 times faster (0.19 against 2.65 s for the 619 skeletons of the 1024² Monaco mosaic) and
// its nodes differ from the exact ones by at most 3e-9 cell there; the exact one is the fallback
// when the fast skeleton is missing or a node lands outside the block (docs/performance.md, round
// 6c, has the fuzzing that found no other failure of CGAL 5.5.1's builder).
using FastKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using ExactKernel = CGAL::Exact_predicates_exact_constructions_kernel;

/// A simple CGAL ring without the closing point, consecutive duplicates or collinear vertices, with
/// the requested orientation; empty when fewer than 3 vertices remain.
template <class Kernel>
CGAL::Polygon_2<Kernel> toCgalRing(const Ring& ring, bool counterClockwise) {
  using CgalPolygon = CGAL::Polygon_2<Kernel>;
  std::vector<typename Kernel::Point_2> points;
  for (size_t i = 0; i + 1 < ring.size(); ++i) {
    const typename Kernel::Point_2 p(ring[i].x, ring[i].y);
    if (points.empty() || points.back() != p) points.push_back(p);
  }
  while (points.size() > 1 && points.front() == points.back()) points.pop_back();
  bool removed = true;
  while (removed && points.size() >= 3) {
    removed = false;
    for (size_t i = 0; i < points.size() && points.size() >= 3; ++i) {
      const auto& a = points[(i + points.size() - 1) % points.size()];
      const auto& c = points[(i + 1) % points.size()];
      if (CGAL::collinear(a, points[i], c)) {
        points.erase(points.begin() + static_cast<long>(i));
        removed = true;
        break;
      }
    }
  }
  if (points.size() < 3) return {};
  CgalPolygon polygon(points.begin(), points.end());
  if (!polygon.is_simple()) return {};
  if (polygon.is_counterclockwise_oriented() != counterClockwise) polygon.reverse_orientation();
  return polygon;
}

/// CGAL's skeleton builder requires every hole strictly inside the outer ring and disjoint from the
/// other holes; a hole touching the outline at one vertex (valid for GEOS, common in real blocks)
/// makes it crash. Such shapes go to the Zhang-Suen fallback instead.
template <class Kernel>
bool holesStrictlyInside(const CGAL::Polygon_with_holes_2<Kernel>& shape) {
  using CgalPolygon = CGAL::Polygon_2<Kernel>;
  std::vector<const CgalPolygon*> rings{&shape.outer_boundary()};
  for (const CgalPolygon& hole : shape.holes()) {
    for (const auto& p : hole.vertices())
      if (shape.outer_boundary().bounded_side(p) != CGAL::ON_BOUNDED_SIDE) return false;
    rings.push_back(&hole);
  }
  for (size_t a = 0; a < rings.size(); ++a)
    for (size_t b = a + 1; b < rings.size(); ++b) {
      if (a > 0)
        for (const auto& p : rings[b]->vertices())
          if (rings[a]->bounded_side(p) != CGAL::ON_UNBOUNDED_SIDE) return false;
      for (auto ea = rings[a]->edges_begin(); ea != rings[a]->edges_end(); ++ea)
        for (auto eb = rings[b]->edges_begin(); eb != rings[b]->edges_end(); ++eb)
          if (CGAL::do_intersect(*ea, *eb)) return false;
    }
  return true;
}

/// The inner bisectors of the skeleton built with Kernel; nullopt when CGAL returns none.
template <class Kernel>
std::optional<SpineGraph> skeletonWithKernel(const Polygon& polygon) {
  using CgalPolygon = CGAL::Polygon_2<Kernel>;
  CgalPolygon outer = toCgalRing<Kernel>(polygon.outer, true);
  if (outer.size() < 3) return SpineGraph{};
  CGAL::Polygon_with_holes_2<Kernel> shape(outer);
  for (const Ring& h : polygon.holes) {
    CgalPolygon hole = toCgalRing<Kernel>(h, false);
    if (hole.size() >= 3) shape.add_hole(hole);
  }
  if (!holesStrictlyInside(shape)) return SpineGraph{};
  auto skeleton = CGAL::create_interior_straight_skeleton_2(shape, Kernel());
  if (!skeleton) return std::nullopt;
  SpineGraph graph;
  std::map<int, int> nodeOf;
  auto node = [&](const auto& vertex) {
    auto [it, inserted] = nodeOf.emplace(vertex->id(), static_cast<int>(graph.nodes.size()));
    if (inserted)
      graph.nodes.emplace_back(CGAL::to_double(vertex->point().x()), CGAL::to_double(vertex->point().y()));
    return it->second;
  };
  for (auto h = skeleton->halfedges_begin(); h != skeleton->halfedges_end(); ++h) {
    if (!h->is_bisector() || !h->is_inner_bisector()) continue;
    if (h->id() > h->opposite()->id()) continue;  // each edge once
    const int a = node(h->vertex());
    const int b = node(h->opposite()->vertex());
    if (a != b) graph.edges.push_back({std::min(a, b), std::max(a, b)});
  }
  return graph;
}

}  // namespace

bool skeletonNodesInside(const SpineGraph& graph, const Polygon& polygon) {
  auto cgalRing = [](const Ring& ring) {
    CGAL::Polygon_2<FastKernel> out;
    for (size_t i = 0; i + 1 < ring.size(); ++i) out.push_back(FastKernel::Point_2(ring[i].x, ring[i].y));
    return out;
  };
  const CGAL::Polygon_2<FastKernel> outer = cgalRing(polygon.outer);
  std::vector<CGAL::Polygon_2<FastKernel>> holes;
  for (const Ring& h : polygon.holes) holes.push_back(cgalRing(h));
  for (const Vec2& p : graph.nodes) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
    const FastKernel::Point_2 q(p.x, p.y);
    if (outer.bounded_side(q) != CGAL::ON_BOUNDED_SIDE) return false;
    for (const auto& hole : holes)
      if (hole.bounded_side(q) != CGAL::ON_UNBOUNDED_SIDE) return false;
  }
  return true;
}

SpineGraph straightSkeletonGraph(const Polygon& polygon, SkeletonKernel kernel) {
  if (kernel == SkeletonKernel::Inexact)
    return skeletonWithKernel<FastKernel>(polygon).value_or(SpineGraph{});
  if (kernel == SkeletonKernel::InexactThenExact) {
    std::optional<SpineGraph> fast = skeletonWithKernel<FastKernel>(polygon);
    if (fast && skeletonNodesInside(*fast, polygon)) return *std::move(fast);
  }
  return skeletonWithKernel<ExactKernel>(polygon).value_or(SpineGraph{});
}

}  // namespace urbanvec::vectorize::parcels
