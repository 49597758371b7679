// Stages A2, A3, A4.8 and A5 on small drawn grids with known answers (spec §11.1).
#include <gtest/gtest.h>

#include <array>

#include "../test_grids.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/vectorize/blocks/raw_blocks.hpp"
#include "urbanvec/vectorize/parcels/parcel_loading.hpp"
#include "urbanvec/vectorize/roads/patch_cleaning.hpp"
#include "urbanvec/vectorize/roads/perimeters.hpp"

using namespace urbanvec;
using namespace urbanvec::vectorize;
using namespace urbanvec::vectorize::testing;

TEST(RawBlocks, EnclosedLandIsInternalWithItsUnusedPatchesAndBorderLandIsExternalWithout) {
  const auto cells = drawGrid({
      "rr.r.....",
      "rsssssss.",
      "rsr.rwrs.",
      "rsrr.wrs.",
      "rsssssss.",
      "rr..r....",
  });
  const RawBlocks rb = buildRawBlocks(cells, {});
  int internal = 0, external = 0;
  for (const SimBlock& b : rb.blocks) {
    (b.internal ? internal : external)++;
    for (int i : b.patches) {
      const int c = i % cells.width, r = i / cells.width;
      if (b.internal)
        EXPECT_FALSE(c == 0 || r == 0 || c == cells.width - 1 || r == cells.height - 1);
      else
        EXPECT_NE(cells.cells[i], static_cast<std::uint8_t>(LandUse::Unused));
    }
  }
  // Inside the ring, water splits the enclosed land into two internal blocks ("two or more blocks
  // surrounded by the same roads"); the left one keeps its unused patch as undeveloped land.
  EXPECT_EQ(internal, 2);
  const SimBlock& left = rb.blocks[rb.blockOf.at(2, 2)];
  EXPECT_TRUE(left.internal);
  EXPECT_EQ(left.area, 6.0);
  EXPECT_EQ(left.undevelopedArea, 2.0);
  EXPECT_TRUE(left.touchesWater);
  EXPECT_EQ(rb.blockOf.at(5, 2), -1);  // water
  // Outside: the residential patches touching the border form external blocks; unused patches are in none.
  EXPECT_GE(external, 2);
  EXPECT_EQ(rb.blockOf.at(2, 0), -1);
  EXPECT_FALSE(rb.blocks[rb.blockOf.at(0, 0)].internal);
  // No two blocks are 4-adjacent.
  for (int r = 0; r < cells.height; ++r)
    for (int c = 0; c + 1 < cells.width; ++c) {
      const int a = rb.blockOf.at(c, r), b = rb.blockOf.at(c + 1, r);
      if (a >= 0 && b >= 0) EXPECT_EQ(a, b);
    }
}

// A window (issue 22) that cuts a ring of road: the land inside reaches the window's edge, yet in the
// whole grid the ring encloses it. With the whole grid's open-regions answer A2 makes it the internal
// block the whole grid has, unused cells included; without it, only its residential cells form an
// external block.
TEST(RawBlocks, OpenRegionsGridGivesAWindowTheWholeGridsEnclosedRegions) {
  const auto cells = drawGrid({
      ".....",
      ".ssss",
      ".s.r.",
      ".s.rr",
      ".ssss",
      ".....",
  });
  const RawBlocks cut = buildRawBlocks(cells, {});
  ASSERT_GE(cut.blockOf.at(3, 2), 0);
  EXPECT_FALSE(cut.blocks[cut.blockOf.at(3, 2)].internal);
  EXPECT_EQ(cut.blocks[cut.blockOf.at(3, 2)].area, 3.0);
  EXPECT_EQ(cut.blockOf.at(2, 2), -1);  // unused land of an open region

  Grid<std::uint8_t> open(cells.width, cells.height, 1);
  for (int r = 2; r <= 3; ++r)
    for (int c = 2; c <= 4; ++c) open.at(c, r) = 0;  // the land inside the ring
  RawBlockOptions options;
  options.openRegions = &open;
  const RawBlocks whole = buildRawBlocks(cells, options);
  ASSERT_EQ(whole.blocks.size(), 1u);
  EXPECT_TRUE(whole.blocks[0].internal);
  EXPECT_EQ(whole.blocks[0].area, 6.0);
  EXPECT_EQ(whole.blocks[0].undevelopedArea, 3.0);
  EXPECT_EQ(whole.blockOf.at(0, 0), -1);  // outside the ring: open land either way

  Grid<std::uint8_t> wrongSize(cells.width + 1, cells.height, 0);
  options.openRegions = &wrongSize;
  EXPECT_THROW(buildRawBlocks(cells, options), Error);
}

