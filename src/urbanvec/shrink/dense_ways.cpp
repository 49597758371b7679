// Step8Pos (spec §B.11): densified ways, moved point by point, and crossing-safe simplification.
#include "urbanvec/shrink/dense_ways.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "urbanvec/core/segment_contact.hpp"
#include "urbanvec/core/uniform_grid.hpp"

namespace urbanvec::shrink {

std::vector<std::vector<int>> densifyWays(const std::vector<std::vector<int>>& ways, double maxStep,
                                          std::vector<Vec2>& pos, std::vector<Vec2>& shadow) {
  std::vector<std::vector<int>> dense;
  dense.reserve(ways.size());
  // A segment shared by several ways (same two nodes) gets the same synthetic points in each.
  std::map<std::pair<int, int>, std::vector<int>> shared;
  for (const auto& way : ways) {
    std::vector<int> out;
    for (size_t i = 0; i < way.size(); ++i) {
      if (i > 0 && way[i - 1] != way[i]) {
        const int u = std::min(way[i - 1], way[i]), v = std::max(way[i - 1], way[i]);
        auto [it, added] = shared.try_emplace({u, v});
        std::vector<int>& inner = it->second;  // from u to v
        if (added) {
          const Vec2 a = pos[static_cast<size_t>(u)], b = pos[static_cast<size_t>(v)];
          const Vec2 sa = shadow[static_cast<size_t>(u)], sb = shadow[static_cast<size_t>(v)];
          const double steps = std::ceil(distance(a, b) / maxStep - 1e-9);
          const int k = static_cast<int>(std::clamp(steps, 1.0, 1e7));
          for (int t = 1; t < k; ++t) {
            const double f = static_cast<double>(t) / k;
            inner.push_back(static_cast<int>(pos.size()));
            pos.push_back(a + (b - a) * f);
            shadow.push_back(sa + (sb - sa) * f);
          }
        }
        if (way[i - 1] == u)
          out.insert(out.end(), inner.begin(), inner.end());
        else
          out.insert(out.end(), inner.rbegin(), inner.rend());
      }
      out.push_back(way[i]);
    }
    dense.push_back(std::move(out));
  }
  return dense;
}

namespace {

/// Uniform grid of the current segments of every way.
class SegmentIndex {
 public:
  struct Seg {
    int a, b;    ///< point ids
    int way, k;  ///< way and dense index of the segment's start, k = -1 for a shortcut
    bool alive = true;
  };

  SegmentIndex(const std::vector<Vec2>& pos, double minX, double minY, double maxX, double maxY, double cell)
      : pos_(pos) {
    // At most 4096 buckets a side: a larger extent gets larger buckets.
    const int nx = std::clamp(static_cast<int>((maxX - minX) / cell) + 1, 1, 4096);
    const int ny = std::clamp(static_cast<int>((maxY - minY) / cell) + 1, 1, 4096);
    grid_.init({minX, minY}, {maxX, maxY},
               std::max({cell, (maxX - minX) / nx * 1.000001, (maxY - minY) / ny * 1.000001, 1e-9}));
  }

  int add(int a, int b, int way, int k) {
    const int id = static_cast<int>(segs_.size());
    segs_.push_back({a, b, way, k, true});
    stamp_.push_back(0);
    grid_.insert(pos_[static_cast<size_t>(a)], pos_[static_cast<size_t>(b)], id);
    return id;
  }
  void kill(int id) { segs_[static_cast<size_t>(id)].alive = false; }

  /// True when a point of a live segment (other than way `way`'s dense segments k in [k0, k1)) lies
  /// inside the ring `ring` (point ids, implicitly closed): dropping the ring's inner points would move
  /// the way to the other side of it.
  bool pocketHolds(const std::vector<int>& ring, int way, int k0, int k1) {
    double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
    for (int n : ring) {
      const Vec2 p = pos_[static_cast<size_t>(n)];
      minX = std::min(minX, p.x), maxX = std::max(maxX, p.x), minY = std::min(minY, p.y),
      maxY = std::max(maxY, p.y);
    }
    auto inside = [&](int id) {
      const Vec2 p = pos_[static_cast<size_t>(id)];
      if (p.x < minX || p.x > maxX || p.y < minY || p.y > maxY) return false;
      if (std::find(ring.begin(), ring.end(), id) != ring.end()) return false;
      bool in = false;
      for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
        const Vec2 a = pos_[static_cast<size_t>(ring[i])], b = pos_[static_cast<size_t>(ring[j])];
        if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) in = !in;
      }
      return in;
    };
    return anyLive({minX, minY}, {maxX, maxY}, way, k0, k1,
                   [&](const Seg& s) { return inside(s.a) || inside(s.b); });
  }

