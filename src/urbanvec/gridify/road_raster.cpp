// Road rasterization (issue 2 §2 "Roads obey the conventions the vectorizer relies on").
#include "urbanvec/gridify/road_raster.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

namespace urbanvec::gridify {

namespace {

constexpr std::uint8_t kSecondary = static_cast<std::uint8_t>(LandUse::SecondaryRoad);
constexpr std::uint8_t kPrimary = static_cast<std::uint8_t>(LandUse::PrimaryRoad);
constexpr int kMaxFixRounds = 12;  // rounds of thinning and diagonal repair of secondary roads

/// Liang–Barsky clip of segment ab to the box; false when nothing is left.
bool clipSegment(Vec2& a, Vec2& b, double minX, double minY, double maxX, double maxY) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = b.x - a.x, dy = b.y - a.y;
  const std::array<double, 4> p{-dx, dx, -dy, dy};
  const std::array<double, 4> q{a.x - minX, maxX - a.x, a.y - minY, maxY - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  const Vec2 start = a + Vec2{dx, dy} * t0;
  const Vec2 end = a + Vec2{dx, dy} * t1;
  a = start;
  b = end;
  return true;
}

/// Cells of a polyline (pixel coordinates), clipped to a margin around the grid.
std::vector<Cell> polylineCells(const LineString& line, int width, int height) {
  std::vector<Cell> cells;
  const double margin = 2.0;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    Vec2 a = line[i], b = line[i + 1];
    if (!clipSegment(a, b, -margin, -margin, width + margin, height + margin)) continue;
    traverseCells(a, b, cells);
  }
  if (line.size() == 1) traverseCells(line[0], line[0], cells);
  return cells;
}

/// True when clearing (c, r) changes no topology of the road network (a "simple point" for 4-connected
/// roads and 8-connected background): its road 4-neighbours stay 4-connected through its
/// 8-neighbourhood, and the background there forms exactly one 8-connected piece, so the removal neither
/// splits a road nor opens a hole.
bool isSimple(const Grid<std::uint8_t>& g, int c, int r) {
  static const std::array<Cell, 8> ring{
      {{-1, -1}, {0, -1}, {1, -1}, {1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}}};
  std::array<bool, 8> fg{};
  for (int i = 0; i < 8; ++i) fg[i] = g.get(c + ring[i].first, r + ring[i].second, 0) != 0;
  // Components among ring cells of one kind; `diagonal` allows 8-adjacency.
  auto label = [&](bool foreground, bool diagonal, std::array<int, 8>& component) {
    component.fill(-1);
    int count = 0;
    for (int start = 0; start < 8; ++start) {
      if (fg[start] != foreground || component[start] >= 0) continue;
      std::vector<int> stack{start};
      component[start] = count;
      while (!stack.empty()) {
        const int k = stack.back();
        stack.pop_back();
        for (int j = 0; j < 8; ++j) {
          if (fg[j] != foreground || component[j] >= 0) continue;
          const int ddx = std::abs(ring[k].first - ring[j].first),
                    ddy = std::abs(ring[k].second - ring[j].second);
          if (ddx + ddy == 1 || (diagonal && ddx == 1 && ddy == 1)) {
            component[j] = count;
            stack.push_back(j);
          }
        }
      }
      ++count;
    }
    return count;
  };
  std::array<int, 8> component{};
  label(true, false, component);
  int seen = -1;
  for (int i : {1, 3, 5, 7}) {  // the 4-neighbours
    if (!fg[i]) continue;
    if (seen >= 0 && component[i] != seen) return false;
    seen = component[i];
  }
  if (seen < 0) return false;  // an isolated cell is a whole road, not a thickening
  std::array<int, 8> background{};
  return label(false, true, background) == 1;
}

/// Components of road cells (any class, 4-connected) and of the other cells (4-connected, as vectorize
/// A2 finds blocks) inside the window [c0, c1] x [r0, r1].
std::pair<int, int> windowComponents(const Grid<std::uint8_t>& g, int c0, int r0, int c1, int r1) {
  const int w = c1 - c0 + 1, h = r1 - r0 + 1;
  std::vector<int> label(static_cast<std::size_t>(w * h), -1);
  int roads = 0, land = 0;
  std::vector<int> stack;
  for (int start = 0; start < w * h; ++start) {
    if (label[start] >= 0) continue;
    const bool road = g.at(c0 + start % w, r0 + start / w) != 0;
    (road ? roads : land)++;
    label[start] = 1;
    stack.assign(1, start);
    while (!stack.empty()) {
      const int k = stack.back();
      stack.pop_back();
      const int x = k % w, y = k / w;
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int d = 0; d < 4; ++d) {
        if (nx[d] < 0 || ny[d] < 0 || nx[d] >= w || ny[d] >= h) continue;
        const int j = ny[d] * w + nx[d];
        if (label[j] < 0 && (g.at(c0 + nx[d], r0 + ny[d]) != 0) == road) {
          label[j] = 1;
          stack.push_back(j);
        }
      }
    }
  }
  return {roads, land};
}

