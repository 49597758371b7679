// Graph noise with Halton sampling (spec chen-streets.md §13.6).
#include "urbanvec/streets/graph_noise.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "urbanvec/core/random.hpp"
#include "urbanvec/core/segment_contact.hpp"
#include "urbanvec/core/uniform_grid.hpp"

namespace urbanvec::streets {

double halton(int index, int base) {
  double f = 1.0, r = 0.0;
  for (int i = index; i > 0; i /= base) {
    f /= base;
    r += f * (i % base);
  }
  return r;
}

namespace {}  // namespace

std::vector<Street> applyGraphNoise(const PlanarGraph& graph, const std::vector<StreetLevel>& edgeLevel,
                                    const GraphNoiseOptions& options) {
  const int edges = static_cast<int>(graph.edgeCount());
  std::vector<int> degree(graph.nodeCount());
  // Street degrees: outline edges (boundary, water) do not count.
  for (int e = 0; e < static_cast<int>(graph.edgeCount()); ++e)
    if (edgeLevel[static_cast<std::size_t>(e)] != StreetLevel::Outline) {
      ++degree[static_cast<std::size_t>(graph.edge(e).a)];
      ++degree[static_cast<std::size_t>(graph.edge(e).b)];
    }
  std::vector<int> minor;
  Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}, hi = lo * -1.0;
  std::vector<Vec2> mid(static_cast<std::size_t>(edges));
  for (int e = 0; e < edges; ++e) {
    const LineString& l = graph.edge(e).line;
    mid[static_cast<std::size_t>(e)] = (l.front() + l.back()) * 0.5;
    if (edgeLevel[static_cast<std::size_t>(e)] != StreetLevel::Minor) continue;
    minor.push_back(e);
    const Vec2& m = mid[static_cast<std::size_t>(e)];
    lo = {std::min(lo.x, m.x), std::min(lo.y, m.y)}, hi = {std::max(hi.x, m.x), std::max(hi.y, m.y)};
  }
  enum Fate : char { Keep, Delete, Cut };
  std::vector<char> fate(static_cast<std::size_t>(edges), Keep);
  std::vector<double> cutFraction(static_cast<std::size_t>(edges), 1.0);
  std::vector<char> cutFromB(static_cast<std::size_t>(edges), 0);
  const int full = static_cast<int>(std::lround(options.fullShare * minor.size()));
  const int partial = static_cast<int>(std::lround(options.partialShare * minor.size()));
  auto eligible = [&](int e) {
    return fate[static_cast<std::size_t>(e)] == Keep &&
           degree[static_cast<std::size_t>(graph.edge(e).a)] >= options.minEndDegree &&
           degree[static_cast<std::size_t>(graph.edge(e).b)] >= options.minEndDegree;
  };
  // Midpoints of the minor edges in buckets of about two edges each.
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, 1.0});
  const double cell = std::max(extent / std::sqrt(std::max<double>(1.0, minor.size() / 2.0)), 1e-6);
  UniformGrid<int> buckets;
  if (!minor.empty()) buckets.init(lo, hi, cell);
  for (int e : minor) buckets.insert(mid[static_cast<std::size_t>(e)], e);
  if (minor.empty())
    return [&] {
      std::vector<Street> out;
      for (int e = 0; e < edges; ++e)
        out.push_back({graph.edge(e).line, edgeLevel[static_cast<std::size_t>(e)], 0});
      return out;
    }();
  // The nearest edge to a Halton point (by midpoint) among those `ok` accepts: rings of buckets
  // outwards until no nearer one can exist; -1 when none is left.
  auto nearestTo = [&](const Vec2& h, const auto& ok) {
    int best = -1;
    double bestD = std::numeric_limits<double>::infinity();
    const int ci = buckets.column(h.x), cj = buckets.row(h.y);
    for (int ring = 0;; ++ring) {
      const double reach = (ring - 1) * cell;
      if (ring > 0 && reach > 0 && reach * reach > bestD) break;
      const bool any = buckets.forRing(ci, cj, ring, [&](const std::vector<int>& bucket) {
        for (int e : bucket) {
          if (!ok(e)) continue;
          const Vec2 d = mid[static_cast<std::size_t>(e)] - h;
          const double d2 = dot(d, d);
          if (d2 < bestD || (d2 == bestD && e < best)) bestD = d2, best = e;
        }
      });
      if (!any) break;
    }
    return best;
  };
  auto halton2 = [&](int index) {
    return Vec2{lo.x + halton(index, 2) * (hi.x - lo.x), lo.y + halton(index, 3) * (hi.y - lo.y)};
  };
  int index = options.startIndex, doneFull = 0, donePartial = 0;
  const int maxTries = 20 * static_cast<int>(minor.size()) + 100;
  for (int tries = 0; tries < maxTries && (doneFull < full || donePartial < partial); ++tries, ++index) {
    const int best = nearestTo(halton2(index), eligible);
    if (best < 0) break;
    const bool cut = doneFull >= full || (donePartial < partial && (index % 4) == 0);
    --degree[static_cast<std::size_t>(graph.edge(best).a)];
    --degree[static_cast<std::size_t>(graph.edge(best).b)];
    if (cut) {
      // The stub keeps 20-60 % of the edge from one end (Halton base 5 for the length, the index's
      // parity for the end) and still counts at that end.
      fate[static_cast<std::size_t>(best)] = Cut;
      cutFraction[static_cast<std::size_t>(best)] = 0.2 + 0.4 * halton(index, 5);
      cutFromB[static_cast<std::size_t>(best)] = static_cast<char>(index % 2);
      ++degree[static_cast<std::size_t>(index % 2 ? graph.edge(best).b : graph.edge(best).a)];
      ++donePartial;
    } else {
      fate[static_cast<std::size_t>(best)] = Delete;
      ++doneFull;
    }
  }
  // Corners: a minor edge is deleted at a T-junction whose two other streets then meet at a turn, so
  // the street turns the corner there (a degree-2 bend) instead of running on; its other end keeps
  // degree >= 2. Only whole, live street edges count at the junction.
  const double turnCos = -std::cos(options.minTurnDegrees * M_PI / 180.0);
  auto awayFrom = [&](int f, int n) {
    const PlanarGraph::Edge& ed = graph.edge(f);
    const Vec2 d = ed.a == n ? ed.line.back() - ed.line.front() : ed.line.front() - ed.line.back();
    return d / std::max(length(d), 1e-300);
  };
  auto turnsAt = [&](int e, int n) {
    if (degree[static_cast<std::size_t>(n)] != 3) return false;
    std::vector<Vec2> rest;
    for (int f : graph.node(n).edges) {
      const auto k = static_cast<std::size_t>(f);
      if (f == e || fate[k] == Delete || edgeLevel[k] == StreetLevel::Outline) continue;
      if (fate[k] == Cut && (cutFromB[k] ? graph.edge(f).b : graph.edge(f).a) != n) continue;
      if (fate[k] == Cut || graph.edge(f).a == graph.edge(f).b) return false;
      rest.push_back(awayFrom(f, n));
    }
    return rest.size() == 2 && dot(rest[0], rest[1]) > turnCos;
  };
  // Whether edge g is a street at node n (a cut-back edge only at its stub's end).
  auto counts = [&](int g, int n) {
    const auto k = static_cast<std::size_t>(g);
    if (fate[k] == Delete || edgeLevel[k] == StreetLevel::Outline) return false;
    return fate[k] != Cut || (cutFromB[k] ? graph.edge(g).b : graph.edge(g).a) == n;
  };
  // Where a street leaving node `from` along edge f ends: the first node of street degree other than
  // 2 (`from` itself round a ring); a cut-back edge ends at its stub's own dead end (-2 - g).
  auto streetEnd = [&](int f, int from) {
    int at = from;
    for (std::size_t steps = 0; steps <= graph.edgeCount(); ++steps) {
      if (fate[static_cast<std::size_t>(f)] == Cut) return -2 - f;
      const int next = graph.edge(f).a == at ? graph.edge(f).b : graph.edge(f).a;
      if (next == from || degree[static_cast<std::size_t>(next)] != 2) return next;
      int other = -1;
      for (int g : graph.node(next).edges)
        if (g != f && counts(g, next)) other = g;
      if (other < 0) return next;
      at = next, f = other;
    }
    return from;
  };
  // Deleting e must not merge streets into a loop: a street from a node back to the same node (a
  // ring left on one spur, or a ring with no junction at all), whose chord is 0.
  auto makesLoop = [&](int e) {
    const PlanarGraph::Edge& ed = graph.edge(e);
    const auto k = static_cast<std::size_t>(e);
    fate[k] = Delete;
    --degree[static_cast<std::size_t>(ed.a)], --degree[static_cast<std::size_t>(ed.b)];
    bool loop = false;
    for (int m : {ed.a, ed.b}) {
      if (degree[static_cast<std::size_t>(m)] != 2) continue;
      std::vector<int> ends;
      for (int g : graph.node(m).edges)
        if (counts(g, m)) ends.push_back(streetEnd(g, m));
      loop = loop || (ends.size() == 2 && ends[0] == ends[1]);
    }
    fate[k] = Keep;
    ++degree[static_cast<std::size_t>(ed.a)], ++degree[static_cast<std::size_t>(ed.b)];
    return loop;
  };
  auto bendable = [&](int e) {
    const PlanarGraph::Edge& ed = graph.edge(e);
    if (fate[static_cast<std::size_t>(e)] != Keep || ed.a == ed.b) return false;
    return ((turnsAt(e, ed.a) && degree[static_cast<std::size_t>(ed.b)] >= 3) ||
            (turnsAt(e, ed.b) && degree[static_cast<std::size_t>(ed.a)] >= 3)) &&
           !makesLoop(e);
  };
  const int bends = static_cast<int>(std::lround(options.bendShare * minor.size()));
  for (int tries = 0, done = 0; tries < maxTries && done < bends; ++tries, ++index) {
    const int best = nearestTo(halton2(index), bendable);
    if (best < 0) break;
    fate[static_cast<std::size_t>(best)] = Delete;
    --degree[static_cast<std::size_t>(graph.edge(best).a)];
    --degree[static_cast<std::size_t>(graph.edge(best).b)];
    ++done;
  }
  std::vector<Street> out;
  for (int e = 0; e < edges; ++e) {
    const auto k = static_cast<std::size_t>(e);
    if (fate[k] == Delete) continue;
    LineString line = graph.edge(e).line;
    if (fate[k] == Cut) {
      if (cutFromB[k]) std::reverse(line.begin(), line.end());
      line = headOfLength(line, cutFraction[k] * length(line));
    }
    out.push_back({std::move(line), edgeLevel[k], 0});
  }
  return out;
}

