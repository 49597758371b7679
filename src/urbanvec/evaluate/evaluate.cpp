// The evaluator (issue 2 §3): runs the road, block and parcel metrics over whichever layers both
// cities have, leaving the others absent.
#include "urbanvec/evaluate/evaluate.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/core/planar_graph.hpp"
#include "urbanvec/evaluate/polygon_metrics.hpp"
#include "urbanvec/evaluate/road_metrics.hpp"

namespace urbanvec::evaluate {

namespace {

void checkOptions(const EvaluationInput& input, const EvaluateOptions& options) {
  if (!(input.cellSize > 0.0) || !std::isfinite(input.cellSize))
    throw invalidOption("the cell size must be a positive number of metres, got " +
                        std::to_string(input.cellSize));
  if (!(options.sampleSpacingCells > 0.0))
    throw invalidOption("the road sample spacing must be a positive number of cells, got " +
                        std::to_string(options.sampleSpacingCells));
  if (!(options.blockMatchIoU > 0.0 && options.blockMatchIoU <= 1.0))
    throw invalidOption("the block match IoU must be in (0, 1], got " +
                        std::to_string(options.blockMatchIoU));
  if (!std::is_sorted(options.bendClassEdges.begin(), options.bendClassEdges.end()) ||
      std::any_of(options.bendClassEdges.begin(), options.bendClassEdges.end(),
                  [](double e) { return !(e > 0.0 && e < 180.0); }))
    throw invalidOption("the bend-size class edges must be ascending angles in (0, 180) degrees");
  if (!(options.sharpBendDegrees >= 0.0 && options.sharpBendDegrees < 180.0))
    throw invalidOption("the sharp bend angle must be in [0, 180) degrees, got " +
                        std::to_string(options.sharpBendDegrees));
  if (!(options.matchableLandShare >= 0.0 && options.matchableLandShare <= 1.0))
    throw invalidOption("the matchable land share must be in [0, 1], got " +
                        std::to_string(options.matchableLandShare));
  if (options.landShareSubsamples < 1 || options.landShareSubsamples > 64)
    throw invalidOption("the land-share sample count per cell edge must be in [1, 64], got " +
                        std::to_string(options.landShareSubsamples));
  if (!(options.minTruthBlockCells >= 0.0) || !std::isfinite(options.minTruthBlockCells))
    throw invalidOption("the smallest truth block must be a non-negative number of cells, got " +
                        std::to_string(options.minTruthBlockCells));
}

/// The truth blocks of at least `minArea` m², as a layer of their own.
Layer blocksAtLeast(const Layer& blocks, double minArea) {
  Layer kept = blocks;
  kept.features.clear();
  for (const Feature& f : blocks.features) {
    double a = 0.0;
    if (const auto* p = std::get_if<Polygon>(&f.geometry)) a = area(*p);
    if (const auto* m = std::get_if<MultiPolygon>(&f.geometry)) a = area(*m);
    if (a >= minArea) kept.features.push_back(f);
  }
  return kept;
}

bool insideRing(const std::vector<Vec2>& ring, const Vec2& p) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Vec2& a = ring[i];
    const Vec2& b = ring[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
  }
  return inside;
}

bool insidePolygon(const Polygon& polygon, const Vec2& p) {
  if (polygon.outer.size() < 3 || !insideRing(polygon.outer, p)) return false;
  for (const auto& hole : polygon.holes)
    if (hole.size() >= 3 && insideRing(hole, p)) return false;
  return true;
}

/// Sample points of the polygon (n x n per cell) and how many of them lie on land cells.
std::pair<std::size_t, std::size_t> landCounts(const Polygon& polygon, const LandUseCells& cells, int n) {
  if (polygon.outer.empty()) return {0, 0};
  double c0 = INFINITY, c1 = -INFINITY, r0 = INFINITY, r1 = -INFINITY;
  for (const Vec2& w : polygon.outer) {
    const Vec2 px = cells.spec.transform.worldToPixel(w);
    c0 = std::min(c0, px.x);
    c1 = std::max(c1, px.x);
    r0 = std::min(r0, px.y);
    r1 = std::max(r1, px.y);
  }
  std::size_t total = 0, land = 0;
  for (int row = static_cast<int>(std::floor(r0)); row <= static_cast<int>(std::floor(r1)); ++row)
    for (int col = static_cast<int>(std::floor(c0)); col <= static_cast<int>(std::floor(c1)); ++col) {
      const bool onLand =
          cells.codes.inside(col, row) && cells.codes.at(col, row) != 2 && cells.codes.at(col, row) != 3;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const Vec2 p = cells.spec.transform.pixelToWorld(col + (i + 0.5) / n, row + (j + 0.5) / n);
          if (!insidePolygon(polygon, p)) continue;
          ++total;
          land += onLand;
        }
    }
  return {total, land};
}