  /// True when segment a-b shares a point with a live segment other than way `way`'s dense segments
  /// k in [k0, k1), apart from a shared end point id.
  bool blocked(int a, int b, int way, int k0, int k1, bool sameSegmentOk = false) {
    const Vec2 p = pos_[static_cast<size_t>(a)], q = pos_[static_cast<size_t>(b)];
    return anyLive(p, q, way, k0, k1, [&](const Seg& s) {
      if (s.a == a || s.a == b || s.b == a || s.b == b) {
        // Sharing an end point: only a collinear overlap beyond it is a conflict.
        const int shared = (s.a == a || s.b == a) ? a : b;
        const int other = s.a == shared ? s.b : s.a;
        const int mine = shared == a ? b : a;
        const Vec2 o = pos_[static_cast<size_t>(other)], m = pos_[static_cast<size_t>(mine)],
                   sp = pos_[static_cast<size_t>(shared)];
        if (other != mine && orientation(sp, m, o) == 0 && dot(m - sp, o - sp) > 0) return true;
        return other == mine && !sameSegmentOk;  // the same segment twice
      }
      return segmentContact(p, q, pos_[static_cast<size_t>(s.a)], pos_[static_cast<size_t>(s.b)]) !=
             SegmentContact::None;
    });
  }

 private:
  /// True when `hit` holds for a live segment in the buckets of the box lo-hi, each looked at once,
  /// leaving out way `way`'s dense segments k in [k0, k1).
  template <class Hit>
  bool anyLive(const Vec2& lo, const Vec2& hi, int way, int k0, int k1, Hit hit) {
    ++query_;
    bool found = false;
    grid_.forBox(lo, hi, [&](const std::vector<int>& bucket) {
      for (std::size_t i = 0; !found && i < bucket.size(); ++i) {
        const int id = bucket[i];
        if (stamp_[static_cast<size_t>(id)] == query_) continue;
        stamp_[static_cast<size_t>(id)] = query_;
        const Seg& s = segs_[static_cast<size_t>(id)];
        if (!s.alive || (s.way == way && s.k >= k0 && s.k < k1)) continue;
        found = hit(s);
      }
    });
    return found;
  }

  const std::vector<Vec2>& pos_;
  UniformGrid<int> grid_;
  std::vector<Seg> segs_;
  std::vector<unsigned> stamp_;
  unsigned query_ = 0;
};

}  // namespace

std::vector<std::vector<int>> simplifyWithoutCrossings(const std::vector<std::vector<int>>& ways,
                                                       const std::vector<Vec2>& pos,
                                                       const std::vector<char>& removable,
                                                       const std::vector<char>& carved, double tolerance,
                                                       SimplifyStats* stats) {
  double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
  size_t segments = 0;
  for (const auto& way : ways) {
    for (int n : way) {
      const Vec2 p = pos[static_cast<size_t>(n)];
      minX = std::min(minX, p.x), maxX = std::max(maxX, p.x), minY = std::min(minY, p.y),
      maxY = std::max(maxY, p.y);
    }
    segments += way.size();
  }
  std::vector<std::vector<int>> out(ways.size());
  if (segments == 0) return out;
  // About four segments per cell on average over the bounding box.
  const double area = std::max((maxX - minX) * (maxY - minY), 1e-12);
  const double cell = std::max(std::sqrt(4.0 * area / static_cast<double>(segments)), 4.0 * tolerance);
  SegmentIndex index(pos, minX, minY, maxX, maxY, cell);
  std::vector<std::vector<int>> ids(ways.size());
  for (size_t w = 0; w < ways.size(); ++w)
    for (size_t k = 1; k < ways[w].size(); ++k)
      ids[w].push_back(index.add(ways[w][k - 1], ways[w][k], static_cast<int>(w), static_cast<int>(k - 1)));
  SimplifyStats local;
  for (size_t w = 0; w < ways.size(); ++w) {
    const std::vector<int>& pts = ways[w];
    std::vector<int>& res = out[w];
    if (pts.empty()) continue;
    res.push_back(pts[0]);
    size_t i = 0;
    while (i + 1 < pts.size()) {
      size_t j = i + 1;  // the current end: pts[i+1..j-1] are dropped
      while (j + 1 < pts.size() && removable[static_cast<size_t>(pts[j])]) {
        const size_t e = j + 1;
        const Vec2 a = pos[static_cast<size_t>(pts[i])], b = pos[static_cast<size_t>(pts[e])];
        bool ok = pts[i] != pts[e];
        for (size_t m = i + 1; ok && m < e; ++m)
          ok = distanceToSegment(pos[static_cast<size_t>(pts[m])], a, b) <= tolerance;
        if (ok)
          ok = !index.blocked(pts[i], pts[e], static_cast<int>(w), static_cast<int>(i), static_cast<int>(e));
        if (ok && e > i + 1) {
          const std::vector<int> ring(pts.begin() + static_cast<std::ptrdiff_t>(i),
                                      pts.begin() + static_cast<std::ptrdiff_t>(e) + 1);
          ok = !index.pocketHolds(ring, static_cast<int>(w), static_cast<int>(i), static_cast<int>(e));
        }
        if (!ok) break;
        j = e;
      }
      if (j > i + 1) {
        for (size_t k = i; k < j; ++k) index.kill(ids[w][k]);
        index.add(pts[i], pts[j], static_cast<int>(w), -1);
        local.removed += static_cast<int>(j - i - 1);
      }
      if (removable[static_cast<size_t>(pts[j])] && j + 1 < pts.size()) {
        ++local.kept;
        local.keptCarved += carved[static_cast<size_t>(pts[j])] ? 1 : 0;
      }
      res.push_back(pts[j]);
      i = j;
    }
  }
  if (stats) *stats = local;
  return out;
}

