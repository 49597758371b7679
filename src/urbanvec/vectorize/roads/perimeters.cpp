// Stage A4.8 (spec §3 A4.8) with the [INFERENCE] edge rule: an edge is on a perimeter iff it
// separates an undeveloped patch (unused, outside the grid, or water per Q7) from a patch of an
// external simulated block. Walks start at vertices with one edge and take the rightmost turn at
// checkerboard (degree-4) vertices.
#include "urbanvec/vectorize/roads/perimeters.hpp"

#include <unordered_map>

#include "urbanvec/core/landuse.hpp"

namespace urbanvec::vectorize {

PerimeterStats addExternalPerimeters(RoadGraph& graph, const Grid<std::uint8_t>& cells,
                                     const Grid<std::int32_t>& blockOf, const std::vector<SimBlock>& blocks,
                                     const PerimeterOptions& options, const Progress& progress) {
  const int w = cells.width, h = cells.height;
  const int vw = w + 1, vh = h + 1;
  auto undeveloped = [&](int c, int r) {
    if (!cells.inside(c, r)) return true;
    const std::uint8_t v = cells.at(c, r);
    return v == static_cast<std::uint8_t>(LandUse::Unused) ||
           (options.waterIsUndeveloped && v == static_cast<std::uint8_t>(LandUse::Water)) ||
           (options.reservedIsUndeveloped && v == static_cast<std::uint8_t>(LandUse::Reserved) &&
            blockOf.at(c, r) < 0);
  };
  auto external = [&](int c, int r) {
    if (!cells.inside(c, r)) return false;
    const int b = blockOf.at(c, r);
    return b >= 0 && !blocks[b].internal;
  };
  auto separates = [&](int c1, int r1, int c2, int r2) {
    return (undeveloped(c1, r1) && external(c2, r2)) || (external(c1, r1) && undeveloped(c2, r2));
  };
  // Edge bits per vertex (cc, rr): N = towards rr-1, E = cc+1, S = rr+1, W = cc-1.
  enum { N = 1, E = 2, S = 4, W = 8 };
  const int dc[4] = {0, 1, 0, -1}, dr[4] = {-1, 0, 1, 0};
  Grid<std::uint8_t> edges(vw, vh, 0);
  for (int rr = 0; rr < vh; ++rr)
    for (int cc = 0; cc < vw; ++cc) {
      // Horizontal edge (cc, rr)-(cc+1, rr): patches (cc, rr-1) above and (cc, rr) below.
      if (cc < w && separates(cc, rr - 1, cc, rr)) {
        edges.at(cc, rr) |= E;
        edges.at(cc + 1, rr) |= W;
      }
      // Vertical edge (cc, rr)-(cc, rr+1): patches (cc-1, rr) left and (cc, rr) right.
      if (rr < h && separates(cc - 1, rr, cc, rr)) {
        edges.at(cc, rr) |= S;
        edges.at(cc, rr + 1) |= N;
      }
    }
  reportProgress(progress, 0.4, "perimeters");

  auto degree = [](std::uint8_t bits) {
    return (bits & 1) + ((bits >> 1) & 1) + ((bits >> 2) & 1) + ((bits >> 3) & 1);
  };
  auto take = [&](int cc, int rr, int dir) {
    edges.at(cc, rr) &= static_cast<std::uint8_t>(~(1 << dir));
    edges.at(cc + dc[dir], rr + dr[dir]) &= static_cast<std::uint8_t>(~(1 << ((dir + 2) % 4)));
  };
  PerimeterStats stats;
  std::vector<std::pair<int, int>> line;
  std::unordered_map<int, int> nodeAt;
  for (int rr = 0; rr < vh; ++rr)
    for (int cc = 0; cc < vw; ++cc) {
      if (degree(edges.at(cc, rr)) != 1) continue;
      line.assign(1, {cc, rr});
      int c = cc, r = rr, dir = -1;
      while (edges.at(c, r) != 0) {
        int next = -1;
        if (dir < 0) {
          for (int d = 0; d < 4 && next < 0; ++d)
            if (edges.at(c, r) & (1 << d)) next = d;
        } else {
          for (int turn : {1, 0, 3})  // rightmost first: right, straight, left
            if (next < 0 && (edges.at(c, r) & (1 << ((dir + turn) % 4)))) next = (dir + turn) % 4;
          if (next < 0) break;
        }
        take(c, r, next);
        c += dc[next];
        r += dr[next];
        dir = next;
        line.emplace_back(c, r);
      }
      int prev = -1;
      for (const auto& v : line) {
        // A vertex met twice (checkerboard crossing) is one node, so no duplicate nodes arise.
        auto [it, isNew] = nodeAt.try_emplace(v.second * vw + v.first, -1);
        if (isNew)
          it->second =
              graph.addNode(Vec2(cells.frameDx + v.first, cells.frameDy + h - v.second), NodeType::Perimeter);
        const int id = it->second;
        if (prev >= 0) graph.link(prev, id);
        prev = id;
      }
      ++stats.lines;
    }
  for (int i = 0; i < vw * vh; ++i)
    if (edges.cells[i]) {
      // Count each remaining closed loop once by clearing it.
      ++stats.closedLoops;
      std::vector<int> stack{i};
      while (!stack.empty()) {
        const int v = stack.back();
        stack.pop_back();
        const int c = v % vw, r = v / vw;
        for (int d = 0; d < 4; ++d)
          if (edges.at(c, r) & (1 << d)) {
            take(c, r, d);
            stack.push_back((r + dr[d]) * vw + c + dc[d]);
          }
      }
    }
  reportProgress(progress, 1.0, "perimeters");
  return stats;
}

}  // namespace urbanvec::vectorize
