// The per-block pipeline (D6 + 50 tries of E1-E5 + E6), threading determinism and the quality checkers.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <sstream>

#include "parcel_fixtures.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/vectorize/parcels/parcels_pipeline.hpp"

using namespace urbanvec;
using namespace urbanvec::vectorize::parcels;

namespace {

const std::vector<LandUse> kSixResidential(6, LandUse::Residential);

/// Every parcel geometry (WKB hex) and attribute, for byte comparison.
std::string serialize(const ParcelsResult& result) {
  geos::Context geos;
  GEOSWKBWriter* writer = GEOSWKBWriter_create_r(geos.handle());
  std::ostringstream out;
  out.precision(17);
  for (const BlockParcels& b : result.blocks) {
    out << "block " << b.report.blockId << ' ' << b.report.parcels << ' ' << b.report.cost << ' '
        << b.report.costUse << ' ' << b.report.costDistance << ' ' << b.report.costSize << ' '
        << b.report.shortfall << ' ' << b.spine.size() << '\n';
    for (const VectorParcel& p : b.parcels) {
      geos::GeomPtr g = geos.polygon(p.polygon);
      size_t size = 0;
      unsigned char* hex = GEOSWKBWriter_writeHEX_r(geos.handle(), writer, g.get(), &size);
      out << std::string(reinterpret_cast<char*>(hex), size) << ' ' << p.undeveloped << ' '
          << static_cast<int>(p.use) << ' ' << p.population << ' ' << p.area << '\n';
      GEOSFree_r(geos.handle(), hex);
    }
  }
  GEOSWKBWriter_destroy_r(geos.handle(), writer);
  return out.str();
}

std::vector<ParcelBlock> randomCity(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<ParcelBlock> blocks;
  for (int k = 0; k < count; ++k) {
    const int w = 4 + static_cast<int>(rng() % 6), h = 6 + static_cast<int>(rng() % 18);
    const double unused = (k % 4 == 0) ? 0.4 : 0.05;
    blocks.push_back(fixtures::randomBlock(k + 1, w, h, 0.37 * k, 0.15, unused, rng));
  }
  return blocks;
}

}  // namespace

class RectangleBlock : public ::testing::TestWithParam<SpineMethod> {};

TEST_P(RectangleBlock, FourByTwelveWithSixSimulatedParcelsGivesSixValidFrontingParcels) {
  geos::Context geos;
  ParcelBlock block = fixtures::stripBlock(12, 4, kSixResidential);
  block.blockId = 42;
  ParcelsOptions options;
  options.spine.method = GetParam();
  const BlockParcels out = parcelBlock(block, options, geos);
  EXPECT_TRUE(out.report.hasSpine);
  EXPECT_EQ(out.report.tries, 50);
  ASSERT_EQ(out.parcels.size(), 6u) << out.report.shortfall;
  EXPECT_TRUE(out.report.shortfall.empty());
  const TilingCheck t = checkTiling(block.polygon, out.parcels, geos);
  EXPECT_EQ(t.invalidParcels, 0);
  EXPECT_LE(t.gapArea, 1e-6 * 48);
  EXPECT_LE(t.overlapArea + t.outsideArea, 1e-6 * 48);
  EXPECT_NEAR(t.parcelArea, 48.0, 1e-6 * 48);
  const RoadFrontage road(geos, block.roadFacing, 1e-4);
  double population = 0.0;
  for (const VectorParcel& p : out.parcels) {
    EXPECT_GE(road.longest(p.polygon), 0.5);
    EXPECT_EQ(p.use, LandUse::Residential);  // single use, fully developed: trivial case
    EXPECT_FALSE(p.undeveloped);
    population += p.population;
  }
  EXPECT_NEAR(population, 60.0, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(BothMethods, RectangleBlock,
                         ::testing::Values(SpineMethod::ZhangSuen, SpineMethod::Skeleton),
                         fixtures::methodName);

TEST(Pipeline, SameSeedGivesIdenticalOutputWithOneAndTwoThreads) {
  const std::vector<ParcelBlock> blocks = randomCity(16, 11);
  ParcelsOptions options;
  options.tries = 8;
  options.seed = 1234;
  options.threads = 1;
  const std::string one = serialize(vectorizeParcels(blocks, options));
  options.threads = 2;
  const std::string two = serialize(vectorizeParcels(blocks, options));
  EXPECT_EQ(one, two);
  options.seed = 1235;
  EXPECT_NE(serialize(vectorizeParcels(blocks, options)), one);  // the seed matters
}

TEST(Pipeline, ProgressEndsAtOneAndCancellationStops) {
  const std::vector<ParcelBlock> blocks = randomCity(6, 3);
  ParcelsOptions options;
  options.tries = 2;
  double last = -1.0;
  bool monotonic = true;
  vectorizeParcels(blocks, options, [&](double f, std::string_view) {
    monotonic = monotonic && f >= last;
    last = f;
    return true;
  });
  EXPECT_TRUE(monotonic);
  EXPECT_DOUBLE_EQ(last, 1.0);
  EXPECT_THROW(vectorizeParcels(blocks, options, [](double, std::string_view) { return false; }), Cancelled);
}

TEST(Pipeline, BadOptionsAreRejectedWithTheOptionName) {
  ParcelsOptions options;
  options.tries = 0;
  try {
    vectorizeParcels({}, options);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidOption);
    EXPECT_EQ(std::string(e.what()), "-tries must be at least 1, got 0.");
  }
}

TEST(Pipeline, DegenerateBlockIsAnInputErrorNamingTheBlock) {
  std::vector<ParcelBlock> blocks = randomCity(3, 1);
  blocks[1].polygon.outer = {{0, 0}, {1, 1}, {0, 0}};
  try {
    vectorizeParcels(blocks, {});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidInput);
    EXPECT_EQ(std::string(e.what()),
              "block 2 has an empty or degenerate polygon (fewer than 3 distinct vertices or no area).");
  }
}