int revertCrossingMoves(const std::vector<std::vector<int>>& ways, const std::vector<Vec2>& from,
                        std::vector<Vec2>& to) {
  const size_t n = to.size();
  // Positions: ids < n are the moved points, n + id the same point before the move (for sweep rings).
  std::vector<Vec2> pos(2 * n);
  std::vector<std::vector<int>> live(ways.size());  // finite points, no repeats
  std::vector<char> refused(ways.size(), 0);
  int refusals = 0;
  for (bool changed = true; changed;) {
    changed = false;
    double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
    size_t segments = 0;
    for (size_t i = 0; i < n; ++i) pos[i] = to[i], pos[n + i] = from[i];
    for (size_t w = 0; w < ways.size(); ++w) {
      live[w].clear();
      for (int id : ways[w]) {
        const Vec2 p = to[static_cast<size_t>(id)];
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
        if (!live[w].empty() && (live[w].back() == id || to[static_cast<size_t>(live[w].back())] == p))
          continue;
        live[w].push_back(id);
        minX = std::min(minX, p.x), maxX = std::max(maxX, p.x), minY = std::min(minY, p.y),
        maxY = std::max(maxY, p.y);
      }
      segments += live[w].size();
    }
    if (segments == 0) break;
    const double area = std::max((maxX - minX) * (maxY - minY), 1e-12);
    SegmentIndex index(pos, minX, minY, maxX, maxY, std::sqrt(4.0 * area / static_cast<double>(segments)));
    constexpr int kAll = 1 << 30;
    for (size_t w = 0; w < ways.size(); ++w)
      for (size_t k = 1; k < live[w].size(); ++k)
        index.add(live[w][k - 1], live[w][k], static_cast<int>(w), static_cast<int>(k - 1));
    for (size_t w = 0; w < ways.size(); ++w) {
      const std::vector<int>& pts = live[w];
      auto moved = [&](int id) { return !(to[static_cast<size_t>(id)] == from[static_cast<size_t>(id)]); };
      bool bad = false;
      for (size_t k = 1; !bad && k < pts.size(); ++k) {
        const int a = pts[k - 1], b = pts[k];
        if (!moved(a) && !moved(b)) continue;
        bad = index.blocked(a, b, static_cast<int>(w), 0, kAll, true) ||
              index.pocketHolds({a, b, b + static_cast<int>(n), a + static_cast<int>(n)}, static_cast<int>(w),
                                0, kAll);
      }
      if (!bad) continue;
      // Back to the carved positions; the ways sharing these points are checked again next round.
      for (int id : ways[w]) to[static_cast<size_t>(id)] = from[static_cast<size_t>(id)];
      refusals += refused[w] ? 0 : 1;
      refused[w] = 1;
      changed = true;
    }
  }
  return refusals;
}

}  // namespace urbanvec::shrink
