// Part of step8Pos of the shrinking pipeline (spec §B.11, "back to vector" by node translation): the
// thesis translates only the ways' nodes, so the straight segment between two distant nodes does not
// follow the carved raster and nearby ways fold over each other (new crossings). Here every skeleton way
// is first densified so consecutive points are at most `spacing` pixels apart (synthetic points, carried
// like real nodes: each moves with its own pixel), and after carving the synthetic points (and the real
// nodes whose pixel a seam removed, which §B.11 deletes) are dropped again only where the shortcut
// crosses or touches no other segment: dropping a point never creates a crossing.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec::shrink {

/// Densifies `ways` (node lists into `pos`) so consecutive points are at most `maxStep` apart: inserts
/// synthetic points, appended to `pos` and to `shadow` (the same point interpolated between the
/// original positions of the segment's ends; `shadow` must be as long as `pos`). Returns the dense lists.
std::vector<std::vector<int>> densifyWays(const std::vector<std::vector<int>>& ways, double maxStep,
                                          std::vector<Vec2>& pos, std::vector<Vec2>& shadow);

/// Pieces of the ways drawn in each pixel, for carveSeams's way separation: each way is cut into
/// pieces of `piece` pixels along it, numbered consecutively (`pieceWay` gives each piece's way), so a
/// way that comes back near itself (a hairpin) is kept apart from itself too. Per pixel (row-major,
/// `width` x `height`, pixel of a point given by `pixelOf`): a piece, -1 for none, -2 for pieces that are
/// not neighbours on one way. `ways` are point lists into `pos`; segments are sampled every third of a
/// pixel.
template <class PixelOf>
std::vector<int> wayLabels(const std::vector<std::vector<int>>& ways, const std::vector<Vec2>& pos, int width,
                           int height, double cell, double piece, std::vector<int>& pieceWay,
                           PixelOf&& pixelOf) {
  std::vector<int> label(static_cast<size_t>(width) * static_cast<size_t>(height), -1);
  pieceWay.clear();
  for (size_t w = 0; w < ways.size(); ++w) {
    double along = 0.0;
    const int first = static_cast<int>(pieceWay.size());
    pieceWay.push_back(static_cast<int>(w));
    auto mark = [&](const Vec2& p) {
      const int id = first + static_cast<int>(along / (piece * cell));
      while (static_cast<int>(pieceWay.size()) <= id) pieceWay.push_back(static_cast<int>(w));
      int& l = label[static_cast<size_t>(pixelOf(p))];
      if (l == -1)
        l = id;
      else if (l != -2 && !(pieceWay[static_cast<size_t>(l)] == static_cast<int>(w) && std::abs(l - id) <= 1))
        l = -2;
    };
    const auto& way = ways[w];
    for (size_t i = 0; i < way.size(); ++i) {
      const Vec2 b = pos[static_cast<size_t>(way[i])];
      if (i == 0) {
        mark(b);
        continue;
      }
      const Vec2 a = pos[static_cast<size_t>(way[i - 1])];
      const double len = distance(a, b);
      const int k = std::max(1, static_cast<int>(std::ceil(3.0 * len / cell)));
      for (int t = 1; t <= k; ++t) {
        along += len / k;
        mark(a + (b - a) * (static_cast<double>(t) / k));
      }
    }
  }
  return label;
}

struct SimplifyStats {
  int removed = 0;     ///< removable points dropped
  int kept = 0;        ///< removable points kept because dropping them would cross or touch a segment
  int keptCarved = 0;  ///< of `kept`: real nodes whose pixel a seam removed
};

/// Drops removable points (`removable[n]`) of the dense `ways` (positions `pos`, all finite) where the
/// shortcut deviates at most `tolerance` from every point it replaces and intersects (crossing, touching
/// or overlapping) no segment of any way other than at a shared point, and the pocket between the
/// shortcut and the points it replaces holds no point of another segment (no way changes sides); greedy along
/// each way, in way order, each accepted shortcut replacing its segments in the index at once. `carved[n]`
/// marks real nodes for the stats.
std::vector<std::vector<int>> simplifyWithoutCrossings(const std::vector<std::vector<int>>& ways,
                                                       const std::vector<Vec2>& pos,
                                                       const std::vector<char>& removable,
                                                       const std::vector<char>& carved, double tolerance,
                                                       SimplifyStats* stats = nullptr);

/// Crossing-safe post-move (for §B.11 straightening): `from` are crossing-free positions, `to` the
/// same points moved (non-finite = dropped). A way with a moved segment that intersects a segment of
/// another way (other than at a shared point or along a shared segment), or whose sweep from its `from`
/// to its `to` position passes over another way's point (that way would change sides), gets all its
/// points back to `from`; repeated until no way is refused. Returns the number of ways refused.
int revertCrossingMoves(const std::vector<std::vector<int>>& ways, const std::vector<Vec2>& from,
                        std::vector<Vec2>& to);

}  // namespace urbanvec::shrink
