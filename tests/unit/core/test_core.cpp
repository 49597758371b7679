#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "urbanvec/app/command.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/landuse.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/core/random.hpp"
#include "urbanvec/core/utm.hpp"

using namespace urbanvec;

TEST(GeoTransform, RoundTripsNorthUpSouthUpAndRotated) {
  for (const std::array<double, 6>& c :
       {std::array<double, 6>{1000, 12, 0, 5000, 0, -12}, std::array<double, 6>{1000, 12, 0, 5000, 0, 12},
        std::array<double, 6>{1000, 8.48528, 8.48528, 5000, 8.48528, -8.48528}}) {
    GeoTransform t{c};
    const Vec2 w = t.pixelToWorld(3.5, 7.25);
    const Vec2 p = t.worldToPixel(w);
    EXPECT_NEAR(p.x, 3.5, 1e-9);
    EXPECT_NEAR(p.y, 7.25, 1e-9);
    EXPECT_NEAR(t.cellSize(), 12.0, 1e-4);
  }
}

TEST(GeoTransform, SingularTransformIsAnError) {
  GeoTransform t{{0, 0, 0, 0, 0, 0}};
  EXPECT_THROW(t.worldToPixel({1, 1}), Error);
}

TEST(Geometry, AreaOfSquareWithHole) {
  Polygon p{{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}}, {{{2, 2}, {2, 4}, {4, 4}, {4, 2}, {2, 2}}}};
  EXPECT_DOUBLE_EQ(area(p), 96.0);
  EXPECT_DOUBLE_EQ(signedArea(p.outer), 100.0);
  EXPECT_DOUBLE_EQ(length(LineString{{0, 0}, {3, 4}, {3, 10}}), 11.0);
}

TEST(Geometry, HeadOfLengthKeepsTheFirstMetres) {
  const LineString l{{0, 0}, {10, 0}, {10, 10}};
  EXPECT_EQ(headOfLength(l, 15), (LineString{{0, 0}, {10, 0}, {10, 5}}));
  EXPECT_EQ(headOfLength(l, 4), (LineString{{0, 0}, {4, 0}}));
  EXPECT_EQ(headOfLength(l, 25), l);
  EXPECT_EQ(headOfLength(l, -3), (LineString{{0, 0}}));
}

TEST(Geometry, ConvexHullIsClosedCounterClockwiseWithoutInnerOrCollinearPoints) {
  // A square with an inner point, a point on an edge and a repeated corner.
  const Ring hull = convexHull({{2, 2}, {0, 0}, {4, 0}, {4, 4}, {1, 1}, {2, 0}, {0, 4}, {4, 4}});
  EXPECT_EQ(hull, (Ring{{0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 0}}));
  EXPECT_DOUBLE_EQ(signedArea(hull), 16.0);
  EXPECT_EQ(convexHull({{0, 0}, {1, 1}, {2, 2}}), (Ring{{0, 0}, {2, 2}, {0, 0}}));
  EXPECT_EQ(convexHull({{3, 1}, {3, 1}}), (Ring{{3, 1}}));
}