/// Two secondary staircases crossing at a slant can overlap in a 2×2 window none of whose cells is
/// simple: clearing any one cuts an arm of the crossing off, and the diagonal repair then cuts a link
/// and joins the blocks around it (issue 20: 19 raw blocks for 32 faces on a street grid at 60
/// degrees). The crossing is redrawn instead with the fewest changes inside the 6×6 cells around the
/// window: one of its cells cleared, then (in this order) one other cell painted; one more road cell
/// cleared and one painted; one cleared and two painted; two cleared and two painted — the first
/// change (in cell order) after which the 8×8 cells around hold no 2×2 window of `kind` near a changed
/// cell and as many road and land components (4-connected) as before: no arm cut off, no block
/// joined, no pocket made. False (nothing changed) when there is none.
bool redrawCrossing(Grid<std::uint8_t>& g, int c, int r, std::uint8_t kind) {
  const int c0 = c - 3, r0 = r - 3, c1 = c + 4, r1 = r + 4;
  if (c0 < 0 || r0 < 0 || c1 >= g.width || r1 >= g.height) return false;
  const std::pair<int, int> before = windowComponents(g, c0, r0, c1, r1);
  std::vector<Cell> empty, road;
  for (int y = r - 2; y <= r + 3; ++y)
    for (int x = c - 2; x <= c + 3; ++x) (g.at(x, y) ? road : empty).emplace_back(x, y);
  auto noBlock = [&]() {
    for (int y = r0; y < r1; ++y)
      for (int x = c0; x < c1; ++x)
        if (g.at(x, y) == kind && g.at(x + 1, y) == kind && g.at(x, y + 1) == kind &&
            g.at(x + 1, y + 1) == kind)
          return false;
    return true;
  };
  auto holds = [&]() { return noBlock() && windowComponents(g, c0, r0, c1, r1) == before; };
  auto set = [&](const Cell& cell, std::uint8_t v) { g.at(cell.first, cell.second) = v; };
  const Cell none{-1, -1};
  for (int extraCuts = 0, fills = 1; fills <= 2; extraCuts == 1 ? (extraCuts = 0, ++fills) : ++extraCuts)
    for (const Cell& cut : {Cell{c, r}, Cell{c + 1, r}, Cell{c, r + 1}, Cell{c + 1, r + 1}}) {
      set(cut, 0);
      for (const Cell& cut2 : extraCuts ? road : std::vector<Cell>{none}) {
        if (cut2 == cut || (cut2 != none && g.at(cut2.first, cut2.second) != kind)) continue;
        if (cut2 != none) set(cut2, 0);
        for (std::size_t a = 0; a < empty.size(); ++a) {
          set(empty[a], kind);
          if (fills == 1 && holds()) return true;
          for (std::size_t b = a + 1; fills == 2 && b < empty.size(); ++b) {
            set(empty[b], kind);
            if (holds()) return true;
            set(empty[b], 0);
          }
          set(empty[a], 0);
        }
        if (cut2 != none) set(cut2, kind);
      }
      set(cut, kind);
    }
  return false;
}

