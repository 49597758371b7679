// 8-direction contour follower, spec wijgerse-boundary.md §5.1-§5.4 (thesis §3.4, Fig. 3.5, §5.2.4).
#include "urbanvec/boundary/contour_trace.hpp"

#include <array>

#include "urbanvec/core/error.hpp"

namespace urbanvec::boundary {

namespace {

// Directions indexed clockwise on screen (y down): N, NE, E, SE, S, SW, W, NW.
constexpr std::array<int, 8> kDx{0, 1, 1, 1, 0, -1, -1, -1};
constexpr std::array<int, 8> kDy{-1, -1, 0, 1, 1, 1, 0, -1};
constexpr int kSouth = 4;

}  // namespace

std::vector<Pixel> traceContour(const Grid<std::uint8_t>& mask, Pixel start) {
  if (!mask.get(start.x, start.y, 0) || mask.get(start.x - 1, start.y, 0))
    throw internalError("a contour trace must start on a filled pixel with an empty west neighbour");
  std::vector<Pixel> chain{start};
  // The thesis starts with "last direction = south-west", whose first candidate (NW) may be filled and
  // then sends the trace the wrong way round, closing after two pixels (spec §5.4 caveat). Starting
  // with "south" makes the first candidate the west neighbour, known to be empty, so the trace always
  // runs round the outer boundary.
  int last = kSouth;
  Pixel current = start;
  // Stop criterion of the thesis (back at the start) plus Jacob's refinement: stop only when the start
  // is re-entered in the direction of the first move, so a start pixel on a one-pixel bridge does not
  // end the trace after one lobe (spec §5.4 caveat).
  int firstMove = -1;
  const size_t limit = 4 * mask.size() + 8;
  while (true) {
    // First candidate: two directions (90 degrees) clockwise from the last move, then sweep
    // counter-clockwise (the thesis's worked example, spec §5.4 resolution).
    const int first = (last + 2) % 8;
    int move = -1;
    for (int k = 0; k < 8; ++k) {
      const int d = (first - k + 8) % 8;
      if (mask.get(current.x + kDx[d], current.y + kDy[d], 0)) {
        move = d;
        break;
      }
    }
    if (move < 0) return chain;  // an isolated pixel
    if (current == start) {
      if (firstMove < 0)
        firstMove = move;
      else if (move == firstMove)
        break;
      else
        chain.push_back(start);  // passing through the start pixel again, towards another lobe
    }
    current = {current.x + kDx[move], current.y + kDy[move]};
    last = move;
    if (current != start) chain.push_back(current);
    if (chain.size() > limit) throw internalError("the contour trace did not close");
  }
  return chain;
}

std::vector<Pixel> traceLongestContour(const Grid<std::uint8_t>& mask, const ContourTraceOptions& options) {
  std::vector<Pixel> best;
  const int rows = options.startRows;
  for (int i = 0; i < rows; ++i) {
    const int y = static_cast<int>((i + 0.5) * mask.height / rows);
    int x = 0;
    while (x < mask.width && !mask.at(x, y)) ++x;
    if (x == mask.width) continue;
    std::vector<Pixel> chain = traceContour(mask, {x, y});
    if (chain.size() > best.size()) best = std::move(chain);
  }
  return best;
}

}  // namespace urbanvec::boundary