// The stretch of an edge within d of a segment (road frontage, issue 21): the line meets the stadium
// around the segment in one interval, from its rectangle or from the discs at its ends.
TEST(Geometry, WithinDistanceIntervalIsTheEdgeInTheStadium) {
  const double d = 1e-3;
  const Vec2 p{0, 0}, q{1, 0};
  auto expectInterval = [&](const Vec2& a, const Vec2& b, double lo, double hi, const char* what) {
    const auto [tLo, tHi] = withinDistanceInterval(a, b, p, q, d);
    EXPECT_NEAR(tLo, lo, 1e-12) << what;
    EXPECT_NEAR(tHi, hi, 1e-12) << what;
  };
  // The segment itself, either way round: exactly the whole edge.
  EXPECT_EQ(withinDistanceInterval(p, q, p, q, d), std::pair(0.0, 1.0));
  EXPECT_EQ(withinDistanceInterval(q, p, p, q, d), std::pair(0.0, 1.0));
  // Grazing the corner q at 0.6 d: only the disc at q holds it, over ±0.8 d around the nearest point
  // (a box around the segment would give ±d, the rectangle alone nothing).
  expectInterval({1.0 + 0.6 * d, -1.0}, {1.0 + 0.6 * d, 1.0}, 0.5 - 0.4 * d, 0.5 + 0.4 * d, "corner");
  // Across the middle: the rectangle, ±d.
  expectInterval({0.5, -1.0}, {0.5, 1.0}, 0.5 - 0.5 * d, 0.5 + 0.5 * d, "across");
  // Along the segment from its middle and beyond q: up to d past q.
  expectInterval({0.5, 0.0}, {2.0, 0.0}, 0.0, (0.5 + d) / 1.5, "collinear");
  // Parallel at 0.5 d: the rectangle, then the disc at q, up to √0.75 d past q.
  expectInterval({-1.0, 0.5 * d}, {2.0, 0.5 * d}, (1.0 - std::sqrt(0.75) * d) / 3.0,
                 (2.0 + std::sqrt(0.75) * d) / 3.0, "parallel");
  // Beyond reach: empty.
  const auto far = withinDistanceInterval({1.0 + 1.01 * d, -1.0}, {1.0 + 1.01 * d, 1.0}, p, q, d);
  EXPECT_GT(far.first, far.second);
  // Against sampled distances on random edges and segments: points inside the interval are within d,
  // points outside it farther.
  std::uint64_t draw = 0;
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unitDraw(7, draw++); };
  int inside = 0;
  for (int k = 0; k < 2000; ++k) {
    auto point = [&] { return Vec2{uniform(0.0, 1.0), uniform(0.0, 1.0)}; };
    const Vec2 a = point(), b = point(), s = point(), e = k % 4 == 0 ? s : point();
    const double reach = uniform(0.01, 0.3);
    const auto [lo, hi] = withinDistanceInterval(a, b, s, e, reach);
    for (int j = 0; j <= 200; ++j) {
      const double t = j / 200.0;
      const double dist = distanceToSegment(a + (b - a) * t, s, e);
      if (t >= lo + 1e-9 && t <= hi - 1e-9) {
        EXPECT_LE(dist, reach * (1 + 1e-9)) << k << " " << t;
        ++inside;
      } else if (t < lo - 1e-9 || t > hi + 1e-9) {
        EXPECT_GT(dist, reach * (1 - 1e-9)) << k << " " << t;
      }
    }
  }
  EXPECT_GT(inside, 20000);
}

TEST(LandUse, CodesAndNames) {
  EXPECT_EQ(static_cast<int>(LandUse::SecondaryRoad), 2);
  EXPECT_EQ(static_cast<int>(LandUse::PrimaryRoad), 3);
  EXPECT_EQ(static_cast<int>(LandUse::Reserved), 8);
  EXPECT_EQ(landUseName(LandUse::Commercial), "commercial");
  EXPECT_EQ(parseLandUse("Secondary Road"), LandUse::SecondaryRoad);
  EXPECT_EQ(parseLandUse("INDUSTRIAL"), LandUse::Industrial);
  EXPECT_FALSE(parseLandUse("farmland").has_value());
  EXPECT_EQ(landUseFromCode(kLandUseNodata), LandUse::Unused);
  EXPECT_TRUE(isDeveloped(LandUse::Park));
  EXPECT_FALSE(isDeveloped(LandUse::Reserved));
}

TEST(Utm, ZonesIncludingExceptions) {
  EXPECT_EQ(utmEpsgFor(7.42, 43.74), 32632);   // Monaco
  EXPECT_EQ(utmEpsgFor(14.40, 50.10), 32633);  // Prague
  EXPECT_EQ(utmEpsgFor(-43.2, -22.9), 32723);  // Rio de Janeiro
  EXPECT_EQ(utmEpsgFor(5.3, 60.4), 32632);     // Bergen (Norway exception)
  EXPECT_EQ(utmEpsgFor(15.6, 78.2), 32633);    // Longyearbyen (Svalbard exception)
  EXPECT_EQ(utmEpsgFor(179.99, 10), 32660);
  EXPECT_EQ(utmEpsgFor(-180.0, 10), 32601);
}

TEST(Progress, SubRangesAreMonotonicAndCancel) {
  std::vector<double> seen;
  Progress root = monotonicProgress([&](double f, std::string_view) {
    seen.push_back(f);
    return true;
  });
  Progress second = subProgress(root, 0.5, 1.0);
  reportProgress(subProgress(root, 0.0, 0.5), 1.0, "a");
  reportProgress(second, 0.0, "b");
  reportProgress(root, 0.2, "late");  // must not go backwards
  reportProgress(second, 1.0, "b");
  EXPECT_EQ(seen, (std::vector<double>{0.5, 0.5, 0.5, 1.0}));
  Progress stop = [](double, std::string_view) { return false; };
  EXPECT_THROW(reportProgress(stop, 0.1, "x"), Cancelled);
}