TEST(Pipeline, BlockWithoutSimulatedParcelsIsOneUndevelopedParcel) {
  geos::Context geos;
  ParcelBlock block;
  block.polygon.outer = fixtures::rectangleRing(5, 5);
  block.roadFacing = {block.polygon.outer};
  const BlockParcels out = parcelBlock(block, {}, geos);
  ASSERT_EQ(out.parcels.size(), 1u);
  EXPECT_TRUE(out.parcels[0].undeveloped);
  EXPECT_DOUBLE_EQ(out.parcels[0].population, 0.0);
}

TEST(Pipeline, UndevelopedBlocksGetExtraUndevelopedParcels) {
  geos::Context geos;
  ParcelBlock block =
      fixtures::stripBlock(16, 6, {LandUse::Residential, LandUse::Commercial, LandUse::Residential});
  // Half the simulated block is unused land: three 16-cell parcels in 96 cells.
  for (SimParcel& p : block.sim.parcels) p.cells = 16;
  block.sim.developedArea = 48;
  block.sim.undevelopedArea = 48;
  ParcelsOptions options;
  const BlockParcels out = parcelBlock(block, options, geos);
  int undeveloped = 0;
  for (const VectorParcel& p : out.parcels) undeveloped += p.undeveloped;
  EXPECT_EQ(static_cast<int>(out.parcels.size()), out.report.targetParcels) << out.report.shortfall;
  EXPECT_GT(undeveloped, 0);
  EXPECT_GT(out.report.targetParcels, 3);
}

TEST(Pipeline, ListedUnusedParcelsAreNotDoubled) {
  // The same half-unused block, but its unused land is listed as two parcels of use unused, as
  // cadastral plots without a use are: the block gets exactly its five listed parcels.
  geos::Context geos;
  ParcelBlock block = fixtures::stripBlock(
      16, 6,
      {LandUse::Residential, LandUse::Unused, LandUse::Commercial, LandUse::Unused, LandUse::Residential});
  for (SimParcel& p : block.sim.parcels) p.cells = p.use == LandUse::Unused ? 24 : 16;
  block.sim.developedArea = 48;
  block.sim.undevelopedArea = 48;
  ParcelsOptions options;
  const BlockParcels out = parcelBlock(block, options, geos);
  EXPECT_EQ(out.report.targetParcels, 5);
  EXPECT_EQ(static_cast<int>(out.parcels.size()), 5) << out.report.shortfall;
  // The documents' rule alone doubles the undeveloped parcels.
  options.undeveloped.skipListedUnusedParcels = false;
  EXPECT_GT(parcelBlock(block, options, geos).report.targetParcels, 5);
}

