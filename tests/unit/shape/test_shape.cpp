// Realism metrics of spec wijgerse-boundary.md §6-§8 on shapes with known answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "urbanvec/core/error.hpp"
#include "urbanvec/shape/enclosed_area.hpp"
#include "urbanvec/shape/fractal_regression.hpp"
#include "urbanvec/shape/shape_metrics.hpp"
#include "urbanvec/shape/structured_walk.hpp"

using namespace urbanvec;
using namespace urbanvec::shape;

namespace {

Ring circle(double radius, int vertices) {
  Ring ring;
  for (int i = 0; i < vertices; ++i) {
    const double a = 2.0 * M_PI * i / vertices;
    ring.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  ring.push_back(ring.front());
  return ring;
}

/// Koch snowflake after `depth` subdivisions of a triangle with sides `side`.
Ring kochSnowflake(double side, int depth) {
  std::vector<Vec2> points{{0, 0}, {side / 2, side * std::sqrt(3.0) / 2}, {side, 0}};
  for (int d = 0; d < depth; ++d) {
    std::vector<Vec2> next;
    for (size_t i = 0; i < points.size(); ++i) {
      const Vec2 a = points[i];
      const Vec2 b = points[(i + 1) % points.size()];
      const Vec2 step = (b - a) / 3.0;
      const Vec2 p = a + step;
      const Vec2 q = a + step * 2.0;
      // Peak: the middle third rotated by +60 degrees, outwards for this clockwise triangle.
      const double c = 0.5;
      const double s = std::sqrt(3.0) / 2;
      const Vec2 peak = p + Vec2{step.x * c - step.y * s, step.x * s + step.y * c};
      next.insert(next.end(), {a, p, peak, q});
    }
    points = std::move(next);
  }
  Ring ring(points.begin(), points.end());
  ring.push_back(ring.front());
  return ring;
}

/// A rough closed outline on the half-pixel lattice, like a traced city boundary: a wobbly circle of
/// radius ~100 with straight runs and 1-pixel steps.
Ring roughOutline(int vertices) {
  Ring ring;
  for (int i = 0; i < vertices; ++i) {
    const double a = 2.0 * M_PI * i / vertices;
    const double r = 100 + 15 * std::sin(5 * a) + 8 * std::sin(17 * a + 1) + 3 * std::sin(53 * a + 2);
    const Vec2 p{std::round(2 * r * std::cos(a)) / 2, std::round(2 * r * std::sin(a)) / 2};
    if (ring.empty() || p != ring.back()) ring.push_back(p);
  }
  if (ring.back() == ring.front()) ring.pop_back();
  ring.push_back(ring.front());
  return ring;
}

/// The structured walk as spec §6.2 defines it, one walk at a time: from the current point, test the
/// ring's vertices in order; the chord ends on the segment into the first vertex at least a chord
/// away. The library walks several at once and must give the same bits.
StructuredWalk referenceWalk(const Ring& ring, const StructuredWalkOptions& o) {
  std::vector<Vec2> v(ring.begin(), ring.end() - 1);
  const size_t n = v.size();
  auto at = [&](size_t i) { return v[i % n]; };
  double perimeter = 0.0;
  for (size_t i = 0; i < n; ++i) perimeter += distance(at(i), at(i + 1));
  StructuredWalk result;
  result.vertices = n;
  result.baseChord = o.baseChord > 0.0 ? o.baseChord : perimeter / n;
  for (int k = 0; k < o.scales; ++k) {
    WalkScale scale;
    scale.chord = result.baseChord * std::pow(o.scaleFactor, k);
    const double chord2 = scale.chord * scale.chord;
    double countSum = 0.0, meanSum = 0.0, fullSum = 0.0;
    size_t starts = 0;
    for (size_t start = 0; start < n; start += static_cast<size_t>(o.skip), ++starts) {
      size_t segment = start;
      double t = 0.0;
      Vec2 centre = at(start);
      long full = 0;
      double leftover = 0.0;
      while (true) {
        size_t exit = segment + 1;
        while (exit <= start + n) {
          const Vec2 e = at(exit) - centre;
          if (e.x * e.x + e.y * e.y >= chord2) break;
          ++exit;
        }
        if (exit > start + n) {
          leftover = distance(at(start), centre);
          break;
        }
        const size_t s = exit - 1;
        const Vec2 a = at(s);
        const Vec2 d = at(exit) - a;
        const Vec2 f = a - centre;
        const double fd = dot(f, d);
        const double disc = std::max(0.0, fd * fd - dot(d, d) * (dot(f, f) - chord2));
        const double root =
            std::clamp((-fd + std::sqrt(disc)) * (1.0 / dot(d, d)), s == segment ? t : 0.0, 1.0);
        centre = a + d * root;
        segment = s;
        t = root;
        ++full;
      }
      const double chords = full + 1.0;
      countSum += chords;
      meanSum += (full * scale.chord + leftover) / chords;
      fullSum += full;
    }
    scale.chordCount = countSum / starts;
    scale.meanChord = meanSum / starts;
    scale.fullChords = fullSum / starts;
    result.startVertices = starts;
    result.scales.push_back(scale);
  }
  return result;
}

}  // namespace

TEST(FractalRegression, ReproducesThesisTable41) {
  // Table 4.1 of the thesis: N_n and r_n for n = 0..11.
  const std::vector<double> r{1.581,  2.236,  3.162,  4.471,  6.321,  8.936,
                              12.628, 17.841, 25.187, 35.535, 50.035, 70.271};
  const std::vector<double> n{3520.590, 2310.507, 1508.597, 968.564, 623.730, 403.482,
                              260.259,  162.776,  105.066,  67.754,  42.599,  25.572};
  const FractalRegression reg = fractalRegression(n, r, 2.5696);
  const std::vector<double> expected{1.215, 1.223, 1.241, 1.249, 1.251, 1.254,
                                     1.268, 1.269, 1.269, 1.278, 1.298};
  ASSERT_EQ(reg.dimensions.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i)
    EXPECT_NEAR(reg.dimensions[i], expected[i], 0.001) << "D_" << i + 1;
  EXPECT_NEAR(reg.slope, 0.02045, 0.0001);
  EXPECT_NEAR(reg.intercept, 1.20403, 0.0005);
  EXPECT_NEAR(reg.sigma, 0.0056, 0.0002);
  EXPECT_NEAR(reg.comparableDimension, 1.2566, 0.0005);
  EXPECT_NEAR(reg.logChordSpan, 3.448, 0.002);
  // Without a fixed R the line is read at the mean ln r_n (2.533 for this example).
  const FractalRegression centred = fractalRegression(n, r, std::nullopt);
  EXPECT_NEAR(centred.evaluationLogChord, 2.533, 0.001);
}

TEST(StructuredWalk, LargeCircleHasDimensionOne) {
  ShapeMetricOptions options;
  options.walk.skip = 7;
  options.evaluationLogChord.reset();
  const ShapeMetrics m = measureShape(circle(1000.0, 4000), options);
  ASSERT_TRUE(m.regression.has_value());
  EXPECT_NEAR(m.regression->comparableDimension, 1.0, 0.005);
  EXPECT_LT(std::abs(m.regression->slope), 0.005);
  EXPECT_EQ(m.walk.scales.size(), 12u);
  // l0 is the mean segment length of the ring; each scale multiplies it by sqrt(2).
  EXPECT_NEAR(m.walk.baseChord, 2 * M_PI * 1000 / 4000, 0.01);
  EXPECT_NEAR(m.walk.scales[2].chord, 2 * m.walk.baseChord, 1e-9);
  // Chords of a circle barely shorten the perimeter: N_n r_n stays the perimeter.
  for (const WalkScale& s : m.walk.scales)
    EXPECT_NEAR(s.chordCount * s.meanChord, 2 * M_PI * 1000, 2 * M_PI * 1000 * 0.01);
  EXPECT_FALSE(m.dimensionRealistic);  // a circle is far too smooth for a city
  EXPECT_TRUE(m.areaRealistic);
}

TEST(StructuredWalk, KochSnowflakeHasItsSimilarityDimension) {
  // 3 * 4^6 unit segments; chords 9, 27, 81, 243 are the snowflake's self-similar scales (ratio 3), a
  // decade above the unit resolution where the polygon stops being fractal. With k = sqrt(2) the
  // individual D_n swing by +-0.1 because the Koch curve is only similar under factors of 3.
  const Ring koch = kochSnowflake(729.0, 6);
  // Outward bumps: area = triangle (1 + 0.6 (1 - (4/9)^6)) after 6 subdivisions.
  EXPECT_NEAR(std::abs(signedArea(koch)),
              (1 + 0.6 * (1 - std::pow(4.0 / 9.0, 6))) * std::sqrt(3.0) / 4 * 729.0 * 729.0,
              1e-6 * 729 * 729);
  ShapeMetricOptions options;
  options.evaluationLogChord.reset();
  options.walk.scaleFactor = 3.0;
  options.walk.scales = 4;
  options.walk.baseChord = 9.0;
  const ShapeMetrics m = measureShape(koch, options);
  ASSERT_TRUE(m.regression.has_value());
  const double similarity = std::log(4.0) / std::log(3.0);
  for (double d : m.regression->dimensions) EXPECT_NEAR(d, similarity, 0.03);
  EXPECT_NEAR(m.regression->comparableDimension, similarity, 0.02);
  EXPECT_LT(m.regression->sigma, 0.02);
}

TEST(StructuredWalk, SkippingStartVerticesChangesLittle) {
  const Ring koch = kochSnowflake(243.0, 5);
  ShapeMetricOptions exact;
  exact.walk.skip = 1;
  ShapeMetricOptions skipped;
  skipped.walk.skip = 15;
  const ShapeMetrics a = measureShape(koch, exact);
  const ShapeMetrics b = measureShape(koch, skipped);
  EXPECT_EQ(a.walk.startVertices, a.walk.vertices);
  EXPECT_EQ(b.walk.startVertices, (b.walk.vertices + 14) / 15);
  EXPECT_NEAR(a.regression->comparableDimension, b.regression->comparableDimension, 0.01);
}

TEST(StructuredWalk, LeftoverChordIsCountedAndShorterThanTheChord) {
  // A 10 x 10 square walked with chords of 3 from (0, 0): three chords per side, each corner cut
  // by a chord across it, and a leftover of 1.2675 back to the start; N_0 counts the leftover.
  const Ring square{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}};
  StructuredWalkOptions options;
  options.baseChord = 3.0;
  options.scales = 2;
  options.skip = 4;
  const StructuredWalk walk = structuredWalk(square, options);
  ASSERT_EQ(walk.startVertices, 1u);
  const WalkScale& s = walk.scales[0];
  EXPECT_GT(s.chordCount, s.fullChords);
  EXPECT_DOUBLE_EQ(s.chordCount, s.fullChords + 1.0);
  const double leftover = s.chordCount * s.meanChord - s.fullChords * 3.0;
  EXPECT_EQ(s.fullChords, 12.0);
  EXPECT_NEAR(leftover, 1.267454, 1e-6);
}

