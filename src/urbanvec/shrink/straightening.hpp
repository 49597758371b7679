// The stretching post-process of the shrinking pipeline (spec §B.11, Fig. 44): ways that were straight
// in the original city and are sinuous after carving are straightened; curved ways are left alone.
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec::shrink {

/// `ways`: node lists; `before`: original positions; `after`: positions after carving (updated in
/// place; non-finite = dropped node, ignored). A way is straight when every original interior node lies
/// within `tolerance` of its chord ([INFERENCE]: the thesis gives no test). Each round, every interior
/// node of a straight way is given the point of the new chord at its original parametric position;
/// nodes of several straight ways take the mean; `pinned` nodes never move. Returns the number of
/// straight ways.
int straightenWays(const std::vector<std::vector<int>>& ways, const std::vector<Vec2>& before,
                   std::vector<Vec2>& after, const std::vector<char>& pinned, double tolerance, int rounds);

}  // namespace urbanvec::shrink
