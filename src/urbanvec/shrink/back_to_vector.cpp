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
  if (carve_.finalRow[static_cast<size_t>(o)] >= 0) {
    out = {p.x - (c - carve_.finalCol[static_cast<size_t>(o)]) * frame_.cell,
           p.y + (r - carve_.finalRow[static_cast<size_t>(o)]) * frame_.cell};
    return true;
  }
  if (!collapse) return false;
  const MergeSide side = carve_.mergeSide[static_cast<size_t>(o)];
  int s = carve_.mergedInto[static_cast<size_t>(o)];
  for (int guard = 0; s >= 0 && carve_.finalRow[static_cast<size_t>(s)] < 0 && guard < 1 << 24; ++guard)
    s = carve_.mergedInto[static_cast<size_t>(s)];
  if (s < 0) return false;
  const int sr = s / w, sc = s % w;
  const int fr = carve_.finalRow[static_cast<size_t>(s)], fc = carve_.finalCol[static_cast<size_t>(s)];
  out = {p.x - (sc - fc) * frame_.cell, p.y + (sr - fr) * frame_.cell};
  switch (side) {
    case MergeSide::OntoLeft:
      out.x = frame_.x0 + (fc + 1) * frame_.cell;
      break;
    case MergeSide::OntoRight:
      out.x = frame_.x0 + fc * frame_.cell;
      break;
    case MergeSide::OntoAbove:
      out.y = frame_.yTop - (fr + 1) * frame_.cell;
      break;
    case MergeSide::OntoBelow:
      out.y = frame_.yTop - fr * frame_.cell;
      break;
    case MergeSide::None:
      break;
  }
  return true;
}

}  // namespace urbanvec::shrink
