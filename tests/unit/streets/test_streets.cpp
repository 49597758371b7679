// Tensor field and street tracing (spec chen-streets.md §19 acceptance checks) on scenes with known
// answers.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <vector>

#include "urbanvec/core/error.hpp"
#include "urbanvec/streets/generate_streets.hpp"
#include "urbanvec/streets/graph_noise.hpp"
#include "urbanvec/streets/polygon_index.hpp"
#include "urbanvec/streets/street_metrics.hpp"
#include "urbanvec/streets/tensor_field.hpp"

using namespace urbanvec;
using namespace urbanvec::streets;

namespace {

/// Angle between two directions modulo pi, in degrees.
double lineAngleDeg(double a, double b) {
  double d = std::fmod(std::abs(a - b), M_PI);
  return std::min(d, M_PI - d) * 180.0 / M_PI;
}

MultiPolygon square(double x0, double y0, double side) {
  return {{{{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}, {x0, y0}}, {}}};
}

/// A scene of one grid element at `degrees` (counter-clockwise from east) inside `boundary`.
StreetsInput oneGridElement(const MultiPolygon& boundary, const Vec2& at, double degrees) {
  StreetsInput in;
  in.boundary = boundary;
  DesignElement e;
  e.position = at;
  e.angle = degrees * M_PI / 180.0;
  in.design = {e};
  return in;
}

StreetsOptions quiet() {
  StreetsOptions o;
  o.field.noiseAmplitude = 0.0;
  o.noise.fullShare = 0.0;
  o.noise.partialShare = 0.0;
  o.noise.bendShare = 0.0;
  o.trace.stopShortShare = 0.0;
  o.bow.ratio = 0.0;
  return o;
}

/// A traced grid: one grid element at `degrees` in the square [0, side]², no noise of any kind, major
/// and minor d_sep as given; `tweak` then sets the option under test.
StreetNetwork tracedGrid(double side, double degrees, double majorDsep, double minorDsep,
                         const std::function<void(StreetsOptions&)>& tweak) {
  StreetsOptions o = quiet();
  o.trace.majorDsep = majorDsep;
  o.trace.minorDsep = minorDsep;
  tweak(o);
  return generateStreets(oneGridElement(square(0, 0, side), {side / 2, side / 2}, degrees), o);
}

/// Streets that touch or cross each other anywhere but at shared end points.
int improperContacts(const std::vector<LineString>& lines) {
  int bad = 0;
  for (std::size_t i = 0; i < lines.size(); ++i)
    for (std::size_t j = i + 1; j < lines.size(); ++j)
      for (std::size_t a = 0; a + 1 < lines[i].size(); ++a)
        for (std::size_t b = 0; b + 1 < lines[j].size(); ++b) {
          const Vec2 p = lines[i][a], q = lines[i][a + 1], r = lines[j][b], t = lines[j][b + 1];
          if (std::max(p.x, q.x) < std::min(r.x, t.x) || std::max(r.x, t.x) < std::min(p.x, q.x) ||
              std::max(p.y, q.y) < std::min(r.y, t.y) || std::max(r.y, t.y) < std::min(p.y, q.y))
            continue;
          const double d = std::min({distanceToSegment(p, r, t), distanceToSegment(q, r, t),
                                     distanceToSegment(r, p, q), distanceToSegment(t, p, q)});
          const bool sharedEnd =
              (a == 0 && (p == lines[j].front() || p == lines[j].back())) ||
              (a + 2 == lines[i].size() && (q == lines[j].front() || q == lines[j].back()));
          const double o1 = cross(q - p, r - p), o2 = cross(q - p, t - p), o3 = cross(t - r, p - r),
                       o4 = cross(t - r, q - r);
          const bool crossing =
              ((o1 > 0) != (o2 > 0)) && ((o3 > 0) != (o4 > 0)) && o1 != 0 && o2 != 0 && o3 != 0 && o4 != 0;
          if (crossing || (d == 0.0 && !sharedEnd)) ++bad;
        }
  return bad;
}

}  // namespace

TEST(Tensor, RoundTripAndPeriodicity) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(0.0, 2 * M_PI), mag(0.1, 10.0);
  for (int i = 0; i < 1000; ++i) {
    const double theta = angle(rng), r = mag(rng);
    const Tensor t = Tensor::fromAngle(theta, r);
    EXPECT_NEAR(t.magnitude(), r, 1e-10 * r);
    EXPECT_LT(lineAngleDeg(t.angle(), theta), 1e-8);
    const Tensor u = Tensor::fromAngle(theta + M_PI, r);
    EXPECT_NEAR(t.a, u.a, 1e-9);
    EXPECT_NEAR(t.b, u.b, 1e-9);
    // From a direction vector (Eq. 1 without trigonometry), including ux = 0.
    const Tensor v = Tensor::fromDirection({std::cos(theta) * r, std::sin(theta) * r});
    EXPECT_NEAR(v.a, t.a, 1e-9);
    EXPECT_NEAR(v.b, t.b, 1e-9);
  }
  const Tensor vertical = Tensor::fromDirection({0.0, 2.0});
  EXPECT_LT(lineAngleDeg(vertical.angle(), M_PI / 2), 1e-12);
}