TEST(RawBlocks, ReservedIsExcludedOnlyWhenAsked) {
  const auto cells = drawGrid({"sssss", "srxrs", "sssss"});
  EXPECT_EQ(buildRawBlocks(cells, {}).blocks.size(), 2u);
  RawBlockOptions paper;
  paper.excludeReserved = false;
  EXPECT_EQ(buildRawBlocks(cells, paper).blocks.size(), 1u);
}

TEST(PatchCleaning, RedundantSecondaryStripBesidePrimaryIsRemoved) {
  auto cells = drawGrid({
      "rrrrrrrrrr",
      "rrssssssrr",
      "PPPPPPPPPP",
      "PPPPPPPPPP",
      "rrrrrrrrrr",
  });
  const PatchCleaningStats s = cleanIntersectionPatches(cells);
  EXPECT_EQ(s.removedPatches, 6u);
  for (int c = 2; c < 8; ++c) EXPECT_EQ(cells.at(c, 1), kRemovedRoad);
}

TEST(PatchCleaning, SecondaryRoadLeavingThePrimaryKeepsOneShortestPath) {
  auto cells = drawGrid({
      "rrrrsrrrrr",
      "rrrrsrrrrr",
      "rrrrsrrrrr",
      "rrssssrrrr",
      "PPPPPPPPPP",
      "PPPPPPPPPP",
  });
  cleanIntersectionPatches(cells);
  const auto sec = static_cast<std::uint8_t>(LandUse::SecondaryRoad);
  // The road going north survives, joined to the primary by the patch right below it.
  for (int r = 0; r <= 3; ++r) EXPECT_EQ(cells.at(4, r), sec) << "row " << r;
  // The sideways stubs hugging the primary are redundant.
  EXPECT_EQ(cells.at(2, 3), kRemovedRoad);
  EXPECT_EQ(cells.at(3, 3), kRemovedRoad);
  EXPECT_EQ(cells.at(5, 3), kRemovedRoad);
}

TEST(Perimeters, LinesRunBetweenUndevelopedLandAndExternalBlocksAndEndAtRoads) {
  // An external residential block at the west border; unused land to its north-east.
  auto cells = drawGrid({
      "rrr......",
      "rrr......",
      "rrrr.....",
      "sssssssss",
      "rrrrrrrrr",
  });
  const RawBlocks rb = buildRawBlocks(cells, {});
  RoadGraph g;
  const PerimeterStats s = addExternalPerimeters(g, cells, rb.blockOf, rb.blocks, {});
  EXPECT_EQ(s.closedLoops, 0u);
  // One line around the north-west block (grid border included) and one around the southern strip.
  ASSERT_EQ(s.lines, 2u);
  // Every line ends where the perimeter meets the road: a patch beside the end vertex is road.
  int ends = 0;
  for (size_t i = 0; i < g.nodes.size(); ++i) {
    if (g.degree(static_cast<int>(i)) != 1) continue;
    ++ends;
    const int cc = static_cast<int>(g.nodes[i].p.x), rr = cells.height - static_cast<int>(g.nodes[i].p.y);
    bool besideRoad = false;
    for (int dc : {-1, 0})
      for (int dr : {-1, 0})
        besideRoad |= cells.inside(cc + dc, rr + dr) && isRoadCode(cells.at(cc + dc, rr + dr));
    EXPECT_TRUE(besideRoad) << "end at vertex " << cc << "," << rr;
  }
  EXPECT_EQ(ends, 4);
  // The lines follow patch edges: every link is one patch edge long and axis-aligned.
  for (size_t i = 0; i < g.nodes.size(); ++i)
    for (int j : g.nodes[i].links) EXPECT_DOUBLE_EQ(distance(g.nodes[i].p, g.nodes[j].p), 1.0);
  for (const RoadNode& n : g.nodes) EXPECT_EQ(n.type, NodeType::Perimeter);
}

namespace {

/// A4.8 on the raw blocks of `cells`.
PerimeterStats perimetersOf(const Grid<std::uint8_t>& cells, const RawBlockOptions& raw = {},
                            const PerimeterOptions& options = {}) {
  const RawBlocks rb = buildRawBlocks(cells, raw);
  RoadGraph g;
  return addExternalPerimeters(g, cells, rb.blockOf, rb.blocks, options);
}

}  // namespace

