#include "urbanvec/vectorize/roads/road_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "urbanvec/core/segment_contact.hpp"
#include "urbanvec/vectorize/roads/road_graph_build.hpp"
#include "urbanvec/vectorize/roads/road_output.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

namespace {

struct Piece {
  Vec2 a, b;
  int line;   ///< feature (or first node id for graph links)
  int index;  ///< piece index within the feature (or second node id)
};

/// Calls visit(i, j) once for every pair of pieces whose bounding boxes share a bucket.
template <class Visit>
void forEachNearPair(const std::vector<Piece>& pieces, Visit visit) {
  if (pieces.size() < 2) return;
  double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
  std::vector<double> lengths;
  lengths.reserve(pieces.size());
  for (const Piece& p : pieces) {
    minX = std::min({minX, p.a.x, p.b.x});
    minY = std::min({minY, p.a.y, p.b.y});
    maxX = std::max({maxX, p.a.x, p.b.x});
    maxY = std::max({maxY, p.a.y, p.b.y});
    lengths.push_back(distance(p.a, p.b));
  }
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  double cell = std::max(2.0 * lengths[lengths.size() / 2], 1e-9 * std::max(maxX - minX, maxY - minY));
  const double extent = std::max(maxX - minX, maxY - minY);
  if (cell <= 0) cell = 1;
  // Keep the bucket count bounded (about 4 per piece at most).
  while ((extent / cell) * (extent / cell) > 4.0 * static_cast<double>(pieces.size()) + 16) cell *= 2;
  const int nx = static_cast<int>((maxX - minX) / cell) + 1, ny = static_cast<int>((maxY - minY) / cell) + 1;
  auto bx = [&](double x) { return std::min(nx - 1, static_cast<int>((x - minX) / cell)); };
  auto by = [&](double y) { return std::min(ny - 1, static_cast<int>((y - minY) / cell)); };
  std::vector<std::int32_t> count(static_cast<size_t>(nx) * ny + 1, 0);
  for (const Piece& p : pieces)
    for (int y = by(std::min(p.a.y, p.b.y)); y <= by(std::max(p.a.y, p.b.y)); ++y)
      for (int x = bx(std::min(p.a.x, p.b.x)); x <= bx(std::max(p.a.x, p.b.x)); ++x) ++count[y * nx + x + 1];
  for (size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
  std::vector<std::int32_t> items(count.back());
  std::vector<std::int32_t> fill(count.begin(), count.end() - 1);
  for (size_t i = 0; i < pieces.size(); ++i) {
    const Piece& p = pieces[i];
    for (int y = by(std::min(p.a.y, p.b.y)); y <= by(std::max(p.a.y, p.b.y)); ++y)
      for (int x = bx(std::min(p.a.x, p.b.x)); x <= bx(std::max(p.a.x, p.b.x)); ++x)
        items[fill[y * nx + x]++] = static_cast<std::int32_t>(i);
  }
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const int b = y * nx + x;
      for (int s = count[b]; s < count[b + 1]; ++s)
        for (int t = s + 1; t < count[b + 1]; ++t) {
          const Piece& p = pieces[items[s]];
          const Piece& q = pieces[items[t]];
          // Report the pair only in the first bucket both boxes share.
          const int fx = std::max(bx(std::min(p.a.x, p.b.x)), bx(std::min(q.a.x, q.b.x)));
          const int fy = std::max(by(std::min(p.a.y, p.b.y)), by(std::min(q.a.y, q.b.y)));
          if (fx != x || fy != y) continue;
          visit(items[s], items[t]);
        }
    }
}

/// True when p lies within a tiny distance of the interior of segment ab (not at its ends).
bool nearInterior(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  if (len2 == 0) return false;
  const double t = dot(p - a, ab) / len2;
  const double eps = 1e-7;
  if (t * std::sqrt(len2) <= eps || (1 - t) * std::sqrt(len2) <= eps) return false;
  return std::fabs(cross(ab, p - a)) / std::sqrt(len2) <= eps;
}

/// Sets mask[cell] = 1 for every cell whose centre lies within r of segment ab (internal frame).
void markWithin(std::vector<std::uint8_t>& mask, const Grid<std::uint8_t>& grid, const Vec2& a, const Vec2& b,
                double r) {
  forEachCellNearSegment(grid, a, b, r, [&](int col, int row, double) {
    mask[static_cast<size_t>(row) * grid.width + col] = 1;
  });
}

struct PointHash {
  size_t operator()(const Vec2& p) const { return std::hash<double>()(p.x) * 31 + std::hash<double>()(p.y); }
};

/// Calls forbidden(p, q) for every pair of pieces of `lines` (Piece::line indexes `lines`) that cross or
/// touch anywhere but where the output contract allows: consecutive pieces of one line at their shared
/// vertex, and pieces of two lines meeting at one shared end that is a node of both.
template <class Forbidden>
void forEachForbiddenContact(const std::vector<Piece>& pieces, const std::vector<const LineString*>& lines,
                             const std::unordered_set<Vec2, PointHash>& nodeAt, Forbidden forbidden) {
  forEachNearPair(pieces, [&](int i, int j) {
    const Piece& p = pieces[i];
    const Piece& q = pieces[j];
    const SegmentContact contact = segmentContact(p.a, p.b, q.a, q.b);
    if (contact == SegmentContact::None) return;
    if (contact == SegmentContact::Touching) {
      const LineString& lp = *lines[p.line];
      const LineString& lq = *lines[q.line];
      const bool collinear = orientation(p.a, p.b, q.a) == 0 && orientation(p.a, p.b, q.b) == 0;
      Vec2 shared;
      int sharedCount = 0;
      for (const Vec2& u : {p.a, p.b})
        for (const Vec2& v : {q.a, q.b})
          if (u == v) {
            shared = u;
            ++sharedCount;
          }
      if (sharedCount == 1 && !(collinear && (inSegmentBox(p.a, p.b, q.a == shared ? q.b : q.a) ||
                                              inSegmentBox(q.a, q.b, p.a == shared ? p.b : p.a)))) {
        if (p.line == q.line && std::abs(p.index - q.index) == 1) return;
        const bool endOfP = shared == lp.front() || shared == lp.back();
        const bool endOfQ = shared == lq.front() || shared == lq.back();
        if (endOfP && endOfQ && nodeAt.count(shared)) return;
      }
    }
    forbidden(p, q);
  });
}

}  // namespace