double featureLandShare(const Geometry& geometry, const LandUseCells& cells, int n) {
  std::size_t total = 0, land = 0;
  auto add = [&](const Polygon& p) {
    const auto [t, l] = landCounts(p, cells, n);
    total += t;
    land += l;
  };
  if (const auto* p = std::get_if<Polygon>(&geometry)) add(*p);
  if (const auto* m = std::get_if<MultiPolygon>(&geometry))
    for (const Polygon& p : *m) add(p);
  return total > 0 ? static_cast<double>(land) / static_cast<double>(total) : 0.0;
}

double totalLengthKm(const std::vector<LineString>& lines) {
  double metres = 0.0;
  for (const LineString& l : lines) metres += length(l);
  return metres / 1000.0;
}

NetworkSummary summariseNetwork(const std::vector<LineString>& lines, double snap) {
  const PlanarGraph graph = PlanarGraph::fromLines(lines, snap);
  NetworkSummary out;
  for (std::size_t n = 0; n < graph.nodeCount(); ++n) {
    const int degree = graph.degree(static_cast<int>(n));
    if (degree >= 3) ++out.intersections;
    if (degree == 1) ++out.deadEnds;
  }
  int components = 0;
  graph.components(&components);
  out.components = static_cast<std::size_t>(components);
  return out;
}

RoadReport measureRoads(const EvaluationInput& input, const EvaluateOptions& options,
                        const Progress& progress) {
  RoadReport report;
  report.bendClassEdges = options.bendClassEdges;
  report.sharpBendDegrees = options.sharpBendDegrees;
  std::vector<LineString> truthLines, resultLines;
  if (input.truth.roads) {
    std::size_t count = 0;
    truthLines = roadCentrelines(*input.truth.roads, options, &count);
    report.truthLines = count;
    report.truthLengthKm = totalLengthKm(truthLines);
    report.truthTurningPerKm = turningPerKm(truthLines);
    report.truthTurningByBend = turningPerKmByBend(truthLines, options.bendClassEdges);
    report.truthSharpTurningPerKm = turningPerKmByBend(truthLines, {options.sharpBendDegrees})[1];
    report.truthNetwork = summariseNetwork(truthLines, options.networkSnapCells * input.cellSize);
  }
  if (input.result.roads) {
    std::size_t count = 0;
    resultLines = roadCentrelines(*input.result.roads, options, &count);
    report.resultLines = count;
    report.resultLengthKm = totalLengthKm(resultLines);
    report.resultTurningPerKm = turningPerKm(resultLines);
    report.resultTurningByBend = turningPerKmByBend(resultLines, options.bendClassEdges);
    report.resultSharpTurningPerKm = turningPerKmByBend(resultLines, {options.sharpBendDegrees})[1];
    report.resultNetwork = summariseNetwork(resultLines, options.networkSnapCells * input.cellSize);
  }
  if (report.truthTurningPerKm && report.resultTurningPerKm && *report.truthTurningPerKm > 0.0)
    report.turningRatio = *report.resultTurningPerKm / *report.truthTurningPerKm;
  if (report.truthSharpTurningPerKm && report.resultSharpTurningPerKm && *report.truthSharpTurningPerKm > 0.0)
    report.sharpTurningRatio = *report.resultSharpTurningPerKm / *report.truthSharpTurningPerKm;
  if (!truthLines.empty() && !resultLines.empty()) {
    const double spacing = options.sampleSpacingCells * input.cellSize;
    const std::vector<double> there =
        nearestDistances(samplePoints(truthLines, spacing), resultLines, subProgress(progress, 0.0, 0.5));
    report.truthToResult = summariseDistances(there, input.cellSize);
    const std::vector<double> back =
        nearestDistances(samplePoints(resultLines, spacing), truthLines, subProgress(progress, 0.5, 1.0));
    report.resultToTruth = summariseDistances(back, input.cellSize);
  }
  reportProgress(progress, 1.0, "road distances");
  return report;
}

