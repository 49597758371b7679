// Step 8Pos (spec §B.11): back to vector by node translation.
#include "urbanvec/shrink/back_to_vector.hpp"

namespace urbanvec::shrink {

bool PointMapper::survives(const Vec2& p) const {
  const size_t o = static_cast<size_t>(frame_.row(p.y)) * static_cast<size_t>(frame_.width) +
                   static_cast<size_t>(frame_.col(p.x));
  return carve_.finalRow[o] >= 0;
}

Vec2 PointMapper::pixelCentre(int pixel) const {
  return frame_.centre(pixel / frame_.width, pixel % frame_.width);
}

bool PointMapper::map(const Vec2& p, bool collapse, Vec2& out) const {
  const int r = frame_.row(p.y), c = frame_.col(p.x);
  const int w = frame_.width;
  int o = r * w + c;
  // The point's place inside its pixel, in pixel units; it follows each collapse of the chain: a
  // pixel removed onto its left neighbour puts its content on that neighbour's right edge, and so on,
  // the last collapse along each axis deciding.
  double fx = (p.x - frame_.x0) / frame_.cell - c, fy = (frame_.yTop - p.y) / frame_.cell - r;
  if (carve_.finalRow[static_cast<size_t>(o)] < 0) {
    if (!collapse) return false;
    for (int guard = 0; o >= 0 && carve_.finalRow[static_cast<size_t>(o)] < 0 && guard < 1 << 24; ++guard) {
      switch (carve_.mergeSide[static_cast<size_t>(o)]) {
        case MergeSide::OntoLeft:
          fx = 1.0;
          break;
        case MergeSide::OntoRight:
          fx = 0.0;
          break;
        case MergeSide::OntoAbove:
          fy = 1.0;
          break;
        case MergeSide::OntoBelow:
          fy = 0.0;
          break;
        case MergeSide::None:
          break;
      }
      o = carve_.mergedInto[static_cast<size_t>(o)];
    }
    if (o < 0 || carve_.finalRow[static_cast<size_t>(o)] < 0) return false;
  }
  if (o == r * w + c) {  // a surviving pixel: a pure translation
    out = {p.x - (c - carve_.finalCol[static_cast<size_t>(o)]) * frame_.cell,
           p.y + (r - carve_.finalRow[static_cast<size_t>(o)]) * frame_.cell};
    return true;
  }
  out = {frame_.x0 + (carve_.finalCol[static_cast<size_t>(o)] + fx) * frame_.cell,
         frame_.yTop - (carve_.finalRow[static_cast<size_t>(o)] + fy) * frame_.cell};
  return true;
}

SeamWays seamWaysOf(const std::vector<std::vector<int>>& ways, const std::vector<Vec2>& pos,
                    const RasterFrame& frame) {
  SeamWays s;
  s.ways = ways;
  for (const Vec2& p : pos) {
    const int r = frame.row(p.y), c = frame.col(p.x);
    s.col.push_back(c), s.row.push_back(r);
    s.fx.push_back((p.x - frame.x0) / frame.cell - c);
    s.fy.push_back((frame.yTop - p.y) / frame.cell - r);
  }
  return s;
}

}  // namespace urbanvec::shrink
