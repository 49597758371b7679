// Step 7 of the shrinking pipeline (spec §B.8): the skeleton city as an image. The thesis renders it
// with Osmarender (important places black, streets grey by importance, empty area white); here it is
// rasterised directly, already inverted (§B.9 item 1): ink 255 for places, 255 * impW for streets,
// 0 for empty area. The frozen pixels of §B.9 item 6 are marked in the same pass.
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/shrink/shrink_options.hpp"

namespace urbanvec::shrink {

/// Square pixels of side `cell` metres; row 0 is the northern edge (y decreases with the row).
struct RasterFrame {
  double x0 = 0.0;    ///< western edge
  double yTop = 0.0;  ///< northern edge
  double cell = 1.0;
  int width = 1;
  int height = 1;
  int col(double x) const;
  int row(double y) const;
  Vec2 centre(int row, int col) const { return {x0 + (col + 0.5) * cell, yTop - (row + 0.5) * cell}; }
};

/// The frame of a bounding box with `imageSize` pixels along its longer side (§B.8); at least 1x1.
RasterFrame frameFor(double minX, double minY, double maxX, double maxY, int imageSize);

struct InkLine {
  std::vector<Vec2> points;
  float ink = 255.0f;
};

/// Pixel owners for frozen pixels: a place index >= 0, or one of these.
constexpr int kNotFrozen = -1;
constexpr int kFrozenStreetNode = -2;

struct SkeletonRaster {
  RasterFrame frame;
  std::vector<float> ink;        ///< inverted grey, [0, 255], row-major
  std::vector<int> freezeOwner;  ///< kNotFrozen, kFrozenStreetNode or the place index, row-major
};

/// Landmark elements to draw (ink 255) and freeze: polygons are filled, lines and points drawn.
struct LandmarkShape {
  std::vector<Vec2> points;
  int place = 0;
};

SkeletonRaster rasteriseSkeleton(const RasterFrame& frame, const std::vector<InkLine>& streets,
                                 const std::vector<LandmarkShape>& landmarks,
                                 const std::vector<Vec2>& frozenStreetNodes, LandmarkFreeze freeze);

}  // namespace urbanvec::shrink
