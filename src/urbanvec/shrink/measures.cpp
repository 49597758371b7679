// Shrinking error measures (spec §E.4 item 3 "error measure", §H.2 items 6-8; issue 19).
#include "urbanvec/shrink/measures.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include "urbanvec/core/planar_graph.hpp"
#include "urbanvec/core/segment_contact.hpp"

namespace urbanvec::shrink {
namespace {

bool finite(const Vec2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

using Edges = std::set<std::pair<int, int>>;

Edges edgesOf(const std::vector<std::vector<int>>& ways, const std::vector<Vec2>& pos) {
  Edges edges;
  for (const auto& way : ways)
    for (size_t i = 1; i < way.size(); ++i) {
      const int a = way[i - 1], b = way[i];
      if (a == b || !finite(pos[static_cast<size_t>(a)]) || !finite(pos[static_cast<size_t>(b)])) continue;
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  return edges;
}

std::map<int, std::vector<int>> adjacency(const Edges& edges) {
  std::map<int, std::vector<int>> adj;
  for (const auto& [a, b] : edges) adj[a].push_back(b), adj[b].push_back(a);
  return adj;
}

int componentCount(const std::map<int, std::vector<int>>& adj) {
  std::set<int> seen;
  int count = 0;
  for (const auto& [start, _] : adj) {
    if (seen.count(start)) continue;
    ++count;
    std::vector<int> stack{start};
    seen.insert(start);
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      for (int m : adj.at(n))
        if (seen.insert(m).second) stack.push_back(m);
    }
  }
  return count;
}

/// Way pairs (i <= j) with two segments crossing properly (not at a shared node).
std::set<std::pair<int, int>> crossingPairs(const std::vector<std::vector<int>>& ways,
                                            const std::vector<Vec2>& pos) {
  struct Seg {
    int way, a, b;
  };
  std::vector<Seg> segs;
  double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
  for (size_t w = 0; w < ways.size(); ++w)
    for (size_t i = 1; i < ways[w].size(); ++i) {
      const int a = ways[w][i - 1], b = ways[w][i];
      const Vec2 pa = pos[static_cast<size_t>(a)], pb = pos[static_cast<size_t>(b)];
      if (a == b || !finite(pa) || !finite(pb)) continue;
      segs.push_back({static_cast<int>(w), a, b});
      minX = std::min({minX, pa.x, pb.x}), maxX = std::max({maxX, pa.x, pb.x});
      minY = std::min({minY, pa.y, pb.y}), maxY = std::max({maxY, pa.y, pb.y});
    }
  std::set<std::pair<int, int>> pairs;
  if (segs.empty()) return pairs;
  const int cells = 256;
  const double cw = std::max((maxX - minX) / cells, 1e-9), ch = std::max((maxY - minY) / cells, 1e-9);
  std::vector<std::vector<int>> grid(static_cast<size_t>(cells) * cells);
  auto cx = [&](double x) { return std::clamp(static_cast<int>((x - minX) / cw), 0, cells - 1); };
  auto cy = [&](double y) { return std::clamp(static_cast<int>((y - minY) / ch), 0, cells - 1); };
  for (size_t s = 0; s < segs.size(); ++s) {
    const Vec2 a = pos[static_cast<size_t>(segs[s].a)], b = pos[static_cast<size_t>(segs[s].b)];
    for (int y = cy(std::min(a.y, b.y)); y <= cy(std::max(a.y, b.y)); ++y)
      for (int x = cx(std::min(a.x, b.x)); x <= cx(std::max(a.x, b.x)); ++x)
        grid[static_cast<size_t>(y) * cells + static_cast<size_t>(x)].push_back(static_cast<int>(s));
  }
  for (const auto& cell : grid)
    for (size_t i = 0; i < cell.size(); ++i)
      for (size_t j = i + 1; j < cell.size(); ++j) {
        const Seg& s = segs[static_cast<size_t>(cell[i])];
        const Seg& t = segs[static_cast<size_t>(cell[j])];
        if (s.a == t.a || s.a == t.b || s.b == t.a || s.b == t.b) continue;
        const Vec2 p1 = pos[static_cast<size_t>(s.a)], p2 = pos[static_cast<size_t>(s.b)];
        const Vec2 q1 = pos[static_cast<size_t>(t.a)], q2 = pos[static_cast<size_t>(t.b)];
        if (segmentsCross(p1, p2, q1, q2)) pairs.insert({std::min(s.way, t.way), std::max(s.way, t.way)});
      }
  return pairs;
}

struct AngleStats {
  double rightShare = 0.0;
  double deviation = 0.0;
};

AngleStats intersectionAngles(const std::map<int, std::vector<int>>& adj, const std::vector<Vec2>& pos) {
  std::vector<double> angles;
  for (const auto& [n, neighbours] : adj) {
    if (neighbours.size() < 3) continue;
    std::vector<double> dirs;
    for (int m : neighbours) {
      const Vec2 d = pos[static_cast<size_t>(m)] - pos[static_cast<size_t>(n)];
      dirs.push_back(std::atan2(d.y, d.x) * 180.0 / M_PI);
    }
    std::sort(dirs.begin(), dirs.end());
    for (size_t i = 0; i < dirs.size(); ++i) {
      const double next = i + 1 < dirs.size() ? dirs[i + 1] : dirs[0] + 360.0;
      angles.push_back(next - dirs[i]);
    }
  }
  AngleStats s;
  if (angles.empty()) return s;
  std::vector<double> dev;
  int right = 0;
  for (double a : angles) {
    dev.push_back(std::abs(a - 90.0));
    if (a >= 80.0 && a <= 100.0) ++right;
  }
  s.rightShare = static_cast<double>(right) / static_cast<double>(angles.size());
  s.deviation = median(dev);
  return s;
}

/// Number and mean area of a planar graph's bounded faces (its blocks).
std::pair<int, double> faceAreas(const PlanarGraph& g) {
  double total = 0.0;
  int count = 0;
  for (const PlanarGraph::Face& f : g.boundedFaces(1e-6)) {
    total += f.twiceSignedArea / 2.0;
    ++count;
  }
  return {count, count ? total / count : 0.0};
}

std::pair<int, double> blockAreas(const Edges& edges, const std::vector<Vec2>& pos) {
  PlanarGraph g;
  std::map<int, int> id;
  for (const auto& [a, b] : edges)
    for (int n : {a, b})
      if (!id.count(n)) id[n] = g.addNode(pos[static_cast<size_t>(n)]);
  for (const auto& [a, b] : edges) g.addEdge(id[a], id[b]);
  g.sortRotations();
  return faceAreas(g);
}

std::vector<std::pair<Vec2, Vec2>> segmentsOf(const Edges& edges, const std::vector<Vec2>& pos) {
  std::vector<std::pair<Vec2, Vec2>> segs;
  for (const auto& [a, b] : edges) segs.push_back({pos[static_cast<size_t>(a)], pos[static_cast<size_t>(b)]});
  return segs;
}

}  // namespace

double orientationEntropy(const std::vector<std::pair<Vec2, Vec2>>& segments) {
  std::vector<double> bins(36, 0.0);
  double total = 0.0;
  for (const auto& [a, b] : segments) {
    const Vec2 d = b - a;
    const double len = length(d);
    if (len <= 0.0) continue;
    for (double sign : {1.0, -1.0}) {
      double bearing = std::atan2(sign * d.x, sign * d.y) * 180.0 / M_PI;  // clockwise from north
      bearing = std::fmod(bearing + 360.0 + 5.0, 360.0);                   // bins centred on 0, 10, ...
      bins[static_cast<size_t>(bearing / 10.0) % 36] += len;
      total += len;
    }
  }
  double h = 0.0;
  for (double b : bins)
    if (b > 0.0) h -= b / total * std::log(b / total);
  return h;
}

ShrinkMeasures measureShrink(const MeasureInput& in) {
  ShrinkMeasures m;
  // Area: bounding boxes of every node in use.
  auto bboxArea = [&](const std::vector<Vec2>& pos, bool useAfter) {
    double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
    auto add = [&](int n) {
      const Vec2 p = pos[static_cast<size_t>(n)];
      if (!finite(p)) return;
      minX = std::min(minX, p.x), maxX = std::max(maxX, p.x), minY = std::min(minY, p.y),
      maxY = std::max(maxY, p.y);
    };
    for (const auto& way : useAfter ? in.waysAfter : in.waysBefore)
      for (int n : way) add(n);
    for (const auto& place : in.landmarks)
      for (const auto& shape : place)
        for (int n : shape) add(n);
    return maxX > minX && maxY > minY ? (maxX - minX) * (maxY - minY) : 0.0;
  };
  const double areaBefore = bboxArea(in.before, false);
  m.areaKept = areaBefore > 0.0 ? bboxArea(in.after, true) / areaBefore : 1.0;

  // Landmarks: translation of every element, then the arrangement of the places' centroids.
  std::vector<Vec2> refBefore, refAfter;
  for (const auto& place : in.landmarks) {
    Vec2 sb, sa;
    int count = 0;
    for (const auto& shape : place) {
      if (shape.empty()) continue;
      const Vec2 offset = in.after[static_cast<size_t>(shape[0])] - in.before[static_cast<size_t>(shape[0])];
      for (int n : shape) {
        const Vec2 d = in.after[static_cast<size_t>(n)] - in.before[static_cast<size_t>(n)] - offset;
        m.landmarkMaxDeviation = std::max(m.landmarkMaxDeviation, finite(d) ? length(d) : 1e300);
        sb += in.before[static_cast<size_t>(n)];
        sa += in.after[static_cast<size_t>(n)];
        ++count;
      }
    }
    if (count == 0) continue;
    refBefore.push_back(sb / count);
    refAfter.push_back(sa / count);
  }
  std::vector<double> bearingChange, ratio;
  const double eps = 1e-6;
  for (size_t i = 0; i < refBefore.size(); ++i)
    for (size_t j = i + 1; j < refBefore.size(); ++j) {
      ++m.landmarkPairs;
      const Vec2 db = refBefore[j] - refBefore[i], da = refAfter[j] - refAfter[i];
      if ((db.x > eps && da.x < -eps) || (db.x < -eps && da.x > eps)) ++m.orderViolationsX;
      if ((db.y > eps && da.y < -eps) || (db.y < -eps && da.y > eps)) ++m.orderViolationsY;
      const double lb = length(db), la = length(da);
      if (lb > eps) {
        ratio.push_back(la / lb);
        double change = (std::atan2(da.y, da.x) - std::atan2(db.y, db.x)) * 180.0 / M_PI;
        change = std::fmod(change + 540.0, 360.0) - 180.0;
        bearingChange.push_back(std::abs(change));
      }
    }
  m.bearingChangeMedian = median(bearingChange);
  if (!ratio.empty()) {
    m.distanceRatioMin = *std::min_element(ratio.begin(), ratio.end());
    m.distanceRatioMax = *std::max_element(ratio.begin(), ratio.end());
    m.distanceRatioMedian = median(ratio);
  }

  // Topology.
  const auto crossBefore = crossingPairs(in.waysBefore, in.before);
  const auto crossAfter = crossingPairs(in.waysAfter, in.after);
  m.crossingsBefore = static_cast<int>(crossBefore.size());
  m.crossingsAfter = static_cast<int>(crossAfter.size());
  for (const auto& p : crossAfter) m.newCrossings += crossBefore.count(p) ? 0 : 1;
  const Edges eb = edgesOf(in.waysBefore, in.before), ea = edgesOf(in.waysAfter, in.after);
  const auto adjB = adjacency(eb), adjA = adjacency(ea);
  for (const auto& [n, neighbours] : adjB) {
    if (neighbours.size() >= 3) {
      ++m.intersectionsBefore;
      auto it = adjA.find(n);
      if (it != adjA.end() && it->second.size() == neighbours.size()) ++m.intersectionsKept;
    }
    if (neighbours.size() == 1) ++m.deadEndsBefore;
  }
  for (const auto& [n, neighbours] : adjA) {
    auto it = adjB.find(n);
    if (neighbours.size() == 1 && (it == adjB.end() || it->second.size() != 1)) ++m.newDeadEnds;
  }
  m.componentsBefore = componentCount(adjB);
  m.componentsAfter = componentCount(adjA);

  // Street realism.
  m.entropyBefore = orientationEntropy(segmentsOf(eb, in.before));
  m.entropyAfter = orientationEntropy(segmentsOf(ea, in.after));
  const AngleStats angB = intersectionAngles(adjB, in.before), angA = intersectionAngles(adjA, in.after);
  m.rightAngleShareBefore = angB.rightShare, m.rightAngleShareAfter = angA.rightShare;
  m.angleDeviationBefore = angB.deviation, m.angleDeviationAfter = angA.deviation;
  std::tie(m.blocksBefore, m.meanBlockAreaBefore) = blockAreas(eb, in.before);
  std::tie(m.blocksAfter, m.meanBlockAreaAfter) = blockAreas(ea, in.after);
  if (!in.cityWays.empty()) {
    // The whole map is noded first (GEOS): its bridges and tunnels cross without a shared node, and
    // seen from above they bound blocks like any street.
    std::vector<LineString> lines;
    for (const auto& way : in.cityWays) {
      LineString l;
      for (int n : way) l.push_back(in.before[static_cast<size_t>(n)]);
      if (l.size() >= 2) lines.push_back(std::move(l));
    }
    std::tie(m.blocksCity, m.meanBlockAreaCity) = faceAreas(PlanarGraph::fromLines(lines, 1e-6));
  }
  return m;
}

}  // namespace urbanvec::shrink