TEST(Random, DerivedSeedsDifferPerItemAndAreStable) {
  EXPECT_NE(deriveSeed(1, 0), deriveSeed(1, 1));
  EXPECT_NE(deriveSeed(1, 0), deriveSeed(2, 0));
  EXPECT_EQ(deriveSeed(42, 7), deriveSeed(42, 7));
  // unitDraw: the top 53 bits of deriveSeed, in [0, 1), spread over it.
  double sum = 0.0;
  for (std::uint64_t i = 0; i < 1000; ++i) {
    const double u = unitDraw(5, i);
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
  }
  EXPECT_NEAR(sum / 1000, 0.5, 0.03);
  EXPECT_EQ(unitDraw(5, 3), static_cast<double>(deriveSeed(5, 3) >> 11) / 9007199254740992.0);
}

namespace {
/// An engine of 64 random bits that returns given values, for the draws at the ends of the range.
struct ListEngine {
  using result_type = std::uint64_t;
  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return ~result_type{0}; }
  std::vector<result_type> values;
  size_t next = 0;
  result_type operator()() { return values[next++ % values.size()]; }
};

bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}
}  // namespace

TEST(Random, DrawsMatchTheStandardDistributionsBitForBit) {
  // canonicalDraw and NormalDraw replace libstdc++'s generate_canonical and normal_distribution in the
  // parcel search (issue 21): the output depends on every draw, so they must be the same values.
  for (const std::uint64_t seed :
       {std::uint64_t{1}, std::uint64_t{2}, std::uint64_t{12345}, deriveSeed(7, 3)}) {
    Rng ours(seed), theirs(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < 20000; ++i) ASSERT_TRUE(sameBits(canonicalDraw(ours), unit(theirs))) << i;
    // One distribution for many calls (each second call takes the kept value of the pair) and, as the
    // split loop does, a new one per attempt with a few calls each.
    NormalDraw normal(0.5, 1.0 / 6.0);
    std::normal_distribution<double> standard(0.5, 1.0 / 6.0);
    for (int i = 0; i < 20000; ++i) ASSERT_TRUE(sameBits(normal(ours), standard(theirs))) << i;
    for (int attempt = 0; attempt < 5000; ++attempt) {
      NormalDraw fresh(0.5, 0.2);
      std::normal_distribution<double> standardFresh(0.5, 0.2);
      for (int k = 0; k < 1 + attempt % 3; ++k)
        ASSERT_TRUE(sameBits(fresh(ours), standardFresh(theirs))) << attempt;
    }
    EXPECT_EQ(ours(), theirs());  // the same number of engine draws
  }
  // The ends: 0, the largest draws (which round to 1 and must give the largest double below 1), and
  // pairs outside the unit circle that the polar method rejects.
  const std::vector<std::uint64_t> ends{0, 1, ~0ULL, ~0ULL - 1024, ~0ULL - 2048, 1ULL << 63, 3ULL << 62};
  ListEngine ours{ends}, theirs{ends};
  for (size_t i = 0; i < ends.size(); ++i)
    EXPECT_TRUE(sameBits(canonicalDraw(ours), std::generate_canonical<double, 53>(theirs))) << i;
  ListEngine circleOurs{{~0ULL, ~0ULL, 0, 0, 1ULL << 62, 3ULL << 61}}, circleTheirs = circleOurs;
  NormalDraw normal(0.0, 1.0);
  std::normal_distribution<double> standard(0.0, 1.0);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(sameBits(normal(circleOurs), standard(circleTheirs))) << i;
  EXPECT_EQ(circleOurs.next, circleTheirs.next);
}

TEST(Arguments, ParsesDefaultsRangesAndUsageErrors) {
  app::CommandSpec spec;
  spec.name = "demo";
  spec.positionals = {{"input", "", app::Role::InputFile}, {"output", "", app::Role::OutputFile}};
  spec.options = {app::option("-tr", app::ValueType::Real, "<m>", "cell size").byDefault("12").atLeast(1e-9),
                  app::option("-te", app::ValueType::Real, "<xmin ymin xmax ymax>", "extent").values(4)};
  app::ParsedArgs a = app::parseArguments(spec, {"in", "-te", "0", "-5", "10", "10", "out"});
  EXPECT_DOUBLE_EQ(a.real("-tr"), 12.0);
  EXPECT_FALSE(a.given("-tr"));
  EXPECT_EQ(a.values("-te").size(), 4u);
  EXPECT_EQ(a.positionals(), (std::vector<std::string>{"in", "out"}));
  EXPECT_THROW(app::parseArguments(spec, {"in", "out", "-bogus"}), app::UsageError);
  EXPECT_THROW(app::parseArguments(spec, {"in"}), app::UsageError);
  EXPECT_THROW(app::parseArguments(spec, {"in", "out", "-tr", "abc"}), app::UsageError);
  // Out-of-range and non-finite values are usage errors (exit 2), like an unknown enum value.
  try {
    app::parseArguments(spec, {"in", "out", "-tr", "0"});
    FAIL();
  } catch (const app::UsageError& e) {
    EXPECT_STREQ(e.what(), "-tr must be at least 1e-09, got 0");
  }
  for (const char* nonFinite : {"nan", "inf", "-inf", "1e999"}) {
    try {
      app::parseArguments(spec, {"in", "out", "-tr", nonFinite});
      ADD_FAILURE() << nonFinite;
    } catch (const app::UsageError& e) {
      EXPECT_EQ(std::string(e.what()), std::string("-tr expects a finite number, got '") + nonFinite + "'");
    }
  }
}