TEST(StructuredWalk, MatchesTheOneWalkAtATimeDefinitionBitForBit) {
  // Start counts that fill the six lanes and ones that leave lanes idle; rings from 4 to 3000 vertices.
  const Ring square{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}};
  const Ring rings[] = {roughOutline(3000), roughOutline(700), kochSnowflake(81.0, 3), circle(50.0, 301),
                        square};
  for (const Ring& ring : rings)
    for (int skip : {1, 2, 3, 5, 15}) {
      StructuredWalkOptions o;
      o.skip = skip;
      if (ring.size() < 10) o.baseChord = 3.0;
      const StructuredWalk a = structuredWalk(ring, o);
      const StructuredWalk b = referenceWalk(ring, o);
      ASSERT_EQ(a.vertices, b.vertices);
      EXPECT_EQ(a.startVertices, b.startVertices);
      EXPECT_EQ(a.baseChord, b.baseChord);
      ASSERT_EQ(a.scales.size(), b.scales.size());
      for (size_t k = 0; k < a.scales.size(); ++k) {
        EXPECT_EQ(a.scales[k].chord, b.scales[k].chord);
        EXPECT_EQ(a.scales[k].chordCount, b.scales[k].chordCount)
            << ring.size() << " skip " << skip << " scale " << k;
        EXPECT_EQ(a.scales[k].meanChord, b.scales[k].meanChord)
            << ring.size() << " skip " << skip << " scale " << k;
        EXPECT_EQ(a.scales[k].fullChords, b.scales[k].fullChords);
      }
    }
}

