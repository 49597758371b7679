// The use of untagged land (issue 20): each rule of inferUntaggedUse on hand-made evidence.
#include <gtest/gtest.h>

#include "urbanvec/gridify/untagged_land.hpp"

using namespace urbanvec;
using namespace urbanvec::gridify;

namespace {

BlockEvidence block(std::size_t cells, std::size_t tagged) {
  BlockEvidence b;
  b.cells = cells;
  b.taggedCells = tagged;
  return b;
}

}  // namespace

TEST(UntaggedLand, TaggedBlocksAndLandOutsideTheStreetsAreLeftAlone) {
  const UntaggedLandOptions options;
  BlockEvidence tagged = block(100, 11);  // 11 % under a land-use polygon: above the 10 % default
  tagged.buildingArea[LandUse::Commercial] = 500;
  EXPECT_EQ(inferUntaggedUse(tagged, options).second, UntaggedRule::Tagged);
  EXPECT_FALSE(inferUntaggedUse(tagged, options).first);
  BlockEvidence nearlyUntagged = tagged;
  nearlyUntagged.taggedCells = 10;
  EXPECT_EQ(inferUntaggedUse(nearlyUntagged, options).first, LandUse::Commercial);

  BlockEvidence outside = block(100, 0);
  outside.external = true;
  outside.buildingArea[LandUse::Residential] = 300;
  EXPECT_EQ(inferUntaggedUse(outside, options).second, UntaggedRule::Outside);
  EXPECT_FALSE(inferUntaggedUse(outside, options).first);

  UntaggedLandOptions off;
  off.enabled = false;
  EXPECT_FALSE(inferUntaggedUse(nearlyUntagged, off).first);
}

TEST(UntaggedLand, BuildingsFirstByFootprintAreaThenStreetsThenTheDefault) {
  const UntaggedLandOptions options;
  BlockEvidence b = block(50, 0);
  b.buildingArea[LandUse::Residential] = 200;
  b.buildingArea[LandUse::Industrial] = 250;
  b.streetLength["residential"] = 400;
  auto [use, rule] = inferUntaggedUse(b, options);
  EXPECT_EQ(use, LandUse::Industrial);
  EXPECT_EQ(rule, UntaggedRule::Buildings);

  // No building: residential streets make 400 of 700 m (>= half), so residential.
  BlockEvidence streets = block(50, 0);
  streets.streetLength["residential"] = 300;
  streets.streetLength["living_street"] = 100;
  streets.streetLength["primary"] = 300;
  std::tie(use, rule) = inferUntaggedUse(streets, options);
  EXPECT_EQ(use, LandUse::Residential);
  EXPECT_EQ(rule, UntaggedRule::Streets);

  // Mostly a primary road: the streets do not tell, the default decides.
  streets.streetLength["primary"] = 500;
  std::tie(use, rule) = inferUntaggedUse(streets, options);
  EXPECT_EQ(use, LandUse::Residential);
  EXPECT_EQ(rule, UntaggedRule::Default);
  UntaggedLandOptions empty;
  empty.defaultUse = LandUse::Unused;
  EXPECT_FALSE(inferUntaggedUse(streets, empty).first);

  // A user's table: service roads of an industrial estate.
  UntaggedLandOptions estate;
  estate.streetUses.push_back({"service", LandUse::Industrial});
  BlockEvidence yard = block(80, 0);
  yard.streetLength["service"] = 600;
  yard.streetLength["residential"] = 100;
  EXPECT_EQ(inferUntaggedUse(yard, estate).first, LandUse::Industrial);
}