TEST(Pipeline, BlockWithAHoleIsTiledExactly) {
  geos::Context geos;
  ParcelBlock block = fixtures::stripBlock(
      20, 10,
      {LandUse::Residential, LandUse::Commercial, LandUse::Residential, LandUse::Residential, LandUse::Park});
  block.polygon.holes = {{{9, 4}, {11, 4}, {11, 6}, {9, 6}, {9, 4}}};
  block.blockId = 5;
  const BlockParcels out = parcelBlock(block, {}, geos);
  EXPECT_EQ(out.parcels.size(), 5u) << out.report.shortfall;
  const TilingCheck t = checkTiling(block.polygon, out.parcels, geos);
  EXPECT_EQ(t.invalidParcels, 0);
  EXPECT_NEAR(t.parcelArea, 196.0, 1e-6 * 196);
  EXPECT_LE(t.gapArea + t.overlapArea + t.outsideArea, 1e-6 * 196);
}

TEST(Checkers, UseShareDistanceFollowsEquation33) {
  SimBlockSummary sim;
  sim.area = 100;
  sim.developedArea = 90;
  sim.undevelopedArea = 10;
  sim.parcels = {{1, LandUse::Residential, 60, 0, {}}, {2, LandUse::Park, 30, 0, {}}};
  auto parcel = [](LandUse use, double a, bool undeveloped = false) {
    VectorParcel p;
    p.use = use;
    p.area = a;
    p.undeveloped = undeveloped;
    return p;
  };
  // 10 % undeveloped (< 0.25): shares of developed land, 2/3 residential and 1/3 park.
  EXPECT_NEAR(useShareDistance(
                  sim, {parcel(LandUse::Residential, 66.6666666667), parcel(LandUse::Park, 33.3333333333)}),
              0.0, 1e-9);
  EXPECT_NEAR(useShareDistance(sim, {parcel(LandUse::Residential, 100)}), 2.0 / 3.0, 1e-9);
  // 40 % undeveloped: undeveloped is a use.
  sim.undevelopedArea = 40;
  sim.area = 130;
  EXPECT_NEAR(useShareDistance(sim, {parcel(LandUse::Residential, 60), parcel(LandUse::Park, 30),
                                     parcel(LandUse::Unused, 40, true)}),
              0.0, 1e-9);
}

TEST(Pipeline, DensityHelperUsesSquareMetres) {
  EXPECT_DOUBLE_EQ(parcelDensity(144.0, 2.0, 12.0), 0.5);
  EXPECT_DOUBLE_EQ(parcelDensity(10.0, 0.0, 12.0), 0.0);
}