void bowStreets(std::vector<Street>& pieces, const BowOptions& options) {
  if (!(options.ratio > 0.0) || !(options.maxOffset > 0.0) || pieces.empty()) return;
  Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}, hi = lo * -1.0;
  for (const Street& s : pieces)
    for (const Vec2& v : s.line)
      lo = {std::min(lo.x, v.x), std::min(lo.y, v.y)}, hi = {std::max(hi.x, v.x), std::max(hi.y, v.y)};
  // Segments of the pieces' current geometry; a bowed piece's old segments are skipped by generation.
  struct Seg {
    Vec2 a, b;
    int piece, generation;
  };
  std::vector<Seg> segs;
  std::vector<int> generation(pieces.size(), 0);
  UniformGrid<int> grid(
      lo, hi, std::max({4.0 * options.maxOffset, (hi.x - lo.x) / 2048.0, (hi.y - lo.y) / 2048.0, 1e-6}));
  auto add = [&](int piece) {
    const LineString& l = pieces[static_cast<std::size_t>(piece)].line;
    for (std::size_t i = 0; i + 1 < l.size(); ++i) {
      grid.insert(l[i], l[i + 1], static_cast<int>(segs.size()));
      segs.push_back({l[i], l[i + 1], piece, generation[static_cast<std::size_t>(piece)]});
    }
  };
  for (int i = 0; i < static_cast<int>(pieces.size()); ++i) add(i);
  // True when the bowed line meets another piece anywhere but at its own two ends.
  auto blocked = [&](int piece, const LineString& l) {
    const Vec2 first = l.front(), last = l.back();
    bool hit = false;
    for (std::size_t i = 0; !hit && i + 1 < l.size(); ++i) {
      const Vec2 p = l[i], q = l[i + 1];
      grid.forBox(p, q, [&](const std::vector<int>& bucket) {
        for (std::size_t k = 0; !hit && k < bucket.size(); ++k) {
          const Seg& s = segs[static_cast<std::size_t>(bucket[k])];
          if (s.piece == piece || s.generation != generation[static_cast<std::size_t>(s.piece)]) continue;
          const SegmentContact c = segmentContact(p, q, s.a, s.b);
          if (c == SegmentContact::None) continue;
          // A segment from an end node may touch the pieces meeting there, at that node only.
          const bool atFirst = i == 0 && (s.a == first || s.b == first) &&
                               distanceToSegment(s.a == first ? s.b : s.a, p, q) > 0.0 &&
                               distanceToSegment(q, s.a, s.b) > 0.0;
          const bool atLast = i + 2 == l.size() && (s.a == last || s.b == last) &&
                              distanceToSegment(s.a == last ? s.b : s.a, p, q) > 0.0 &&
                              distanceToSegment(p, s.a, s.b) > 0.0;
          hit = c == SegmentContact::Crossing || !(atFirst || atLast);
        }
      });
    }
    return hit;
  };
  for (int i = 0; i < static_cast<int>(pieces.size()); ++i) {
    Street& s = pieces[static_cast<std::size_t>(i)];
    if ((s.level != StreetLevel::Major && s.level != StreetLevel::Minor) || s.line.size() < 2) continue;
    const Vec2 a = s.line.front(), b = s.line.back();
    const double chord = distance(a, b);
    if (!(chord > 0.0)) continue;
    const double u = unitDraw(options.seed ^ 0xb0e5ULL, static_cast<std::uint64_t>(i));
    double offset =
        std::clamp((2.0 * u - 1.0) * options.ratio * chord, -options.maxOffset, options.maxOffset);
    // The piece densified to at least 8 pieces (a traced street has a vertex every integration step, an
    // eighth of the minor d_sep, already), each vertex moved along the chord's normal by offset × sin(π s /
    // length), s its distance along the piece.
    const LineString dense = densified(s.line, chord / 8.0);
    const double total = length(dense);
    const Vec2 normal{-(b.y - a.y) / chord, (b.x - a.x) / chord};
    for (int attempt = 0; attempt < 2 && std::abs(offset) > 0.0; ++attempt, offset *= 0.5) {
      LineString bowed{dense.front()};
      double at = 0.0;
      for (std::size_t k = 1; k < dense.size(); ++k) {
        at += distance(dense[k - 1], dense[k]);
        bowed.push_back(k + 1 == dense.size() ? dense.back()
                                              : dense[k] + normal * (offset * std::sin(M_PI * at / total)));
      }
      if (blocked(i, bowed)) continue;
      s.line = std::move(bowed);
      ++generation[static_cast<std::size_t>(i)];
      add(i);
      break;
    }
  }
}

}  // namespace urbanvec::streets
