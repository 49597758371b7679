#include "urbanvec/core/planar_graph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <queue>
#include <utility>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geos.hpp"

namespace urbanvec {

namespace {

constexpr double kTwoPi = 6.283185307179586;

/// Azimuth of a direction, clockwise from due north, in [0, 2 pi).
double azimuthOf(const Vec2& d) {
  double a = std::atan2(d.x, d.y);
  if (a < 0.0) a += kTwoPi;
  return a;
}

}  // namespace

int PlanarGraph::origin(int h) const {
  const Edge& e = edge(edgeOf(h));
  return (h & 1) ? e.b : e.a;
}

int PlanarGraph::target(int h) const {
  const Edge& e = edge(edgeOf(h));
  return (h & 1) ? e.a : e.b;
}

int PlanarGraph::addNode(const Vec2& p) {
  nodes_.push_back({p, {}});
  rotationIndexValid_ = false;
  return static_cast<int>(nodes_.size()) - 1;
}

int PlanarGraph::addEdge(int a, int b, LineString line) {
  if (a == b || a < 0 || b < 0 || a >= static_cast<int>(nodes_.size()) ||
      b >= static_cast<int>(nodes_.size()))
    throw internalError("PlanarGraph::addEdge: bad end nodes " + std::to_string(a) + " and " +
                        std::to_string(b));
  if (line.size() < 2) line = {node(a).p, node(b).p};
  const int id = static_cast<int>(edges_.size());
  edges_.push_back({a, b, std::move(line)});
  nodes_[static_cast<std::size_t>(a)].edges.push_back(id);
  nodes_[static_cast<std::size_t>(b)].edges.push_back(id);
  rotationIndexValid_ = false;
  return id;
}

void PlanarGraph::sortRotations() {
  for (std::size_t n = 0; n < nodes_.size(); ++n) {
    std::vector<std::pair<double, int>> keyed;
    for (int e : nodes_[n].edges) {
      const LineString& line = edge(e).line;
      const Vec2 d = edge(e).a == static_cast<int>(n) ? line[1] - line[0]
                                                      : line[line.size() - 2] - line[line.size() - 1];
      keyed.emplace_back(azimuthOf(d), e);
    }
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t k = 0; k < keyed.size(); ++k) nodes_[n].edges[k] = keyed[k].second;
  }
  rotationIndexValid_ = false;
}

void PlanarGraph::setRotation(int n, std::vector<int> edgesClockwise) {
  std::vector<int> a = edgesClockwise, b = node(n).edges;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  if (a != b) throw internalError("PlanarGraph::setRotation: not the edges of node " + std::to_string(n));
  nodes_[static_cast<std::size_t>(n)].edges = std::move(edgesClockwise);
  rotationIndexValid_ = false;
}

void PlanarGraph::buildRotationIndex() const {
  if (rotationIndexValid_) return;
  rotationIndex_.assign(2 * edges_.size(), -1);
  for (std::size_t n = 0; n < nodes_.size(); ++n) {
    const std::vector<int>& around = nodes_[n].edges;
    for (std::size_t k = 0; k < around.size(); ++k)
      rotationIndex_[static_cast<std::size_t>(outgoing(static_cast<int>(n), around[k]))] =
          static_cast<int>(k);
  }
  rotationIndexValid_ = true;
}

std::vector<PlanarGraph::Face> PlanarGraph::faces() const {
  buildRotationIndex();
  std::vector<char> done(2 * edges_.size(), 0);
  std::vector<Face> out;
  for (std::size_t n = 0; n < nodes_.size(); ++n)
    for (int e : nodes_[n].edges) {
      int h = outgoing(static_cast<int>(n), e);
      if (done[static_cast<std::size_t>(h)]) continue;
      Face face;
      while (!done[static_cast<std::size_t>(h)]) {
        done[static_cast<std::size_t>(h)] = 1;
        face.halfEdges.push_back(h);
        const LineString& line = edge(edgeOf(h)).line;
        // Shoelace terms along the polyline, in the direction walked.
        if (h & 1) {
          for (std::size_t k = line.size() - 1; k > 0; --k)
            face.twiceSignedArea += line[k].x * line[k - 1].y - line[k - 1].x * line[k].y;
        } else {
          for (std::size_t k = 0; k + 1 < line.size(); ++k)
            face.twiceSignedArea += line[k].x * line[k + 1].y - line[k + 1].x * line[k].y;
        }
        // Leftmost turn: at v, the edge after v->u clockwise keeps the face on the left.
        const int v = target(h);
        const std::vector<int>& around = node(v).edges;
        const int back = h ^ 1;
        const int next = around[static_cast<std::size_t>(rotationIndex_[static_cast<std::size_t>(back)] + 1) %
                                around.size()];
        h = outgoing(v, next);
      }
      out.push_back(std::move(face));
    }
  return out;
}

