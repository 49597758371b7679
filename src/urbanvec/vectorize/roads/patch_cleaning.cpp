// Stage A3 (spec §3 A3), with the [INFERENCE] choices stated there: every visited patch is marked
// processed, and ties between equally short paths are broken by the neighbour order N, E, S, W.
#include "urbanvec/vectorize/roads/patch_cleaning.hpp"

#include <vector>

#include "urbanvec/core/landuse.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

PatchCleaningStats cleanIntersectionPatches(Grid<std::uint8_t>& cells, const Progress& progress,
                                            const PatchCleaningOptions& options) {
  const int w = cells.width, h = cells.height;
  const auto primary = static_cast<std::uint8_t>(LandUse::PrimaryRoad);
  const auto secondary = static_cast<std::uint8_t>(LandUse::SecondaryRoad);
  // Primary membership is taken from the input: A3 only ever changes secondary patches.
  auto isPrimary = [&](int c, int r) { return cells.inside(c, r) && cells.at(c, r) == primary; };
  auto touchesPrimary4 = [&](int c, int r) {
    return isPrimary(c, r - 1) || isPrimary(c + 1, r) || isPrimary(c, r + 1) || isPrimary(c - 1, r);
  };
  auto touchesPrimary8 = [&](int c, int r) {
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc)
        if ((dc || dr) && isPrimary(c + dc, r + dr)) return true;
    return false;
  };
  const int dcs[4] = {0, 1, 0, -1}, drs[4] = {-1, 0, 1, 0};  // N, E, S, W
  // Two or more runs of primary patches around the patch's 8-ring that hold one of its 4-neighbours:
  // those primary patches meet only through this patch.
  auto bridgesPrimaries = [&](int c, int r) {
    const int ringC[8] = {0, 1, 1, 1, 0, -1, -1, -1},
              ringR[8] = {-1, -1, 0, 1, 1, 1, 0, -1};  // N, NE, E, ...
    bool ring[8];
    for (int k = 0; k < 8; ++k) ring[k] = isPrimary(c + ringC[k], r + ringR[k]);
    int start = 0;
    while (start < 8 && ring[start]) ++start;
    if (start == 8) return false;  // surrounded by primary
    int runs = 0;
    bool inRun = false, runHasSide = false;
    for (int step = 1; step <= 8; ++step) {
      const int k = (start + step) % 8;
      if (ring[k]) {
        if (!inRun) inRun = true, runHasSide = false;
        runHasSide |= k % 2 == 0;
      } else if (inRun) {
        inRun = false;
        runs += runHasSide ? 1 : 0;
      }
    }
    return runs >= 2;
  };

  PatchCleaningStats stats;
  std::vector<char> processed(static_cast<size_t>(w) * h, 0);
  std::vector<std::int32_t> mark(static_cast<size_t>(w) * h, -1);  // search id that visited the patch
  std::vector<std::int32_t> parent(static_cast<size_t>(w) * h, -1);
  std::vector<int> visited, disconnected, queue;
  ProgressTicker ticker(progress, "patch cleaning", static_cast<size_t>(h));
  for (int r = 0; r < h; ++r, ticker.tick()) {
    for (int c = 0; c < w; ++c) {
      const int s = r * w + c;
      if (cells.cells[s] != secondary || processed[s] || !touchesPrimary4(c, r)) continue;
      const int search = static_cast<int>(stats.searches++);
      // BFS over 4-connected secondary patches; primary-disconnected patches are recorded, not expanded.
      visited.assign(1, s);
      disconnected.clear();
      mark[s] = search;
      for (size_t k = 0; k < visited.size(); ++k) {
        const int i = visited[k];
        const int ic = i % w, ir = i / w;
        if (!touchesPrimary8(ic, ir)) {
          disconnected.push_back(i);
          continue;
        }
        for (int d = 0; d < 4; ++d) {
          const int nc = ic + dcs[d], nr = ir + drs[d];
          if (!cells.inside(nc, nr)) continue;
          const int j = nr * w + nc;
          if (cells.cells[j] != secondary || mark[j] == search) continue;
          mark[j] = search;
          visited.push_back(j);
        }
      }
      for (int i : visited) processed[i] = 1;
      if (!disconnected.empty()) {
        // Multi-source BFS from the visited patches that touch primary (4-connected), inside the
        // visited set; each disconnected patch then follows its parents to the closest such patch.
        queue.clear();
        for (int i : visited) {
          parent[i] = -2;
          if (touchesPrimary4(i % w, i / w)) {
            parent[i] = i;
            queue.push_back(i);
          }
        }
        for (size_t k = 0; k < queue.size(); ++k) {
          const int i = queue[k];
          const int ic = i % w, ir = i / w;
          if (!touchesPrimary8(ic, ir)) continue;
          for (int d = 0; d < 4; ++d) {
            const int nc = ic + dcs[d], nr = ir + drs[d];
            if (!cells.inside(nc, nr)) continue;
            const int j = nr * w + nc;
            if (mark[j] != search || parent[j] != -2) continue;
            parent[j] = i;
            queue.push_back(j);
          }
        }
        // parent == -3 marks a kept patch.
        for (int d : disconnected) {
          int i = d;
          while (i >= 0 && parent[i] != -3) {
            const int p = parent[i];
            parent[i] = -3;
            if (p == i || p < 0) break;
            i = p;
          }
        }
      }
      for (int i : visited) {
        if (!disconnected.empty() && parent[i] == -3) continue;
        if (options.keepPrimaryBridges && bridgesPrimaries(i % w, i / w)) {
          ++stats.bridgesKept;
          continue;
        }
        cells.cells[i] = kRemovedRoad;
        ++stats.removedPatches;
      }
    }
  }
  ticker.finish();
  return stats;
}

}  // namespace urbanvec::vectorize
