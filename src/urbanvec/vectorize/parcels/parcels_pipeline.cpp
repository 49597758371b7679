// Vectorizer part 3 driver (spec §1: "Per block, E1-E5 form one generate-and-test iteration. The
// iteration runs 50 times and the lowest-cost result is kept"; E6 runs once on the kept result).
#include "urbanvec/vectorize/parcels/parcels_pipeline.hpp"

#include <algorithm>
#include <array>
#include <memory>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/parallel.hpp"
#include "urbanvec/core/random.hpp"
#include "urbanvec/vectorize/parcels/population.hpp"

namespace urbanvec::vectorize::parcels {

namespace {

std::vector<UseParcel> useParcels(const std::vector<SubdivisionParcel>& parcels) {
  std::vector<UseParcel> out;
  for (const SubdivisionParcel& p : parcels) out.push_back({p.area, polygonMoments(p.polygon).centroid});
  return out;
}

/// Whether a parcel's lists hold at most about twice what its polygon needs.
bool compactLists(const SubdivisionParcel& p) {
  const size_t vertices = p.polygon.outer.size();
  return p.polygon.outer.capacity() <= 2 * vertices + 16 && p.index.prefix.capacity() <= 2 * vertices + 16;
}

int countUndeveloped(const std::vector<UseChoice>& uses) {
  return static_cast<int>(
      std::count_if(uses.begin(), uses.end(), [](const UseChoice& c) { return c.undeveloped; }));
}

}  // namespace

void validateParcelsOptions(const ParcelsOptions& o) {
  if (o.tries < 1) throw invalidOption("-tries must be at least 1, got " + std::to_string(o.tries) + ".");
  if (o.patience < 0)
    throw invalidOption("-patience must be 0 (all tries) or more, got " + std::to_string(o.patience) + ".");
  if (o.relaxationRounds < 0 || o.relaxedTries < 1)
    throw invalidOption("relaxation rounds must be non-negative and relaxed tries at least 1.");
  if (o.threads < 0) throw invalidOption("the thread count must be 0 (all cores) or more.");
  if (o.spine.pixelsPerCell < 1 || o.spine.pixelsPerCell > 64)
    throw invalidOption("the spine resolution must be 1 to 64 pixels per cell.");
  if (o.spine.oblongAspect < 0.0 || o.spine.oblongAspect > 1.0)
    throw invalidOption("the oblong aspect threshold must be within [0, 1].");
  if (o.spine.trimDistance < 0.0 || o.spine.turningThreshold <= 0.0 || o.spine.smoothingPasses < 0 ||
      o.spine.minBranchEdges < 0)
    throw invalidOption(
        "spine trim distance, turning threshold, smoothing passes and branch length must be positive.");
  const RegularSubdivisionOptions& r = o.regular;
  if (r.minAreaFraction < 0.0 || r.minFrontage < 0.0 || r.aspectThreshold < 0.0 || r.aspectThreshold > 1.0 ||
      r.minChildShare < 0.0 || r.minChildShare > 0.5 || r.residentialShare < 0.0 || r.residentialShare > 1.0)
    throw invalidOption(
        "subdivision constraints are out of range (shares within [0, 1], child share at most 0.5).");
  if (r.positionSigma <= 0.0 || r.simplifyTolerance < 0.0 || r.maxLargestAttempts < 0 || r.maxAttempts < 1 ||
      r.frontageTolerance <= 0.0)
    throw invalidOption("subdivision sampling options must be positive.");
  if (o.undeveloped.multiplier < 1.0) throw invalidOption("the undeveloped multiplier must be at least 1.");
}

BlockParcels parcelBlock(const ParcelBlock& block, const ParcelsOptions& options, const geos::Context& geos) {
  if (block.polygon.outer.size() < 4 || !(area(block.polygon) > 0.0))
    throw invalidInput("block " + std::to_string(block.blockId) +
                       " has an empty or degenerate polygon (fewer than 3 distinct vertices or no area).");
  BlockParcels out;
  BlockReport& report = out.report;
  report.blockId = block.blockId;
  const SimBlockSummary& sim = block.sim;
  const int simCount = static_cast<int>(sim.parcels.size());
  report.simParcels = simCount;
  for (const SimParcel& p : sim.parcels) report.simPopulation += p.population;
  Rng rng(deriveSeed(options.seed,
                     block.seedStream ? *block.seedStream : static_cast<std::uint64_t>(block.blockId)));
  const double blockArea = area(block.polygon);
  const double diagonal = block.obbDiagonal > 0.0 ? block.obbDiagonal : orientedBox(block.polygon).diagonal();

  // D6
  SpineGraph spine;
  if (needsSpine(block, options.spine)) spine = buildSpine(block.polygon, options.spine, geos);
  out.spine = spineBranches(spine);
  report.hasSpine = !spine.edges.empty();

  // Q13: a vector block without simulated parcels is one undeveloped parcel.
  if (simCount == 0) {
    VectorParcel only;
    only.polygon = block.polygon;
    only.undeveloped = true;
    only.area = blockArea;
    out.parcels.push_back(only);
    report.targetParcels = report.parcels = 1;
    report.ignoredPopulation = report.simPopulation;
    return out;
  }

  // E1 is deterministic: compute once, start every try from it.
  double smallestSim = 0.0;
  for (const SimParcel& p : sim.parcels)
    if (smallestSim == 0.0 || p.cells < smallestSim) smallestSim = p.cells;
  const SpineParcels spineParcels =
      spineSubdivision(block.polygon, spine, simCount, smallestSim, options.spineSubdivision, geos);
  report.spineDiscarded = report.hasSpine && !spineParcels.used;
  MultiPolygon initial = spineParcels.used ? spineParcels.parcels : MultiPolygon{block.polygon};

  const RoadFrontage frontage(geos, block.roadFacing, options.regular.frontageTolerance);
  SplitRules rules = splitRules(sim, options.regular);
  if (options.regular.scaleMinAreaToBlock) {
    double simParcelArea = 0.0;
    for (const SimParcel& p : sim.parcels) simParcelArea += p.cells;
    if (simParcelArea > blockArea && simParcelArea > 0.0) rules.minArea *= blockArea / simParcelArea;
  }
  const UseModel model = buildUseModel(sim, options.landUse);
  // Every try starts from the E1 parcels: simplify them and find their road-facing edges once, not
  // once per try.
  std::vector<SubdivisionParcel> initialParcels;
  for (const Polygon& p : initial) {
    initialParcels.emplace_back(p);
    prepare(initialParcels.back(), options.regular, frontage, geos);
  }

  struct Best {
    bool set = false;
    int missing = 0;
    double cost = 0.0;
    Cost parts;
    int target = 0;
    std::vector<SubdivisionParcel> parcels;
    std::vector<UseChoice> uses;
    std::string shortfall;
    int relaxed = 0;
  } best;

  // One buffer for the try's parcels: copy-assigning the start parcels into it reuses the memory of
  // the last try's polygons (a new vector only after a try became the best and took the buffer).
  std::vector<SubdivisionParcel> parcels;
  SubdivisionScratch scratch;  // the attempts' children and the spare parcels of earlier tries
  auto runTries = [&](const SplitRules& rules, int tries, int relaxed) {
    int lastImprovement = 0;
    for (int attempt = 0; attempt < tries; ++attempt) {
      if (options.patience > 0 && best.set && best.missing == 0 && best.relaxed == relaxed &&
          attempt - lastImprovement >= options.patience)
        break;
      // The parcels past the start ones serve the next try as spares, unless a slot's lists grew to a
      // much larger polygon it held before (the start parcels' copies travel through the slots):
      // those are freed, so a block keeps few lists of its largest parcels' size.
      for (size_t k = initialParcels.size(); k < parcels.size(); ++k)
        if (compactLists(parcels[k])) scratch.spare.push_back(std::move(parcels[k]));
      parcels.assign(initialParcels.begin(), initialParcels.end());
      SplitStats stats;
      int target = std::max(simCount, static_cast<int>(parcels.size()));
      subdivide(parcels, target, rules, options.regular, frontage, geos, rng, stats, scratch);  // E2
      std::vector<UseParcel> described = useParcels(parcels);
      std::vector<UseChoice> uses = assignLandUse(described, blockArea, model, options.landUse, rng);  // E4
      const int extra = undevelopedExtraParcels(sim, countUndeveloped(uses), options.undeveloped);     // E3
      if (extra > 0) {
        target += extra;
        subdivide(parcels, target, rules, options.regular, frontage, geos, rng, stats, scratch);
        described = useParcels(parcels);
        uses = assignLandUse(described, blockArea, model, options.landUse, rng);
      }
      const Cost cost =
          scoreParcels(described, uses, blockArea, diagonal, model, sim, options.scoring);  // E5
      const int missing = std::max(0, target - static_cast<int>(parcels.size()));
      ++report.tries;
      report.splitAttempts += stats.accepted;
      for (int r : stats.rejected) report.splitAttempts += r;
      report.shortTries += missing > 0;
      // [INFERENCE] a complete subdivision beats any short one; among equals the lower cost wins.
      // A relaxed round only replaces the result of an earlier round by making more parcels.
      if (!best.set || missing < best.missing ||
          (missing == best.missing && relaxed == best.relaxed && cost.total() < best.cost)) {
        best.set = true;
        best.missing = missing;
        best.cost = cost.total();
        best.parts = cost;
        best.target = target;
        std::swap(best.parcels, parcels);  // the old best's memory serves the next try
        best.uses = std::move(uses);
        best.shortfall =
            missing > 0 ? (rules.minFrontage > 0.0 && frontage.empty() ? "block has no road-facing boundary"
                                                                       : stats.shortfallReason())
                        : std::string();
        best.relaxed = relaxed;
        lastImprovement = attempt;
      }
    }
  };
  runTries(rules, options.tries, 0);
  SplitRules relaxedRules = rules;
  for (int round = 1; round <= options.relaxationRounds && best.missing > 0; ++round) {
    relaxedRules.minArea *= 0.5;
    relaxedRules.aspectThreshold *= 0.5;
    runTries(relaxedRules, options.relaxedTries, round);
  }

  // E6 on the kept result.
  const std::vector<UseParcel> described = useParcels(best.parcels);
  const PopulationResult population = assignPopulation(described, best.uses, sim);
  for (size_t k = 0; k < best.parcels.size(); ++k) {
    VectorParcel p;
    // A copy, not a move: the try's parcels reuse their lists (issue 21), so a ring's capacity can be
    // that of a larger polygon the slot held before, and the output keeps every parcel to the end.
    p.polygon = best.parcels[k].polygon;
    p.undeveloped = best.uses[k].undeveloped;
    p.use = best.uses[k].use;
    p.population = population.population[k];
    p.area = described[k].area;
    out.parcels.push_back(std::move(p));
  }
  report.targetParcels = best.target;
  report.parcels = static_cast<int>(out.parcels.size());
  report.cost = best.cost;
  report.costUse = best.parts.use;
  report.costDistance = best.parts.distance;
  report.costSize = best.parts.size;
  report.shortfall = best.shortfall;
  report.relaxedRules = best.relaxed;
  report.ignoredPopulation = population.ignoredPopulation;
  report.ignoredUses = population.ignoredUses;
  return out;
}

ParcelsResult vectorizeParcels(const std::vector<ParcelBlock>& blocks, const ParcelsOptions& options,
                               const Progress& progress) {
  validateParcelsOptions(options);
  ParcelsResult result;
  result.blocks.resize(blocks.size());
  const size_t n = blocks.size();
  ProgressTicker ticker(progress, "parcels", n);
  if (n == 0) {
    ticker.finish();
    return result;
  }
  // One GEOS context per worker; each block writes only its own slot, so the thread count does not
  // change the result.
  const size_t workers = std::min(workerCount(options.threads), n);
  std::vector<std::unique_ptr<geos::Context>> contexts;
  for (size_t w = 0; w < workers; ++w) contexts.push_back(std::make_unique<geos::Context>());
  runParallel(
      workers, n,
      [&](size_t i, size_t worker) { result.blocks[i] = parcelBlock(blocks[i], options, *contexts[worker]); },
      [&](size_t done) { ticker.tick(done); });
  ticker.finish();
  return result;
}

TilingCheck checkTiling(const Polygon& block, const std::vector<VectorParcel>& parcels,
                        const geos::Context& geos) {
  TilingCheck check;
  GEOSContextHandle_t h = geos.handle();
  check.blockArea = area(block);
  MultiPolygon all;
  for (const VectorParcel& p : parcels) {
    check.parcelArea += area(p.polygon);
    geos::GeomPtr g = geos.polygon(p.polygon);
    if (GEOSisValid_r(h, g.get()) != 1) ++check.invalidParcels;
    all.push_back(p.polygon);
  }
  geos::GeomPtr blockGeom = geos.polygon(block);
  geos::GeomPtr collection = geos.multiPolygon(all);
  geos::GeomPtr merged = geos.own(GEOSUnaryUnion_r(h, collection.get()), "union");
  double unionArea = 0.0;
  GEOSArea_r(h, merged.get(), &unionArea);
  check.overlapArea = std::max(0.0, check.parcelArea - unionArea);
  geos::GeomPtr gap = geos.own(GEOSDifference_r(h, blockGeom.get(), merged.get()), "difference");
  geos::GeomPtr outside = geos.own(GEOSDifference_r(h, merged.get(), blockGeom.get()), "difference");
  GEOSArea_r(h, gap.get(), &check.gapArea);
  GEOSArea_r(h, outside.get(), &check.outsideArea);
  return check;
}

double useShareDistance(const SimBlockSummary& sim, const std::vector<VectorParcel>& parcels,
                        double undevelopedSwitch) {
  // Index 0..8 by LandUse, index 9 for undeveloped.
  double simShare[10] = {}, vecShare[10] = {};
  double simTotal = 0.0, vecTotal = 0.0;
  const std::array<double, kLandUseClassCount> areas = simulatedUseAreas(sim);
  for (int use = 0; use < kLandUseClassCount; ++use)
    if (isDeveloped(static_cast<LandUse>(use))) {
      simShare[use] = areas[static_cast<size_t>(use)];
      simTotal += simShare[use];
    }
  if (sim.area > 0.0 && sim.undevelopedArea / sim.area >= undevelopedSwitch) {
    simShare[9] = sim.undevelopedArea;
    simTotal += sim.undevelopedArea;
  }
  for (const VectorParcel& p : parcels) {
    vecShare[p.undeveloped ? 9 : static_cast<int>(p.use)] += p.area;
    vecTotal += p.area;
  }
  double l1 = 0.0;
  for (int i = 0; i < 10; ++i)
    l1 += std::fabs((simTotal > 0.0 ? simShare[i] / simTotal : 0.0) -
                    (vecTotal > 0.0 ? vecShare[i] / vecTotal : 0.0));
  return l1;
}

ParcelsQuality assessParcels(const std::vector<ParcelBlock>& blocks, const ParcelsResult& result,
                             const ParcelsOptions& options) {
  ParcelsQuality q;
  geos::Context geos;
  int withSim = 0;
  for (size_t b = 0; b < blocks.size() && b < result.blocks.size(); ++b) {
    const ParcelBlock& block = blocks[b];
    const BlockParcels& out = result.blocks[b];
    ++q.blocks;
    q.parcels += static_cast<int>(out.parcels.size());
    const TilingCheck t = checkTiling(block.polygon, out.parcels, geos);
    q.invalidParcels += t.invalidParcels;
    if (t.blockArea > 0.0) {
      q.worstGapRatio = std::max(q.worstGapRatio, t.gapArea / t.blockArea);
      q.worstOverlapRatio = std::max(q.worstOverlapRatio, (t.overlapArea + t.outsideArea) / t.blockArea);
    }
    const RoadFrontage frontage(geos, block.roadFacing, options.regular.frontageTolerance);
    for (const VectorParcel& p : out.parcels) {
      if (p.undeveloped) continue;
      ++q.developedParcels;
      if (frontage.longestGeos(p.polygon) < options.regular.minFrontage) ++q.developedWithoutFrontage;
    }
    if (out.report.parcels < out.report.targetParcels) ++q.shortfallBlocks;
    if (!block.sim.parcels.empty()) {
      q.meanUseShareDistance += useShareDistance(block.sim, out.parcels, options.landUse.undevelopedSwitch);
      ++withSim;
    }
    q.simPopulation += out.report.simPopulation;
    q.ignoredPopulation += out.report.ignoredPopulation;
    q.ignoredUses += out.report.ignoredUses;
    for (const VectorParcel& p : out.parcels) q.outputPopulation += p.population;
  }
  if (withSim > 0) q.meanUseShareDistance /= withSim;
  return q;
}

}  // namespace urbanvec::vectorize::parcels