std::vector<PlanarGraph::Face> PlanarGraph::facesOutlineFirst() const {
  std::vector<Face> all = faces();
  int count = 0;
  const std::vector<int> component = components(&count);
  // The lowest node of each component (least y, then x, then id).
  std::vector<int> lowest(static_cast<std::size_t>(count), -1);
  for (std::size_t n = 0; n < nodes_.size(); ++n) {
    int& best = lowest[static_cast<std::size_t>(component[n])];
    const Vec2& p = nodes_[n].p;
    if (best < 0 || p.y < node(best).p.y || (p.y == node(best).p.y && p.x < node(best).p.x))
      best = static_cast<int>(n);
  }
  // Its outer face: among the faces through that node, the one with the least signed area.
  std::vector<int> outline(static_cast<std::size_t>(count), -1);
  for (std::size_t f = 0; f < all.size(); ++f) {
    const int c = component[static_cast<std::size_t>(origin(all[f].halfEdges.front()))];
    bool throughLowest = false;
    for (int h : all[f].halfEdges)
      throughLowest = throughLowest || origin(h) == lowest[static_cast<std::size_t>(c)];
    int& chosen = outline[static_cast<std::size_t>(c)];
    if (throughLowest &&
        (chosen < 0 || all[f].twiceSignedArea < all[static_cast<std::size_t>(chosen)].twiceSignedArea))
      chosen = static_cast<int>(f);
  }
  std::vector<Face> out;
  std::vector<char> taken(all.size(), 0);
  for (int f : outline)
    if (f >= 0) {
      out.push_back(all[static_cast<std::size_t>(f)]);
      taken[static_cast<std::size_t>(f)] = 1;
    }
  for (std::size_t f = 0; f < all.size(); ++f)
    if (!taken[f]) out.push_back(std::move(all[f]));
  return out;
}

std::vector<PlanarGraph::Face> PlanarGraph::boundedFaces(double minTwiceArea) const {
  std::vector<Face> all = faces();
  std::vector<Face> out;
  for (Face& f : all)
    if (f.twiceSignedArea > minTwiceArea) out.push_back(std::move(f));
  return out;
}

std::vector<int> PlanarGraph::faceNodes(const Face& face) const {
  std::vector<int> out;
  out.reserve(face.halfEdges.size());
  for (int h : face.halfEdges) out.push_back(origin(h));
  return out;
}

Ring PlanarGraph::faceRing(const Face& face) const {
  Ring ring;
  for (int h : face.halfEdges) {
    const LineString& line = edge(edgeOf(h)).line;
    if (h & 1) {
      for (std::size_t k = line.size(); k-- > 1;) ring.push_back(line[k]);
    } else {
      for (std::size_t k = 0; k + 1 < line.size(); ++k) ring.push_back(line[k]);
    }
  }
  if (!ring.empty()) ring.push_back(ring.front());
  return ring;
}

std::vector<int> PlanarGraph::components(int* count) const {
  std::vector<int> id(nodes_.size(), -1);
  int next = 0;
  std::vector<int> stack;
  for (std::size_t start = 0; start < nodes_.size(); ++start) {
    if (id[start] >= 0) continue;
    id[start] = next;
    stack.assign(1, static_cast<int>(start));
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      for (int e : node(n).edges) {
        const int m = otherEnd(e, n);
        if (id[static_cast<std::size_t>(m)] < 0) {
          id[static_cast<std::size_t>(m)] = next;
          stack.push_back(m);
        }
      }
    }
    ++next;
  }
  if (count) *count = next;
  return id;
}

double PlanarGraph::edgeLength(int e) const {
  return length(edge(e).line);
}

std::function<double(int)> PlanarGraph::euclideanHeuristic(int to) const {
  const Vec2 goal = node(to).p;
  return [this, goal](int n) { return distance(node(n).p, goal); };
}

