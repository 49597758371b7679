// E4 probability terms, the trivial case, E5 cost, E6 population mapping.
#include <gtest/gtest.h>

#include <numeric>

#include "urbanvec/vectorize/parcels/land_use_assignment.hpp"
#include "urbanvec/vectorize/parcels/parcel_scoring.hpp"
#include "urbanvec/vectorize/parcels/population.hpp"

using namespace urbanvec;
using namespace urbanvec::vectorize::parcels;

namespace {

double sum(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

SimBlockSummary mixedBlock() {
  SimBlockSummary sim;
  sim.area = 40;
  sim.developedArea = 40;
  sim.parcels = {{1, LandUse::Residential, 8, 30, {2, 2}},
                 {2, LandUse::Residential, 12, 50, {6, 2}},
                 {3, LandUse::Commercial, 10, 5, {2, 6}},
                 {4, LandUse::Park, 10, 0, {6, 6}}};
  return sim;
}

}  // namespace

TEST(Probabilities, EachTermSumsToOne) {
  const auto pd = distanceProbabilities({1.0, 2.0, 4.0}, 1e-6);
  EXPECT_NEAR(sum(pd), 1.0, 1e-12);
  EXPECT_GT(pd[0], pd[1]);  // nearer use more likely
  const auto pdZero = distanceProbabilities({0.0, 3.0}, 1e-6);
  EXPECT_NEAR(sum(pdZero), 1.0, 1e-12);

  const auto pu = proportionProbabilities({0.5, 0.3, 0.2}, {0.1, 0.3, 0.05});
  EXPECT_NEAR(sum(pu), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(pu[1], 0.0);  // puu_i = 0 once u_i ≥ us_i

  const auto ps = sizeProbabilities(10.0, {8.0, 20.0, 100.0}, {2.0, 5.0, 10.0});
  EXPECT_NEAR(sum(ps), 1.0, 1e-12);
  EXPECT_GT(ps[0], ps[2]);

  const auto p = combinedProbabilities(pd, pu, ps);
  EXPECT_NEAR(sum(p), 1.0, 1e-12);
  for (double x : p) EXPECT_GE(x, 0.0);
  const auto c = cumulativeProbabilities(p);
  EXPECT_DOUBLE_EQ(c.back(), 1.0);
  for (size_t i = 1; i < c.size(); ++i) EXPECT_GE(c[i], c[i - 1]);
  EXPECT_EQ(pickInterval(c, 0.0), p[0] > 0 ? 0u : 1u);

  // Degenerate product (pu all zero) falls back to pd·ps, still a distribution.
  const auto fallback = combinedProbabilities(pd, {0, 0, 0}, ps);
  EXPECT_NEAR(sum(fallback), 1.0, 1e-12);
}

TEST(UseModel, SharesFollowEquation33) {
  SimBlockSummary sim = mixedBlock();
  UseModel model = buildUseModel(sim, {});
  EXPECT_FALSE(model.undevelopedActive);
  EXPECT_FALSE(model.trivial);
  EXPECT_NEAR(sum(model.simShare), 1.0, 1e-12);
  // Now 40% undeveloped: shares are of all land and undeveloped becomes a candidate.
  sim.area = 66.6666666666666667;
  sim.undevelopedArea = sim.area - 40;
  model = buildUseModel(sim, {});
  EXPECT_TRUE(model.undevelopedActive);
  EXPECT_NEAR(sum(model.simShare) + model.simUndevelopedShare, 1.0, 1e-9);
}

TEST(UseModel, SharesComeFromTheBlocksPatchesNotFromParcelsReachingIntoOtherBlocks) {
  // A 10-patch block: 5 residential, 5 commercial patches. Its residential parcel has 95 more cells
  // in blocks across a road (a plot the grid's roads cut), so its cell count says nothing of this
  // block: the share is of the block's own patches.
  SimBlockSummary sim;
  sim.area = 10;
  sim.developedArea = 10;
  sim.useArea.assign(256, 0.0);
  sim.useArea[static_cast<size_t>(LandUse::Residential)] = 5;
  sim.useArea[static_cast<size_t>(LandUse::Commercial)] = 5;
  sim.parcels = {{1, LandUse::Residential, 100, 30, {2, 2}}, {2, LandUse::Commercial, 5, 5, {6, 2}}};
  const UseModel model = buildUseModel(sim, {});
  ASSERT_EQ(model.simShare.size(), 2u);
  EXPECT_DOUBLE_EQ(model.simShare[0], 0.5);
  EXPECT_DOUBLE_EQ(model.simShare[1], 0.5);
  // Half and half in the vector block costs nothing in cu (it cost 9.5 from the parcels' cells).
  const std::vector<UseParcel> parcels = {{5.0, {2, 2}}, {5.0, {6, 2}}};
  const std::vector<UseChoice> uses = {{false, LandUse::Residential}, {false, LandUse::Commercial}};
  EXPECT_NEAR(scoreParcels(parcels, uses, 10.0, 10.0, model, sim, {}).use, 0.0, 1e-12);
}

TEST(LandUse, SingleUseFullyDevelopedBlockGetsThatUseEverywhere) {
  SimBlockSummary sim;
  sim.area = 30;
  sim.developedArea = 30;
  sim.parcels = {{1, LandUse::Industrial, 10, 0, {1, 1}}, {2, LandUse::Industrial, 20, 0, {5, 1}}};
  const UseModel model = buildUseModel(sim, {});
  EXPECT_TRUE(model.trivial);
  std::vector<UseParcel> parcels(5, UseParcel{6.0, {2, 2}});
  Rng rng(1);
  for (const UseChoice& c : assignLandUse(parcels, 30, model, {}, rng)) {
    EXPECT_FALSE(c.undeveloped);
    EXPECT_EQ(c.use, LandUse::Industrial);
  }
}

TEST(LandUse, MixedBlockUsesOnlySimulatedUsesAndNoUndevelopedBelowTheSwitch) {
  const SimBlockSummary sim = mixedBlock();
  const UseModel model = buildUseModel(sim, {});
  std::vector<UseParcel> parcels;
  for (int k = 0; k < 8; ++k) parcels.push_back({5.0, {1.0 + k, 1.0 + (k % 2) * 4}});
  Rng rng(5);
  for (const UseChoice& c : assignLandUse(parcels, 40, model, {}, rng)) {
    EXPECT_FALSE(c.undeveloped);
    EXPECT_TRUE(c.use == LandUse::Residential || c.use == LandUse::Commercial || c.use == LandUse::Park);
  }
}

TEST(Scoring, PerfectMatchCostsNothingButSize) {
  const SimBlockSummary sim = mixedBlock();
  const UseModel model = buildUseModel(sim, {});
  std::vector<UseParcel> parcels;
  std::vector<UseChoice> uses;
  for (const SimParcel& p : sim.parcels) {
    parcels.push_back({p.cells, p.centre});
    uses.push_back({false, p.use});
  }
  const Cost cost = scoreParcels(parcels, uses, 40, 10, model, sim, {});
  EXPECT_NEAR(cost.use, 0.0, 1e-12);
  EXPECT_NEAR(cost.distance, 0.0, 1e-12);
  EXPECT_NEAR(cost.size, 0.0, 1e-12);
  uses[3].use = LandUse::Commercial;  // park parcel labelled commercial
  const Cost worse = scoreParcels(parcels, uses, 40, 10, model, sim, {});
  EXPECT_NEAR(worse.use, 0.5, 1e-12);
  EXPECT_GT(worse.distance, 0.0);
}

TEST(Population, ConservedWhenMoreVectorParcelsThanSimulated) {
  SimBlockSummary sim;
  sim.parcels = {{1, LandUse::Residential, 10, 30, {0, 0}}, {2, LandUse::Residential, 10, 70, {10, 0}}};
  // Four vector parcels: the two smallest (near x=10) are grouped and share 70 people by area.
  const std::vector<UseParcel> parcels = {{10, {0, 0}}, {8, {2, 0}}, {2, {9, 0}}, {6, {11, 0}}};
  const std::vector<UseChoice> uses(4, UseChoice{false, LandUse::Residential});
  const PopulationResult r = assignPopulation(parcels, uses, sim);
  EXPECT_NEAR(sum(r.population), 100.0, 1e-9);
  EXPECT_NEAR(r.population[2] / r.population[3], 2.0 / 6.0, 1e-9);  // grouped: proportional to area
  EXPECT_DOUBLE_EQ(r.ignoredPopulation, 0.0);
}

TEST(Population, ConservedWhenCountsAreEqual) {
  SimBlockSummary sim;
  sim.parcels = {{1, LandUse::Commercial, 10, 12, {0, 0}}, {2, LandUse::Commercial, 10, 4, {10, 0}}};
  const std::vector<UseParcel> parcels = {{9, {9, 0}}, {11, {1, 0}}};
  const std::vector<UseChoice> uses(2, UseChoice{false, LandUse::Commercial});
  const PopulationResult r = assignPopulation(parcels, uses, sim);
  EXPECT_DOUBLE_EQ(r.population[1], 12.0);  // nearest simulated parcel
  EXPECT_DOUBLE_EQ(r.population[0], 4.0);
}

TEST(Population, ConservedWhenFewerVectorParcelsAndIgnoredUseIsCounted) {
  SimBlockSummary sim;
  sim.parcels = {{1, LandUse::Residential, 10, 10, {0, 0}},
                 {2, LandUse::Residential, 10, 20, {5, 0}},
                 {3, LandUse::Residential, 10, 40, {10, 0}},
                 {4, LandUse::Industrial, 5, 7, {20, 0}}};
  const std::vector<UseParcel> parcels = {{15, {1, 0}}, {5, {10, 0}}, {4, {20, 0}}};
  std::vector<UseChoice> uses(3, UseChoice{false, LandUse::Residential});
  uses[2].undeveloped = true;
  const PopulationResult r = assignPopulation(parcels, uses, sim);
  EXPECT_NEAR(r.population[0] + r.population[1], 70.0, 1e-9);
  EXPECT_DOUBLE_EQ(r.population[2], 0.0);  // undeveloped
  EXPECT_DOUBLE_EQ(r.ignoredPopulation, 7.0);
  EXPECT_EQ(r.ignoredUses, 1);
  // Parcel 0 got sim 1 (10) plus 3/4 of the unmapped sim 2 (20); parcel 1 got sim 3 (40) plus 1/4.
  EXPECT_NEAR(r.population[0], 10.0 + 15.0, 1e-9);
  EXPECT_NEAR(r.population[1], 40.0 + 5.0, 1e-9);
}