TEST(Perimeters, ReservedLandAlongTheEdgeDoesNotCutTheLine) {
  // The external block's edge to the open land passes reserved patches (x) halfway along: one line
  // still runs from road to road, around the reserved patches, unless they count as developed.
  const auto cells = drawGrid({
      "....xx...",
      "rrrrrrrrr",
      "rrrrrrrrr",
      "sssssssss",
  });
  EXPECT_EQ(perimetersOf(cells).lines, 1u);
  PerimeterOptions reservedDeveloped;
  reservedDeveloped.reservedIsUndeveloped = false;
  EXPECT_EQ(perimetersOf(cells, {}, reservedDeveloped).lines, 2u);
  // Reserved patches inside a block (when A2 keeps them in blocks) are land of that block, not open
  // land: no line around them.
  const auto inner = drawGrid({
      ".........",
      "rrrxxrrrr",
      "rrrxxrrrr",
      "sssssssss",
  });
  RawBlockOptions keepReserved;
  keepReserved.excludeReserved = false;
  const PerimeterStats s = perimetersOf(inner, keepReserved);
  EXPECT_EQ(s.lines, 1u);
  EXPECT_EQ(s.closedLoops, 0u);
}

TEST(ParcelLoading, ParcelsJoinTheBlockOfTheirFirstPatchAndTakeTableValues) {
  VectorizeInput in = drawInput({
      "sssss",
      "srrrs",
      "srrrs",
      "sssss",
  });
  in.parcelIds = Grid<std::int32_t>(5, 4, 0);
  in.parcelIds.at(1, 1) = 7;
  in.parcelIds.at(2, 1) = 7;
  in.parcelIds.at(1, 2) = 9;
  in.parcelIds.at(0, 0) = 11;  // first patch on the road: attached to nothing
  in.density = Grid<float>(5, 4, 2.5f);
  in.parcelTable = {{7, LandUse::Commercial, 42.0, 2}};
  RawBlocks rb = buildRawBlocks(in.landUse, {});
  const ParcelLoading pl = loadParcels(in, rb.blockOf, rb.blocks);
  ASSERT_EQ(pl.parcels.size(), 3u);
  EXPECT_EQ(pl.parcels[0].id, 7);
  EXPECT_EQ(pl.parcels[0].use, LandUse::Commercial);
  EXPECT_DOUBLE_EQ(pl.parcels[0].population, 42.0);
  EXPECT_EQ(pl.parcels[0].simBlock, rb.blockOf.at(1, 1));
  EXPECT_EQ(pl.parcels[1].id, 9);
  EXPECT_EQ(pl.parcels[1].use, LandUse::Residential);  // derived: majority of its patches
  EXPECT_DOUBLE_EQ(pl.parcels[1].population, 2.5);     // derived: density sum
  EXPECT_EQ(pl.parcels[2].simBlock, -1);
  EXPECT_EQ(pl.unattached, 1u);
  EXPECT_EQ(pl.derivedFromRaster, 2u);
  EXPECT_EQ(rb.blocks[rb.blockOf.at(1, 1)].parcels, (std::vector<int>{0, 1}));
}

namespace {

/// A one-cell-wide west block (column 1) and a three-cell-wide east block (columns 3-5), rows 1-2,
/// with an empty parcels raster.
VectorizeInput twoBlocksAcrossARoad() {
  VectorizeInput in = drawInput({
      "sssssss",
      "srsrrrs",
      "srsrrrs",
      "sssssss",
  });
  in.parcelIds = Grid<std::int32_t>(7, 4, 0);
  return in;
}

}  // namespace

TEST(ParcelLoading, AParcelTheRoadsSplitJoinsTheBlockHoldingMostOfIt) {
  // Plot 5 has its first patch (row-major) in the west block and three patches in the east block.
  VectorizeInput in = twoBlocksAcrossARoad();
  for (auto [c, r] : std::vector<std::pair<int, int>>{{1, 1}, {3, 1}, {4, 1}, {3, 2}})
    in.parcelIds.at(c, r) = 5;
  in.parcelIds.at(0, 0) = 6;  // one patch on the road, one in the west block: a tie, the first patch's
  in.parcelIds.at(1, 2) = 6;
  in.parcelTable = {{5, LandUse::Commercial, 40.0, 4}, {6, LandUse::Residential, 10.0, 2}};
  RawBlocks rb = buildRawBlocks(in.landUse, {});
  const int west = rb.blockOf.at(1, 1), east = rb.blockOf.at(4, 1);
  ASSERT_NE(west, east);
  std::vector<SimBlock> blocks = rb.blocks;
  const ParcelLoading majority = loadParcels(in, rb.blockOf, blocks);
  EXPECT_EQ(majority.parcels[0].simBlock, east);
  EXPECT_EQ(majority.parcels[1].simBlock, -1);
  EXPECT_EQ(majority.unattached, 1u);
  EXPECT_EQ(blocks[east].parcels, (std::vector<int>{0}));
  // The documents' first-patch rule puts the whole commercial plot, and its 40 people, in the west
  // block, which holds one of its four patches.
  blocks = rb.blocks;
  ParcelLoadingOptions firstPatch;
  firstPatch.majorityBlock = false;
  EXPECT_EQ(loadParcels(in, rb.blockOf, blocks, {}, firstPatch).parcels[0].simBlock, west);
}

