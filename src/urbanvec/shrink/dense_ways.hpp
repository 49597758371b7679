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
