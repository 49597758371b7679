// E1/E2 geometry: the four split constraints, spine parcels, frontage.
#include <gtest/gtest.h>

#include "parcel_fixtures.hpp"
#include "urbanvec/vectorize/parcels/regular_subdivision.hpp"
#include "urbanvec/vectorize/parcels/spine_subdivision.hpp"

using namespace urbanvec;
using namespace urbanvec::vectorize::parcels;

namespace {

Polygon box(double x0, double y0, double x1, double y1) {
  return Polygon{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}}, {}};
}

SplitRules looseRules() {
  SplitRules r;
  r.minArea = 0.0;
  r.minFrontage = 0.5;
  r.aspectThreshold = 0.25;
  r.residentialRule = false;
  r.minChildShare = 0.3;
  return r;
}

class Constraints : public ::testing::Test {
 protected:
  geos::Context geos;
  // A 4×4 parcel whose south side (y = 0) is the road.
  RoadFrontage road{geos, {{{-10, 0}, {10, 0}}}, 1e-4};
  Polygon parent = box(0, 0, 4, 4);
};

}  // namespace

TEST_F(Constraints, AnEvenCutAlongTheRoadIsAccepted) {
  EXPECT_EQ(checkSplit(parent, box(0, 0, 2, 4), box(2, 0, 4, 4), looseRules(), road), SplitVerdict::Accepted);
}

TEST_F(Constraints, MinimumSizeRejectsASmallChild) {
  SplitRules rules = looseRules();
  rules.minArea = 0.75 * 8.0;  // smallest simulated parcel of 8 cells
  EXPECT_EQ(checkSplit(parent, box(0, 0, 1.4, 4), box(1.4, 0, 4, 4), rules, road), SplitVerdict::TooSmall);
  EXPECT_EQ(checkSplit(parent, box(0, 0, 2, 4), box(2, 0, 4, 4), rules, road), SplitVerdict::Accepted);
}

TEST_F(Constraints, RoadAccessRejectsABackLot) {
  EXPECT_EQ(checkSplit(parent, box(0, 0, 4, 2), box(0, 2, 4, 4), looseRules(), road),
            SplitVerdict::NoRoadAccess);
  // 0.4 cell of frontage is not enough either.
  SplitRules rules = looseRules();
  rules.aspectThreshold = 0.0;
  EXPECT_EQ(checkSplit(parent, box(0, 0, 0.4, 4), box(0.4, 0, 4, 4), rules, road),
            SplitVerdict::NoRoadAccess);
  EXPECT_NEAR(road.longest(box(0, 0, 0.4, 4)), 0.4, 1e-3);
}

TEST_F(Constraints, RectangularityRejectsSlivers) {
  // Parent aspect 1 > 0.25: children must stay ≥ 0.25; 0.8×4 has 0.2.
  EXPECT_EQ(checkSplit(parent, box(0, 0, 0.8, 4), box(0.8, 0, 4, 4), looseRules(), road),
            SplitVerdict::TooRectangular);
  // Parent 8×1 (aspect 0.125 < 0.25): both children must increase it; 4×1 (0.25) does, a lengthwise
  // cut into two 8×0.5 strips (0.0625) does not.
  const Polygon wide = box(0, 0, 8, 1);
  const RoadFrontage around(geos, {wide.outer}, 1e-4);
  EXPECT_EQ(checkSplit(wide, box(0, 0, 4, 1), box(4, 0, 8, 1), looseRules(), around), SplitVerdict::Accepted);
  EXPECT_EQ(checkSplit(wide, box(0, 0, 8, 0.5), box(0, 0.5, 8, 1), looseRules(), around),
            SplitVerdict::TooRectangular);
}

TEST_F(Constraints, ResidentialBlocksRejectUnequalChildren) {
  SplitRules rules = looseRules();
  rules.residentialRule = true;
  // 1.1×4 is 27.5% of the parent (aspect 0.275 passes constraint 3).
  EXPECT_EQ(checkSplit(parent, box(0, 0, 1.1, 4), box(1.1, 0, 4, 4), rules, road),
            SplitVerdict::UnequalResidential);
  rules.residentialRule = false;
  EXPECT_EQ(checkSplit(parent, box(0, 0, 1.1, 4), box(1.1, 0, 4, 4), rules, road), SplitVerdict::Accepted);
}