TEST(Tensor, RadialElementHasCircularMajorAndRadialMinor) {
  DesignElement e;
  e.kind = ElementKind::Radial;
  e.position = {100, 200};
  e.size = 1.0;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-500, 500);
  for (int i = 0; i < 1000; ++i) {
    const Vec2 p{100 + u(rng), 200 + u(rng)};
    const Vec2 r = p - e.position;
    const Tensor t = basisTensor(e, p);
    EXPECT_LT(std::abs(dot(t.major(), r)) / length(r), 1e-9);
    EXPECT_LT(std::abs(cross(t.minor(), r)), 1e-9 * length(r));
    EXPECT_NEAR(t.magnitude(), dot(r, r), 1e-12 * dot(r, r));
  }
}

TEST(TensorField, HeightFieldMinorFollowsTheGradient) {
  // H = 0.03 x + 0.04 y on a 10 m raster: minor ∥ (3, 4), major ∥ (−4, 3), R = slope 0.05.
  HeightMap dem;
  dem.spec.width = dem.spec.height = 100;
  dem.spec.transform.c = {0, 10, 0, 1000, 0, -10};
  dem.heights = Grid<float>(100, 100);
  for (int r = 0; r < 100; ++r)
    for (int c = 0; c < 100; ++c) {
      const Vec2 w = dem.spec.cellCentre(c, r);
      dem.heights.at(c, r) = static_cast<float>(0.03 * w.x + 0.04 * w.y);
    }
  FieldOptions o;
  o.cellSize = 20;
  o.heightWeight = 1.0;
  o.noiseAmplitude = 0;
  o.smoothingIterations = 0;
  const TensorField f = buildField({200, 200}, {800, 800}, {}, &dem, o);
  const Tensor t = f.sample({500, 500});
  EXPECT_LT(lineAngleDeg(t.angle(), std::atan2(3.0, -4.0)), 0.01);
  EXPECT_LT(lineAngleDeg(std::atan2(t.minor().y, t.minor().x), std::atan2(4.0, 3.0)), 0.01);
  EXPECT_NEAR(t.magnitude(), 0.05, 1e-4);
}

TEST(TensorField, Eq3BlendingIsLocalNearEachElement) {
  // Two grid elements at 0 and 45 degrees 1000 m apart with d D^2 = 20.
  const double D = 1000.0, d = 20.0 / (D * D);
  DesignElement a, b;
  a.position = {0, 0}, a.angle = 0.0, a.decay = d;
  b.position = {D, 0}, b.angle = M_PI / 4, b.decay = d;
  FieldOptions o;
  o.cellSize = 10;
  o.smoothingIterations = 0;
  o.noiseAmplitude = 0;
  const TensorField f = buildField({-200, -200}, {D + 200, 200}, {a, b}, nullptr, o);
  EXPECT_LT(lineAngleDeg(f.sample({0.05 * D, 0}).angle(), 0.0), 0.5);
  EXPECT_LT(lineAngleDeg(f.sample({0.95 * D, 0}).angle(), M_PI / 4), 0.5);
  // Monotonic in between.
  double last = -1.0;
  for (double x = 0; x <= D; x += D / 50) {
    const double ang = f.sample({x, 0}).angle();
    EXPECT_GE(ang, last - 1e-9);
    last = ang;
  }
  EXPECT_THROW(buildField({0, 0}, {1, 1}, {}, nullptr, o), Error);
}

TEST(Streets, GridSceneIsAGridOfFourWayCrossings) {
  // One grid element at 30 degrees, major roads only, no noise: both families straight at 30 and 120
  // degrees, spaced d_sep; interior crossings are 4-way.
  const StreetsInput in = oneGridElement(square(0, 0, 3000), {1500, 1500}, 30.0);
  const DesignElement& e = in.design.front();
  StreetsOptions o = quiet();
  o.trace.majorDsep = 200;
  o.trace.minorDsep = 100;
  o.trace.minorRoads = false;
  const StreetNetwork net = generateStreets(in, o);
  ASSERT_GT(net.streets.size(), 50u);
  for (const StreetEdge& s : net.streets)
    for (std::size_t i = 0; i + 1 < s.line.size(); ++i) {
      const Vec2 d = s.line[i + 1] - s.line[i];
      if (length(d) < 1.0) continue;
      const double ang = std::atan2(d.y, d.x);
      EXPECT_LT(std::min(lineAngleDeg(ang, e.angle), lineAngleDeg(ang, e.angle + M_PI / 2)), 0.5);
    }
  int interior = 0, fourWay = 0;
  for (const StreetNode& n : net.nodes) {
    if (n.p.x < 200 || n.p.y < 200 || n.p.x > 2800 || n.p.y > 2800) continue;
    ++interior;
    fourWay += n.degree == 4;
  }
  ASSERT_GT(interior, 50);
  EXPECT_GE(fourWay, 0.95 * interior);
  // Spacing: 3000² m² / (200 m)² = 225 blocks, minus those cut by the boundary.
  const StreetMetrics m = measureStreets(
      [&] {
        std::vector<LineString> l;
        for (const StreetEdge& s : net.streets) l.push_back(s.line);
        return l;
      }(),
      {}, square(300, 300, 2400));
  EXPECT_NEAR(m.medianEdgeLength, 200.0, 10.0);
  EXPECT_NEAR(m.orientationEntropy, std::log(4.0), 1e-9);
}

