// Stage D6 steps 1-3 by the thesis method (spec §3 D6 "How"; Zhang & Suen 1984): rasterize the block's
// axis-aligned bounding box at 8 pixels per cell, thin with Zhang-Suen, re-vectorize the pixels.
#pragma once

#include <cstdint>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/vectorize/parcels/spines.hpp"

namespace urbanvec::vectorize::parcels {

/// A binary image; pixel (i, j) has its centre at origin + ((i + 0.5), (j + 0.5)) * pixelSize, j up.
struct BinaryImage {
  int width = 0;
  int height = 0;
  Vec2 origin;
  double pixelSize = 1.0;
  std::vector<std::uint8_t> pixels;  ///< 1 = foreground (inside the block), row-major from j = 0
  bool at(int i, int j) const {
    return i >= 0 && j >= 0 && i < width && j < height && pixels[static_cast<size_t>(j) * width + i] != 0;
  }
  Vec2 centre(int i, int j) const { return origin + Vec2(i + 0.5, j + 0.5) * pixelSize; }
};

/// Pixels whose centre lies inside the polygon (even-odd over all rings) are foreground; the image
/// covers the bounding box plus `padding` background pixels on every side.
BinaryImage rasterizePolygon(const Polygon& polygon, int pixelsPerCell, int padding = 1);

/// Standard two-sub-iteration Zhang-Suen thinning (spec Q15: "constrained" is undefined); only
/// foreground pixels are removed. Runs in time proportional to the removed pixels' neighbourhoods.
void zhangSuenThin(BinaryImage& image);

/// Re-vectorization (spec D6 step 3): an edge between every pair of 4-connected foreground pixels,
/// then 8-connected edges at pixels with at most one edge; components still apart are joined by
/// their diagonal contacts. Vertices are pixel centres, in the image's frame.
SpineGraph pixelSpineGraph(const BinaryImage& image);

/// Steps 1-3 for a polygon.
SpineGraph zhangSuenSpineGraph(const Polygon& polygon, int pixelsPerCell);

}  // namespace urbanvec::vectorize::parcels