/// Clears cells of value `kind` until no 2×2 window is all `kind`. Simple cells (see isSimple) are peeled
/// first, pass after pass, so thick areas thin from their border inwards; when no simple cell is left
/// in any such window, a crossing is redrawn (with `crossings`, see redrawCrossing) or else one cell is
/// cleared regardless (the width rule wins). Returns the cells cleared or moved.
std::size_t thinBlocks(Grid<std::uint8_t>& g, std::uint8_t kind, bool crossings = false) {
  auto allKind = [&](int c, int r) {
    return g.at(c, r) == kind && g.at(c + 1, r) == kind && g.at(c, r + 1) == kind &&
           g.at(c + 1, r + 1) == kind;
  };
  std::size_t removed = 0;
  for (;;) {
    bool changed = false;
    for (int r = 0; r + 1 < g.height; ++r) {
      for (int c = 0; c + 1 < g.width; ++c) {
        if (!allKind(c, r)) continue;
        for (const Cell& cell : {Cell{c, r}, Cell{c + 1, r}, Cell{c, r + 1}, Cell{c + 1, r + 1}}) {
          if (isSimple(g, cell.first, cell.second)) {
            g.at(cell.first, cell.second) = 0;
            ++removed;
            changed = true;
            break;
          }
        }
      }
    }
    if (changed) continue;
    bool forced = false;
    for (int r = 0; r + 1 < g.height && !forced; ++r)
      for (int c = 0; c + 1 < g.width && !forced; ++c)
        if (allKind(c, r)) {
          if (!crossings || !redrawCrossing(g, c, r, kind)) g.at(c, r) = 0;
          ++removed;
          forced = true;
        }
    if (!forced) return removed;
  }
}

/// Fills runs of at most `gap` empty corners lying between two set corners on a row or a column.
std::size_t closeGaps(Grid<std::uint8_t>& corners, int gap) {
  std::size_t added = 0;
  for (int axis = 0; axis < 2; ++axis) {
    const int outer = axis == 0 ? corners.height : corners.width;
    const int inner = axis == 0 ? corners.width : corners.height;
    auto at = [&](int o, int i) -> std::uint8_t& { return axis == 0 ? corners.at(i, o) : corners.at(o, i); };
    for (int o = 0; o < outer; ++o) {
      int last = -1;
      for (int i = 0; i < inner; ++i) {
        if (!at(o, i)) continue;
        if (last >= 0 && i - last > 1 && i - last - 1 <= gap) {
          for (int k = last + 1; k < i; ++k) at(o, k) = 2;  // 2 marks an added corner for this pass
          added += static_cast<std::size_t>(i - last - 1);
        }
        last = i;
      }
    }
  }
  for (auto& v : corners.cells) v = v ? 1 : 0;
  return added;
}

/// Where two road cells touch only diagonally, paints one of the two cells beside both as secondary
/// (the step becomes an L), preferring the one that makes no 2×2 all-secondary window. With
/// `safeOnly`, a link whose both fills would make such a window is cut instead: its secondary cell is
/// cleared (when both are primary, the link stays and is reported by checkRoadWidths).
std::size_t connectDiagonals(Grid<std::uint8_t>& g, bool safeOnly) {
  auto road = [&](int c, int r) { return g.get(c, r, 0) != 0; };
  auto makesBlock = [&](int c, int r) {
    for (int dr = -1; dr <= 0; ++dr)
      for (int dc = -1; dc <= 0; ++dc) {
        bool all = true;
        for (int y = 0; y < 2 && all; ++y)
          for (int x = 0; x < 2 && all; ++x) {
            const int cc = c + dc + x, rr = r + dr + y;
            all = (cc == c && rr == r) || g.get(cc, rr, 0) == kSecondary;
          }
        if (all) return true;
      }
    return false;
  };
  std::size_t changes = 0;
  for (int r = 0; r + 1 < g.height; ++r)
    for (int c = 0; c < g.width; ++c) {
      for (int dc : {-1, 1}) {
        if (!road(c, r) || !road(c + dc, r + 1) || road(c + dc, r) || road(c, r + 1)) continue;
        const Cell a{c + dc, r}, b{c, r + 1};
        const bool aBlocks = makesBlock(a.first, a.second), bBlocks = makesBlock(b.first, b.second);
        if (!safeOnly || !aBlocks || !bBlocks) {
          const Cell fill = aBlocks && !bBlocks ? b : a;
          g.at(fill.first, fill.second) = kSecondary;
        } else if (g.at(c + dc, r + 1) == kSecondary) {
          g.at(c + dc, r + 1) = 0;
        } else if (g.at(c, r) == kSecondary) {
          g.at(c, r) = 0;
        } else {
          continue;
        }
        ++changes;
      }
    }
  return changes;
}

