// Cell regions traced along cell edges (see the header). The boundary edges are those between a cell of
// the mask and one outside it, walked with the region on the right. Where two cells of the mask touch
// only at a corner, the walk turns so that no ring passes that corner twice, which needs to know whether
// the two cells are of one 4-connected region: the components of the mask's row runs tell, and they
// also give each hole its polygon.
#include "urbanvec/core/cell_regions.hpp"

#include <algorithm>
#include <vector>

#include "urbanvec/core/error.hpp"

namespace urbanvec {

namespace {

// Directions of a boundary edge, clockwise; the mask cell lies on its right.
enum Direction : int { East = 0, South = 1, West = 2, North = 3 };
constexpr int kStepX[4] = {1, 0, -1, 0};
constexpr int kStepY[4] = {0, 1, 0, -1};  // rows grow downwards

struct Run {
  int row, first, last;  ///< cells [first, last] of the row
  int parent;            ///< union-find over runs
};

int root(std::vector<Run>& runs, int i) {
  while (runs[i].parent != i) {
    runs[i].parent = runs[runs[i].parent].parent;
    i = runs[i].parent;
  }
  return i;
}

}  // namespace

MultiPolygon cellRegions(const Grid<std::uint8_t>& mask) {
  const int w = mask.width, h = mask.height;
  auto in = [&](int col, int row) {
    return col >= 0 && row >= 0 && col < w && row < h && mask.at(col, row) != 0;
  };

  // 4-connected components of the row runs.
  std::vector<Run> runs;
  std::vector<int> rowStart(static_cast<size_t>(h) + 1, 0);
  for (int row = 0; row < h; ++row) {
    rowStart[row] = static_cast<int>(runs.size());
    for (int col = 0; col < w;) {
      if (!in(col, row)) {
        ++col;
        continue;
      }
      const int first = col;
      while (col < w && in(col, row)) ++col;
      runs.push_back({row, first, col - 1, static_cast<int>(runs.size())});
    }
  }
  rowStart[h] = static_cast<int>(runs.size());
  for (int row = 0; row + 1 < h; ++row) {
    int a = rowStart[row], b = rowStart[row + 1];
    while (a < rowStart[row + 1] && b < rowStart[row + 2]) {
      if (runs[a].first <= runs[b].last && runs[b].first <= runs[a].last) {
        const int ra = root(runs, a), rb = root(runs, b);
        if (ra != rb) runs[std::max(ra, rb)].parent = std::min(ra, rb);
      }
      if (runs[a].last < runs[b].last)
        ++a;
      else
        ++b;
    }
  }
  auto component = [&](int col, int row) {
    const auto begin = runs.begin() + rowStart[row], end = runs.begin() + rowStart[row + 1];
    const auto it = std::upper_bound(begin, end, col, [](int c, const Run& r) { return c < r.first; });
    if (it == begin || std::prev(it)->last < col)
      throw internalError("cellRegions: a boundary cell has no run");
    return root(runs, static_cast<int>(std::prev(it) - runs.begin()));
  };

  // Boundary edges leaving corner (x, y) (x = column, y = row of the corner, both 0..size), as a bit per
  // direction, from the four cells around it.
  auto outgoing = [&](int x, int y) {
    const bool nw = in(x - 1, y - 1), ne = in(x, y - 1), sw = in(x - 1, y), se = in(x, y);
    return (se && !ne ? 1 << East : 0) | (sw && !se ? 1 << South : 0) | (nw && !sw ? 1 << West : 0) |
           (ne && !nw ? 1 << North : 0);
  };
  const int top = mask.frameDy + h;
  auto point = [&](int x, int y) { return Vec2(mask.frameDx + x, top - y); };
  const size_t stride = static_cast<size_t>(w) + 1;
  std::vector<std::uint8_t> walked(stride * (static_cast<size_t>(h) + 1), 0);

  MultiPolygon out;
  std::vector<int> polygonOf(runs.size(), -1);  // by component root
  struct Hole {
    int component;
    Ring ring;
  };
  std::vector<Hole> holes;
  for (int y = 0; y <= h; ++y)
    for (int x = 0; x <= w; ++x) {
      for (int open = outgoing(x, y) & ~walked[y * stride + x]; open != 0;
           open = outgoing(x, y) & ~walked[y * stride + x]) {
        // (x, y) is the ring's first corner in row-major order: it leaves to the east or the south.
        const int start = open & (1 << East) ? East : South;
        if (!(open & (1 << start))) throw internalError("cellRegions: a ring starts at an inner corner");
        Ring ring{point(x, y)};
        long long twiceArea = 0;  // in (column, row) units; clockwise in the frame is positive here
        int cx = x, cy = y, d = start;
        for (;;) {
          std::uint8_t& mark = walked[cy * stride + cx];
          if (mark & (1 << d)) throw internalError("cellRegions: a boundary walk did not close");
          mark |= static_cast<std::uint8_t>(1 << d);
          const int nx = cx + kStepX[d], ny = cy + kStepY[d];
          twiceArea += static_cast<long long>(cx) * ny - static_cast<long long>(nx) * cy;
          cx = nx;
          cy = ny;
          const int next = outgoing(cx, cy);
          int turn = 0;
          if (next == (1 << ((d + 1) % 4) | 1 << ((d + 3) % 4))) {
            // Two cells of the mask touch only at this corner. Of one region, their rings (outer ring and
            // hole, or two holes) each go round the corner of a cell outside the mask: turn left. Of two
            // regions, each ring goes round the corner of its own cell: turn right.
            const bool nwse = next & (1 << East);
            const bool oneRegion = nwse ? component(cx - 1, cy - 1) == component(cx, cy)
                                        : component(cx, cy - 1) == component(cx - 1, cy);
            turn = oneRegion ? (d + 3) % 4 : (d + 1) % 4;
          } else {
            turn = __builtin_ctz(static_cast<unsigned>(next));
          }
          if (cx == x && cy == y && turn == start) break;
          if (turn != d) ring.push_back(point(cx, cy));
          d = turn;
        }
        ring.push_back(ring.front());
        // The cell right of the first edge.
        const int comp = start == East ? component(x, y) : component(x - 1, y);
        if (twiceArea > 0) {  // row axis downwards: clockwise in the frame, an outer ring
          polygonOf[comp] = static_cast<int>(out.size());
          out.push_back(Polygon{std::move(ring), {}});
        } else {
          holes.push_back({comp, std::move(ring)});
        }
      }
    }
  for (Hole& hole : holes) {
    if (polygonOf[hole.component] < 0) throw internalError("cellRegions: a hole without its outer ring");
    out[polygonOf[hole.component]].holes.push_back(std::move(hole.ring));
  }
  return out;
}

}  // namespace urbanvec
