// Suburbs: the islands the thesis discards, kept when large enough (spec wijgerse-boundary.md §5.3 and
// §12 item 3, thesis §3.4 and §7.3 future work).
#pragma once

#include <cstdint>
#include <vector>

#include "urbanvec/boundary/contour_trace.hpp"
#include "urbanvec/core/grid.hpp"

namespace urbanvec::boundary {

/// Traces the outer boundary of every 8-connected region of `mask` of at least `minimumPixels` pixels
/// that is neither the region of `mainChain` nor lies inside the outline of `mainChain` or of a larger
/// island already kept. Islands come largest first (ties by position, so the order is deterministic).
std::vector<std::vector<Pixel>> traceIslands(const Grid<std::uint8_t>& mask,
                                             const std::vector<Pixel>& mainChain, double minimumPixels);

/// True when the pixel centre of `p` lies inside the polygon through the centres of `chain`.
bool insideChain(const std::vector<Pixel>& chain, Pixel p);

}  // namespace urbanvec::boundary