/// Clears the secondary cell of every pair of road cells touching only diagonally (a pair of primary
/// cells is left: widening it would break the primary width rule).
std::size_t cutDiagonals(Grid<std::uint8_t>& g) {
  auto road = [&](int c, int r) { return g.get(c, r, 0) != 0; };
  std::size_t cleared = 0;
  for (int r = 0; r + 1 < g.height; ++r)
    for (int c = 0; c < g.width; ++c)
      for (int dc : {-1, 1}) {
        if (!road(c, r) || !road(c + dc, r + 1) || road(c + dc, r) || road(c, r + 1)) continue;
        if (g.at(c + dc, r + 1) == kSecondary)
          g.at(c + dc, r + 1) = 0;
        else if (g.at(c, r) == kSecondary)
          g.at(c, r) = 0;
        else
          continue;
        ++cleared;
      }
  return cleared;
}

void paintPrimary(const Grid<std::uint8_t>& corners, Grid<std::uint8_t>& primary) {
  std::fill(primary.cells.begin(), primary.cells.end(), 0);
  for (int j = 1; j + 1 < corners.height; ++j)
    for (int i = 1; i + 1 < corners.width; ++i)
      if (corners.at(i, j))
        for (int dr = -1; dr <= 0; ++dr)
          for (int dc = -1; dc <= 0; ++dc) primary.at(i + dc, j + dr) = 1;
}

/// The top-left cell of the first 3×3 all-primary window at or after row `fromRow`, or (-1, -1).
Cell findWideWindow(const Grid<std::uint8_t>& primary, int fromRow) {
  for (int r = std::max(0, fromRow); r + 2 < primary.height; ++r)
    for (int c = 0; c + 2 < primary.width; ++c) {
      bool all = true;
      for (int dr = 0; dr < 3 && all; ++dr)
        for (int dc = 0; dc < 3 && all; ++dc) all = primary.at(c + dc, r + dr) != 0;
      if (all) return {c, r};
    }
  return {-1, -1};
}

/// Removes path corners until no 3×3 window is all primary. A thinned corner path can still paint one
/// where two of its runs lie two corners apart (the skeleton of a merged dual carriageway, or a spur
/// beside a bend); the corner removed is, in this order of preference, an end of a run, then any
/// corner whose removal keeps the path's topology, then the window's first corner.
std::size_t trimWidePrimary(Grid<std::uint8_t>& corners, Grid<std::uint8_t>& primary) {
  std::size_t removed = 0;
  int fromRow = 0;
  for (;;) {
    const Cell window = findWideWindow(primary, fromRow);
    if (window.first < 0) return removed;
    fromRow = window.second - 3;  // a removal only changes cells near it
    struct Candidate {
      int rank, j, i;
    };
    std::vector<Candidate> candidates;
    for (int j = window.second; j <= window.second + 3; ++j)
      for (int i = window.first; i <= window.first + 3; ++i) {
        if (!corners.get(i, j, 0)) continue;
        int neighbours = 0;
        for (const Cell& d : {Cell{1, 0}, Cell{-1, 0}, Cell{0, 1}, Cell{0, -1}})
          neighbours += corners.get(i + d.first, j + d.second, 0) != 0;
        const int rank = neighbours == 1 ? 0 : isSimple(corners, i, j) ? 1 : 2;
        candidates.push_back({rank, j, i});
      }
    if (candidates.empty()) return removed;  // cannot happen: painted cells come from corners
    const Candidate best =
        *std::min_element(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
          return std::tie(x.rank, x.j, x.i) < std::tie(y.rank, y.j, y.i);
        });
    corners.at(best.i, best.j) = 0;
    ++removed;
    for (int r = best.j - 1; r <= best.j; ++r)
      for (int c = best.i - 1; c <= best.i; ++c) {
        if (!primary.inside(c, r)) continue;
        primary.at(c, r) =
            corners.at(c, r) || corners.at(c + 1, r) || corners.at(c, r + 1) || corners.at(c + 1, r + 1);
      }
  }
}

}  // namespace

