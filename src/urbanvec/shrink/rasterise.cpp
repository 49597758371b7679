// Step 7 (spec §B.8): rasterise the skeleton city; frozen pixels of §B.9 item 6.
#include "urbanvec/shrink/rasterise.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace urbanvec::shrink {

int RasterFrame::col(double x) const {
  return std::clamp(static_cast<int>(std::floor((x - x0) / cell)), 0, width - 1);
}
int RasterFrame::row(double y) const {
  return std::clamp(static_cast<int>(std::floor((yTop - y) / cell)), 0, height - 1);
}

RasterFrame frameFor(double minX, double minY, double maxX, double maxY, int imageSize) {
  RasterFrame f;
  const double w = std::max(0.0, maxX - minX), h = std::max(0.0, maxY - minY);
  const double longest = std::max(w, h);
  f.cell = longest > 0.0 ? longest / imageSize : 1.0;
  f.width = std::clamp(static_cast<int>(std::ceil(w / f.cell - 1e-9)), 1, imageSize);
  f.height = std::clamp(static_cast<int>(std::ceil(h / f.cell - 1e-9)), 1, imageSize);
  f.x0 = minX;
  f.yTop = maxY;
  return f;
}

namespace {

void drawSegment(const RasterFrame& f, const Vec2& a, const Vec2& b,
                 const std::function<void(int, int)>& put) {
  const double steps = std::ceil(2.0 * distance(a, b) / f.cell) + 1.0;
  const int n = static_cast<int>(std::min(steps, 1e7));
  int lastR = -1, lastC = -1;
  for (int i = 0; i <= n; ++i) {
    const Vec2 p = a + (b - a) * (static_cast<double>(i) / n);
    const int r = f.row(p.y), c = f.col(p.x);
    if (r == lastR && c == lastC) continue;
    put(r, c);
    lastR = r, lastC = c;
  }
}

/// Even-odd fill of a closed ring on pixel centres.
void fillRing(const RasterFrame& f, const std::vector<Vec2>& ring, const std::function<void(int, int)>& put) {
  double minY = 1e300, maxY = -1e300;
  for (const Vec2& p : ring) minY = std::min(minY, p.y), maxY = std::max(maxY, p.y);
  std::vector<double> xs;
  for (int r = f.row(maxY); r <= f.row(minY); ++r) {
    const double y = f.yTop - (r + 0.5) * f.cell;
    xs.clear();
    for (size_t i = 1; i < ring.size(); ++i) {
      const Vec2& a = ring[i - 1];
      const Vec2& b = ring[i];
      if ((a.y > y) != (b.y > y)) xs.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
    }
    std::sort(xs.begin(), xs.end());
    for (size_t k = 0; k + 1 < xs.size(); k += 2) {
      const int c0 = static_cast<int>(std::ceil((xs[k] - f.x0) / f.cell - 0.5));
      const int c1 = static_cast<int>(std::floor((xs[k + 1] - f.x0) / f.cell - 0.5));
      for (int c = std::max(c0, 0); c <= std::min(c1, f.width - 1); ++c) put(r, c);
    }
  }
}

}  // namespace

SkeletonRaster rasteriseSkeleton(const RasterFrame& frame, const std::vector<InkLine>& streets,
                                 const std::vector<LandmarkShape>& landmarks,
                                 const std::vector<Vec2>& frozenStreetNodes, LandmarkFreeze freeze) {
  SkeletonRaster raster;
  raster.frame = frame;
  const size_t w = static_cast<size_t>(frame.width);
  raster.ink.assign(w * static_cast<size_t>(frame.height), 0.0f);
  raster.freezeOwner.assign(raster.ink.size(), kNotFrozen);
  for (const InkLine& line : streets) {
    auto put = [&](int r, int c) {
      float& v = raster.ink[static_cast<size_t>(r) * w + static_cast<size_t>(c)];
      v = std::max(v, line.ink);
    };
    if (line.points.size() == 1) put(frame.row(line.points[0].y), frame.col(line.points[0].x));
    for (size_t i = 1; i < line.points.size(); ++i)
      drawSegment(frame, line.points[i - 1], line.points[i], put);
  }
  for (const LandmarkShape& shape : landmarks) {
    if (shape.points.empty()) continue;
    auto put = [&](int r, int c) {
      raster.ink[static_cast<size_t>(r) * w + static_cast<size_t>(c)] = 255.0f;
    };
    for (size_t i = 1; i < shape.points.size(); ++i)
      drawSegment(frame, shape.points[i - 1], shape.points[i], put);
    const bool closed = shape.points.size() >= 4 && shape.points.front() == shape.points.back();
    if (closed) fillRing(frame, shape.points, put);
    int r0 = frame.height, r1 = -1, c0 = frame.width, c1 = -1;
    for (const Vec2& p : shape.points) {
      const int r = frame.row(p.y), c = frame.col(p.x);
      put(r, c);
      r0 = std::min(r0, r), r1 = std::max(r1, r), c0 = std::min(c0, c), c1 = std::max(c1, c);
      if (freeze == LandmarkFreeze::Nodes)
        raster.freezeOwner[static_cast<size_t>(r) * w + static_cast<size_t>(c)] = shape.place;
    }
    // The pixel bounding box: no seam can pass between two pixels of it, so every node of the element
    // moves by the same number of pixels (a pure translation).
    if (freeze == LandmarkFreeze::BoundingBox)
      for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c)
          raster.freezeOwner[static_cast<size_t>(r) * w + static_cast<size_t>(c)] = shape.place;
  }
  for (const Vec2& p : frozenStreetNodes) {
    int& owner =
        raster.freezeOwner[static_cast<size_t>(frame.row(p.y)) * w + static_cast<size_t>(frame.col(p.x))];
    if (owner == kNotFrozen) owner = kFrozenStreetNode;
  }
  return raster;
}

}  // namespace urbanvec::shrink
