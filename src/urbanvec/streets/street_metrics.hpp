// Street-network metrics of any line layer (issue 18 "Street-network metrics"; Boeing 2019/2020's
// indicator set as OSMnx 1.2.3 computes it): the lines are noded (every crossing a node, GEOS), then
// simplified into edges between nodes of degree != 2 (PlanarGraph::chains), and measured:
//   orientation entropy H over 36 bins of 10 degrees, centred on 0, 10, ... degrees, of both bearings
//   of each simplified edge (straight line from end to end), orientation order
//   phi = 1 - ((H - ln 4) / (ln 36 - ln 4))^2, shares of dead-end / 3-way / 4-way nodes, average
//   degree, circuity (sum of edge lengths / sum of end-to-end distances), median edge length and
//   intersection density (nodes of degree >= 2 per km^2).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/planar_graph.hpp"
#include "urbanvec/core/progress.hpp"

namespace urbanvec::streets {

struct StreetMetricOptions {
  /// Simplified edges shorter than this (metres) are left out of the orientation histogram, as
  /// OSMnx's min_length; every other figure uses all edges.
  double minEdgeLength = 0.0;
  /// Number of orientation bins over 360 degrees (Boeing 2019: 36 bins of 10 degrees).
  int orientationBins = 36;
  /// Snapping grid of the noding (metres); 0 = exact GEOS noding.
  double nodingTolerance = 0.0;
};

struct StreetMetrics {
  double orientationEntropy = 0.0;   ///< H, nats
  double orientationOrder = 0.0;     ///< phi
  double shareDeadEnd = 0.0;         ///< share of nodes with degree 1
  double share3Way = 0.0;            ///< degree 3
  double share4Way = 0.0;            ///< degree 4
  double averageDegree = 0.0;        ///< 2 edges / nodes of the simplified graph
  double circuity = 0.0;             ///< sum of lengths / sum of straight end-to-end distances
  double medianEdgeLength = 0.0;     ///< metres
  double intersectionDensity = 0.0;  ///< nodes of degree >= 2 per km^2 of `area`
  double areaKm2 = 0.0;              ///< area the density refers to
  std::size_t edges = 0;             ///< simplified edges
  std::size_t nodes = 0;             ///< nodes of degree != 2 (dead ends and intersections)
};

/// The simplified network: nodes of degree != 2 and the chains between them.
struct SimplifiedNetwork {
  PlanarGraph graph;                     ///< the noded network (every crossing a node)
  std::vector<int> nodes;                ///< graph nodes kept (degree != 2), by id
  std::vector<std::vector<int>> chains;  ///< graph edges of each simplified edge
};

/// Nodes the lines (MultiLineStrings flattened by the caller) and merges edges through degree-2 nodes.
SimplifiedNetwork simplifyNetwork(const std::vector<LineString>& lines, const StreetMetricOptions& options);

/// Measures a network. With `area`, only nodes inside it and edges with both ends inside it count
/// (degrees stay those of the whole network, so a street cut by the area's edge is no dead end) and
/// the density refers to its area; without, everything counts and the density refers to the convex
/// hull of the nodes. Throws InvalidInput when no edge remains.
StreetMetrics measureStreets(const std::vector<LineString>& lines, const StreetMetricOptions& options,
                             const std::optional<MultiPolygon>& area = std::nullopt,
                             const Progress& progress = {});

/// The same, on a network already simplified.
StreetMetrics measureNetwork(const SimplifiedNetwork& network, const StreetMetricOptions& options,
                             const std::optional<MultiPolygon>& area = std::nullopt);

/// Entropy (nats) of the orientation histogram of these bearings (degrees, each counted once; the
/// caller adds reverse bearings) and OSMnx's bin layout (bins centred on multiples of 360/bins).
double orientationEntropy(const std::vector<double>& bearingsDegrees, int bins);
/// phi = 1 - ((H - ln 4) / (ln bins - ln 4))^2.
double orientationOrder(double entropy, int bins);

}  // namespace urbanvec::streets