TEST(SplitRulesFromSim, ResidentialRuleAndMinimumAreaComeFromTheSimulatedBlock) {
  SimBlockSummary sim;
  sim.area = 100;
  sim.parcels = {{1, LandUse::Residential, 70, 0, {}}, {2, LandUse::Commercial, 12, 0, {}}};
  RegularSubdivisionOptions options;
  SplitRules rules = splitRules(sim, options);
  EXPECT_TRUE(rules.residentialRule);
  EXPECT_DOUBLE_EQ(rules.minArea, 9.0);
  sim.parcels[0].cells = 69;
  EXPECT_FALSE(splitRules(sim, options).residentialRule);
}

TEST(RegularSubdivision, RandomSplitsTileTheParcelAndRespectConstraints) {
  geos::Context geos;
  const Polygon block = box(0, 0, 10, 6);
  RoadFrontage road(geos, {block.outer}, 1e-4);
  SplitRules rules = looseRules();
  rules.minArea = 4.0;
  RegularSubdivisionOptions options;
  Rng rng(3);
  std::vector<SubdivisionParcel> parcels{SubdivisionParcel(block)};
  SplitStats stats;
  ASSERT_TRUE(subdivide(parcels, 6, rules, options, road, geos, rng, stats));
  ASSERT_EQ(parcels.size(), 6u);
  double total = 0.0;
  for (const auto& p : parcels) {
    total += p.area;
    EXPECT_GE(p.area, 4.0);
    EXPECT_GE(road.longest(p.polygon), 0.5);
  }
  EXPECT_NEAR(total, 60.0, 1e-9);
}

TEST(RegularSubdivision, ParcelsWithAHoleSplitAroundIt) {
  geos::Context geos;
  Polygon block = box(0, 0, 10, 6);
  block.holes.push_back(box(6, 2, 8, 4).outer);  // a courtyard
  RoadFrontage road(geos, {box(0, 0, 10, 6).outer}, 1e-4);
  SplitRules rules = looseRules();
  rules.minArea = 4.0;
  RegularSubdivisionOptions options;
  Rng rng(5);
  std::vector<SubdivisionParcel> parcels{SubdivisionParcel(block)};
  SplitStats stats;
  ASSERT_TRUE(subdivide(parcels, 4, rules, options, road, geos, rng, stats));
  double total = 0.0;
  size_t holes = 0;
  for (const auto& p : parcels) {
    total += p.area;
    holes += p.polygon.holes.size();
    EXPECT_EQ(GEOSisValid_r(geos.handle(), geos.polygon(p.polygon).get()), 1);
  }
  EXPECT_NEAR(total, 56.0, 1e-9);
  EXPECT_EQ(holes, 1u);  // the courtyard went, whole, to one child
}

TEST(SpineSubdivision, SpineWithTwoEndsHalvesARectangle) {
  geos::Context geos;
  const Polygon block = box(0, 0, 12, 4);
  SpineGraph spine;
  spine.nodes = {{2, 2}, {6, 2}, {10, 2}};
  spine.edges = {{0, 1}, {1, 2}};
  const SpineParcels parcels = spineSubdivision(block, spine, 6, 0.0, {}, geos);
  ASSERT_TRUE(parcels.used);
  ASSERT_EQ(parcels.parcels.size(), 2u);
  EXPECT_NEAR(area(parcels.parcels[0]), 24.0, 1e-6);
  EXPECT_NEAR(area(parcels.parcels[1]), 24.0, 1e-6);
}

TEST(SpineSubdivision, DiscardRuleFollowsTheRationaleUnlessLiteral) {
  geos::Context geos;
  const Polygon block = box(0, 0, 12, 4);
  SpineGraph spine;
  spine.nodes = {{2, 2}, {10, 2}};
  spine.edges = {{0, 1}};
  // 2 ends > 1 simulated parcel: too many parcels, discarded.
  EXPECT_TRUE(spineSubdivision(block, spine, 1, 0.0, {}, geos).discarded);
  EXPECT_TRUE(spineSubdivision(block, spine, 3, 0.0, {}, geos).used);
  SpineSubdivisionOptions literal;
  literal.literalDiscardRule = true;  // "more simulated parcels than ends" discards
  EXPECT_TRUE(spineSubdivision(block, spine, 3, 0.0, literal, geos).discarded);
  EXPECT_TRUE(spineSubdivision(block, spine, 1, 0.0, literal, geos).used);
}