TEST(Streets, NoStreetIsSeededOnTheBoundary) {
  // A grid element at 10 degrees in a slanted boundary (a kite): every street is clipped at the
  // boundary, and the seeds placed along it start at that clipped end, which lies on the edge up to
  // rounding. A street of the other family traced from there meets the clipped one at a right-angle
  // corner on the boundary, merged into one street through it. With the edge-seed rule no street
  // touches the boundary except at its own ends.
  const Ring kite{{1000, 0}, {2100, 900}, {1000, 2000}, {-100, 1100}, {1000, 0}};
  auto cornersOnBoundary = [&](double edgeSeedRatio) {
    const StreetsInput in = oneGridElement({{kite, {}}}, {1000, 1000}, 10.0);
    StreetsOptions o = quiet();
    o.trace.majorDsep = 150;
    o.trace.minorRoads = false;
    o.trace.edgeSeedRatio = edgeSeedRatio;
    const StreetNetwork net = generateStreets(in, o);
    int corners = 0;
    for (const StreetEdge& s : net.streets)
      for (std::size_t i = 1; i + 1 < s.line.size(); ++i) {
        double d = 1e300;
        for (std::size_t k = 0; k + 1 < kite.size(); ++k)
          d = std::min(d, distanceToSegment(s.line[i], kite[k], kite[k + 1]));
        corners += d < 1e-6;
      }
    return corners;
  };
  EXPECT_GT(cornersOnBoundary(0.0), 0);
  EXPECT_EQ(cornersOnBoundary(1.0), 0);
}

TEST(Streets, NoStreetInWaterAllInsideBoundaryEveryCrossingANode) {
  StreetsInput in;
  in.boundary = square(0, 0, 2000);
  in.water = {{{{700, -100}, {1000, -100}, {1100, 2100}, {800, 2100}, {700, -100}}, {}}};  // a river
  DesignElement e;
  e.position = {300, 300};
  e.angle = 0.3;
  in.design = {e};
  StreetsOptions o;  // defaults: noise and graph noise on
  o.trace.majorDsep = 240;
  o.trace.minorDsep = 80;
  const StreetNetwork net = generateStreets(in, o);
  ASSERT_GT(net.streets.size(), 30u);
  const PolygonIndex water(in.water);
  for (const StreetEdge& s : net.streets) {
    EXPECT_GT(length(s.line), 0.0);
    for (std::size_t i = 0; i + 1 < s.line.size(); ++i) {
      const Vec2 mid = (s.line[i] + s.line[i + 1]) * 0.5;
      EXPECT_FALSE(water.contains(mid)) << mid.x << " " << mid.y;
      EXPECT_GE(mid.x, -1e-6);
      EXPECT_LE(mid.x, 2000 + 1e-6);
      EXPECT_GE(mid.y, -1e-6);
      EXPECT_LE(mid.y, 2000 + 1e-6);
    }
  }
  // Re-noding the output adds no node: every crossing already is one.
  std::vector<LineString> lines;
  for (const StreetEdge& s : net.streets) lines.push_back(s.line);
  const SimplifiedNetwork again = simplifyNetwork(lines, {});
  std::size_t chainEnds = 0;
  for (int n = 0; n < static_cast<int>(again.graph.nodeCount()); ++n) chainEnds += again.graph.degree(n) != 2;
  std::size_t outputEnds = 0;
  for (const StreetNode& n : net.nodes) outputEnds += n.degree != 2;
  EXPECT_EQ(chainEnds, outputEnds);
  // Blocks lie on land and their areas add up to at most the land area.
  double blockArea = 0.0;
  for (const Block& b : net.blocks) {
    blockArea += area(b.shape);
    EXPECT_EQ(b.landUse, "residential");
  }
  // The river covers 0.6 km² of the 4 km²: blocks fill most of the rest and none of it.
  EXPECT_GT(blockArea, 0.8 * (4e6 - 6e5));
  EXPECT_LE(blockArea, (4e6 - 6e5) * (1.0 + 1e-6));
}

TEST(Streets, DeterministicForAnyThreadCount) {
  StreetsInput in;
  in.boundary = square(0, 0, 1500);
  DesignElement g, r;
  g.position = {400, 400}, g.angle = 0.5;
  r.kind = ElementKind::Radial, r.position = {1100, 1000}, r.size = 200;
  in.design = {g, r};
  StreetsOptions o;
  o.trace.majorDsep = 200;
  o.trace.minorDsep = 80;
  o.field.threads = 1;
  const StreetNetwork a = generateStreets(in, o);
  o.field.threads = 3;
  const StreetNetwork b = generateStreets(in, o);
  ASSERT_EQ(a.streets.size(), b.streets.size());
  for (std::size_t i = 0; i < a.streets.size(); ++i) ASSERT_EQ(a.streets[i].line, b.streets[i].line);
  // Another seed moves the noise and the graph noise.
  o.seed = 2;
  const StreetNetwork c = generateStreets(in, o);
  bool differs = c.streets.size() != a.streets.size();
  for (std::size_t i = 0; !differs && i < a.streets.size(); ++i)
    differs = a.streets[i].line != c.streets[i].line;
  EXPECT_TRUE(differs);
}