std::string RoadNetworkCheck::describe() const {
  std::string where;
  for (size_t k = 0; k < crossingSamples.size(); ++k) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s(%.3f %.3f)", k == 0 ? " (crossings near " : ", ", crossingSamples[k].x,
                  crossingSamples[k].y);
    where += buf;
  }
  if (!where.empty()) where += ")";
  return std::to_string(segments) + " segments: " + std::to_string(crossings) + " crossings, " +
         std::to_string(zeroLengthPieces) + " zero-length pieces, " + std::to_string(duplicateNodes) +
         " duplicate nodes, " + std::to_string(loneEnds) + " segment ends without a node" + where;
}

std::string RoadCoverageCheck::describe() const {
  std::ostringstream s;
  s << "road cells farther than " << maxDistance << " cells from a road: " << far << " of " << roadCells
    << " (" << removedOnPurpose() << " more removed on purpose: " << farRemovedPatches
    << " extraneous or 2x2 patches (A3, A4.3), " << farRemovedCycles << " short-cycle roads (B4), "
    << farRemovedDeadEnds << " dead ends (B5))";
  for (size_t k = 0; k < farSamples.size(); ++k)
    s << (k == 0 ? "; far cells at column,row " : ", ") << farSamples[k].col << "," << farSamples[k].row;
  if (far > farSamples.size()) s << ", ...";
  return s.str();
}