/// Land-use area of the parcels assigned to each block.
std::vector<std::map<std::string, double>> landUseAreas(
    const Layer& layer, const PolygonLayer& parcels,
    const std::vector<std::optional<std::size_t>>& parcelBlock, std::size_t blockCount, int field) {
  std::vector<std::map<std::string, double>> out(blockCount);
  for (std::size_t p = 0; p < parcels.size(); ++p)
    if (parcelBlock[p])
      out[*parcelBlock[p]]
         [landUseKey(layer.features[parcels.featureIndex(p)].values[static_cast<std::size_t>(field)])] +=
          parcels.area(p);
  return out;
}

std::vector<std::size_t> countPerBlock(const std::vector<std::optional<std::size_t>>& parcelBlock,
                                       std::size_t blockCount) {
  std::vector<std::size_t> counts(blockCount, 0);
  for (const auto& b : parcelBlock)
    if (b) ++counts[*b];
  return counts;
}

double median(const std::vector<double>& values) {
  return quantile(values, 0.5);
}

void extend(std::optional<Extent>& box, const Vec2& p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
  if (!box) {
    box = Extent{p.x, p.y, p.x, p.y};
    return;
  }
  box->minX = std::min(box->minX, p.x);
  box->minY = std::min(box->minY, p.y);
  box->maxX = std::max(box->maxX, p.x);
  box->maxY = std::max(box->maxY, p.y);
}

void extend(std::optional<Extent>& box, const std::vector<Vec2>& points) {
  for (const Vec2& p : points) extend(box, p);
}

void extend(std::optional<Extent>& box, const Polygon& polygon) {
  extend(box, polygon.outer);  // holes lie inside the outer ring
}

}  // namespace

std::optional<Extent> cityExtent(const CityLayers& city) {
  std::optional<Extent> box;
  for (const std::optional<Layer>* layer : {&city.roads, &city.blocks, &city.parcels}) {
    if (!*layer) continue;
    for (const Feature& f : (*layer)->features) {
      if (const auto* p = std::get_if<Vec2>(&f.geometry)) extend(box, *p);
      if (const auto* l = std::get_if<LineString>(&f.geometry)) extend(box, *l);
      if (const auto* ml = std::get_if<MultiLineString>(&f.geometry))
        for (const LineString& l : *ml) extend(box, l);
      if (const auto* p = std::get_if<Polygon>(&f.geometry)) extend(box, *p);
      if (const auto* mp = std::get_if<MultiPolygon>(&f.geometry))
        for (const Polygon& p : *mp) extend(box, p);
    }
  }
  return box;
}

double landShare(const Polygon& polygon, const LandUseCells& cells, int subsamples) {
  return featureLandShare(Geometry(polygon), cells, subsamples);
}

bool extentsOverlap(const Extent& a, const Extent& b) {
  return a.minX <= b.maxX && b.minX <= a.maxX && a.minY <= b.maxY && b.minY <= a.maxY;
}