TEST(Streets, OneSeedDrivesEveryRandomStage) {
  // StreetsOptions::seed alone, the stages' own seed fields left as they are: each random stage on its
  // own (field noise, stopping short, graph noise, bows) draws otherwise for another seed (1000: the
  // graph noise starts its Halton points at 1 + seed, so seeds 1 and 2 share all but one point).
  const std::vector<std::function<void(StreetsOptions&)>> stages = {
      [](StreetsOptions& o) { o.field.noiseAmplitude = StreetsOptions{}.field.noiseAmplitude; },
      [](StreetsOptions& o) { o.trace.stopShortShare = 0.5; },
      [](StreetsOptions& o) { o.noise.fullShare = 0.3; },
      [](StreetsOptions& o) { o.bow.ratio = BowOptions{}.ratio; }};
  for (std::size_t k = 0; k < stages.size(); ++k) {
    auto run = [&](std::uint64_t seed) {
      return tracedGrid(1500, 20.0, 200, 100, [&](StreetsOptions& o) {
        stages[k](o);
        o.seed = seed;
      });
    };
    const StreetNetwork a = run(1), b = run(1), c = run(1000);
    ASSERT_EQ(a.streets.size(), b.streets.size()) << "stage " << k;
    bool same = true, differs = a.streets.size() != c.streets.size();
    for (std::size_t i = 0; i < a.streets.size(); ++i) same = same && a.streets[i].line == b.streets[i].line;
    for (std::size_t i = 0; !differs && i < a.streets.size(); ++i)
      differs = a.streets[i].line != c.streets[i].line;
    EXPECT_TRUE(same) << "stage " << k;
    EXPECT_TRUE(differs) << "stage " << k << ": seed 1000 draws as seed 1";
  }
}

TEST(Streets, LookAheadTurnsDanglingEndsIntoJunctions) {
  // Two grid elements at different angles: lines converge and stop; look-ahead joins them.
  StreetsInput in;
  in.boundary = square(0, 0, 2000);
  DesignElement a, b;
  a.position = {300, 1000}, a.angle = 0.0, a.decay = 1.0 / (600.0 * 600.0);
  b.position = {1700, 1000}, b.angle = 0.6, b.decay = 1.0 / (600.0 * 600.0);
  in.design = {a, b};
  StreetsOptions o = quiet();
  o.trace.majorDsep = 200;
  o.trace.minorDsep = 100;
  auto deadEnds = [&](double ratio) {
    o.trace.lookaheadRatio = ratio;
    const StreetNetwork net = generateStreets(in, o);
    int dead = 0;
    for (const StreetNode& n : net.nodes)
      dead += n.degree == 1 && n.p.x > 1 && n.p.y > 1 && n.p.x < 1999 && n.p.y < 1999;
    return dead;
  };
  const int without = deadEnds(0.0), with = deadEnds(1.0);
  EXPECT_LT(with, without);
}

TEST(Streets, BadInputIsRefused) {
  StreetsInput in;
  in.boundary = square(0, 0, 1000);
  StreetsOptions o;
  EXPECT_THROW(generateStreets(in, o), Error);  // empty design
  DesignElement e;
  e.position = {2000, 2000};
  in.design = {e};
  EXPECT_THROW(generateStreets(in, o), Error);  // outside the boundary
  in.design[0].position = {500, 500};
  o.trace.dtestRatio = 1.5;
  EXPECT_THROW(generateStreets(in, o), Error);  // d_test > d_sep
  o.trace.dtestRatio = 0.5;
  o.trace.minorDsep = 0;
  EXPECT_THROW(generateStreets(in, o), Error);
  o.trace.minorDsep = 50;
  in.design.assign(o.maxDesignElements + 1, in.design[0]);
  EXPECT_THROW(generateStreets(in, o), Error);
  // Water over everything: an empty network, no error.
  in.design.resize(1);
  in.water = square(-10, -10, 1020);
  const StreetNetwork net = generateStreets(in, o);
  EXPECT_TRUE(net.streets.empty());
  EXPECT_TRUE(net.blocks.empty());
}