TEST(RoadFrontageMeasure, FastAndGeosFormsAgree) {
  geos::Context geos;
  std::mt19937_64 rng(9);
  const ParcelBlock block = fixtures::randomBlock(1, 9, 20, 0.4, 0.15, 0.0, rng);
  // Only the first half of the boundary is road-facing.
  const Ring& ring = block.polygon.outer;
  const LineString half(ring.begin(), ring.begin() + static_cast<long>(ring.size() / 2));
  const RoadFrontage road(geos, {half}, 1e-4);
  SplitRules rules = looseRules();
  rules.minArea = 3.0;
  rules.minFrontage = 0.0;
  RegularSubdivisionOptions options;
  const RoadFrontage all(geos, block.roadFacing, 1e-4);
  Rng r(4);
  std::vector<SubdivisionParcel> parcels{SubdivisionParcel(block.polygon)};
  SplitStats stats;
  subdivide(parcels, 12, rules, options, all, geos, r, stats);
  ASSERT_GE(parcels.size(), 8u);
  int fronting = 0;
  for (const auto& p : parcels) {
    const double fast = road.longest(p.polygon);
    EXPECT_NEAR(fast, road.longestGeos(p.polygon), 1e-3);
    fronting += fast > 0.5;
  }
  EXPECT_GT(fronting, 0);
  EXPECT_LT(fronting, static_cast<int>(parcels.size()));
}

TEST(RegularSubdivision, ACutAcrossTheMouthOfACourtyardBayCutsOffThePocket) {
  // A courtyard shaped like an upside-down U: its bay (x 4..6, y 3..6) is parcel land reached from the
  // south. The only road-facing edge is the bay's west side, so every cut runs east across the bay
  // from the courtyard back to the courtyard and cuts off the pocket above it (issue 21: plain code,
  // no GEOS noding). The two children tile the parcel and are valid.
  geos::Context geos;
  Polygon block = box(0, 0, 10, 10);
  block.holes.push_back({{3, 3}, {4, 3}, {4, 6}, {6, 6}, {6, 3}, {7, 3}, {7, 8}, {3, 8}, {3, 3}});
  const double blockArea = area(block);
  ASSERT_NEAR(blockArea, 86.0, 1e-12);
  RoadFrontage road(geos, {{{4, 3}, {4, 6}}}, 1e-4);
  SplitRules rules = looseRules();
  RegularSubdivisionOptions options;
  int accepted = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    Rng rng(seed);
    SubdivisionParcel parcel(block);
    std::array<Polygon, 2> children;
    if (trySplit(parcel, rules, options, road, geos, rng, children) != SplitVerdict::Accepted) continue;
    ++accepted;
    EXPECT_NEAR(area(children[0]) + area(children[1]), blockArea, 1e-9);
    for (const Polygon& c : children) EXPECT_EQ(GEOSisValid_r(geos.handle(), geos.polygon(c).get()), 1);
    const Polygon& pocket = children[0].holes.empty() ? children[0] : children[1];
    const Polygon& rest = children[0].holes.empty() ? children[1] : children[0];
    ASSERT_TRUE(pocket.holes.empty());
    ASSERT_EQ(rest.holes.size(), 1u);
    for (const Vec2& p : pocket.outer) {
      EXPECT_GE(p.x, 4.0 - 1e-12);
      EXPECT_LE(p.x, 6.0 + 1e-12);
      EXPECT_GE(p.y, 3.0);
      EXPECT_LE(p.y, 6.0 + 1e-12);
    }
    EXPECT_NEAR(std::fabs(signedArea(rest.holes.front())), 14.0 + area(pocket), 1e-9);  // the grown courtyard
  }
  EXPECT_GE(accepted, 10);
}