std::optional<std::vector<int>> PlanarGraph::shortestPath(int from, int to,
                                                          const std::function<double(int)>& cost,
                                                          const std::function<double(int)>& heuristic) const {
  if (from == to) return std::vector<int>{};
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> best(nodes_.size(), inf);
  std::vector<int> viaEdge(nodes_.size(), -1);
  std::vector<char> closed(nodes_.size(), 0);
  using Entry = std::pair<double, int>;  // estimated total, node: ties go to the lower node id
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  auto estimate = [&](int n) { return heuristic ? heuristic(n) : 0.0; };
  best[static_cast<std::size_t>(from)] = 0.0;
  open.emplace(estimate(from), from);
  while (!open.empty()) {
    const int n = open.top().second;
    open.pop();
    if (closed[static_cast<std::size_t>(n)]) continue;
    closed[static_cast<std::size_t>(n)] = 1;
    if (n == to) break;
    for (int e : node(n).edges) {
      const int m = otherEnd(e, n);
      if (closed[static_cast<std::size_t>(m)]) continue;
      const double c = cost(e);
      if (!(c >= 0.0)) throw internalError("PlanarGraph::shortestPath: edge cost must be >= 0");
      const double g = best[static_cast<std::size_t>(n)] + c;
      if (g < best[static_cast<std::size_t>(m)]) {
        best[static_cast<std::size_t>(m)] = g;
        viaEdge[static_cast<std::size_t>(m)] = e;
        open.emplace(g + estimate(m), m);
      }
    }
  }
  if (viaEdge[static_cast<std::size_t>(to)] < 0) return std::nullopt;
  std::vector<int> path;
  for (int n = to; n != from;) {
    const int e = viaEdge[static_cast<std::size_t>(n)];
    path.push_back(e);
    n = otherEnd(e, n);
  }
  std::reverse(path.begin(), path.end());
  return path;
}

std::vector<std::vector<int>> PlanarGraph::chains(const std::function<bool(int)>& keepNode) const {
  auto passes = [&](int n) { return degree(n) == 2 && !(keepNode && keepNode(n)); };
  auto otherEdgeAt = [&](int n, int e) {
    const std::vector<int>& around = node(n).edges;
    return around[0] == e ? around[1] : around[0];
  };
  std::vector<char> used(edges_.size(), 0);
  std::vector<std::vector<int>> out;
  for (std::size_t first = 0; first < edges_.size(); ++first) {
    if (used[first]) continue;
    // Walk back from edge `first` to the chain's end (or around its cycle).
    int startEdge = static_cast<int>(first);
    int startNode = edge(startEdge).a;
    bool cycle = false;
    for (int e = startEdge, n = startNode; passes(n);) {
      const int previous = otherEdgeAt(n, e);
      if (previous == static_cast<int>(first)) {
        cycle = true;
        break;
      }
      e = previous;
      n = otherEnd(e, n);
      startEdge = e;
      startNode = n;
    }
    if (cycle) {
      startEdge = static_cast<int>(first);
      startNode = edge(startEdge).a;
    }
    std::vector<int> chain;
    for (int e = startEdge, n = startNode;;) {
      chain.push_back(e);
      used[static_cast<std::size_t>(e)] = 1;
      const int m = otherEnd(e, n);
      if (!passes(m)) break;
      const int next = otherEdgeAt(m, e);
      if (next == startEdge) break;
      e = next;
      n = m;
    }
    out.push_back(std::move(chain));
  }
  return out;
}

std::vector<int> PlanarGraph::chainNodes(const std::vector<int>& chain,
                                         const std::function<bool(int)>& keepNode) const {
  std::vector<int> out;
  if (chain.empty()) return out;
  const Edge& e0 = edge(chain[0]);
  int n = e0.a;
  if (chain.size() > 1) {
    const Edge& e1 = edge(chain[1]);
    const bool bShared = e0.b == e1.a || e0.b == e1.b, aShared = e0.a == e1.a || e0.a == e1.b;
    if (bShared && aShared) {
      // Two edges between the same two nodes: the chain runs from the node it cannot pass through
      // (chains()' rule); when it can pass both, it is a closed ring walked from e0.a.
      auto passes = [&](int v) { return degree(v) == 2 && !(keepNode && keepNode(v)); };
      n = passes(e0.a) && !passes(e0.b) ? e0.b : e0.a;
    } else {
      n = bShared ? e0.a : e0.b;
    }
  }
  out.push_back(n);
  for (int e : chain) out.push_back(n = otherEnd(e, n));
  return out;
}

