// Issue 21, the parcel search per try: a split attempt judged from its parent's SplitIndex (prefix sums
// with rounding bounds, runs of edges) must give the verdict and children of the plain check, and the
// road frontage entries a child inherits from its parent must equal a fresh measure of its edges. Both
// run on real block outlines (the truth blocks of the two samples, in cells as the pipeline has them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "parcel_fixtures.hpp"
#include "urbanvec/core/random.hpp"
#include "urbanvec/vectorize/parcels/regular_subdivision.hpp"

using namespace urbanvec;
using namespace urbanvec::vectorize::parcels;

namespace {

/// The first half of the outer ring: road-facing lines that cover some parcel edges and not others.
MultiLineString halfOfOuterRing(const Polygon& block) {
  const Ring& ring = block.outer;
  return {LineString(ring.begin(), ring.begin() + static_cast<long>(ring.size() / 2 + 1))};
}

bool sameCover(const RoadFrontage::RingCover& a, const RoadFrontage::RingCover& b) {
  return a.intervals == b.intervals && a.start == b.start && a.length == b.length;
}

/// A random line through the square around the parcel's bounding box (its SplitIndex's origin and
/// largest half extent): a point q on it and its direction.
std::pair<Vec2, Vec2> randomLine(const Polygon& parcel, Rng& rng) {
  const SplitIndex index = buildSplitIndex(parcel);
  std::uniform_real_distribution<double> offset(-index.maxLocal, index.maxLocal),
      angle(0.0, 6.283185307179586);
  const Vec2 q{index.origin.x + offset(rng), index.origin.y + offset(rng)};
  const double a = angle(rng);
  return {q, Vec2{std::cos(a), std::sin(a)}};
}

/// Split rules with the given minimum area and aspect threshold and 0.5 cells of frontage.
SplitRules rulesWith(double minArea, double aspectThreshold, bool residential) {
  SplitRules rules;
  rules.minArea = minArea;
  rules.aspectThreshold = aspectThreshold;
  rules.residentialRule = residential;
  rules.minChildShare = 0.3;
  rules.minFrontage = 0.5;
  return rules;
}

/// Rules that accept any split with children of some area.
SplitRules looseRules() {
  SplitRules loose;
  loose.minArea = 0.0;
  loose.aspectThreshold = 0.0;
  loose.minFrontage = 0.0;
  return loose;
}

/// Whether the plain check (no screen) accepts the cut q-dir of `parcel` under looseRules(), with the
/// smaller area and aspect of its children.
bool plainChildren(const SubdivisionParcel& parcel, const Vec2& q, const Vec2& dir, const RoadFrontage& road,
                   const geos::Context& geos, double& smallest, double& thinnest) {
  std::array<SubdivisionParcel, 2> children;
  SubdivisionParcel copy = parcel;
  if (splitAlong(copy, q, dir, looseRules(), road, geos, children, false) != SplitVerdict::Accepted)
    return false;
  smallest = std::min(children[0].area, children[1].area);
  thinnest = std::min(orientedBox(children[0].polygon).aspect(), orientedBox(children[1].polygon).aspect());
  return true;
}

class RealBlocks : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(RealBlocks, ScreenedSplitsGiveThePlainVerdictAndChildren) {
  geos::Context geos;
  const std::vector<Polygon> blocks = fixtures::sampleBlocks(GetParam());
  ASSERT_GE(blocks.size(), 9u);
  // Rules that reject for each reason in turn: the minimum area and aspect near their typical values.
  const SplitRules rules = rulesWith(12.0, 0.3, true);
  RegularSubdivisionOptions options;
  Rng rng(7);
  int attempts = 0, screened = 0, accepted = 0;
  int verdicts[6] = {0, 0, 0, 0, 0, 0};
  for (const Polygon& block : blocks) {
    const RoadFrontage road(geos, halfOfOuterRing(block), 1e-4);
    // A parcel and, as splits are accepted, its children and grandchildren (inherited entries).
    std::vector<SubdivisionParcel> queue{SubdivisionParcel(block)};
    for (size_t next = 0; next < queue.size() && next < 12; ++next) {
      prepare(queue[next], options, road, geos);
      for (int k = 0; k < 150; ++k) {
        const auto [q, dir] = randomLine(queue[next].polygon, rng);
        SubdivisionParcel plainParent = queue[next], screenParent = queue[next];
        std::array<SubdivisionParcel, 2> plain, screen;
        const SplitVerdict expected = splitAlong(plainParent, q, dir, rules, road, geos, plain, false);
        const SplitVerdict got = splitAlong(screenParent, q, dir, rules, road, geos, screen, true);
        ++attempts;
        ++verdicts[static_cast<int>(got)];
        ASSERT_EQ(got, expected) << GetParam() << " block with " << block.outer.size() << " vertices";
        if (got != SplitVerdict::Accepted) continue;
        ++accepted;
        for (size_t c = 0; c < 2; ++c) {
          ASSERT_EQ(screen[c].polygon.outer, plain[c].polygon.outer);
          ASSERT_EQ(screen[c].polygon.holes, plain[c].polygon.holes);
          EXPECT_EQ(screen[c].area, area(screen[c].polygon));
        }
        if (queue.size() < 12) {
          queue.push_back(std::move(screen[0]));
          queue.push_back(std::move(screen[1]));
        }
      }
    }
  }
  // Every verdict the screen can take occurred, and splits were accepted.
  for (int v : {0, 1, 3, 4}) EXPECT_GT(verdicts[v], 0) << verdictName(static_cast<SplitVerdict>(v));
  EXPECT_GT(accepted, 20);
  EXPECT_GT(attempts, 2000);
}

TEST_P(RealBlocks, ThresholdsOneUlpFromTheChildrensValuesGiveThePlainVerdict) {
  // The screen's estimates differ from the plain computation in the last bits; its rounding bounds
  // must leave a cut whose child sits at a threshold to the plain check. Thresholds set to the plain
  // children's area and aspect and one ulp either side.
  geos::Context geos;
  std::vector<Polygon> blocks = fixtures::sampleBlocks(GetParam());
  for (Polygon& far : fixtures::sampleBlocks(GetParam(), 4000.0)) blocks.push_back(std::move(far));
  RegularSubdivisionOptions options;
  Rng rng(11);
  int cases = 0;
  for (const Polygon& block : blocks) {
    const RoadFrontage road(geos, {block.outer}, 1e-4);
    SubdivisionParcel parcel(block);
    prepare(parcel, options, road, geos);
    if (!parcel.polygon.holes.empty()) continue;  // the screen leaves parcels with holes alone
    for (int k = 0; k < 40; ++k) {
      const auto [q, dir] = randomLine(parcel.polygon, rng);
      const SplitRules loose = looseRules();
      double smallest = 0.0, thinnest = 0.0;
      if (!plainChildren(parcel, q, dir, road, geos, smallest, thinnest)) continue;
      for (const double step : {-1.0, 0.0, 1.0}) {
        SplitRules size = loose, shape = loose, share = loose;
        size.minArea = step == 0.0 ? smallest : std::nextafter(smallest, step * 1e300);
        shape.aspectThreshold = step == 0.0 ? thinnest : std::nextafter(thinnest, step * 1e300);
        shape.compareParentAspect = true;  // against the parent's aspect too, below
        share.residentialRule = true;
        share.minChildShare = (step == 0.0 ? smallest : std::nextafter(smallest, step * 1e300)) / parcel.area;
        for (SplitRules rules : {size, shape, share}) {  // NOLINT(performance-for-range-copy)
          for (const bool parentAspect : {false, true}) {
            rules.compareParentAspect = parentAspect;
            std::array<SubdivisionParcel, 2> plain, screen;
            SubdivisionParcel plainParent = parcel, screenParent = parcel;
            if (parentAspect) plainParent.aspect = screenParent.aspect = thinnest;
            const SplitVerdict expected = splitAlong(plainParent, q, dir, rules, road, geos, plain, false);
            ASSERT_EQ(splitAlong(screenParent, q, dir, rules, road, geos, screen, true), expected);
            ++cases;
          }
        }
      }
    }
  }
  EXPECT_GT(cases, 2000);
}

TEST_P(RealBlocks, InheritedFrontageEntriesEqualAFreshMeasure) {
  geos::Context geos;
  const std::vector<Polygon> blocks = fixtures::sampleBlocks(GetParam());
  ASSERT_GE(blocks.size(), 9u);
  const SplitRules rules = rulesWith(6.0, 0.2, false);
  RegularSubdivisionOptions options;
  int inherited = 0, checked = 0, fronting = 0, coveredEdges = 0, bareEdges = 0;
  std::int64_t seed = 1;
  for (const Polygon& block : blocks) {
    const RoadFrontage road(geos, halfOfOuterRing(block), 1e-4);
    const RoadFrontage fresh(geos, halfOfOuterRing(block), 1e-4);
    Rng rng(static_cast<std::uint64_t>(seed++));
    std::vector<SubdivisionParcel> parcels{SubdivisionParcel(block)};
    SplitStats stats;
    subdivide(parcels, 10, rules, options, road, geos, rng, stats);
    for (const SubdivisionParcel& p : parcels) {
      if (p.cover.empty()) continue;  // a child of the GEOS fallback: measured when first tried
      ++checked;
      inherited += !p.prepared;  // a child never tried: all its entries came from its parent and the cut
      ASSERT_EQ(p.cover.size(), 1 + p.polygon.holes.size());
      RoadFrontage::RingCover measured;
      fresh.coverRing(p.polygon.outer, measured);
      ASSERT_TRUE(sameCover(p.cover[0], measured)) << GetParam() << ": outer ring of a parcel";
      for (size_t h = 0; h < p.polygon.holes.size(); ++h) {
        fresh.coverRing(p.polygon.holes[h], measured);
        ASSERT_TRUE(sameCover(p.cover[h + 1], measured)) << GetParam() << ": hole " << h;
      }
      double best = road.longestOfCover(p.cover[0]);
      for (size_t h = 1; h < p.cover.size(); ++h) best = std::max(best, road.longestOfCover(p.cover[h]));
      EXPECT_EQ(best, fresh.longest(p.polygon));
      fronting += best >= 0.5;
      for (size_t e = 0; e < p.cover[0].edges(); ++e)
        (p.cover[0].start[e + 1] > p.cover[0].start[e] ? coveredEdges : bareEdges) += 1;
    }
  }
  EXPECT_GT(checked, 60);
  EXPECT_GT(inherited, 20);
  EXPECT_GT(fronting, 0);
  EXPECT_GT(coveredEdges, 100);
  EXPECT_GT(bareEdges, 100);
}

TEST_P(RealBlocks, RoadWithinAgreesWithAScanOfEverySegment) {
  // RoadFrontage::within visits the grid cells near the point and stops at the first segment within
  // the limit (issue 21): the same answer as measuring every road-facing segment. Points near the
  // lines, at distances around the limit, near the origin and 4000 cells out.
  geos::Context geos;
  std::vector<Polygon> blocks = fixtures::sampleBlocks(GetParam());
  for (Polygon& far : fixtures::sampleBlocks(GetParam(), 4000.0)) blocks.push_back(std::move(far));
  Rng rng(3);
  int near = 0, far = 0;
  for (const Polygon& block : blocks) {
    const MultiLineString lines = halfOfOuterRing(block);
    const RoadFrontage road(geos, lines, 1e-4);
    const Ring& line = lines.front();
    std::uniform_int_distribution<size_t> pick(0, line.size() - 2);
    std::uniform_real_distribution<double> along(0.0, 1.0), offset(-1.5, 1.5);
    for (int k = 0; k < 400; ++k) {
      const size_t i = pick(rng);
      const Vec2 a = line[i], b = line[i + 1];
      if (a == b) continue;
      const Vec2 d = (b - a) / distance(a, b);
      const double limit = k % 2 == 0 ? 0.5001 : 1e-4;
      // A point off the line by a random amount, or by the limit itself (the boundary case).
      const double off = k % 4 < 2 ? offset(rng) : (k % 8 < 4 ? limit : -limit);
      const Vec2 p = a + (b - a) * along(rng) + Vec2{-d.y, d.x} * off;
      bool scan = false;
      for (size_t j = 0; j + 1 < line.size(); ++j)
        if (line[j] != line[j + 1] && distanceToSegment(p, line[j], line[j + 1]) <= limit) scan = true;
      ASSERT_EQ(road.within(p, limit), scan) << GetParam() << " point " << p.x << " " << p.y;
      (scan ? near : far) += 1;
    }
  }
  EXPECT_GT(near, 1000);
  EXPECT_GT(far, 1000);
}

TEST(TouchingHoles, CutsGEOSWouldJudgeGetItsVerdictWithoutIt) {
  // A hole that touches the outer ring at its first or second vertex leaves cutPolygon unsure of its
  // side, and splitAlong gives the cut to GEOS; a certain rejection is now judged without it (issue 21).
  // Random cuts of blocks with such holes, near the origin and 4000 cells out, under rules set at
  // GEOS's children's values and one ulp either side, must give the verdict of the GEOS path.
  geos::Context geos;
  RegularSubdivisionOptions options;
  Rng rng(5);
  int cases = 0, rejected = 0;
  for (const double offset : {0.0, 4000.0}) {
    Ring outer;
    for (double x = 0; x < 40; x += 4) outer.push_back({x, 0});
    for (double y = 0; y < 24; y += 4) outer.push_back({40, y});
    for (double x = 40; x > 0; x -= 4) outer.push_back({x, 24});
    for (double y = 24; y > 0; y -= 4) outer.push_back({0, y});
    outer.push_back(outer.front());
    // Holes touching the outer ring by their first or second vertex, on the top and the right side
    // (where the crossing test counts the touching vertex outside the ring, so its two first vertices
    // disagree on the side when the hole lies in the first child).
    Polygon block{outer,
                  {{{12, 24}, {10, 20}, {14, 20}, {12, 24}},
                   {{26, 20}, {28, 24}, {30, 20}, {26, 20}},
                   {{40, 8}, {36, 10}, {33, 8}, {35, 5}, {37, 6}, {40, 8}}}};
    for (Ring* ring : {&block.outer, &block.holes[0], &block.holes[1], &block.holes[2]})
      for (Vec2& p : *ring) p = p + Vec2{offset, offset};
    const RoadFrontage road(geos, {block.outer}, 1e-4);
    SubdivisionParcel parcel(block);
    prepare(parcel, options, road, geos);
    for (int k = 0; k < 300; ++k) {
      const auto [q, dir] = randomLine(parcel.polygon, rng);
      const SplitRules loose = looseRules();
      double smallest = 0.0, thinnest = 0.0;
      if (!plainChildren(parcel, q, dir, road, geos, smallest, thinnest)) continue;
      std::vector<SplitRules> ruleSets;
      for (const double step : {-1.0, 0.0, 1.0}) {
        SplitRules size = loose, shape = loose, share = loose;
        size.minArea = step == 0.0 ? smallest : std::nextafter(smallest, step * 1e300);
        shape.aspectThreshold = step == 0.0 ? thinnest : std::nextafter(thinnest, step * 1e300);
        share.residentialRule = true;
        share.minChildShare = (step == 0.0 ? smallest : std::nextafter(smallest, step * 1e300)) / parcel.area;
        ruleSets.insert(ruleSets.end(), {size, shape, share});
      }
      // Typical rules, each reason in turn.
      for (const double minArea : {5.0, 40.0, 120.0})
        for (const double aspect : {0.2, 0.45})
          for (const bool residential : {false, true})
            ruleSets.push_back(rulesWith(minArea, aspect, residential));
      for (const SplitRules& rules : ruleSets) {
        std::array<SubdivisionParcel, 2> plain, screen;
        SubdivisionParcel plainParent = parcel, screenParent = parcel;
        const SplitVerdict expected = splitAlong(plainParent, q, dir, rules, road, geos, plain, false);
        ASSERT_EQ(splitAlong(screenParent, q, dir, rules, road, geos, screen, true), expected)
            << "offset " << offset << ", cut " << k;
        ++cases;
        rejected += expected != SplitVerdict::Accepted;
      }
    }
  }
  EXPECT_GT(cases, 3000);
  EXPECT_GT(rejected, 1000);
}

TEST_P(RealBlocks, ReusedParcelMemoryGivesTheSameSubdivisions) {
  // The split loop swaps parcels instead of moving them and takes new parcels' lists from spare ones
  // (issue 21), as the pipeline's tries do with the parcels of the try before: a slot that kept an
  // old parcel's simplified edges, index or frontage entries must not leak into a new one.
  geos::Context geos;
  const std::vector<Polygon> blocks = fixtures::sampleBlocks(GetParam());
  const SplitRules rules = rulesWith(4.0, 0.2, true);
  RegularSubdivisionOptions options;
  int compared = 0, reused = 0;
  std::uint64_t seed = 1;
  for (const Polygon& block : blocks) {
    const RoadFrontage road(geos, halfOfOuterRing(block), 1e-4);
    SubdivisionParcel start(block);
    prepare(start, options, road, geos);
    std::vector<SubdivisionParcel> parcels;
    SubdivisionScratch scratch;
    for (int attempt = 0; attempt < 6; ++attempt, ++seed) {
      Rng plainRng(seed), reusingRng(seed);
      std::vector<SubdivisionParcel> plain{start};
      SplitStats plainStats, reusingStats;
      subdivide(plain, 12, rules, options, road, geos, plainRng, plainStats);
      reused += static_cast<int>(parcels.size() > 1 ? parcels.size() - 1 : 0);
      for (size_t k = 1; k < parcels.size(); ++k) scratch.spare.push_back(std::move(parcels[k]));
      parcels.assign(1, start);
      subdivide(parcels, 12, rules, options, road, geos, reusingRng, reusingStats, scratch);
      ASSERT_EQ(parcels.size(), plain.size()) << GetParam();
      ASSERT_EQ(reusingStats.accepted, plainStats.accepted);
      for (int v = 0; v < 6; ++v) ASSERT_EQ(reusingStats.rejected[v], plainStats.rejected[v]);
      for (size_t k = 0; k < plain.size(); ++k) {
        ASSERT_EQ(parcels[k].polygon.outer, plain[k].polygon.outer) << GetParam() << " parcel " << k;
        ASSERT_EQ(parcels[k].polygon.holes, plain[k].polygon.holes);
        ASSERT_EQ(parcels[k].area, plain[k].area);
        ASSERT_EQ(parcels[k].roadEdges, plain[k].roadEdges);
        ++compared;
      }
      ASSERT_EQ(reusingRng(), plainRng());
    }
  }
  EXPECT_GT(compared, 200);
  EXPECT_GT(reused, 100);
}

INSTANTIATE_TEST_SUITE_P(Samples, RealBlocks, ::testing::Values("monaco", "bubenec"));
