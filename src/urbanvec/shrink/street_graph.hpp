// The CityLib street-network structures the shrinking steps query (spec §C.2, §C.3): the direct graph
// (one node per street node, one edge per way segment, as a core PlanarGraph so A* is the shared
// shortestPath), the intersection accelerator (ways per node) and a proximity grid of segments.
#pragma once

#include <vector>

#include "urbanvec/core/planar_graph.hpp"
#include "urbanvec/shrink/city.hpp"

namespace urbanvec::shrink {

struct StreetGraph {
  PlanarGraph graph;
  std::vector<int> cityNode;   ///< graph node -> city node
  std::vector<int> graphNode;  ///< city node -> graph node, -1 when no street uses it
  std::vector<int> edgeWay;    ///< graph edge -> street index
  std::vector<int> wayCount;   ///< city node -> number of distinct streets through it (§C.2 accelerator)
};

/// Builds the direct graph of `streets` over `nodes` (§C.2 directGraph; no street direction).
StreetGraph buildStreetGraph(const std::vector<CityNode>& nodes, const std::vector<CityWay>& streets);

/// Proximity accelerator (§C.3): a uniform grid of street segments, so that the nearest street of a
/// point is found without the thesis's extra negative-id nodes (each segment is listed in every cell
/// its bounding box covers).
class SegmentGrid {
 public:
  SegmentGrid(const std::vector<CityNode>& nodes, const std::vector<CityWay>& streets, double cellSize);
  /// Index of the street nearest to p within maxDistance (ties: lower index), or -1.
  int nearestStreet(const Vec2& p, double maxDistance, double* distanceOut = nullptr) const;

 private:
  struct Segment {
    Vec2 a, b;
    int way;
  };
  std::vector<Segment> segments_;
  std::vector<std::vector<int>> cells_;
  Vec2 origin_;
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  int cellX(double x) const;
  int cellY(double y) const;
};

/// Even-odd point-in-ring test.
bool insideRing(const Vec2& p, const Ring& ring);

}  // namespace urbanvec::shrink