TEST(StructuredWalk, RejectsDegenerateRingsAndOptions) {
  EXPECT_THROW(structuredWalk(Ring{{0, 0}, {1, 0}, {0, 0}}, {}), Error);
  StructuredWalkOptions bad;
  bad.scaleFactor = 1.0;
  EXPECT_THROW(structuredWalk(circle(10, 50), bad), Error);
}

TEST(EnclosedArea, CircleIsOneAndThesisVillageIsTheThreshold) {
  const EnclosedArea c = enclosedArea(circle(500.0, 20000));
  EXPECT_NEAR(c.ratio, 1.0, 1e-3);
  EXPECT_NEAR(c.diameter, 1000.0, 1e-6);
  // The thesis's least compact village: 200 m wide, 4 km long.
  const EnclosedArea village = enclosedArea(Ring{{0, 0}, {4000, 0}, {4000, 200}, {0, 200}, {0, 0}});
  EXPECT_NEAR(village.area, 800000.0, 1e-6);
  EXPECT_NEAR(village.diameter, 4004.997, 1e-3);
  EXPECT_NEAR(village.ratio, 0.0635, 0.00005);
  ShapeMetricOptions options;
  options.minimumEnclosedAreaRatio = 0.0635;
  EXPECT_TRUE(measureShape(Ring{{0, 0}, {4000, 0}, {4000, 200}, {0, 200}, {0, 0}}, options).areaRealistic);
  EXPECT_FALSE(measureShape(Ring{{0, 0}, {4000, 0}, {4000, 190}, {0, 190}, {0, 0}}, options).areaRealistic);
}

TEST(EnclosedArea, DiameterOfAnIrregularPointSet) {
  const std::vector<Vec2> points{{0, 0}, {3, 1}, {1, 5}, {-2, 2}, {4, 4}, {0.5, 0.5}, {2, -3}};
  double brute = 0.0;
  for (const Vec2& a : points)
    for (const Vec2& b : points) brute = std::max(brute, distance(a, b));
  EXPECT_DOUBLE_EQ(diameter(points), brute);
}

TEST(ShapeMetrics, TooFewChordsGiveNoDimension) {
  // A triangle walked with its own side length: N_n falls below 3 at once, so no dimension.
  const ShapeMetrics m = measureShape(Ring{{0, 0}, {10, 0}, {5, 8}, {0, 0}}, {});
  EXPECT_FALSE(m.regression.has_value());
  EXPECT_FALSE(m.dimensionRealistic);
  EXPECT_FALSE(m.realistic());
}