RoadCoverageCheck checkRoadCoverage(const Grid<std::uint8_t>& landUse, const Grid<std::uint8_t>& cleaned,
                                    const RoadNetwork& network,
                                    const std::vector<std::array<Vec2, 2>>& cycleRemovedLinks,
                                    const std::vector<std::array<Vec2, 2>>& deadEndRemovedLinks,
                                    double maxDistance) {
  RoadCoverageCheck check;
  check.maxDistance = maxDistance;
  const int w = landUse.width, h = landUse.height;
  if (w <= 0 || h <= 0) return check;
  std::vector<std::uint8_t> nearRoad(static_cast<size_t>(w) * h, 0);
  for (const NetworkSegment& s : network.segments) {
    if (s.roadClass == RoadClass::Perimeter) continue;
    for (size_t k = 0; k + 1 < s.points.size(); ++k)
      markWithin(nearRoad, landUse, s.points[k], s.points[k + 1], maxDistance);
    if (s.points.size() == 1) markWithin(nearRoad, landUse, s.points[0], s.points[0], maxDistance);
  }
  std::vector<std::uint8_t> nearRemoved, nearDeadEnd;
  if (!cycleRemovedLinks.empty()) {
    nearRemoved.assign(nearRoad.size(), 0);
    for (const auto& [a, b] : cycleRemovedLinks) markWithin(nearRemoved, landUse, a, b, maxDistance);
  }
  if (!deadEndRemovedLinks.empty()) {
    nearDeadEnd.assign(nearRoad.size(), 0);
    for (const auto& [a, b] : deadEndRemovedLinks) markWithin(nearDeadEnd, landUse, a, b, maxDistance);
  }
  const bool haveCleaned = cleaned.width == w && cleaned.height == h;
  for (size_t i = 0; i < landUse.cells.size(); ++i) {
    if (!isRoadCode(landUse.cells[i])) continue;
    ++check.roadCells;
    if (nearRoad[i]) continue;
    if (haveCleaned && cleaned.cells[i] == kRemovedRoad) {
      ++check.farRemovedPatches;
    } else if (!nearRemoved.empty() && nearRemoved[i]) {
      ++check.farRemovedCycles;
    } else if (!nearDeadEnd.empty() && nearDeadEnd[i]) {
      ++check.farRemovedDeadEnds;
    } else {
      ++check.far;
      if (check.farSamples.size() < 5)
        check.farSamples.push_back({static_cast<std::int32_t>(i % w), static_cast<std::int32_t>(i / w)});
    }
  }
  return check;
}

RoadNetworkCheck checkRoadNetwork(const Layer& roads, const Layer& roadNodes) {
  RoadNetworkCheck check;
  std::unordered_set<Vec2, PointHash> nodeAt;
  for (const Feature& f : roadNodes.features)
    if (const Vec2* p = std::get_if<Vec2>(&f.geometry))
      if (!nodeAt.insert(*p).second) ++check.duplicateNodes;
  std::vector<Piece> pieces;
  std::vector<const LineString*> lines;
  for (const Feature& f : roads.features) {
    const LineString* l = std::get_if<LineString>(&f.geometry);
    if (!l) continue;
    const int id = static_cast<int>(lines.size());
    lines.push_back(l);
    ++check.segments;
    if (l->size() < 2 || length(*l) == 0) {
      ++check.zeroLengthPieces;
      continue;
    }
    if (!nodeAt.count(l->front())) ++check.loneEnds;
    if (!nodeAt.count(l->back())) ++check.loneEnds;
    for (size_t k = 0; k + 1 < l->size(); ++k) {
      if ((*l)[k] == (*l)[k + 1]) {
        ++check.zeroLengthPieces;
        continue;
      }
      pieces.push_back({(*l)[k], (*l)[k + 1], id, static_cast<int>(k)});
    }
  }
  forEachForbiddenContact(pieces, lines, nodeAt, [&](const Piece& p, const Piece&) {
    ++check.crossings;
    if (check.crossingSamples.size() < 5) check.crossingSamples.push_back((p.a + p.b) * 0.5);
  });
  return check;
}

std::size_t restoreTouchingSegments(RoadNetwork& simplified, const RoadNetwork& exact) {
  if (simplified.segments.size() != exact.segments.size()) return 0;
  std::unordered_set<Vec2, PointHash> nodeAt;
  for (const NetworkNode& n : simplified.nodes) nodeAt.insert(n.position);
  std::size_t restored = 0;
  // Each round restores at least one segment or stops, so this ends; the exact lines are planar.
  for (size_t round = 0; round <= simplified.segments.size(); ++round) {
    std::vector<const LineString*> lines;
    std::vector<Piece> pieces;
    for (const NetworkSegment& s : simplified.segments) {
      const int id = static_cast<int>(lines.size());
      lines.push_back(&s.points);
      for (size_t k = 0; k + 1 < s.points.size(); ++k)
        if (!(s.points[k] == s.points[k + 1]))
          pieces.push_back({s.points[k], s.points[k + 1], id, static_cast<int>(k)});
    }
    std::vector<char> bad(lines.size(), 0);
    forEachForbiddenContact(pieces, lines, nodeAt, [&](const Piece& p, const Piece& q) {
      bad[static_cast<size_t>(p.line)] = 1;
      bad[static_cast<size_t>(q.line)] = 1;
    });
    std::size_t changed = 0;
    for (size_t k = 0; k < bad.size(); ++k) {
      if (!bad[k] || simplified.segments[k].points == exact.segments[k].points) continue;
      simplified.segments[k].points = exact.segments[k].points;
      ++changed;
    }
    if (changed == 0) break;
    restored += changed;
  }
  return restored;
}

