// Raster grids as plain data (CONVENTIONS.md "Gridded input"): a georeferenced frame plus cells.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec {

/// GDAL-style affine geotransform: world = (c0 + col*c1 + row*c2, c3 + col*c4 + row*c5), where
/// (col, row) are pixel coordinates with (0, 0) at the top-left corner of the first cell.
struct GeoTransform {
  std::array<double, 6> c{0.0, 1.0, 0.0, 0.0, 0.0, -1.0};

  Vec2 pixelToWorld(double col, double row) const {
    return {c[0] + col * c[1] + row * c[2], c[3] + col * c[4] + row * c[5]};
  }
  /// Inverse of pixelToWorld; throws urbanvec::Error when the transform is singular.
  Vec2 worldToPixel(const Vec2& world) const;
  /// Edge length of a cell in world units (square root of the cell's area).
  double cellSize() const;
  bool isNorthUp() const { return c[2] == 0.0 && c[4] == 0.0 && c[5] < 0.0; }
  bool operator==(const GeoTransform& o) const { return c == o.c; }
};

/// The frame shared by all rasters of one grid.
struct GridSpec {
  int width = 0;
  int height = 0;
  GeoTransform transform;
  std::string crsWkt;  ///< empty when the raster has no CRS
  /// A window of a larger raster (urbanvec vectorize -srcwin, issue 22): its first cell's column and
  /// row in the whole raster, and the whole raster's height; frameHeight 0 = not a window. A window's
  /// `transform` is then the whole raster's, and the vectorizer's internal frame (x = col,
  /// y = height - row) is the whole raster's: x = frameDx() + col, y = frameDy() + height - row, so
  /// every floating-point operation on a feature is the same in any window that holds it.
  int frameCol = 0;
  int frameRow = 0;
  int frameHeight = 0;
  int frameDx() const { return frameHeight > 0 ? frameCol : 0; }
  int frameDy() const { return frameHeight > 0 ? frameHeight - frameRow - height : 0; }

  size_t cellCount() const { return static_cast<size_t>(width) * static_cast<size_t>(height); }
  /// World coordinates of a cell's centre.
  Vec2 cellCentre(int col, int row) const { return transform.pixelToWorld(col + 0.5, row + 0.5); }
};

/// A row-major 2-D array of cells.
template <class T>
struct Grid {
  int width = 0;
  int height = 0;
  std::vector<T> cells;
  /// GridSpec::frameDx() / frameDy() of the raster this grid holds (0 unless a window of a larger
  /// raster): the internal-frame offset of its cells.
  int frameDx = 0;
  int frameDy = 0;

  Grid() = default;
  Grid(int w, int h, T fill = T{})
      : width(w), height(h), cells(static_cast<size_t>(w) * static_cast<size_t>(h), fill) {}

  bool inside(int col, int row) const { return col >= 0 && row >= 0 && col < width && row < height; }
  T& at(int col, int row) { return cells[static_cast<size_t>(row) * width + col]; }
  const T& at(int col, int row) const { return cells[static_cast<size_t>(row) * width + col]; }
  /// The cell's value, or `outside` when (col, row) is off the grid.
  T get(int col, int row, T outside) const { return inside(col, row) ? at(col, row) : outside; }
  size_t size() const { return cells.size(); }
};

}  // namespace urbanvec
