// Step 8SC of the shrinking pipeline (spec §B.10): seam carving of the skeleton image with frozen
// pixels (+infinity energy) and an index matrix kept aligned with the image, so every surviving pixel
// knows its original position (§B.9 items 3-5 reduce to that lookup).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "urbanvec/core/progress.hpp"
#include "urbanvec/shrink/shrink_options.hpp"

namespace urbanvec::shrink {

/// How a removed pixel collapsed onto a neighbour that survived its seam.
enum class MergeSide : std::int8_t { None, OntoLeft, OntoRight, OntoAbove, OntoBelow };

struct CarvedSeam {
  bool vertical = true;     ///< true: one pixel per row (removes a column)
  std::vector<int> pixels;  ///< original pixel indices (row-major), one per row or per column
};

struct CarveResult {
  int width = 0;  ///< final size
  int height = 0;
  int verticalRemoved = 0;
  int horizontalRemoved = 0;
  std::vector<int> finalRow;  ///< per original pixel; -1 when removed
  std::vector<int> finalCol;
  std::vector<int> mergedInto;  ///< per removed pixel: the original pixel it collapsed onto, else -1
  std::vector<MergeSide> mergeSide;
  std::vector<CarvedSeam> seams;  ///< in removal order
  /// When a direction could not be carved to the end: an original pixel of a line (row for vertical
  /// seams, column for horizontal ones) frozen from edge to edge, or -1 when frozen pixels block every
  /// path without filling a line; -2 when the direction was not blocked.
  int verticalBlockedAt = -2;
  int horizontalBlockedAt = -2;
  /// Pixels given +infinity to keep distinct ways apart (with wayLabels), initially and after seams.
  size_t separationFrozen = 0;
};

/// Removes up to `vertical` vertical and `horizontal` horizontal minimal-energy 8-connected seams
/// (dynamic programming, O(pixels) per seam; +infinity pixels are never crossed), in `order`. The
/// energy is not recomputed: it is carried with the pixels (§B.10 [INFERENCE]). Deterministic ties:
/// the lowest column of the last row; backtracking prefers straight down, then left, then right.
///
/// `wayLabels` (optional, per original pixel): the piece of street way drawn in the pixel, -1 for none,
/// -2 for several (see wayLabels in dense_ways.hpp; `pieceWay` gives each piece's way: consecutive
/// pieces of one way count as the same way). Pixels holding several ways, or 8-adjacent to a pixel of another
/// way, get +infinity, and so do the pixels that become such after a seam (a removed pixel's ways move onto
/// the neighbour it collapses onto; pixels on both sides of the seam become neighbours): a seam never moves
/// one way and not another within a pixel of it, nor collapses two ways onto one pixel edge.
CarveResult carveSeams(const std::vector<float>& energy, int width, int height, int vertical, int horizontal,
                       SeamOrder order, const Progress& progress = {},
                       const std::vector<int>* wayLabels = nullptr,
                       const std::vector<int>* pieceWay = nullptr);

}  // namespace urbanvec::shrink