TEST(GraphNoise, HaltonAndCounts) {
  EXPECT_DOUBLE_EQ(halton(1, 2), 0.5);
  EXPECT_DOUBLE_EQ(halton(2, 2), 0.25);
  EXPECT_DOUBLE_EQ(halton(3, 2), 0.75);
  EXPECT_NEAR(halton(1, 3), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(halton(5, 3), 7.0 / 9.0, 1e-15);
  // A 10 x 10 grid of minor streets: 20 % of its 180 inner segments go, all ends stay crossings.
  std::vector<LineString> lines;
  for (int i = 0; i < 10; ++i) {
    lines.push_back({{i * 100.0, -50}, {i * 100.0, 950}});
    lines.push_back({{-50, i * 100.0}, {950, i * 100.0}});
  }
  const PlanarGraph g = PlanarGraph::fromLines(lines);
  std::vector<StreetLevel> levels(g.edgeCount(), StreetLevel::Minor);
  GraphNoiseOptions o;
  o.fullShare = 0.1;
  o.partialShare = 0.0;
  o.bendShare = 0.0;
  const std::vector<Street> kept = applyGraphNoise(g, levels, o);
  EXPECT_EQ(g.edgeCount() - kept.size(), static_cast<std::size_t>(std::lround(0.1 * g.edgeCount())));
  const StreetMetrics m = measureStreets(
      [&] {
        std::vector<LineString> l;
        for (const Street& s : kept) l.push_back(s.line);
        return l;
      }(),
      {});
  EXPECT_GT(m.share3Way, 0.2);
  EXPECT_NEAR(m.shareDeadEnd * m.nodes, 40.0, 1e-9);  // only the 40 original ends are dead ends
}

TEST(GraphNoise, BendsTurnTJunctionsIntoCorners) {
  // The 10 x 10 grid of minor streets after 10 % deletions has T-junctions but only straight edges
  // (circuity exactly 1); bends delete an arm of a T so the two streets left there meet at a right
  // angle: degree-2 corners, edges that turn, circuity above 1, and no new dead end.
  std::vector<LineString> lines;
  for (int i = 0; i < 10; ++i) {
    lines.push_back({{i * 100.0, -50}, {i * 100.0, 950}});
    lines.push_back({{-50, i * 100.0}, {950, i * 100.0}});
  }
  const PlanarGraph g = PlanarGraph::fromLines(lines);
  const std::vector<StreetLevel> levels(g.edgeCount(), StreetLevel::Minor);
  auto measure = [&](double bendShare, std::size_t* removed, int* corners) {
    GraphNoiseOptions o;
    o.fullShare = 0.1;
    o.partialShare = 0.0;
    o.bendShare = bendShare;
    const std::vector<Street> kept = applyGraphNoise(g, levels, o);
    *removed = g.edgeCount() - kept.size();
    std::vector<LineString> l;
    for (const Street& s : kept) l.push_back(s.line);
    // Corners: degree-2 nodes whose two edges meet at a right angle.
    const PlanarGraph k = PlanarGraph::fromLines(l);
    *corners = 0;
    for (int n = 0; n < static_cast<int>(k.nodeCount()); ++n) {
      if (k.degree(n) != 2) continue;
      Vec2 d[2];
      for (int i = 0; i < 2; ++i) {
        const int e = k.node(n).edges[static_cast<std::size_t>(i)];
        d[i] =
            (k.edge(e).a == n ? k.edge(e).line[1] : k.edge(e).line[k.edge(e).line.size() - 2]) - k.node(n).p;
      }
      if (std::abs(dot(d[0], d[1])) < 1e-9 * length(d[0]) * length(d[1])) ++*corners;
    }
    return measureStreets(l, {});
  };
  std::size_t removedStraight = 0, removedBent = 0;
  int cornersStraight = 0, cornersBent = 0;
  const StreetMetrics straight = measure(0.0, &removedStraight, &cornersStraight);
  const StreetMetrics bent = measure(0.1, &removedBent, &cornersBent);
  EXPECT_DOUBLE_EQ(straight.circuity, 1.0);
  EXPECT_EQ(cornersStraight, 0);
  const auto bends = static_cast<std::size_t>(std::lround(0.1 * g.edgeCount()));
  EXPECT_EQ(removedBent - removedStraight, bends);
  // Each bend leaves a corner where it was taken (a T-junction whose two other streets turn).
  EXPECT_GE(static_cast<std::size_t>(cornersBent), bends);
  // Every bend is a right-angle corner merged into one edge: legs of 100 m give 200 / (100 sqrt 2).
  EXPECT_GT(bent.circuity, 1.02);
  EXPECT_NEAR(bent.shareDeadEnd * bent.nodes, 40.0, 1e-9);
  EXPECT_LT(bent.share3Way * bent.nodes, straight.share3Way * straight.nodes);
}

TEST(GraphNoise, BowsCurveStreetsBetweenFixedNodes) {
  // A 6 x 6 grid of 100 m pieces (traced streets), one existing road and an outline, and two parallel
  // streets 2 m apart whose bows towards each other would cross: bows keep every end, curve the traced
  // pieces (a half sine of relative amplitude r adds about (pi r)^2 / 4 to the circuity), leave the
  // other pieces alone and never make a contact.
  std::vector<Street> pieces;
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 5; ++k) {
      pieces.push_back({{{i * 100.0, k * 100.0}, {i * 100.0, k * 100.0 + 100.0}}, StreetLevel::Minor, 0});
      pieces.push_back({{{k * 100.0, i * 100.0}, {k * 100.0 + 100.0, i * 100.0}}, StreetLevel::Major, 0});
    }
  pieces.push_back({{{700, 0}, {700, 500}}, StreetLevel::Existing, 0});
  pieces.push_back({{{-10, -10}, {510, -10}}, StreetLevel::Outline, 0});
  pieces.push_back({{{800, 0}, {800, 100}}, StreetLevel::Minor, 0});
  pieces.push_back({{{802, 0}, {802, 100}}, StreetLevel::Minor, 0});
  const std::vector<Street> before = pieces;
  BowOptions o;
  o.ratio = 0.2;
  o.maxOffset = 30.0;
  bowStreets(pieces, o);
  ASSERT_EQ(pieces.size(), before.size());
  double len = 0.0, chord = 0.0;
  int bowed = 0;
  std::vector<LineString> lines;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    EXPECT_EQ(pieces[i].line.front(), before[i].line.front());
    EXPECT_EQ(pieces[i].line.back(), before[i].line.back());
    if (before[i].level == StreetLevel::Existing || before[i].level == StreetLevel::Outline)
      EXPECT_EQ(pieces[i].line, before[i].line);
    if (i < 60) {
      len += length(pieces[i].line);
      chord += distance(pieces[i].line.front(), pieces[i].line.back());
      bowed += pieces[i].line != before[i].line;
    }
    lines.push_back(pieces[i].line);
  }
  EXPECT_GT(bowed, 50);
  EXPECT_GT(len / chord, 1.01);
  EXPECT_LT(len / chord, 1.0 + std::pow(M_PI * 0.2, 2) / 4.0 + 1e-3);
  EXPECT_EQ(improperContacts(lines), 0);
  // The two close parallels: at most one of them bows, and then away from the other (or not at all).
  const double gapMid =
      std::abs(pieces[63].line[pieces[63].line.size() / 2].x - pieces[62].line[pieces[62].line.size() / 2].x);
  EXPECT_GT(gapMid, 0.0);
  // Deterministic, and another seed draws other bows.
  std::vector<Street> again = before, other = before;
  bowStreets(again, o);
  for (std::size_t i = 0; i < pieces.size(); ++i) EXPECT_EQ(again[i].line, pieces[i].line);
  o.seed = 2;
  bowStreets(other, o);
  bool differs = false;
  for (std::size_t i = 0; i < pieces.size(); ++i) differs = differs || other[i].line != pieces[i].line;
  EXPECT_TRUE(differs);
}

