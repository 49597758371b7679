// Vertex cleaning by collapsing (spec pueyo-urban-data.md §A.4). See vertex_collapsing.hpp.
#include "urbanvec/cadastre/vertex_collapsing.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace urbanvec::cadastre {
namespace {

/// A representative vertex: the original coordinates (distinct ids) it stands for.
struct Rep {
  std::vector<int> members;
  Vec2 sum;
  Vec2 pos;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // bounding box of the members
  void recompute(const std::vector<Vec2>& coords) {
    sum = {0, 0};
    x0 = y0 = std::numeric_limits<double>::infinity();
    x1 = y1 = -x0;
    for (int m : members) {
      const Vec2& c = coords[static_cast<size_t>(m)];
      sum += c;
      x0 = std::min(x0, c.x), y0 = std::min(y0, c.y), x1 = std::max(x1, c.x), y1 = std::max(y1, c.y);
    }
    pos = sum / static_cast<double>(members.size());
  }
};

/// Neighbours per coordinate considered by the closest-first collapse.
constexpr std::size_t kClosestNeighbours = 24;

/// Whether m and n are the opposite ends of two copies of one line: a segment from m and one from n run
/// in opposite directions, parallel, over most of the shorter one (a short edge drawn twice, whose
/// copies' ends may lie closer across the edge than along it). Not the two halves of a split line,
/// which meet end to end.
bool oppositeEndsOfCopies(const std::vector<Vec2>& coords, const std::vector<std::vector<int>>& adjacent,
                          int m, int n) {
  constexpr double kParallel = 0.966;  // cos 15 degrees
  constexpr double kOverlap = 0.75;    // share of the shorter segment run side by side
  const Vec2 pm = coords[static_cast<size_t>(m)], pn = coords[static_cast<size_t>(n)];
  for (int a : adjacent[static_cast<size_t>(m)]) {
    const Vec2 u = coords[static_cast<size_t>(a)] - pm;
    const double lu = length(u);
    if (!(lu > 0.0)) continue;
    const Vec2 uh = u / lu;
    for (int b : adjacent[static_cast<size_t>(n)]) {
      const Vec2 v = coords[static_cast<size_t>(b)] - pn;
      const double lv = length(v);
      if (!(lv > 0.0) || dot(uh, v) / lv > -kParallel) continue;
      const double t0 = dot(pn - pm, uh), t1 = dot(coords[static_cast<size_t>(b)] - pm, uh);
      const double overlap = std::min(lu, std::max(t0, t1)) - std::max(0.0, std::min(t0, t1));
      if (overlap > kOverlap * std::min(lu, lv)) return true;
    }
  }
  return false;
}

/// Closest pairs first (see collapseVertices): returns, for every coordinate, the id of one coordinate
/// of its cluster (the same for the whole cluster; the caller numbers the clusters).
std::vector<int> closestFirstClusters(const std::vector<Vec2>& coords,
                                      const std::vector<std::vector<int>>& adjacent,
                                      const std::vector<char>& joinedVertex, bool freeEndsOnly,
                                      double threshold, std::size_t neighbours, CollapseStats& stats,
                                      const Progress& progress) {
  const double t2 = threshold * threshold;
  // Coordinates sorted by cell (row, column) of the threshold's size: a query scans three runs.
  auto cellOf = [&](double v) { return static_cast<std::int64_t>(std::floor(v / threshold)); };
  std::vector<std::pair<std::pair<std::int64_t, std::int64_t>, int>> cells(coords.size());
  for (size_t i = 0; i < coords.size(); ++i)
    cells[i] = {{cellOf(coords[i].y), cellOf(coords[i].x)}, static_cast<int>(i)};
  std::sort(cells.begin(), cells.end());
  struct Pair {
    double d2;
    int x, y;
  };
  std::vector<Pair> pairs;
  std::vector<Pair> near;
  ProgressTicker ticker(progress, "collapsing vertices", coords.size());
  // Points in cell order: the runs of the rows above, at and below (columns c - 1 .. c + 1) only move
  // forward, so three cursors replace a search per point.
  size_t cursor[3] = {0, 0, 0};
  for (size_t k = 0; k < cells.size(); ++k) {
    ticker.tick();
    const int x = cells[k].second;
    const Vec2 p = coords[static_cast<size_t>(x)];
    const std::int64_t row0 = cells[k].first.first, col = cells[k].first.second;
    near.clear();
    for (int r = 0; r < 3; ++r) {
      const std::pair<std::int64_t, std::int64_t> from{row0 - 1 + r, col - 1};
      size_t& i = cursor[r];
      while (i < cells.size() && cells[i].first < from) ++i;
      for (size_t j = i;
           j < cells.size() && cells[j].first.first == from.first && cells[j].first.second <= col + 1; ++j) {
        const int y = cells[j].second;
        if (y == x) continue;
        const Vec2 d = coords[static_cast<size_t>(y)] - p;
        const double d2 = dot(d, d);
        if (d2 < t2) near.push_back({d2, std::min(x, y), std::max(x, y)});
      }
    }
    // The nearest few only: a pile of coordinates on one spot stays linear.
    auto closer = [](const Pair& u, const Pair& v) {
      return u.d2 != v.d2 ? u.d2 < v.d2 : (u.x != v.x ? u.x < v.x : u.y < v.y);
    };
    if (near.size() > neighbours) {
      std::nth_element(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(neighbours), near.end(),
                       closer);
      near.resize(neighbours);
    }
    // Each pair once (from its lower id), unless the list was cut to the nearest: then from both.
    const bool cut = near.size() >= neighbours;
    for (const Pair& q : near)
      if (cut || (q.x == x ? q.y : q.x) > x) pairs.push_back(q);
  }
  ticker.finish();
  auto closer = [](const Pair& u, const Pair& v) {
    return u.d2 != v.d2 ? u.d2 < v.d2 : (u.x != v.x ? u.x < v.x : u.y < v.y);
  };
  std::sort(pairs.begin(), pairs.end(), closer);
  pairs.erase(std::unique(pairs.begin(), pairs.end(),
                          [](const Pair& u, const Pair& v) { return u.x == v.x && u.y == v.y; }),
              pairs.end());
  std::vector<int> cluster(coords.size());
  std::vector<std::vector<int>> members(coords.size());
  std::vector<char> allJoined(joinedVertex.begin(), joinedVertex.end());
  for (size_t i = 0; i < coords.size(); ++i)
    cluster[i] = static_cast<int>(i), members[i] = {static_cast<int>(i)};
  // Vertices once refused stay refused: a merge only grows them, and every refusal (a segment between
  // them, copies of one line, too wide) holds for any larger vertex.
  std::unordered_set<std::uint64_t> refused;
  auto refusal = [](int a, int b) {
    return static_cast<std::uint64_t>(std::min(a, b)) << 32 | static_cast<std::uint32_t>(std::max(a, b));
  };
  for (const Pair& q : pairs) {
    int cx = cluster[static_cast<size_t>(q.x)], cy = cluster[static_cast<size_t>(q.y)];
    if (cx == cy || refused.count(refusal(cx, cy))) continue;
    if (freeEndsOnly && allJoined[static_cast<size_t>(cx)] && allJoined[static_cast<size_t>(cy)]) continue;
    if (members[static_cast<size_t>(cx)].size() < members[static_cast<size_t>(cy)].size()) std::swap(cx, cy);
    auto& big = members[static_cast<size_t>(cx)];
    auto& small = members[static_cast<size_t>(cy)];
    // Two coordinates joined by a segment never become one vertex.
    bool linked = false;
    for (int m : small) {
      for (int a : adjacent[static_cast<size_t>(m)])
        if (cluster[static_cast<size_t>(a)] == cx) linked = true;
      if (linked) break;
    }
    if (linked) {
      refused.insert(refusal(cx, cy));
      continue;
    }
    for (int m : small) {
      for (int n : big)
        if (oppositeEndsOfCopies(coords, adjacent, m, n)) {
          linked = true;
          break;
        }
      if (linked) break;
    }
    if (linked) {
      refused.insert(refusal(cx, cy));
      continue;
    }
    // Anti-drift: no two coordinates of the merged vertex farther apart than the threshold.
    bool wide = false;
    for (int m : small) {
      for (int n : big)
        if (dot(coords[static_cast<size_t>(m)] - coords[static_cast<size_t>(n)],
                coords[static_cast<size_t>(m)] - coords[static_cast<size_t>(n)]) >= t2) {
          wide = true;
          break;
        }
      if (wide) break;
    }
    if (wide) {
      ++stats.reverted;
      refused.insert(refusal(cx, cy));
      continue;
    }
    for (int m : small) cluster[static_cast<size_t>(m)] = cx;
    big.insert(big.end(), small.begin(), small.end());
    small.clear();
    small.shrink_to_fit();
    allJoined[static_cast<size_t>(cx)] =
        allJoined[static_cast<size_t>(cx)] && allJoined[static_cast<size_t>(cy)];
  }
  return cluster;
}

}  // namespace

