#include "urbanvec/vectorize/roads/road_graph.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include "urbanvec/core/parallel.hpp"

namespace urbanvec::vectorize {

int RoadGraph::addNode(const Vec2& p, NodeType type, int col, int row) {
  RoadNode n;
  n.p = p;
  n.placed = p;
  n.type = type;
  n.col = col;
  n.row = row;
  nodes.push_back(std::move(n));
  return static_cast<int>(nodes.size()) - 1;
}

bool RoadGraph::linked(int a, int b) const {
  const auto& l = nodes[a].links;
  return std::find(l.begin(), l.end(), b) != l.end();
}

void RoadGraph::link(int a, int b) {
  if (a == b || linked(a, b)) return;
  nodes[a].links.push_back(b);
  nodes[b].links.push_back(a);
}

void RoadGraph::unlink(int a, int b) {
  auto drop = [](std::vector<std::int32_t>& l, int x) {
    auto it = std::find(l.begin(), l.end(), x);
    if (it != l.end()) l.erase(it);
  };
  drop(nodes[a].links, b);
  drop(nodes[b].links, a);
}

void RoadGraph::removeNode(int a) {
  const std::vector<std::int32_t> links = nodes[a].links;
  for (int b : links) unlink(a, b);
  nodes[a].alive = false;
}

size_t RoadGraph::aliveCount() const {
  return static_cast<size_t>(
      std::count_if(nodes.begin(), nodes.end(), [](const RoadNode& n) { return n.alive; }));
}

size_t RoadGraph::linkCount() const {
  size_t twice = 0;
  for (const RoadNode& n : nodes)
    if (n.alive) twice += n.links.size();
  return twice / 2;
}

void RoadGraph::compact() {
  std::vector<std::int32_t> newId(nodes.size(), -1);
  std::int32_t next = 0;
  for (size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].alive) newId[i] = next++;
  std::vector<RoadNode> kept;
  kept.reserve(static_cast<size_t>(next));
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (!nodes[i].alive) continue;
    RoadNode n = std::move(nodes[i]);
    for (auto& l : n.links) l = newId[l];
    kept.push_back(std::move(n));
  }
  nodes = std::move(kept);
}

double azimuth(const Vec2& a, const Vec2& b) {
  double az = std::atan2(b.x - a.x, b.y - a.y);
  if (az < 0) az += 2 * M_PI;
  return az;
}

void RoadGraph::sortLinksClockwise(int threads) {
  runChunks(workerCount(threads), nodes.size(), 4096, [&](size_t begin, size_t end, size_t) {
    for (size_t i = begin; i < end; ++i) {
      RoadNode& n = nodes[i];
      if (!n.alive || n.links.size() < 2) continue;
      std::sort(n.links.begin(), n.links.end(), [&](int a, int b) {
        const double za = azimuth(n.p, nodes[a].p), zb = azimuth(n.p, nodes[b].p);
        return za != zb ? za < zb : a < b;
      });
    }
  });
}

int RoadGraph::sameTypeDegree(int a) const {
  int k = 0;
  for (int b : nodes[a].links) k += nodes[b].type == nodes[a].type;
  return k;
}

void updateIntersectionFlags(RoadGraph& graph) {
  std::deque<int> candidates;
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
    RoadNode& n = graph.nodes[i];
    n.intersection = n.alive && n.links.size() > 2;
    if (n.intersection)
      for (int b : n.links) candidates.push_back(b);
  }
  while (!candidates.empty()) {
    const int c = candidates.front();
    candidates.pop_front();
    RoadNode& n = graph.nodes[c];
    if (n.intersection || n.links.empty()) continue;
    const bool allIntersections =
        std::all_of(n.links.begin(), n.links.end(), [&](int b) { return graph.nodes[b].intersection; });
    if (!allIntersections) continue;
    n.intersection = true;
    for (int b : n.links) candidates.push_back(b);
  }
}

std::vector<int> followChain(const RoadGraph& graph, int start, int next, bool throughFlagged) {
  std::vector<int> chain;
  int prev = start, cur = next;
  while (true) {
    chain.push_back(cur);
    const RoadNode& n = graph.nodes[cur];
    if (cur == start || (n.intersection && !throughFlagged) || n.links.size() != 2) break;
    const int after = n.links[0] == prev ? n.links[1] : n.links[0];
    prev = cur;
    cur = after;
  }
  return chain;
}

