// Street-network metrics (issue 18 "Street-network metrics"), computed as OSMnx 1.2.3 does:
// bearing.orientation_entropy (both bearings of each simplified edge, bins centred on multiples of
// 10 degrees), stats.count_streets_per_node shares, stats.circuity_avg and basic_stats.
#include "urbanvec/streets/street_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "urbanvec/core/error.hpp"
#include "urbanvec/streets/polygon_index.hpp"

namespace urbanvec::streets {
namespace {

/// Compass bearing (degrees clockwise from north, [0, 360)) from a to b.
double bearing(const Vec2& a, const Vec2& b) {
  double deg = std::atan2(b.x - a.x, b.y - a.y) * 180.0 / M_PI;
  if (deg < 0.0) deg += 360.0;
  return deg >= 360.0 ? deg - 360.0 : deg;
}

}  // namespace

double orientationEntropy(const std::vector<double>& bearingsDegrees, int bins) {
  if (bins < 2)
    throw invalidOption("the orientation histogram needs at least 2 bins, not " + std::to_string(bins));
  // OSMnx: 2 x bins half-bins from 0, the last rolled to the front, pairs summed: bin i is centred
  // on i * 360 / bins, so 359.99 and 0.01 degrees share a bin.
  std::vector<double> count(static_cast<std::size_t>(bins), 0.0);
  const double half = 360.0 / (2.0 * bins);
  for (double b : bearingsDegrees) {
    if (!std::isfinite(b)) continue;
    double x = std::fmod(b, 360.0);
    if (x < 0) x += 360.0;
    long h = static_cast<long>(std::floor(x / half));
    h = std::min<long>(h, 2L * bins - 1);
    const long bin = ((h + 1) % (2L * bins)) / 2;
    count[static_cast<std::size_t>(bin)] += 1.0;
  }
  const double total = std::accumulate(count.begin(), count.end(), 0.0);
  if (total <= 0.0) return 0.0;
  double h = 0.0;
  for (double c : count)
    if (c > 0.0) h -= (c / total) * std::log(c / total);
  return h;
}

double orientationOrder(double entropy, int bins) {
  const double hMax = std::log(static_cast<double>(bins)), hGrid = std::log(4.0);
  const double r = (entropy - hGrid) / (hMax - hGrid);
  return 1.0 - r * r;
}

SimplifiedNetwork simplifyNetwork(const std::vector<LineString>& lines, const StreetMetricOptions& options) {
  SimplifiedNetwork net;
  net.graph = PlanarGraph::fromLines(lines, options.nodingTolerance);
  for (int n = 0; n < static_cast<int>(net.graph.nodeCount()); ++n)
    if (net.graph.degree(n) != 2) net.nodes.push_back(n);
  net.chains = net.graph.chains();
  return net;
}

StreetMetrics measureNetwork(const SimplifiedNetwork& net, const StreetMetricOptions& options,
                             const std::optional<MultiPolygon>& area) {
  const PlanarGraph& g = net.graph;
  std::optional<PolygonIndex> inside;
  if (area) inside.emplace(*area);
  auto in = [&](int node) { return !inside || inside->contains(g.node(node).p); };

  StreetMetrics m;
  std::size_t dead = 0, three = 0, four = 0, intersections = 0;
  std::vector<Vec2> nodePoints;
  for (int n : net.nodes) {
    if (!in(n)) continue;
    const int d = g.degree(n);
    ++m.nodes;
    dead += d == 1;
    three += d == 3;
    four += d == 4;
    intersections += d >= 2;
    nodePoints.push_back(g.node(n).p);
  }
  std::vector<double> bearings, lengths;
  double totalLength = 0.0, totalStraight = 0.0;
  std::size_t innerDegreeSum = 0;
  for (const std::vector<int>& chain : net.chains) {
    const std::vector<int> nodes = g.chainNodes(chain);
    const int a = nodes.front(), b = nodes.back();
    // A closed ring of degree-2 nodes only: OSMnx keeps it unsimplified; it counts as one loop here.
    if (!in(a) || !in(b)) continue;
    double len = 0.0;
    for (int e : chain) len += g.edgeLength(e);
    const Vec2 pa = g.node(a).p, pb = g.node(b).p;
    ++m.edges;
    innerDegreeSum += 2;
    lengths.push_back(len);
    totalLength += len;
    totalStraight += distance(pa, pb);
    if (a != b && len >= options.minEdgeLength) {
      const double br = bearing(pa, pb);
      bearings.push_back(br);
      bearings.push_back(std::fmod(br + 180.0, 360.0));
    }
  }
  if (m.edges == 0)
    throw invalidInput("the network has no street edge to measure" +
                       std::string(area ? " inside the area" : ""));
  m.orientationEntropy = orientationEntropy(bearings, options.orientationBins);
  m.orientationOrder = orientationOrder(m.orientationEntropy, options.orientationBins);
  if (m.nodes > 0) {
    const double n = static_cast<double>(m.nodes);
    m.shareDeadEnd = static_cast<double>(dead) / n;
    m.share3Way = static_cast<double>(three) / n;
    m.share4Way = static_cast<double>(four) / n;
    // OSMnx basic_stats: k_avg = 2 m / n on the (truncated) simplified graph.
    m.averageDegree = static_cast<double>(innerDegreeSum) / n;
  }
  m.circuity = totalStraight > 0.0 ? totalLength / totalStraight : 0.0;
  std::sort(lengths.begin(), lengths.end());
  const std::size_t k = lengths.size();
  m.medianEdgeLength = k % 2 ? lengths[k / 2] : 0.5 * (lengths[k / 2 - 1] + lengths[k / 2]);
  m.areaKm2 = (area ? urbanvec::area(*area) : std::abs(signedArea(convexHull(nodePoints)))) / 1e6;
  m.intersectionDensity = m.areaKm2 > 0.0 ? static_cast<double>(intersections) / m.areaKm2 : 0.0;
  return m;
}

StreetMetrics measureStreets(const std::vector<LineString>& lines, const StreetMetricOptions& options,
                             const std::optional<MultiPolygon>& area, const Progress& progress) {
  if (options.minEdgeLength < 0.0)
    throw invalidOption("-min-edge-length must be >= 0, not " + std::to_string(options.minEdgeLength));
  reportProgress(progress, 0.0, "noding");
  const SimplifiedNetwork net = simplifyNetwork(lines, options);
  reportProgress(progress, 0.7, "measuring");
  StreetMetrics m = measureNetwork(net, options, area);
  reportProgress(progress, 1.0, "measuring");
  return m;
}

}  // namespace urbanvec::streets
