// Polygon rasterization by cell centre (issue 2 §2).
#include "urbanvec/gridify/polygon_raster.hpp"

#include <algorithm>
#include <cmath>

namespace urbanvec::gridify {

void cellsInside(const Polygon& polygon, int width, int height, std::vector<Cell>& out) {
  if (polygon.outer.size() < 3) return;
  double minY = polygon.outer[0].y, maxY = minY;
  for (const Vec2& p : polygon.outer) {
    minY = std::min(minY, p.y);
    maxY = std::max(maxY, p.y);
  }
  const int firstRow = std::max(0, static_cast<int>(std::floor(minY - 0.5)));
  const int lastRow = std::min(height - 1, static_cast<int>(std::ceil(maxY - 0.5)));
  std::vector<double> crossings;
  auto addRing = [&](const Ring& ring, double y) {
    const size_t n = ring.size();
    for (size_t i = 0; i < n; ++i) {
      const Vec2& a = ring[i];
      const Vec2& b = ring[(i + 1) % n];
      if ((a.y <= y && y < b.y) || (b.y <= y && y < a.y))
        crossings.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
    }
  };
  for (int row = firstRow; row <= lastRow; ++row) {
    const double y = row + 0.5;
    crossings.clear();
    addRing(polygon.outer, y);
    for (const Ring& hole : polygon.holes) addRing(hole, y);
    std::sort(crossings.begin(), crossings.end());
    for (size_t k = 0; k + 1 < crossings.size(); k += 2) {
      // Columns whose centre c + 0.5 lies in [x0, x1).
      const int c0 = std::max(0, static_cast<int>(std::ceil(crossings[k] - 0.5)));
      const int c1 = std::min(width - 1, static_cast<int>(std::ceil(crossings[k + 1] - 0.5)) - 1);
      for (int c = c0; c <= c1; ++c) out.emplace_back(c, row);
    }
  }
}

void cellsInside(const MultiPolygon& polygons, int width, int height, std::vector<Cell>& out) {
  for (const Polygon& p : polygons) cellsInside(p, width, height, out);
}

}  // namespace urbanvec::gridify