TEST(ParcelLoading, ATieBetweenABlockAndNoBlockGoesToTheBlock) {
  // Plot 8: its first patch in the west block, two patches on the road, two in the east block.
  VectorizeInput in = twoBlocksAcrossARoad();
  for (auto [c, r] : std::vector<std::pair<int, int>>{{1, 1}, {2, 1}, {2, 2}, {4, 1}, {5, 1}})
    in.parcelIds.at(c, r) = 8;
  RawBlocks rb = buildRawBlocks(in.landUse, {});
  const ParcelLoading pl = loadParcels(in, rb.blockOf, rb.blocks);
  ASSERT_EQ(pl.parcels.size(), 1u);
  EXPECT_EQ(pl.parcels[0].simBlock, rb.blockOf.at(4, 1));
  EXPECT_EQ(pl.unattached, 0u);
}

TEST(ParcelLoading, ParcelsOutsideEveryBlockAreCountedByTheLandTheyLieOnWithTheirPeople) {
  // Issue 15: one block (the residential cells); parcels on open land, water, road and reserved land.
  VectorizeInput in = drawInput({
      "rrr..",
      "rrr..",
      "sssss",
      "wwxx.",
  });
  in.parcelIds = Grid<std::int32_t>(5, 4, 0);
  in.parcelIds.at(0, 0) = 1;  // in the block
  in.parcelIds.at(3, 0) = 2;  // open land
  in.parcelIds.at(4, 1) = 2;
  in.parcelIds.at(0, 3) = 3;  // water
  in.parcelIds.at(2, 2) = 4;  // road
  in.parcelIds.at(2, 3) = 5;  // reserved
  in.parcelIds.at(4, 0) = 6;  // open land
  in.density = Grid<float>(5, 4, 0.0f);
  in.density.at(0, 3) = 2.5f;
  RawBlocks rb = buildRawBlocks(in.landUse, {});
  ParcelLoading pl = loadParcels(in, rb.blockOf, rb.blocks);
  EXPECT_EQ(pl.unattached, 5u);
  EXPECT_DOUBLE_EQ(pl.unattachedPopulation, 2.5);
  EXPECT_EQ(pl.unattachedOn, (std::array<std::size_t, 4>{2, 1, 1, 1}));
  EXPECT_EQ(unattachedParcelsWarning(pl, true),
            "5 input parcels (2.5 people) lie mostly outside every block (2 on open land (unused cells), "
            "1 on road, 1 on water, 1 on reserved land): no block takes them, so they are left out of the "
            "parcels layer with their 2.5 people");
  // The sample grids' case: only empty plots on open land.
  pl.unattached = 210;
  pl.unattachedPopulation = 0.0;
  pl.unattachedOn = {210, 0, 0, 0};
  EXPECT_EQ(unattachedParcelsWarning(pl, true),
            "210 input parcels (0 people) lie mostly on open land (unused cells) outside every block: no "
            "block takes them, so they are left out of the parcels layer and no population is lost");
  EXPECT_EQ(
      unattachedParcelsWarning(pl, false),
      "210 input parcels (0 people) have their first cell on open land (unused cells) outside every "
      "block: no block takes them, so they are left out of the parcels layer and no population is lost");
  pl.unattached = 0;
  EXPECT_EQ(unattachedParcelsWarning(pl, true), "");
  EXPECT_EQ(peopleText(1.0), "1 person");
  EXPECT_EQ(peopleText(0.04), "0 people");
  EXPECT_EQ(peopleText(6250.0), "6250 people");
  EXPECT_EQ(peopleText(54197.78), "54197.8 people");
}