#include "urbanvec/core/geos.hpp"

TEST(Geos, RoundTripsPolygonWithHoleAndComputesArea) {
  geos::Context ctx;
  Polygon p{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{2, 2}, {2, 4}, {4, 4}, {4, 2}}}};
  geos::GeomPtr g = ctx.polygon(p);
  double a = 0;
  GEOSArea_r(ctx.handle(), g.get(), &a);
  EXPECT_DOUBLE_EQ(a, 96.0);
  MultiPolygon back = ctx.toPolygons(g.get());
  ASSERT_EQ(back.size(), 1u);
  EXPECT_DOUBLE_EQ(area(back[0]), 96.0);
  EXPECT_EQ(back[0].outer.size(), 5u);  // closed
}

// Context::withinDistance stands in for GEOSPreparedDistanceWithin (D3's inside test against the
// perimeter ring, issue 21): the same answer for pieces apart, touching, at exactly the distance, inside
// the prepared polygon, inside its hole, and around it; and for points near a prepared ring.
TEST(Geos, WithinDistanceAgreesWithPreparedDistanceWithin) {
  geos::Context ctx;
  GEOSContextHandle_t h = ctx.handle();
  const Polygon block{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{4, 4}, {4, 6}, {6, 6}, {6, 4}}}};
  geos::GeomPtr g = ctx.polygon(block);
  const GEOSPreparedGeometry* prepared = GEOSPrepare_r(h, g.get());
  ASSERT_NE(prepared, nullptr);
  auto square = [](double x, double y, double s) {
    return Polygon{{{x, y}, {x + s, y}, {x + s, y + s}, {x, y + s}}, {}};
  };
  struct Case {
    Polygon piece;
    bool within;
  };
  const std::vector<Case> cases = {
      {square(13, 0, 1), true},                                           // 3 apart, exactly the distance
      {square(13.001, 0, 1), false},                                      // just beyond
      {square(10, 2, 1), true},                                           // touching
      {square(1, 1, 1), true},                                            // inside the block
      {square(4.5, 4.5, 1), false},                                       // in the hole, 0.5 from it: > 0.4
      {Polygon{{{-20, -20}, {30, -20}, {30, 30}, {-20, 30}}, {}}, true},  // around the block
      {Polygon{{{-20, -20}, {30, -20}, {30, 30}, {-20, 30}}, {{{-5, -5}, {-5, 15}, {15, 15}, {15, -5}}}},
       false},  // the block in its hole, 5 away
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const double d = i == 4 ? 0.4 : 3.0;
    geos::GeomPtr piece = ctx.polygon(cases[i].piece);
    EXPECT_EQ(GEOSPreparedDistanceWithin_r(h, prepared, piece.get(), d) == 1, cases[i].within)
        << "case " << i;
    EXPECT_EQ(ctx.withinDistance(prepared, piece.get(), d), cases[i].within) << "case " << i;
  }
  GEOSPreparedGeom_destroy_r(h, prepared);
  // D3 asks it of points against the prepared boundary ring of the perimeter.
  geos::GeomPtr ring = ctx.own(GEOSBoundary_r(h, g.get()), "boundary");
  const GEOSPreparedGeometry* preparedRing = GEOSPrepare_r(h, ring.get());
  ASSERT_NE(preparedRing, nullptr);
  const std::vector<std::pair<Vec2, double>> points = {{{5, 5}, 1.0},   {{5, 5}, 0.99},   {{5, 3}, 1.0},
                                                       {{5, 3}, 0.999}, {{12, 12}, 2.83}, {{12, 12}, 2.82},
                                                       {{0, 0}, 0.0}};
  for (const auto& [p, d] : points) {
    geos::GeomPtr pt = ctx.point(p);
    EXPECT_EQ(ctx.withinDistance(preparedRing, pt.get(), d),
              GEOSPreparedDistanceWithin_r(h, preparedRing, pt.get(), d) == 1)
        << p.x << " " << p.y << " " << d;
  }
  GEOSPreparedGeom_destroy_r(h, preparedRing);
}