TEST(Streets, BowsRaiseTheCircuityOfATracedGrid) {
  // A traced grid (one grid element, no field noise) has straight streets, circuity 1; bows curve them
  // between their nodes: the same nodes, circuity above Boeing's 5th percentile (1.02), no contact.
  auto run = [](double ratio) {
    return tracedGrid(2000, 20.0, 200, 100, [&](StreetsOptions& o) { o.bow.ratio = ratio; });
  };
  const StreetNetwork straight = run(0.0), bowed = run(BowOptions{}.ratio);
  auto metricsOf = [](const StreetNetwork& n) {
    std::vector<LineString> l;
    for (const StreetEdge& s : n.streets) l.push_back(s.line);
    return measureStreets(l, {});
  };
  const StreetMetrics a = metricsOf(straight), b = metricsOf(bowed);
  EXPECT_LT(a.circuity, 1.001);
  EXPECT_GT(b.circuity, 1.02);
  // Bows of u x ratio x chord, u uniform in [-1, 1], add about pi^2 ratio^2 / 12 (a few are halved).
  const double r = BowOptions{}.ratio;
  EXPECT_NEAR(b.circuity - 1.0, M_PI * M_PI * r * r / 12.0, 0.008);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_DOUBLE_EQ(a.share4Way, b.share4Way);
  ASSERT_EQ(straight.nodes.size(), bowed.nodes.size());
  for (std::size_t i = 0; i < straight.nodes.size(); ++i) EXPECT_EQ(straight.nodes[i].p, bowed.nodes[i].p);
  std::vector<LineString> l;
  for (const StreetEdge& s : bowed.streets) l.push_back(s.line);
  EXPECT_EQ(improperContacts(l), 0);
}

TEST(Streets, MajorClearanceFillsTheRegionsBetweenMajorRoads) {
  // A grid design with d_sep_minor = d_sep_major / 2 (the default ratio) and the field's default noise:
  // the one minor road a region between two major roads can hold lies d_sep_minor from both, so with
  // the full d_sep as clearance most regions stay empty and the nodes are mostly major crossings;
  // keeping only d_test (0.5) from the major roads fills them with minor roads ending in T-junctions.
  auto run = [](double clearance) {
    StreetsOptions o = quiet();
    o.field.noiseAmplitude = StreetsOptions{}.field.noiseAmplitude;
    o.trace.majorDsep = 200;
    o.trace.minorDsep = 100;
    o.trace.majorClearanceRatio = clearance;
    const StreetNetwork n = generateStreets(oneGridElement(square(0, 0, 2000), {1000, 1000}, 20.0), o);
    int three = 0, four = 0, minor = 0;
    for (const StreetNode& v : n.nodes) three += v.degree == 3, four += v.degree == 4;
    for (const StreetEdge& s : n.streets) minor += s.level == StreetLevel::Minor;
    return std::make_tuple(three, four, minor);
  };
  const auto [three1, four1, minor1] = run(1.0);
  const auto [three05, four05, minor05] = run(0.5);
  // Measured 164 -> 410 minor streets, 176 -> 341 T-junctions, 4-way share of the junctions 0.39 -> 0.36.
  EXPECT_GT(minor05, 2 * minor1);
  EXPECT_GT(three05, 1.6 * three1);
  EXPECT_LT(static_cast<double>(four05) / (three05 + four05),
            static_cast<double>(four1) / (three1 + four1) - 0.02);
}