void traverseCells(const Vec2& a, const Vec2& b, std::vector<Cell>& out) {
  int c = static_cast<int>(std::floor(a.x)), r = static_cast<int>(std::floor(a.y));
  const int endC = static_cast<int>(std::floor(b.x)), endR = static_cast<int>(std::floor(b.y));
  auto emit = [&](int cc, int rr) {
    if (out.empty() || out.back() != Cell{cc, rr}) out.emplace_back(cc, rr);
  };
  emit(c, r);
  const double dx = b.x - a.x, dy = b.y - a.y;
  const int stepX = dx > 0 ? 1 : -1, stepY = dy > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  const double tDeltaX = dx != 0.0 ? 1.0 / std::fabs(dx) : inf;
  const double tDeltaY = dy != 0.0 ? 1.0 / std::fabs(dy) : inf;
  double tMaxX = dx != 0.0 ? (stepX > 0 ? (c + 1 - a.x) : (a.x - c)) * tDeltaX : inf;
  double tMaxY = dy != 0.0 ? (stepY > 0 ? (r + 1 - a.y) : (a.y - r)) * tDeltaY : inf;
  int steps = std::abs(endC - c) + std::abs(endR - r);
  while (steps-- > 0) {
    // Stay on the segment's side of the target: never step past the end cell on an axis.
    const bool canX = c != endC, canY = r != endR;
    if (canX && (!canY || tMaxX < tMaxY)) {
      c += stepX;
      tMaxX += tDeltaX;
    } else {
      r += stepY;
      tMaxY += tDeltaY;
    }
    emit(c, r);
  }
}

RoadRaster rasterizeRoads(const std::vector<PixelRoad>& roads, int width, int height,
                          const RoadRasterOptions& options) {
  RoadRaster out;
  out.classes = Grid<std::uint8_t>(width, height, 0);
  out.rasterized.assign(roads.size(), false);

  // Primary: corner paths. Corner (i, j) sits at pixel point (i, j); corners on the grid's border are
  // dropped so that every painted 2×2 lies inside the grid.
  Grid<std::uint8_t> corners(width + 1, height + 1, 0);
  std::vector<std::vector<Cell>> roadCells(roads.size());
  for (size_t k = 0; k < roads.size(); ++k) {
    const PixelRoad& road = roads[k];
    if (road.roadClass == LandUse::PrimaryRoad) {
      LineString shifted;
      for (const Vec2& p : road.line) shifted.push_back(p + Vec2{0.5, 0.5});
      for (const Cell& corner : polylineCells(shifted, width + 1, height + 1)) {
        if (corner.first < 1 || corner.second < 1 || corner.first >= width || corner.second >= height)
          continue;
        corners.at(corner.first, corner.second) = 1;
        // The cells around the corner, to tell later whether the road survived.
        roadCells[k].emplace_back(corner.first, corner.second);
      }
    } else {
      for (const Cell& cell : polylineCells(road.line, width, height))
        if (out.classes.inside(cell.first, cell.second)) {
          out.classes.at(cell.first, cell.second) = kSecondary;
          roadCells[k].push_back(cell);
        }
    }
  }

  Grid<std::uint8_t> primary(width, height, 0);
  out.adjustments += closeGaps(corners, options.mergeGapCells);
  out.adjustments += thinBlocks(corners, 1);
  paintPrimary(corners, primary);
  out.adjustments += trimWidePrimary(corners, primary);

  for (size_t i = 0; i < primary.cells.size(); ++i)
    if (primary.cells[i]) out.classes.cells[i] = kPrimary;
  // Thinning and diagonal repair can feed each other in dense tangles; after a few rounds the last
  // rounds only make repairs that create no 2×2 window, so the width rule always holds.
  for (int round = 0; round < kMaxFixRounds; ++round) {
    out.adjustments += thinBlocks(out.classes, kSecondary, true);
    const std::size_t changes = connectDiagonals(out.classes, round >= kMaxFixRounds / 2);
    out.adjustments += changes;
    if (!changes) break;
  }
  // Last, links that still touch only diagonally are cut (their secondary cell cleared); clearing
  // cells cannot make a 2×2 window, and the count of secondary cells only falls, so this ends.
  out.adjustments += thinBlocks(out.classes, kSecondary, true);
  for (int round = 0; round < kMaxFixRounds * 4; ++round) {
    const std::size_t changes = cutDiagonals(out.classes);
    out.adjustments += changes;
    if (!changes) break;
  }

  for (size_t k = 0; k < roads.size(); ++k) {
    for (const Cell& cell : roadCells[k]) {
      const bool alive = roads[k].roadClass == LandUse::PrimaryRoad
                             ? corners.at(cell.first, cell.second) != 0 ||
                                   out.classes.at(cell.first - 1, cell.second - 1) == kPrimary
                             : out.classes.at(cell.first, cell.second) != 0;
      if (alive) {
        out.rasterized[k] = true;
        break;
      }
    }
  }
  return out;
}

