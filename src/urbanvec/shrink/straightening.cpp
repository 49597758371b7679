// Stretching post-process (spec §B.11): re-straighten originally straight ways.
#include "urbanvec/shrink/straightening.hpp"

#include <cmath>

namespace urbanvec::shrink {

int straightenWays(const std::vector<std::vector<int>>& ways, const std::vector<Vec2>& before,
                   std::vector<Vec2>& after, const std::vector<char>& pinned, double tolerance, int rounds) {
  struct Straight {
    const std::vector<int>* nodes;
    std::vector<double> t;  ///< parametric position of each node along the original chord
  };
  std::vector<Straight> straight;
  for (const std::vector<int>& way : ways) {
    if (way.size() < 3) continue;
    const Vec2 a = before[static_cast<size_t>(way.front())], b = before[static_cast<size_t>(way.back())];
    const Vec2 ab = b - a;
    const double len2 = dot(ab, ab);
    if (len2 <= 0.0) continue;
    bool ok = true;
    Straight s{&way, {}};
    for (int n : way) {
      const Vec2 p = before[static_cast<size_t>(n)];
      if (distanceToSegment(p, a, b) > tolerance) ok = false;
      s.t.push_back(dot(p - a, ab) / len2);
    }
    if (ok) straight.push_back(std::move(s));
  }
  std::vector<Vec2> sum(after.size());
  std::vector<int> count(after.size(), 0);
  for (int round = 0; round < rounds; ++round) {
    std::fill(sum.begin(), sum.end(), Vec2{});
    std::fill(count.begin(), count.end(), 0);
    for (const Straight& s : straight) {
      const std::vector<int>& way = *s.nodes;
      const Vec2 a = after[static_cast<size_t>(way.front())], b = after[static_cast<size_t>(way.back())];
      if (!std::isfinite(a.x) || !std::isfinite(b.x)) continue;
      for (size_t i = 1; i + 1 < way.size(); ++i) {
        const size_t n = static_cast<size_t>(way[i]);
        if (pinned[n] || !std::isfinite(after[n].x)) continue;
        sum[n] += a + (b - a) * s.t[i];
        ++count[n];
      }
    }
    for (size_t n = 0; n < after.size(); ++n)
      if (count[n] > 0) after[n] = sum[n] / count[n];
  }
  return static_cast<int>(straight.size());
}

}  // namespace urbanvec::shrink