TEST(Streets, StopShortLeavesDeadEndsWhereStreetsWouldJoin) {
  // A traced grid has no dead end inside: every minor road ends on a major road. With a stop-short
  // share s, about s of those ends stop d_test short of the road instead (dead ends), d_test from it.
  auto run = [](double share) {
    return tracedGrid(3000, 20.0, 300, 100, [&](StreetsOptions& o) { o.trace.stopShortShare = share; });
  };
  auto inside = [](const Vec2& p) { return p.x > 150 && p.y > 150 && p.x < 2850 && p.y < 2850; };
  auto count = [&](const StreetNetwork& n, int degree) {
    int k = 0;
    for (const StreetNode& v : n.nodes) k += v.degree == degree && inside(v.p);
    return k;
  };
  const StreetNetwork none = run(0.0), some = run(0.3);
  const int tees = count(none, 3);
  ASSERT_GT(tees, 100);
  EXPECT_EQ(count(none, 1), 0);
  const int dead = count(some, 1);
  EXPECT_GT(dead, 0.15 * tees);
  EXPECT_LT(dead, 0.45 * tees);
  // Each dead end lies d_test (50 m) short of the street it would have met: no street closer than
  // 40 m other than its own.
  for (const StreetNode& v : some.nodes) {
    if (v.degree != 1 || !inside(v.p)) continue;
    double nearest = 1e300;
    for (const StreetEdge& s : some.streets) {
      if (s.line.front() == v.p || s.line.back() == v.p) continue;
      for (std::size_t i = 0; i + 1 < s.line.size(); ++i)
        nearest = std::min(nearest, distanceToSegment(v.p, s.line[i], s.line[i + 1]));
    }
    EXPECT_GT(nearest, 40.0) << v.p.x << " " << v.p.y;
  }
  // However many ends stop short, no street is cut off: the network stays one connected piece.
  auto pieces = [](const StreetNetwork& n) {
    std::map<std::pair<double, double>, int> id;
    std::vector<int> parent;
    auto node = [&](const Vec2& p) {
      const auto [it, added] = id.emplace(std::make_pair(p.x, p.y), static_cast<int>(parent.size()));
      if (added) parent.push_back(it->second);
      return it->second;
    };
    std::function<int(int)> root = [&](int i) { return parent[i] == i ? i : parent[i] = root(parent[i]); };
    for (const StreetEdge& s : n.streets) parent[root(node(s.line.front()))] = root(node(s.line.back()));
    int roots = 0;
    for (int i = 0; i < static_cast<int>(parent.size()); ++i) roots += root(i) == i;
    return roots;
  };
  EXPECT_EQ(pieces(none), 1);
  EXPECT_EQ(pieces(run(1.0)), 1);
}

TEST(Streets, RoadSpacingIsThatOfAGridWithAsMuchRoad) {
  // Roads every 200 m across a 1000 m square (x, y = 100, 300, ..., 900): 2 A / L = 200 m; their parts
  // outside the boundary do not count. With water over 620 <= x <= 980 only the land counts: 0.64 km²
  // and 3 verticals of 1000 m plus 5 horizontals of 620 + 20 m, 2 A / L = 1.28e6 / 6200.
  std::vector<LineString> roads;
  for (int i = 0; i < 5; ++i) {
    roads.push_back({{100.0 + 200 * i, -300}, {100.0 + 200 * i, 1300}});
    roads.push_back({{-300, 100.0 + 200 * i}, {1300, 100.0 + 200 * i}});
  }
  EXPECT_NEAR(roadSpacing(roads, square(0, 0, 1000), {}), 200.0, 1e-9);
  const MultiPolygon water{{{{620, -100}, {980, -100}, {980, 1100}, {620, 1100}, {620, -100}}, {}}};
  EXPECT_NEAR(roadSpacing(roads, square(0, 0, 1000), water), 1.28e6 / 6200.0, 1e-9);
  EXPECT_EQ(roadSpacing({{{2000, 0}, {3000, 0}}}, square(0, 0, 1000), {}), 0.0);
}

TEST(GraphNoise, BendsNeverLeaveARingOnOneSpur) {
  // A square ring (major) joined at (0, 0) by a spur from the west and at (100, 100) by a minor street
  // to a crossing street at x = 200. Deleting the minor street would turn the corner at (100, 100),
  // but it would leave the ring on its one spur: a street from (0, 0) round to (0, 0), chord 0. So no
  // bend is taken, and no street of the result is a loop.
  const std::vector<LineString> lines{{{0, 0}, {100, 0}, {100, 100}, {0, 100}, {0, 0}},
                                      {{-100, 0}, {0, 0}},
                                      {{100, 100}, {200, 100}},
                                      {{200, 0}, {200, 200}}};
  const PlanarGraph g = PlanarGraph::fromLines(lines);
  std::vector<StreetLevel> levels(g.edgeCount(), StreetLevel::Major);
  int minorEdges = 0;
  for (int e = 0; e < static_cast<int>(g.edgeCount()); ++e) {
    const LineString& l = g.edge(e).line;
    if ((l.front() == Vec2{100, 100} && l.back() == Vec2{200, 100}) ||
        (l.back() == Vec2{100, 100} && l.front() == Vec2{200, 100}))
      levels[static_cast<std::size_t>(e)] = StreetLevel::Minor, ++minorEdges;
  }
  ASSERT_EQ(minorEdges, 1);
  GraphNoiseOptions o;
  o.fullShare = 0.0;
  o.partialShare = 0.0;
  o.bendShare = 1.0;
  const std::vector<Street> kept = applyGraphNoise(g, levels, o);
  EXPECT_EQ(kept.size(), g.edgeCount());
  std::vector<LineString> l;
  for (const Street& s : kept) l.push_back(s.line);
  const PlanarGraph k = PlanarGraph::fromLines(l);
  for (const std::vector<int>& chain : k.chains()) {
    const std::vector<int> ends = k.chainNodes(chain);
    EXPECT_NE(ends.front(), ends.back());
  }
}

