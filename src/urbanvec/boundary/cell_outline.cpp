// Pixel outline of a traced island; the geometry written for spec wijgerse-boundary.md §5 (see header).
#include "urbanvec/boundary/cell_outline.hpp"

#include <vector>

#include "urbanvec/core/error.hpp"

namespace urbanvec::boundary {

namespace {

/// Marks the 8-connected island of `seed` in `mask`.
Grid<std::uint8_t> island(const Grid<std::uint8_t>& mask, Pixel seed) {
  Grid<std::uint8_t> region(mask.width, mask.height, 0);
  std::vector<Pixel> stack{seed};
  region.at(seed.x, seed.y) = 1;
  while (!stack.empty()) {
    const Pixel p = stack.back();
    stack.pop_back();
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = p.x + dx;
        const int y = p.y + dy;
        if (mask.get(x, y, 0) && !region.at(x, y)) {
          region.at(x, y) = 1;
          stack.push_back({x, y});
        }
      }
  }
  return region;
}

/// Fills every background pixel that is not 4-connected to the image border (outside the grid counts
/// as background); returns whether anything changed.
bool fillHoles(Grid<std::uint8_t>& region) {
  Grid<std::uint8_t> outside(region.width, region.height, 0);
  std::vector<Pixel> stack;
  auto push = [&](int x, int y) {
    if (region.inside(x, y) && !region.at(x, y) && !outside.at(x, y)) {
      outside.at(x, y) = 1;
      stack.push_back({x, y});
    }
  };
  for (int x = 0; x < region.width; ++x) push(x, 0), push(x, region.height - 1);
  for (int y = 0; y < region.height; ++y) push(0, y), push(region.width - 1, y);
  while (!stack.empty()) {
    const Pixel p = stack.back();
    stack.pop_back();
    push(p.x + 1, p.y), push(p.x - 1, p.y), push(p.x, p.y + 1), push(p.x, p.y - 1);
  }
  bool changed = false;
  for (size_t i = 0; i < region.size(); ++i)
    if (!region.cells[i] && !outside.cells[i]) region.cells[i] = 1, changed = true;
  return changed;
}

/// Removes every 2 x 2 checkerboard (two pixels touching only at a corner) by filling the upper empty
/// pixel of the block; returns whether anything changed.
bool joinCornerContacts(Grid<std::uint8_t>& region) {
  bool changed = false;
  for (int y = 0; y + 1 < region.height; ++y)
    for (int x = 0; x + 1 < region.width; ++x) {
      const bool tl = region.at(x, y), tr = region.at(x + 1, y), bl = region.at(x, y + 1),
                 br = region.at(x + 1, y + 1);
      if (tl && br && !tr && !bl)
        region.at(x + 1, y) = 1, changed = true;
      else if (tr && bl && !tl && !br)
        region.at(x, y) = 1, changed = true;
    }
  return changed;
}

}  // namespace

Ring cellOutline(const Grid<std::uint8_t>& mask, Pixel seed) {
  if (!mask.get(seed.x, seed.y, 0))
    throw internalError("the outline of an island must start on one of its pixels");
  Grid<std::uint8_t> region = island(mask, seed);
  // Filling a corner contact can close a bay into a hole, and filling a hole cannot create a contact
  // with the outside, so alternate until both hold.
  fillHoles(region);
  while (joinCornerContacts(region)) fillHoles(region);

  Pixel first{-1, -1};
  for (int y = 0; y < region.height && first.x < 0; ++y)
    for (int x = 0; x < region.width; ++x)
      if (region.at(x, y)) {
        first = {x, y};
        break;
      }
  // Follow pixel edges with the island on the right (screen frame, y down), starting eastwards along
  // the top edge of the topmost-leftmost pixel. Directions: 0 E, 1 S, 2 W, 3 N.
  static const int kStepX[4] = {1, 0, -1, 0};
  static const int kStepY[4] = {0, 1, 0, -1};
  // Pixels ahead-left and ahead-right of a corner (cx, cy) per direction, as offsets from the corner
  // to the pixel's top-left corner.
  static const int kLeftX[4] = {0, 0, -1, -1};
  static const int kLeftY[4] = {-1, 0, 0, -1};
  static const int kRightX[4] = {0, -1, -1, 0};
  static const int kRightY[4] = {0, 0, -1, -1};
  auto filled = [&](int x, int y) { return region.get(x, y, 0) != 0; };
  Ring ring{Vec2(first.x, first.y)};
  int cx = first.x;
  int cy = first.y;
  int direction = 0;
  const size_t limit = 4 * region.size() + 4;
  while (true) {
    cx += kStepX[direction];
    cy += kStepY[direction];
    if (cx == first.x && cy == first.y) break;
    const bool left = filled(cx + kLeftX[direction], cy + kLeftY[direction]);
    const bool right = filled(cx + kRightX[direction], cy + kRightY[direction]);
    const int next = left ? (direction + 3) % 4 : right ? direction : (direction + 1) % 4;
    if (next != direction) ring.emplace_back(cx, cy);
    direction = next;
    if (ring.size() > limit) throw internalError("the pixel outline did not close");
  }
  ring.push_back(ring.front());
  return ring;
}

}  // namespace urbanvec::boundary