std::size_t restoreUncoveringSegments(RoadNetwork& simplified, const RoadNetwork& exact,
                                      const Grid<std::uint8_t>& landUse, const Grid<std::uint8_t>& cleaned,
                                      double tolerance, double maxDistance) {
  if (simplified.segments.size() != exact.segments.size()) return 0;
  const int w = landUse.width, h = landUse.height;
  if (w <= 0 || h <= 0) return 0;
  auto roads = [&landUse](const RoadNetwork& net, std::vector<std::uint8_t>& mask, double r) {
    for (const NetworkSegment& s : net.segments) {
      if (s.roadClass == RoadClass::Perimeter) continue;
      for (size_t k = 0; k + 1 < s.points.size(); ++k)
        markWithin(mask, landUse, s.points[k], s.points[k + 1], r);
    }
  };
  std::vector<std::uint8_t> nearSimplified(static_cast<size_t>(w) * h, 0);
  roads(simplified, nearSimplified, maxDistance);
  // The road cells the simplification uncovered: near no simplified road (and not removed on purpose).
  std::vector<std::uint8_t> lost(nearSimplified.size(), 0);
  bool anyLost = false;
  const bool haveCleaned = cleaned.width == w && cleaned.height == h;
  for (size_t i = 0; i < lost.size(); ++i) {
    if (!isRoadCode(landUse.cells[i]) || nearSimplified[i]) continue;
    if (haveCleaned && cleaned.cells[i] == kRemovedRoad) continue;
    lost[i] = 1;
    anyLost = true;
  }
  if (!anyLost) return 0;
  // Every segment whose exact line passes within maxDistance of a lost cell gets that line back.
  std::size_t restored = 0;
  std::vector<std::uint8_t> near(lost.size(), 0);
  for (size_t k = 0; k < exact.segments.size(); ++k) {
    const NetworkSegment& s = exact.segments[k];
    if (s.roadClass == RoadClass::Perimeter || simplified.segments[k].points == s.points) continue;
    std::vector<size_t> touched;
    for (size_t j = 0; j + 1 < s.points.size(); ++j)
      forEachCellNearSegment(landUse, s.points[j], s.points[j + 1], maxDistance,
                             [&](int col, int row, double) {
                               const size_t i = static_cast<size_t>(row) * w + col;
                               if (!lost[i] || near[i]) return;
                               near[i] = 1;
                               touched.push_back(i);
                             });
    if (!touched.empty()) {
      // The coarsest of half, a quarter of the tolerance, or none, that covers the cells again.
      LineString line = s.points;
      for (double t = tolerance * 0.5; t > 0.0 && t >= tolerance * 0.25; t *= 0.5) {
        LineString candidate = simplifyTogether({s.points}, t).front();
        bool covers = true;
        for (size_t i : touched) {
          const Vec2 c = patchCentre(landUse, static_cast<int>(i % w), static_cast<int>(i / w));
          bool near = false;
          for (size_t j = 0; j + 1 < candidate.size() && !near; ++j)
            near = distanceToSegment(c, candidate[j], candidate[j + 1]) <= maxDistance + 1e-9;
          covers = covers && near;
        }
        if (covers) {
          line = std::move(candidate);
          break;
        }
      }
      simplified.segments[k].points = std::move(line);
      ++restored;
    }
    for (size_t i : touched) near[i] = 0;
  }
  return restored;
}