TEST(Streets, DensityAndParksWidenTheSpacing) {
  // A density ramp, 0 on the westmost 500 m and rising to 1 in the east: blocks are larger where
  // density is low (spec §19.2 check 22); then a park over the north half.
  StreetsInput in;
  in.boundary = square(0, 0, 3000);
  DesignElement e;
  e.position = {1500, 1500};
  in.design = {e};
  GridSpec spec;
  spec.width = spec.height = 30;
  spec.transform.c = {0, 100, 0, 3000, 0, -100};
  in.densitySpec = spec;
  in.density = Grid<float>(30, 30);
  for (int r = 0; r < 30; ++r)
    for (int c = 0; c < 30; ++c) in.density.at(c, r) = std::max(0.0f, static_cast<float>(c - 5) / 24.0f);
  StreetsOptions o = quiet();
  o.trace.majorDsep = 240;
  o.trace.minorDsep = 80;
  const StreetNetwork net = generateStreets(in, o);
  double westArea = 0, eastArea = 0;
  int west = 0, east = 0;
  for (const Block& b : net.blocks) {
    Vec2 c;
    for (std::size_t i = 0; i + 1 < b.shape.outer.size(); ++i) c += b.shape.outer[i];
    c = c / static_cast<double>(b.shape.outer.size() - 1);
    if (c.x < 1000) westArea += area(b.shape), ++west;
    if (c.x > 2000) eastArea += area(b.shape), ++east;
  }
  ASSERT_GT(west, 0);
  ASSERT_GT(east, 0);
  // d_sep is about 2.5x in the west: mean blocks several times larger.
  EXPECT_GT(westArea / west, 2.0 * eastArea / east);
  // Blocks where the raster is 0 (the westmost 500 m) get the empty use; others residential.
  bool unused = false;
  for (const Block& b : net.blocks) unused |= b.landUse == "unused";
  EXPECT_TRUE(unused);

  // A park over the north half: fewer streets there than in the south.
  StreetsInput withPark;
  withPark.boundary = in.boundary;
  withPark.design = in.design;
  withPark.parks = {{{{0, 1500}, {3000, 1500}, {3000, 3000}, {0, 3000}, {0, 1500}}, {}}};
  const StreetNetwork parked = generateStreets(withPark, o);
  double north = 0, south = 0;
  for (const StreetEdge& s : parked.streets)
    for (std::size_t i = 0; i + 1 < s.line.size(); ++i)
      ((s.line[i].y + s.line[i + 1].y) / 2 > 1500 ? north : south) += distance(s.line[i], s.line[i + 1]);
  EXPECT_LT(north, 0.75 * south);
  int parkBlocks = 0;
  for (const Block& b : parked.blocks) parkBlocks += b.landUse == "park";
  EXPECT_GT(parkBlocks, 0);
}

TEST(Streets, KeptRoadsStayAndTracedRoadsEndOnThem) {
  // Spec §14: an east-west road across the land and a north-south one stopping 300 m short of it are
  // kept; the traced roads grow around them, minor roads end on them, and the short one is continued
  // until it meets a street.
  StreetsInput in;
  in.boundary = square(0, 0, 2000);
  const LineString across{{0, 1000}, {700, 1040}, {1300, 1040}, {2000, 1100}};
  const LineString stopping{{1000, 0}, {1000, 700}};
  in.fieldLines = {across, stopping};
  in.existingRoads = in.fieldLines;
  StreetsOptions o = quiet();
  o.trace.majorDsep = 300;
  o.trace.minorDsep = 100;
  const StreetNetwork net = generateStreets(in, o);
  double kept = 0.0;
  for (const StreetEdge& s : net.streets)
    if (s.level == StreetLevel::Existing) kept += length(s.line);
  EXPECT_NEAR(kept, length(across) + length(stopping), 0.01);  // noded on a 1 cm grid
  // The short road no longer ends at (1000, 700).
  for (const StreetNode& n : net.nodes)
    if (distance(n.p, {1000, 700}) < 1.0) EXPECT_GE(n.degree, 2);
  // Junctions on the kept roads: the traced roads meeting them.
  int onKept = 0, tees = 0;
  for (const StreetNode& n : net.nodes) {
    const double d = std::min(distanceToSegment(n.p, {1000, 0}, {1000, 700}),
                              std::min(std::min(distanceToSegment(n.p, across[0], across[1]),
                                                distanceToSegment(n.p, across[1], across[2])),
                                       distanceToSegment(n.p, across[2], across[3])));
    if (d > 1e-6 || n.p.x < 1 || n.p.x > 1999 || n.p.y < 1 || n.p.y > 1999) continue;
    ++onKept;
    tees += n.degree == 3;
  }
  EXPECT_GE(onKept, 16) << tees;
  EXPECT_GE(tees, 0.7 * onKept);
  // Without keeping them, the roads only shape the field.
  in.existingRoads.clear();
  for (const StreetEdge& s : generateStreets(in, o).streets) EXPECT_NE(s.level, StreetLevel::Existing);
}

TEST(Streets, BlocksTakeGridifysUntaggedLandRule) {
  // One rule with gridify (issue 20): a block mostly edged by minor (residential) streets is
  // residential; one edged by major roads only takes the default use.
  StreetsInput in;
  in.boundary = square(0, 0, 2000);
  DesignElement e;
  e.position = {1000, 1000};
  in.design = {e};
  StreetsOptions o = quiet();
  o.trace.majorDsep = 400;
  o.trace.minorDsep = 100;
  o.defaultUse = "commercial";
  auto shares = [&] {
    const StreetNetwork net = generateStreets(in, o);
    double residential = 0, commercial = 0;
    for (const Block& b : net.blocks)
      (b.landUse == "residential"  ? residential
       : b.landUse == "commercial" ? commercial
                                   : residential) += area(b.shape);
    return std::make_pair(residential, commercial);
  };
  const auto [res, com] = shares();
  EXPECT_GT(res, 0.9 * (res + com));
  o.trace.minorRoads = false;
  const auto [res2, com2] = shares();
  EXPECT_EQ(res2, 0.0);
  EXPECT_NEAR(com2, 4e6, 1.0);
}
