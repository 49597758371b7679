// The rotation trick of the shrinking pipeline (spec §B.11, thesis §4.6.1 and CityLib RotateCity §C.4):
// rotate the skeleton so its dominant street direction is axis-aligned before carving, rotate back
// afterwards.
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec::shrink {

/// Dominant bearing of a set of segments in degrees [0, 90): the mode of their directions modulo 90,
/// weighted by length, on a 1-degree histogram smoothed over +-2 degrees (ties: the smaller angle),
/// refined to the weighted mean direction within 3 degrees of it.
double dominantBearing(const std::vector<std::pair<Vec2, Vec2>>& segments);

/// Rotates p counter-clockwise by `degrees` about `centre` (RotateCity).
Vec2 rotatePoint(const Vec2& p, const Vec2& centre, double degrees);

}  // namespace urbanvec::shrink
