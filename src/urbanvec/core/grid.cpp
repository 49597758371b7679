#include "urbanvec/core/grid.hpp"

#include <cmath>

#include "urbanvec/core/error.hpp"

namespace urbanvec {

Vec2 GeoTransform::worldToPixel(const Vec2& world) const {
  const double det = c[1] * c[5] - c[2] * c[4];
  if (det == 0.0) throw invalidInput("the raster's geotransform is singular (zero cell size)");
  const double dx = world.x - c[0];
  const double dy = world.y - c[3];
  return {(c[5] * dx - c[2] * dy) / det, (-c[4] * dx + c[1] * dy) / det};
}

double GeoTransform::cellSize() const { return std::sqrt(std::fabs(c[1] * c[5] - c[2] * c[4])); }

}  // namespace urbanvec