Linework collapseVertices(const std::vector<CadLine>& lines, double threshold, CollapseStats& stats,
                          const Progress& progress, bool revert, bool freeEndsOnly, bool closestFirst) {
  stats = {};
  // 1. Identical coordinates are one vertex (§A.4 case 1); ids in order of first occurrence.
  std::unordered_map<std::pair<std::uint64_t, std::uint64_t>, int, CoordinateHash> idOf;
  std::vector<Vec2> coords;
  std::vector<std::vector<int>> lineIds(lines.size());
  for (size_t l = 0; l < lines.size(); ++l)
    for (const Vec2& p : lines[l].line) {
      ++stats.inputVertices;
      auto [it, fresh] = idOf.emplace(coordinateKey(p), static_cast<int>(coords.size()));
      if (fresh) coords.push_back(p);
      lineIds[l].push_back(it->second);
    }
  stats.distinctVertices = coords.size();
  // Adjacency between distinct vertices: those joined by a segment never collapse together.
  std::vector<std::vector<int>> adjacent(coords.size());
  for (const auto& ids : lineIds)
    for (size_t i = 1; i < ids.size(); ++i)
      if (ids[i] != ids[i - 1]) {
        adjacent[static_cast<size_t>(ids[i])].push_back(ids[i - 1]);
        adjacent[static_cast<size_t>(ids[i - 1])].push_back(ids[i]);
      }

  // Vertices where lines already meet exactly (two or more segment ends) are sound; with
  // `freeEndsOnly` two of them never collapse together, only a free end joins another vertex.
  std::vector<char> joinedVertex(coords.size(), 0);
  for (size_t i = 0; i < coords.size(); ++i) joinedVertex[i] = adjacent[i].size() >= 2;
  std::vector<char> repJoined;  // per representative: all its members are joined vertices
  // 2. Collapse onto the nearest representative within the threshold (§A.4 cases 2 and 3).
  std::vector<int> repOf(coords.size(), -1);
  std::vector<Rep> reps;
  if (closestFirst) {
    const std::vector<int> cluster = closestFirstClusters(coords, adjacent, joinedVertex, freeEndsOnly,
                                                          threshold, kClosestNeighbours, stats, progress);
    std::vector<int> repOfCluster(coords.size(), -1);
    for (size_t i = 0; i < coords.size(); ++i) {
      int& r = repOfCluster[static_cast<size_t>(cluster[i])];
      if (r < 0) {
        r = static_cast<int>(reps.size());
        reps.emplace_back();
        repJoined.push_back(1);
      }
      reps[static_cast<size_t>(r)].members.push_back(static_cast<int>(i));
      repJoined[static_cast<size_t>(r)] = repJoined[static_cast<size_t>(r)] && joinedVertex[i];
      repOf[i] = r;
    }
    for (Rep& r : reps) r.recompute(coords);
  }
  CellGrid grid(threshold);
  const double t2 = threshold * threshold;
  ProgressTicker ticker(progress, "collapsing vertices", coords.size());
  std::vector<std::pair<double, int>> candidates;
  for (size_t x = 0; x < coords.size() && !closestFirst; ++x) {
    ticker.tick();
    const Vec2 p = coords[x];
    candidates.clear();
    grid.query(p.x - threshold, p.y - threshold, p.x + threshold, p.y + threshold, [&](int r) {
      const Vec2 d = reps[static_cast<size_t>(r)].pos - p;
      const double d2 = dot(d, d);
      if (d2 < t2) candidates.emplace_back(d2, r);
    });
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    int chosen = -1;
    for (const auto& [d2, r] : candidates) {
      bool joined = false;
      for (int y : adjacent[x])
        if (repOf[static_cast<size_t>(y)] == r) joined = true;
      if (freeEndsOnly && joinedVertex[x] && repJoined[static_cast<size_t>(r)]) joined = true;
      if (!joined) {
        chosen = r;
        break;
      }
    }
    auto newRep = [&](int id) {
      Rep rep;
      rep.members = {id};
      rep.recompute(coords);
      repOf[static_cast<size_t>(id)] = static_cast<int>(reps.size());
      repJoined.push_back(joinedVertex[static_cast<size_t>(id)]);
      grid.insert(rep.pos, static_cast<int>(reps.size()));
      reps.push_back(std::move(rep));
    };
    if (chosen < 0) {
      newRep(static_cast<int>(x));
      continue;
    }
    Rep& r = reps[static_cast<size_t>(chosen)];
    // Anti-drift: every original the representative stands for must be within the threshold of p.
    // The members' bounding box answers at once when its farthest corner is close enough.
    const double fx = std::max(std::abs(r.x0 - p.x), std::abs(r.x1 - p.x));
    const double fy = std::max(std::abs(r.y0 - p.y), std::abs(r.y1 - p.y));
    int farthest = -1;
    if (fx * fx + fy * fy >= t2) {
      double worst = -1.0;
      for (int m : r.members) {
        const Vec2 d = coords[static_cast<size_t>(m)] - p;
        if (dot(d, d) > worst) worst = dot(d, d), farthest = m;
      }
      if (worst < t2) farthest = -1;
    }
    grid.erase(r.pos, chosen);
    if (farthest < 0) {
      r.members.push_back(static_cast<int>(x));
      repOf[x] = chosen;
      repJoined[static_cast<size_t>(chosen)] = repJoined[static_cast<size_t>(chosen)] && joinedVertex[x];
      r.recompute(coords);
      grid.insert(r.pos, chosen);
    } else if (!revert) {
      // The collapse would stretch the representative over more than the threshold: p stays apart.
      ++stats.reverted;
      grid.insert(r.pos, chosen);
      newRep(static_cast<int>(x));
    } else {
      // Revert (Fig. 10 ii.b): the farthest original and the new vertex become vertices of their own.
      ++stats.reverted;
      r.members.erase(std::find(r.members.begin(), r.members.end(), farthest));
      r.recompute(coords);
      grid.insert(r.pos, chosen);
      newRep(farthest);
      newRep(static_cast<int>(x));
    }
  }
  ticker.finish();

  // 3. Segments between representatives.
  Linework out;
  out.vertices.reserve(reps.size());
  for (const Rep& r : reps) out.vertices.push_back(r.pos);
  if (freeEndsOnly) out.sound.assign(repJoined.begin(), repJoined.end());
  stats.outputVertices = reps.size();
  for (size_t l = 0; l < lines.size(); ++l) {
    const auto& ids = lineIds[l];
    for (size_t i = 1; i < ids.size(); ++i) {
      const int a = repOf[static_cast<size_t>(ids[i - 1])], b = repOf[static_cast<size_t>(ids[i])];
      if (a == b) {
        if (ids[i] != ids[i - 1]) ++stats.zeroLengthSegments;
        continue;
      }
      out.segments.push_back({a, b, lines[l].layer});
      out.copies.push_back({a, b, lines[l].line[i - 1]});
      out.copies.push_back({b, a, lines[l].line[i]});
    }
  }
  return out;
}

}  // namespace urbanvec::cadastre