RoadWidthReport checkRoadWidths(const Grid<std::uint8_t>& g) {
  RoadWidthReport report;
  auto is = [&](int c, int r, std::uint8_t v) { return g.get(c, r, 0) == v; };
  auto road = [&](int c, int r) { return isRoad(landUseFromCode(g.get(c, r, 0))); };
  auto allIn = [&](int c, int r, int n, std::uint8_t v) {
    for (int dr = 0; dr < n; ++dr)
      for (int dc = 0; dc < n; ++dc)
        if (!g.inside(c + dc, r + dr) || !is(c + dc, r + dr, v)) return false;
    return true;
  };
  for (int r = 0; r < g.height; ++r) {
    for (int c = 0; c < g.width; ++c) {
      if (allIn(c, r, 2, kSecondary)) ++report.secondaryBlocks2x2;
      if (allIn(c, r, 3, kPrimary)) ++report.primaryBlocks3x3;
      if (is(c, r, kPrimary) && !allIn(c - 1, r - 1, 2, kPrimary) && !allIn(c, r - 1, 2, kPrimary) &&
          !allIn(c - 1, r, 2, kPrimary) && !allIn(c, r, 2, kPrimary))
        ++report.primaryOutside2x2;
      if (!road(c, r)) continue;
      for (int dc : {-1, 1}) {  // each diagonal pair once: look down-left and down-right
        if (road(c + dc, r + 1) && !road(c + dc, r) && !road(c, r + 1)) ++report.diagonalOnlyLinks;
      }
    }
  }
  return report;
}

MultiLineString partsOnRoadCells(const LineString& line, const Grid<std::uint8_t>& classes, double reachCells,
                                 double stepCells) {
  const int reach = static_cast<int>(std::ceil(reachCells));
  auto onRoad = [&](const Vec2& p) {
    const int pc = static_cast<int>(std::floor(p.x)), pr = static_cast<int>(std::floor(p.y));
    for (int r = pr - reach; r <= pr + reach; ++r)
      for (int c = pc - reach; c <= pc + reach; ++c)
        if (classes.inside(c, r) && classes.at(c, r) != 0 &&
            distance(p, Vec2(c + 0.5, r + 0.5)) <= reachCells)
          return true;
    return false;
  };
  MultiLineString parts;
  LineString run;
  auto closeRun = [&] {
    if (run.size() >= 2) parts.push_back(std::move(run));
    run.clear();
  };
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Vec2 a = line[i], b = line[i + 1];
    const int steps = std::max(1, static_cast<int>(std::ceil(distance(a, b) / stepCells)));
    // The segment's start and its inner samples; the end is the next segment's start.
    for (int k = 0; k < steps; ++k) {
      const Vec2 p = a + (b - a) * (static_cast<double>(k) / steps);
      if (onRoad(p)) {
        run.push_back(p);
      } else {
        closeRun();
      }
    }
  }
  if (!line.empty() && onRoad(line.back())) run.push_back(line.back());
  closeRun();
  // Samples between a segment's ends are collinear: keep the original vertices and the run ends only.
  for (LineString& part : parts) {
    LineString kept{part.front()};
    for (std::size_t k = 1; k + 1 < part.size(); ++k) {
      const Vec2 u = part[k] - kept.back(), v = part[k + 1] - part[k];
      if (std::fabs(u.x * v.y - u.y * v.x) > 1e-12 * (length(u) * length(v) + 1e-300))
        kept.push_back(part[k]);
    }
    kept.push_back(part.back());
    part = std::move(kept);
  }
  return parts;
}

}  // namespace urbanvec::gridify