LineString PlanarGraph::chainLine(const std::vector<int>& chain,
                                  const std::function<bool(int)>& keepNode) const {
  LineString out;
  if (chain.empty()) return out;
  int n = chainNodes(chain, keepNode).front();
  for (int e : chain) {
    const LineString& line = edge(e).line;
    const bool forward = edge(e).a == n;
    const std::size_t skip = out.empty() ? 0 : 1;
    if (forward)
      out.insert(out.end(), line.begin() + static_cast<std::ptrdiff_t>(skip), line.end());
    else
      out.insert(out.end(), line.rbegin() + static_cast<std::ptrdiff_t>(skip), line.rend());
    n = otherEnd(e, n);
  }
  return out;
}

PlanarGraph PlanarGraph::fromLines(const std::vector<LineString>& lines, double tolerance) {
  geos::Context ctx;
  MultiLineString soup;
  for (const LineString& l : lines)
    if (l.size() >= 2) soup.push_back(l);
  PlanarGraph graph;
  if (soup.empty()) return graph;
  const geos::GeomPtr input = ctx.multiLineString(soup);
  // Union nodes the lines wherever they cross or touch and dissolves repeated pieces; with a grid size
  // it also snap-rounds every coordinate, merging ends that lie within the tolerance.
  const geos::GeomPtr noded =
      ctx.own(tolerance > 0.0 ? GEOSUnaryUnionPrec_r(ctx.handle(), input.get(), tolerance)
                              : GEOSUnaryUnion_r(ctx.handle(), input.get()),
              "noding the lines");
  MultiLineString pieces;
  for (LineString& piece : ctx.toLines(noded.get())) {
    LineString clean;
    for (const Vec2& p : piece)
      if (clean.empty() || p != clean.back()) clean.push_back(p);
    if (clean.size() >= 2) pieces.push_back(std::move(clean));
  }
  auto key = [](const Vec2& p) { return std::make_pair(p.x, p.y); };
  std::map<std::pair<double, double>, int> nodeId;
  for (const LineString& piece : pieces) {
    nodeId.emplace(key(piece.front()), 0);
    nodeId.emplace(key(piece.back()), 0);
  }
  for (auto& [p, id] : nodeId) id = graph.addNode({p.first, p.second});
  // Edges by their (lower) end nodes, then by their points: an order independent of GEOS's output.
  for (LineString& piece : pieces) {
    if (nodeId[key(piece.back())] < nodeId[key(piece.front())] ||
        (piece.front() == piece.back() &&
         std::lexicographical_compare(piece.rbegin(), piece.rend(), piece.begin(), piece.end(),
                                      [&](const Vec2& a, const Vec2& b) { return key(a) < key(b); })))
      std::reverse(piece.begin(), piece.end());
  }
  std::sort(pieces.begin(), pieces.end(), [&](const LineString& a, const LineString& b) {
    const auto ka = std::make_pair(nodeId[key(a.front())], nodeId[key(a.back())]);
    const auto kb = std::make_pair(nodeId[key(b.front())], nodeId[key(b.back())]);
    if (ka != kb) return ka < kb;
    return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(),
                                        [&](const Vec2& p, const Vec2& q) { return key(p) < key(q); });
  });
  for (LineString& piece : pieces) {
    const int a = nodeId[key(piece.front())];
    const int b = nodeId[key(piece.back())];
    if (a == b) {
      // A closed piece (a ring with one node): split it at its middle vertex so that no edge is a loop.
      const std::size_t mid = piece.size() / 2;
      if (piece.size() < 4) continue;  // a ring needs at least 3 distinct points
      const int m = graph.addNode(piece[mid]);
      graph.addEdge(a, m, LineString(piece.begin(), piece.begin() + static_cast<std::ptrdiff_t>(mid) + 1));
      graph.addEdge(m, b, LineString(piece.begin() + static_cast<std::ptrdiff_t>(mid), piece.end()));
      continue;
    }
    graph.addEdge(a, b, std::move(piece));
  }
  graph.sortRotations();
  return graph;
}

}  // namespace urbanvec