EvaluationReport evaluate(const EvaluationInput& input, const EvaluateOptions& options,
                          const Progress& progress) {
  checkOptions(input, options);
  EvaluationReport report;
  report.cellSize = input.cellSize;
  report.resultExtent = cityExtent(input.result);
  report.truthExtent = cityExtent(input.truth);
  report.layersOverlap = !report.resultExtent || !report.truthExtent ||
                         extentsOverlap(*report.resultExtent, *report.truthExtent);
  reportProgress(progress, 0.0, "road distances");
  report.roads = measureRoads(input, options, subProgress(progress, 0.0, 0.5));

  geos::Context ctx;
  std::optional<PolygonLayer> truthBlocks, resultBlocks, truthParcels, resultParcels;
  std::optional<Layer> countedTruthBlocks;
  if (input.truth.blocks) {
    countedTruthBlocks =
        blocksAtLeast(*input.truth.blocks, options.minTruthBlockCells * input.cellSize * input.cellSize);
    truthBlocks.emplace(ctx, *countedTruthBlocks);
  }
  if (input.result.blocks) resultBlocks.emplace(ctx, *input.result.blocks);
  if (input.truth.parcels) truthParcels.emplace(ctx, *input.truth.parcels);
  if (input.result.parcels) resultParcels.emplace(ctx, *input.result.parcels);

  BlockReport& blocks = report.blocks;
  blocks.iouThreshold = options.blockMatchIoU;
  blocks.minTruthBlockCells = options.minTruthBlockCells;
  blocks.matchableLandShare = options.matchableLandShare;
  if (truthBlocks) {
    blocks.truthCount = truthBlocks->size();
    blocks.truthSmallCount = input.truth.blocks->features.size() - truthBlocks->size();
  }
  if (resultBlocks) {
    blocks.resultCount = resultBlocks->size();
    blocks.resultInvalidCount = resultBlocks->invalidCount();
  }
  std::optional<BlockMatching> matching;
  if (truthBlocks && resultBlocks) {
    matching = matchBlocks(ctx, *truthBlocks, *resultBlocks, subProgress(progress, 0.5, 0.7));
    std::size_t matched = 0;
    double iouSum = 0.0;
    for (std::size_t t = 0; t < truthBlocks->size(); ++t) {
      iouSum += matching->bestIoU[t];
      if (matching->bestIoU[t] >= options.blockMatchIoU) ++matched;
    }
    blocks.matchedCount = matched;
    if (truthBlocks->size() > 0) {
      blocks.matchedShare = static_cast<double>(matched) / static_cast<double>(truthBlocks->size());
      blocks.meanBestIoU = iouSum / static_cast<double>(truthBlocks->size());
    }
    const int kindField = countedTruthBlocks->fieldIndex("kind");
    if (input.landUse) {
      std::size_t matchable = 0, matchableMatched = 0;
      for (std::size_t t = 0; t < truthBlocks->size(); ++t) {
        const Feature& f = countedTruthBlocks->features[truthBlocks->featureIndex(t)];
        if (kindField >= 0)
          if (const auto* kind = std::get_if<std::string>(&f.values[kindField]); kind && *kind == "external")
            continue;
        if (featureLandShare(f.geometry, *input.landUse, options.landShareSubsamples) <
            options.matchableLandShare)
          continue;
        ++matchable;
        if (matching->bestIoU[t] >= options.blockMatchIoU) ++matchableMatched;
      }
      blocks.matchableTruthCount = matchable;
      blocks.matchableMatchedCount = matchableMatched;
      if (matchable > 0)
        blocks.matchableMatchedShare = static_cast<double>(matchableMatched) / static_cast<double>(matchable);
    }
    if (kindField >= 0) {
      std::size_t internalCount = 0, internalMatched = 0;
      for (std::size_t t = 0; t < truthBlocks->size(); ++t) {
        const Feature& f = countedTruthBlocks->features[truthBlocks->featureIndex(t)];
        const auto* kind = std::get_if<std::string>(&f.values[kindField]);
        if (!kind || *kind != "internal") continue;
        ++internalCount;
        if (matching->bestIoU[t] >= options.blockMatchIoU) ++internalMatched;
      }
      blocks.internalTruthCount = internalCount;
      blocks.internalMatchedCount = internalMatched;
      if (internalCount > 0)
        blocks.internalMatchedShare =
            static_cast<double>(internalMatched) / static_cast<double>(internalCount);
    }
  }
  reportProgress(progress, 0.7, "parcels");

  ParcelReport& parcels = report.parcels;
  if (truthParcels) parcels.truthCount = truthParcels->size();
  if (resultParcels) {
    // Count and share over every polygonal feature, including those too broken to build or repair.
    std::size_t polygonal = 0;
    for (const Feature& f : input.result.parcels->features)
      if (std::holds_alternative<Polygon>(f.geometry) || std::holds_alternative<MultiPolygon>(f.geometry))
        ++polygonal;
    parcels.resultCount = polygonal;
    parcels.invalidCount = resultParcels->invalidCount();
    if (polygonal > 0)
      parcels.invalidShare =
          static_cast<double>(resultParcels->invalidCount()) / static_cast<double>(polygonal);
  }
  if (resultParcels && resultBlocks) {
    const auto resultParcelBlock = assignToBlocks(ctx, *resultParcels, *resultBlocks);
    const Coverage coverage = parcelCoverage(ctx, *resultParcels, *resultBlocks, resultParcelBlock,
                                             subProgress(progress, 0.7, 0.95));
    if (coverage.blockArea > 0.0) {
      parcels.gapShare = coverage.gapArea / coverage.blockArea;
      parcels.overlapShare = coverage.overlapArea / coverage.blockArea;
    }
    if (matching && truthParcels) {
      const auto truthParcelBlock = assignToBlocks(ctx, *truthParcels, *truthBlocks);
      const auto truthCounts = countPerBlock(truthParcelBlock, truthBlocks->size());
      const auto resultCounts = countPerBlock(resultParcelBlock, resultBlocks->size());
      const int truthUse = input.truth.parcels->fieldIndex(options.truthLandUseField);
      const int resultUse = input.result.parcels->fieldIndex(options.resultLandUseField);
      const bool withUse = truthUse >= 0 && resultUse >= 0;
      std::vector<std::map<std::string, double>> truthAreas, resultAreas;
      if (withUse) {
        truthAreas = landUseAreas(*input.truth.parcels, *truthParcels, truthParcelBlock, truthBlocks->size(),
                                  truthUse);
        resultAreas = landUseAreas(*input.result.parcels, *resultParcels, resultParcelBlock,
                                   resultBlocks->size(), resultUse);
      }
      std::vector<double> ratios, errors;
      for (std::size_t t = 0; t < truthBlocks->size(); ++t) {
        if (matching->bestIoU[t] < options.blockMatchIoU || truthCounts[t] == 0) continue;
        const std::size_t r = *matching->bestResult[t];
        ratios.push_back(static_cast<double>(resultCounts[r]) / static_cast<double>(truthCounts[t]));
        if (withUse) errors.push_back(landUseShareError(resultAreas[r], truthAreas[t]));
      }
      parcels.comparedBlocks = ratios.size();
      if (!ratios.empty()) {
        double sum = 0.0;
        for (double v : ratios) sum += v;
        parcels.countRatioMean = sum / static_cast<double>(ratios.size());
        parcels.countRatioMedian = median(ratios);
      }
      if (!errors.empty()) {
        double sum = 0.0;
        for (double v : errors) sum += v;
        parcels.landUseErrorMean = sum / static_cast<double>(errors.size());
      }
    }
  }
  reportProgress(progress, 1.0, "done");
  return report;
}

}  // namespace urbanvec::evaluate