std::size_t nodeCrossingsAndContractTinyLinks(RoadGraph& graph, double minLength) {
  // Contract tiny links first: a zero-length link would otherwise survive as a zero-length segment.
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
    if (!graph.nodes[i].alive) continue;
    bool again = true;
    while (again) {
      again = false;
      for (int j : graph.nodes[i].links) {
        if (distance(graph.nodes[i].p, graph.nodes[j].p) >= minLength) continue;
        const std::vector<std::int32_t> others = graph.nodes[j].links;
        if (graph.nodes[j].type == NodeType::Primary && graph.nodes[i].type == NodeType::Secondary)
          graph.nodes[i].type = NodeType::Primary;
        graph.removeNode(j);
        for (int o : others)
          if (o != static_cast<int>(i)) graph.link(static_cast<int>(i), o);
        again = true;
        break;
      }
    }
  }
  std::size_t noded = 0;
  for (int round = 0; round < 16; ++round) {
    std::vector<Piece> pieces;
    for (size_t i = 0; i < graph.nodes.size(); ++i) {
      if (!graph.nodes[i].alive) continue;
      for (int j : graph.nodes[i].links)
        if (j > static_cast<int>(i))
          pieces.push_back({graph.nodes[i].p, graph.nodes[j].p, static_cast<int>(i), j});
    }
    std::vector<std::pair<int, int>> crossingPairs;
    std::vector<std::pair<int, int>> touches;  // (piece, node lying on its interior)
    forEachNearPair(pieces, [&](int i, int j) {
      const Piece& p = pieces[i];
      const Piece& q = pieces[j];
      if (p.line == q.line || p.line == q.index || p.index == q.line || p.index == q.index) {
        // Sharing a node: the far end of one may still lie on the other (a link folded back).
        for (const auto& [piece, other] : {std::pair<int, int>{i, j}, std::pair<int, int>{j, i}}) {
          const Piece& a = pieces[piece];
          const Piece& b = pieces[other];
          for (int node : {b.line, b.index})
            if (node != a.line && node != a.index && nearInterior(graph.nodes[node].p, a.a, a.b))
              touches.emplace_back(piece, node);
        }
        return;
      }
      if (segmentsCross(p.a, p.b, q.a, q.b)) crossingPairs.emplace_back(i, j);
      for (int node : {q.line, q.index})
        if (nearInterior(graph.nodes[node].p, p.a, p.b)) touches.emplace_back(i, node);
      for (int node : {p.line, p.index})
        if (nearInterior(graph.nodes[node].p, q.a, q.b)) touches.emplace_back(j, node);
    });
    if (crossingPairs.empty() && touches.empty()) break;
    std::set<std::pair<int, int>> split;  // links already split this round
    // A node lying on another link (a T without a node, or collinear overlap) splits that link.
    for (const auto& [i, node] : touches) {
      const Piece& p = pieces[i];
      const std::pair<int, int> kp{p.line, p.index};
      if (split.count(kp) || !graph.linked(p.line, p.index)) continue;
      graph.unlink(p.line, p.index);
      graph.link(p.line, node);
      graph.link(node, p.index);
      split.insert(kp);
      ++noded;
    }
    for (const auto& [i, j] : crossingPairs) {
      const Piece& p = pieces[i];
      const Piece& q = pieces[j];
      const std::pair<int, int> kp{p.line, p.index}, kq{q.line, q.index};
      if (split.count(kp) || split.count(kq) || !graph.linked(p.line, p.index) ||
          !graph.linked(q.line, q.index))
        continue;
      const Vec2 r = p.b - p.a, s = q.b - q.a;
      const double t = cross(q.a - p.a, s) / cross(r, s);
      const Vec2 at = p.a + r * t;
      // The new node takes the highest class of the two links so each piece keeps its class.
      const NodeType tp = linkType(graph, p.line, p.index), tq = linkType(graph, q.line, q.index);
      const NodeType type = tp == NodeType::Primary || tq == NodeType::Primary       ? NodeType::Primary
                            : tp == NodeType::Secondary || tq == NodeType::Secondary ? NodeType::Secondary
                                                                                     : NodeType::Perimeter;
      const int m = graph.addNode(at, type);
      graph.unlink(p.line, p.index);
      graph.unlink(q.line, q.index);
      for (int e : {p.line, p.index, q.line, q.index}) graph.link(m, e);
      split.insert(kp);
      split.insert(kq);
      ++noded;
    }
  }
  graph.compact();
  updateIntersectionFlags(graph);
  graph.sortLinksClockwise();
  return noded;
}

}  // namespace urbanvec::vectorize
