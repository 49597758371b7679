// Step 4 of the Wijgerse (2007) boundary generator: the 8-direction contour follower that turns the
// thresholded bitmap into a closed chain of pixel positions (spec wijgerse-boundary.md §5, thesis §3.4
// and §5.2.4).
#pragma once

#include <cstdint>
#include <vector>

#include "urbanvec/core/grid.hpp"

namespace urbanvec::boundary {

struct Pixel {
  int x = 0;  ///< column
  int y = 0;  ///< row, growing downwards
  bool operator==(const Pixel& o) const { return x == o.x && y == o.y; }
  bool operator!=(const Pixel& o) const { return !(*this == o); }
};

struct ContourTraceOptions {
  /// Rows on the left edge from which a trace starts; the longest trace is kept (thesis: 16).
  int startRows = 16;
};

/// Traces the outer boundary of the filled region containing `start`, which must be filled and have
/// an empty west neighbour. The chain lists each boundary step (a pixel may appear twice where the
/// region is one pixel wide) and does not repeat the start at the end; consecutive pixels are
/// 8-neighbours and the last is an 8-neighbour of the first.
std::vector<Pixel> traceContour(const Grid<std::uint8_t>& mask, Pixel start);

/// Starts a trace at the first filled pixel of each of `startRows` equally spaced rows
/// (y_i = floor((i + 0.5) H / rows)) and returns the trace with the most positions; empty when none
/// of those rows holds a filled pixel.
std::vector<Pixel> traceLongestContour(const Grid<std::uint8_t>& mask, const ContourTraceOptions& options);

}  // namespace urbanvec::boundary
