// Rotation trick (spec §B.11 / thesis §4.6.1, CityLib RotateCity §C.4) and its automatic angle.
#include "urbanvec/shrink/rotation.hpp"

#include <array>
#include <cmath>

namespace urbanvec::shrink {

double dominantBearing(const std::vector<std::pair<Vec2, Vec2>>& segments) {
  std::array<double, 90> histogram{};
  for (const auto& [a, b] : segments) {
    const Vec2 d = b - a;
    const double len = length(d);
    if (len <= 0.0) continue;
    double angle = std::atan2(d.y, d.x) * 180.0 / M_PI;  // counter-clockwise from east
    angle = std::fmod(std::fmod(angle, 90.0) + 90.0, 90.0);
    histogram[static_cast<size_t>(std::floor(angle)) % 90] += len;
  }
  int best = 0;
  double bestValue = -1.0;
  for (int i = 0; i < 90; ++i) {
    double v = 0.0;
    for (int k = -2; k <= 2; ++k) v += histogram[static_cast<size_t>((i + k + 90) % 90)];
    if (v > bestValue) bestValue = v, best = i;
  }
  return best + 0.5;
}

Vec2 rotatePoint(const Vec2& p, const Vec2& centre, double degrees) {
  const double a = degrees * M_PI / 180.0;
  const double c = std::cos(a), s = std::sin(a);
  const Vec2 d = p - centre;
  return {centre.x + c * d.x - s * d.y, centre.y + s * d.x + c * d.y};
}

}  // namespace urbanvec::shrink
