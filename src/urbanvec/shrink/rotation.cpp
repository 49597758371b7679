// Rotation trick (spec §B.11 / thesis §4.6.1, CityLib RotateCity §C.4) and its automatic angle.
#include "urbanvec/shrink/rotation.hpp"

#include <array>
#include <cmath>
#include <utility>

namespace urbanvec::shrink {

double dominantBearing(const std::vector<std::pair<Vec2, Vec2>>& segments) {
  std::array<double, 90> histogram{};
  std::vector<std::pair<double, double>> angles;  // (angle modulo 90, length)
  for (const auto& [a, b] : segments) {
    const Vec2 d = b - a;
    const double len = length(d);
    if (len <= 0.0) continue;
    double angle = std::atan2(d.y, d.x) * 180.0 / M_PI;  // counter-clockwise from east
    angle = std::fmod(std::fmod(angle, 90.0) + 90.0, 90.0);
    histogram[static_cast<size_t>(std::floor(angle)) % 90] += len;
    angles.emplace_back(angle, len);
  }
  int best = 0;
  double bestValue = -1.0;
  for (int i = 0; i < 90; ++i) {
    double v = 0.0;
    for (int k = -2; k <= 2; ++k) v += histogram[static_cast<size_t>((i + k + 90) % 90)];
    if (v > bestValue) bestValue = v, best = i;
  }
  // Refine: the length-weighted mean of the directions within 3 degrees of the mode.
  const double mode = best + 0.5;
  double sum = 0.0, weight = 0.0;
  for (const auto& [angle, len] : angles) {
    const double diff = std::fmod(angle - mode + 135.0, 90.0) - 45.0;
    if (std::abs(diff) <= 3.0) sum += diff * len, weight += len;
  }
  const double refined = weight > 0.0 ? mode + sum / weight : mode;
  return std::fmod(refined + 90.0, 90.0);
}

Vec2 rotatePoint(const Vec2& p, const Vec2& centre, double degrees) {
  const double a = degrees * M_PI / 180.0;
  const double c = std::cos(a), s = std::sin(a);
  const Vec2 d = p - centre;
  return {centre.x + c * d.x - s * d.y, centre.y + s * d.x + c * d.y};
}

}  // namespace urbanvec::shrink
