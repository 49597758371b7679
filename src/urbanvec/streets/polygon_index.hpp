// Fast point-in-polygon and segment-crossing tests against a fixed set of polygons (boundary, water,
// parks), used millions of times while tracing streets and when measuring a network inside an area.
// Edges are bucketed in horizontal slabs, so a test looks only at the edges of one slab.
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec::streets {

class PolygonIndex {
 public:
  PolygonIndex() = default;
  /// `slabs`: number of horizontal buckets (0 = about sqrt of the edge count).
  explicit PolygonIndex(const MultiPolygon& polygons, int slabs = 0);

  bool empty() const { return edges_.empty(); }
  /// Inside by the even-odd rule over every ring (outer rings and holes alike); on-edge is arbitrary.
  bool contains(const Vec2& p) const;
  /// The first crossing of segment a-b with any ring edge, as the fraction t in [0, 1] along a-b; a
  /// value > 1 when the segment crosses no edge.
  double firstCrossing(const Vec2& a, const Vec2& b) const;
  /// Distance from p to the nearest ring edge, searching at most `maxDistance` away (returns
  /// maxDistance when nothing is nearer).
  double distanceToEdge(const Vec2& p, double maxDistance) const;

 private:
  struct Edge {
    Vec2 a, b;
  };
  std::vector<Edge> edges_;
  double minY_ = 0.0, slabHeight_ = 1.0, minX_ = 0.0, maxX_ = 0.0;
  std::vector<std::vector<int>> slabs_;
  int slabOf(double y) const;
};

}  // namespace urbanvec::streets