/// The measurement behind the default `-spine-method` (docs/vectorize_parcels.md): the same random
/// city with both methods; hard invariants asserted, figures printed.
TEST(Pipeline, QualityOnRandomCityForBothSpineMethods) {
  const std::vector<ParcelBlock> blocks = randomCity(60, 2026);
  for (SpineMethod method : {SpineMethod::ZhangSuen, SpineMethod::Skeleton}) {
    ParcelsOptions options;
    options.spine.method = method;
    options.seed = 7;
    const auto start = std::chrono::steady_clock::now();
    const ParcelsResult result = vectorizeParcels(blocks, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const ParcelsQuality q = assessParcels(blocks, result, options);
    double cost = 0.0;
    int spines = 0, spineUsed = 0;
    long attempts = 0, shortTries = 0;
    for (const BlockParcels& b : result.blocks) {
      attempts += b.report.splitAttempts;
      shortTries += b.report.shortTries;
      cost += b.report.cost;
      spines += b.report.hasSpine;
      spineUsed += b.report.hasSpine && !b.report.spineDiscarded;
    }
    std::printf(
        "[measure] method=%s blocks=%d parcels=%d spines=%d used=%d mean_cost=%.3f shortfall_blocks=%d "
        "no_frontage=%d/%d mean_use_L1=%.3f worst_gap=%.2e worst_overlap=%.2e pop_error=%.2e ignored=%.1f "
        "time=%.2fs attempts=%ld short_tries=%ld\n",
        method == SpineMethod::Skeleton ? "skeleton" : "zhang-suen", q.blocks, q.parcels, spines, spineUsed,
        cost / q.blocks, q.shortfallBlocks, q.developedWithoutFrontage, q.developedParcels,
        q.meanUseShareDistance, q.worstGapRatio, q.worstOverlapRatio, q.populationError(),
        q.ignoredPopulation, seconds, attempts, shortTries);
    EXPECT_EQ(q.invalidParcels, 0);
    EXPECT_LE(q.worstGapRatio, 1e-6);
    EXPECT_LE(q.worstOverlapRatio, 1e-6);
    EXPECT_LE(q.populationError(), 1e-9);
    EXPECT_GT(spines, 5);
  }
}

TEST(Pipeline, BlockSmallerThanItsSimulatedParcelsScalesTheMinimumSize) {
  // Four simulated parcels of 12 cells must fit a 6 x 4 block: 6 cells each, below 75% of 12.
  geos::Context geos;
  ParcelBlock block = fixtures::stripBlock(12, 4, std::vector<LandUse>(4, LandUse::Residential));
  block.polygon.outer = fixtures::rectangleRing(6, 4);
  block.roadFacing = {block.polygon.outer};
  ParcelsOptions options;
  options.relaxationRounds = 0;
  const BlockParcels scaled = parcelBlock(block, options, geos);
  EXPECT_EQ(scaled.report.parcels, 4) << scaled.report.shortfall;
  EXPECT_EQ(scaled.report.relaxedRules, 0);
  // The documents' threshold alone cannot: the report says why.
  options.regular.scaleMinAreaToBlock = false;
  const BlockParcels strict = parcelBlock(block, options, geos);
  EXPECT_LT(strict.report.parcels, 4);
  EXPECT_NE(strict.report.shortfall.find("minimum parcel size"), std::string::npos)
      << strict.report.shortfall;
  // A relaxation round halves the threshold and reaches the count, and says so.
  options.relaxationRounds = 2;
  const BlockParcels relaxed = parcelBlock(block, options, geos);
  EXPECT_EQ(relaxed.report.parcels, 4) << relaxed.report.shortfall;
  EXPECT_EQ(relaxed.report.relaxedRules, 1);
  EXPECT_TRUE(relaxed.report.shortfall.empty());
}

TEST(Pipeline, PatienceStopsABlockWhoseCompleteBestStopsImprovingAndKeepsItsPrefix) {
  // -patience p (issue 21): a block stops once its complete best has not improved for p tries. The
  // tries it runs are the first tries of the full search (same seed stream), so its best is the best
  // of that prefix: never cheaper than the full search's, and equal to it when the full search found
  // nothing better later.
  const std::vector<ParcelBlock> blocks = randomCity(12, 21);
  ParcelsOptions full;
  full.threads = 1;
  ParcelsOptions patient = full;
  patient.patience = 3;
  const ParcelsResult a = vectorizeParcels(blocks, full);
  const ParcelsResult b = vectorizeParcels(blocks, patient);
  int fewer = 0, total = 0, patientTotal = 0;
  for (size_t k = 0; k < blocks.size(); ++k) {
    const BlockReport& ra = a.blocks[k].report;
    const BlockReport& rb = b.blocks[k].report;
    total += ra.tries;
    patientTotal += rb.tries;
    if (ra.parcels < ra.targetParcels || blocks[k].sim.parcels.empty()) continue;
    EXPECT_LE(rb.tries, ra.tries);
    EXPECT_GE(rb.cost, ra.cost - 1e-9) << "block " << ra.blockId;
    fewer += rb.tries < ra.tries;
  }
  EXPECT_GE(fewer, 6);                      // most complete blocks stop early
  EXPECT_LT(patientTotal, total * 6 / 10);  // and the search is much shorter
  // 0 = all tries; a negative patience is an option error.
  patient.patience = -1;
  try {
    vectorizeParcels(blocks, patient);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidOption);
    EXPECT_EQ(std::string(e.what()), "-patience must be 0 (all tries) or more, got -1.");
  }
}