NodeIndex::NodeIndex(const RoadGraph& graph, double bucketSize, const std::function<bool(int)>& accept)
    : graph_(graph), bucket_(bucketSize) {
  std::vector<int> chosen;
  double maxX = 0, maxY = 0;
  minX_ = std::numeric_limits<double>::max();
  minY_ = std::numeric_limits<double>::max();
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
    if (!graph.nodes[i].alive || (accept && !accept(static_cast<int>(i)))) continue;
    chosen.push_back(static_cast<int>(i));
    const Vec2& p = graph.nodes[i].p;
    minX_ = std::min(minX_, p.x);
    minY_ = std::min(minY_, p.y);
    maxX = std::max(maxX, p.x);
    maxY = std::max(maxY, p.y);
  }
  if (chosen.empty()) {
    minX_ = minY_ = 0;
    nx_ = ny_ = 1;
    offsets_.assign(2, 0);
    return;
  }
  nx_ = static_cast<int>((maxX - minX_) / bucket_) + 1;
  ny_ = static_cast<int>((maxY - minY_) / bucket_) + 1;
  offsets_.assign(static_cast<size_t>(nx_) * ny_ + 1, 0);
  std::vector<std::int32_t> bucketOf(chosen.size());
  for (size_t k = 0; k < chosen.size(); ++k) {
    const Vec2& p = graph.nodes[chosen[k]].p;
    bucketOf[k] = bucketY(p.y) * nx_ + bucketX(p.x);
    ++offsets_[bucketOf[k] + 1];
  }
  for (size_t b = 1; b < offsets_.size(); ++b) offsets_[b] += offsets_[b - 1];
  ids_.resize(chosen.size());
  std::vector<std::int32_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (size_t k = 0; k < chosen.size(); ++k) ids_[fill[bucketOf[k]]++] = chosen[k];
}

int NodeIndex::bucketX(double x) const {
  return std::clamp(static_cast<int>(std::floor((x - minX_) / bucket_)), 0, nx_ - 1);
}
int NodeIndex::bucketY(double y) const {
  return std::clamp(static_cast<int>(std::floor((y - minY_) / bucket_)), 0, ny_ - 1);
}

std::vector<int> NodeIndex::within(const Vec2& p, double r) const {
  std::vector<int> out;
  if (ids_.empty()) return out;
  const int x0 = bucketX(p.x - r), x1 = bucketX(p.x + r), y0 = bucketY(p.y - r), y1 = bucketY(p.y + r);
  for (int by = y0; by <= y1; ++by)
    for (int bx = x0; bx <= x1; ++bx) {
      const int b = by * nx_ + bx;
      for (int k = offsets_[b]; k < offsets_[b + 1]; ++k)
        if (distance(graph_.nodes[ids_[k]].p, p) <= r) out.push_back(ids_[k]);
    }
  std::sort(out.begin(), out.end());
  return out;
}

int NodeIndex::nearest(const Vec2& p, double maxDistance, const std::function<bool(int)>& filter) const {
  if (ids_.empty()) return -1;
  // Grow the search square ring by ring until the best hit is closer than any unsearched bucket.
  const int cx = bucketX(p.x), cy = bucketY(p.y);
  int best = -1;
  double bestD = maxDistance;
  const int maxRing = std::max(nx_, ny_);
  for (int ring = 0; ring <= maxRing; ++ring) {
    if ((ring - 1) * bucket_ > bestD) break;
    for (int by = cy - ring; by <= cy + ring; ++by) {
      if (by < 0 || by >= ny_) continue;
      const bool edgeRow = by == cy - ring || by == cy + ring;
      for (int bx = cx - ring; bx <= cx + ring; bx += edgeRow ? 1 : 2 * ring) {
        if (bx >= 0 && bx < nx_) {
          const int b = by * nx_ + bx;
          for (int k = offsets_[b]; k < offsets_[b + 1]; ++k) {
            const int id = ids_[k];
            const double d = distance(graph_.nodes[id].p, p);
            if ((d < bestD || (d == bestD && best >= 0 && id < best) || (d == bestD && best < 0)) &&
                (!filter || filter(id))) {
              best = id;
              bestD = d;
            }
          }
        }
        if (ring == 0) break;
      }
    }
  }
  return best;
}

}  // namespace urbanvec::vectorize
