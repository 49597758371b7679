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

/// The street ways drawn on the image, for the crossing guard of carveSeams: points in pixel units
/// (`col`, `row` the pixel, `fx`, `fy` in [0, 1] the place inside it, as PointMapper computes them) and
/// the ways as point lists.
struct SeamWays {
  std::vector<int> col, row;
  std::vector<double> fx, fy;
  std::vector<std::vector<int>> ways;
  /// Landmark places: the points of each (their centroid is the place's position): no seam may flip the
  /// left-right or above-below order of two places' centroids (issue 19 "arrangement").
  std::vector<std::vector<int>> places;
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
  /// When blocked with no frozen line: true when a path would exist without the crossing guard's pixels.
  bool verticalBlockedByGuard = false;
  bool horizontalBlockedByGuard = false;
  /// Crossing guard: pixels given +infinity because the seam through them would have made two way
  /// segments cross or touch, and the seams that had to be searched again because of that.
  size_t crossingFrozen = 0;
  /// Pixels given +infinity because the seam through them would have flipped two landmark places.
  size_t orderFrozen = 0;
  size_t seamRetries = 0;
  /// Cumulative-energy cells recomputed, over all seam searches (the O(pixels) per seam bound).
  size_t cellsUpdated = 0;
};

/// Removes up to `vertical` vertical and `horizontal` horizontal minimal-energy 8-connected seams
/// (dynamic programming, O(pixels) per seam; +infinity pixels are never crossed), in `order`. The
/// energy is not recomputed: it is carried with the pixels (§B.10 [INFERENCE]). Deterministic ties:
/// the lowest column of the last row; backtracking prefers straight down, then left, then right.
/// The cumulative energy is updated after each seam only where it changed (the cone below the removed
/// seam, where the values differ), which gives the same values as a full recomputation.
///
/// `ways` (optional): the crossing guard. Each seam found is first applied to the ways' points (a
/// point moves with its pixel; a point of a removed pixel goes to the edge of the neighbour it collapses
/// onto); when a segment of a way would then cross or touch a segment it did not touch before (another
/// way's or its own), the seam's pixels on the lines of those segments' points get +infinity and the
/// seam is searched again. So no seam ever makes two ways cross, and only the pixels where a crossing
/// would really arise are frozen. Likewise when the seam would flip the order (along its axis) of two
/// landmark places' centroids relative to the original: the seam's pixels on the lines of the points of
/// the place it moves get +infinity.
///
/// `threads` (0 = every core) move the rows of large images in bands; the result does not depend on it.
CarveResult carveSeams(const std::vector<float>& energy, int width, int height, int vertical, int horizontal,
                       SeamOrder order, const Progress& progress = {}, const SeamWays* ways = nullptr,
                       int threads = 1);

}  // namespace urbanvec::shrink
