// Stage A2 (spec §3 A2): the [INFERENCE] two-pass algorithm given there.
#include "urbanvec/vectorize/blocks/raw_blocks.hpp"

#include <algorithm>

#include "urbanvec/core/error.hpp"

namespace urbanvec::vectorize {

namespace {

/// 4-connected flood fill from `seed` over cells accepted by `eligible`, labelling them `label`.
template <class Eligible>
void floodFill(int seed, std::int32_t label, int width, int height, Grid<std::int32_t>& labels,
               std::vector<std::int32_t>& stack, std::vector<std::int32_t>* members, Eligible eligible) {
  stack.clear();
  stack.push_back(seed);
  labels.cells[seed] = label;
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    if (members) members->push_back(i);
    const int c = i % width, r = i / width;
    const int nb[4][2] = {{c, r - 1}, {c + 1, r}, {c, r + 1}, {c - 1, r}};
    for (const auto& n : nb) {
      if (n[0] < 0 || n[1] < 0 || n[0] >= width || n[1] >= height) continue;
      const int j = n[1] * width + n[0];
      if (labels.cells[j] != -1 || !eligible(j)) continue;
      labels.cells[j] = label;
      stack.push_back(j);
    }
  }
}

}  // namespace

RawBlocks buildRawBlocks(const Grid<std::uint8_t>& cells, const RawBlockOptions& options,
                         const Progress& progress) {
  const int w = cells.width, h = cells.height;
  if (options.openRegions && (options.openRegions->width != w || options.openRegions->height != h))
    throw invalidInput("the open-regions grid does not have the size of the land-use grid");
  auto code = [&](int i) { return static_cast<LandUse>(cells.cells[i]); };
  auto isRoadLike = [&](int i) { return isRoadCode(cells.cells[i]); };

  // Region pass over non-road patches.
  Grid<std::int32_t> region(w, h, -1);
  std::vector<char> enclosed;
  std::vector<std::int32_t> stack, members;
  for (int i = 0; i < w * h; ++i) {
    if (region.cells[i] != -1 || isRoadLike(i)) continue;
    members.clear();
    floodFill(i, static_cast<std::int32_t>(enclosed.size()), w, h, region, stack, &members,
              [&](int j) { return !isRoadLike(j); });
    bool touchesBorder = false;
    if (options.openRegions) {  // the whole grid's answer for a window (issue 22)
      for (int m : members) touchesBorder = touchesBorder || options.openRegions->cells[m] != 0;
    } else {
      for (int m : members) {
        const int c = m % w, r = m / w;
        if (c == 0 || r == 0 || c == w - 1 || r == h - 1) touchesBorder = true;
      }
    }
    enclosed.push_back(!touchesBorder);
  }
  reportProgress(progress, 0.4, "raw blocks");

  auto eligible = [&](int i) {
    if (isRoadLike(i) || cells.cells[i] == kRemovedRoad) return false;
    const LandUse u = code(i);
    if (u == LandUse::Water) return false;
    if (options.excludeReserved && u == LandUse::Reserved) return false;
    if (u == LandUse::Unused && !enclosed[region.cells[i]]) return false;
    return true;
  };

  RawBlocks out;
  out.blockOf = Grid<std::int32_t>(w, h, -1);
  for (int i = 0; i < w * h; ++i) {
    if (out.blockOf.cells[i] != -1 || !eligible(i)) continue;
    SimBlock b;
    b.id = static_cast<int>(out.blocks.size());
    b.internal = enclosed[region.cells[i]];
    floodFill(i, b.id, w, h, out.blockOf, stack, &b.patches, eligible);
    std::sort(b.patches.begin(), b.patches.end());
    Vec2 sum;
    for (int m : b.patches) {
      const int c = m % w, r = m / w;
      const LandUse u = code(m);
      b.developedArea += isDeveloped(u);
      b.undevelopedArea += u == LandUse::Unused;
      sum += patchCentre(cells, c, r);
      const int nb[4][2] = {{c, r - 1}, {c + 1, r}, {c, r + 1}, {c - 1, r}};
      for (const auto& n : nb)
        if (cells.inside(n[0], n[1]) && cells.at(n[0], n[1]) == static_cast<std::uint8_t>(LandUse::Water))
          b.touchesWater = true;
    }
    b.area = static_cast<double>(b.patches.size());
    b.center = sum / b.area;
    out.blocks.push_back(std::move(b));
  }
  reportProgress(progress, 1.0, "raw blocks");
  return out;
}

}  // namespace urbanvec::vectorize
