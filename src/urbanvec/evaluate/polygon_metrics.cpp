// Block and parcel metrics of the evaluator (issue 2 §3): see polygon_metrics.hpp.
#include "urbanvec/evaluate/polygon_metrics.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <set>
#include <variant>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/landuse.hpp"

namespace urbanvec::evaluate {

namespace {

/// GEOS needs at least three distinct corners to build a ring; fewer is an invalid polygon.
bool buildable(const Polygon& p) {
  auto ringOk = [](const Ring& r) {
    std::set<std::pair<double, double>> distinct;
    for (const Vec2& v : r) distinct.insert({v.x, v.y});
    return distinct.size() >= 3;
  };
  if (!ringOk(p.outer)) return false;
  return std::all_of(p.holes.begin(), p.holes.end(), ringOk);
}

double geosArea(const geos::Context& ctx, const GEOSGeometry* g) {
  double a = 0.0;
  if (!GEOSArea_r(ctx.handle(), g, &a))
    throw internalError("GEOS could not compute an area: " + ctx.lastError());
  return a;
}

geos::GeomPtr clone(const geos::Context& ctx, const GEOSGeometry* g) {
  return ctx.own(GEOSGeom_clone_r(ctx.handle(), g), "clone");
}

geos::GeomPtr intersection(const geos::Context& ctx, const GEOSGeometry* a, const GEOSGeometry* b) {
  return ctx.own(GEOSIntersection_r(ctx.handle(), a, b), "intersection");
}

void collectItem(void* item, void* userdata) {
  static_cast<std::vector<std::size_t>*>(userdata)->push_back(reinterpret_cast<std::uintptr_t>(item) - 1);
}

}  // namespace

PolygonLayer::PolygonLayer(const geos::Context& ctx, const Layer& layer) : ctx_(ctx) {
  const GEOSContextHandle_t h = ctx.handle();
  for (std::size_t f = 0; f < layer.features.size(); ++f) {
    MultiPolygon parts;
    if (const auto* p = std::get_if<Polygon>(&layer.features[f].geometry)) parts.push_back(*p);
    if (const auto* mp = std::get_if<MultiPolygon>(&layer.features[f].geometry)) parts = *mp;
    if (parts.empty()) continue;
    if (!std::all_of(parts.begin(), parts.end(), buildable)) {
      ++invalid_;
      continue;
    }
    geos::GeomPtr g = parts.size() == 1 ? ctx.polygon(parts.front()) : ctx.multiPolygon(parts);
    if (GEOSisValid_r(h, g.get()) != 1) {
      ++invalid_;
      geos::GeomPtr repaired = ctx.own(GEOSMakeValid_r(h, g.get()), "make valid");
      // A repaired bow-tie or spike may come back as a collection with lines: keep its area only.
      const MultiPolygon polygonal = ctx.toPolygons(repaired.get());
      if (polygonal.empty()) continue;
      g = ctx.multiPolygon(polygonal);
    }
    areas_.push_back(geosArea(ctx, g.get()));
    geometries_.push_back(std::move(g));
    features_.push_back(f);
  }
  tree_ = GEOSSTRtree_create_r(h, 10);
  if (!tree_) throw internalError("GEOS could not create an STRtree: " + ctx.lastError());
  for (std::size_t i = 0; i < geometries_.size(); ++i)
    GEOSSTRtree_insert_r(h, tree_, geometries_[i].get(),
                         reinterpret_cast<void*>(static_cast<std::uintptr_t>(i + 1)));
  prepared_.assign(geometries_.size(), nullptr);
}

PolygonLayer::~PolygonLayer() {
  for (const GEOSPreparedGeometry* p : prepared_)
    if (p) GEOSPreparedGeom_destroy_r(ctx_.handle(), p);
  if (tree_) GEOSSTRtree_destroy_r(ctx_.handle(), tree_);
}

const GEOSPreparedGeometry* PolygonLayer::prepared(std::size_t i) const {
  if (!prepared_[i]) {
    prepared_[i] = GEOSPrepare_r(ctx_.handle(), geometries_[i].get());
    if (!prepared_[i]) throw internalError("GEOS could not prepare a polygon: " + ctx_.lastError());
  }
  return prepared_[i];
}

std::vector<std::size_t> PolygonLayer::candidates(const GEOSGeometry* g) const {
  std::vector<std::size_t> found;
  if (geometries_.empty()) return found;
  GEOSSTRtree_query_r(ctx_.handle(), tree_, g, collectItem, &found);
  std::sort(found.begin(), found.end());
  return found;
}

BlockMatching matchBlocks(const geos::Context& ctx, const PolygonLayer& truth, const PolygonLayer& result,
                          const Progress& progress) {
  BlockMatching matching;
  matching.bestResult.assign(truth.size(), std::nullopt);
  matching.bestIoU.assign(truth.size(), 0.0);
  ProgressTicker ticker(progress, "matching blocks", truth.size());
  for (std::size_t t = 0; t < truth.size(); ++t) {
    const GEOSGeometry* block = truth.geometry(t);
    for (std::size_t r : result.candidates(block)) {
      if (GEOSPreparedIntersects_r(ctx.handle(), result.prepared(r), block) != 1) continue;
      const double shared = geosArea(ctx, intersection(ctx, block, result.geometry(r)).get());
      const double unionArea = truth.area(t) + result.area(r) - shared;
      const double iou = unionArea > 0.0 ? shared / unionArea : 0.0;
      if (iou > matching.bestIoU[t]) {
        matching.bestIoU[t] = iou;
        matching.bestResult[t] = r;
      }
    }
    ticker.tick();
  }
  ticker.finish();
  return matching;
}

std::vector<std::optional<std::size_t>> assignToBlocks(const geos::Context& ctx, const PolygonLayer& parcels,
                                                       const PolygonLayer& blocks) {
  std::vector<std::optional<std::size_t>> out(parcels.size());
  for (std::size_t p = 0; p < parcels.size(); ++p) {
    geos::GeomPtr inside =
        ctx.own(GEOSPointOnSurface_r(ctx.handle(), parcels.geometry(p)), "point on surface");
    for (std::size_t b : blocks.candidates(inside.get())) {
      if (GEOSPreparedIntersects_r(ctx.handle(), blocks.prepared(b), inside.get()) == 1) {
        out[p] = b;
        break;
      }
    }
  }
  return out;
}

Coverage parcelCoverage(const geos::Context& ctx, const PolygonLayer& parcels, const PolygonLayer& blocks,
                        const std::vector<std::optional<std::size_t>>& parcelBlock,
                        const Progress& progress) {
  std::vector<std::vector<std::size_t>> members(blocks.size());
  for (std::size_t p = 0; p < parcelBlock.size(); ++p)
    if (parcelBlock[p]) members[*parcelBlock[p]].push_back(p);
  Coverage coverage;
  const GEOSContextHandle_t h = ctx.handle();
  ProgressTicker ticker(progress, "parcel gaps and overlaps", blocks.size());
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    ticker.tick();
    if (members[b].empty()) continue;
    const GEOSGeometry* block = blocks.geometry(b);
    double inBlock = 0.0;  // parcel areas inside the block, overlaps counted as often as they occur
    std::vector<geos::GeomPtr> parts;
    for (std::size_t p : members[b]) {
      const GEOSGeometry* parcel = parcels.geometry(p);
      inBlock += GEOSPreparedCovers_r(h, blocks.prepared(b), parcel) == 1
                     ? parcels.area(p)
                     : geosArea(ctx, intersection(ctx, block, parcel).get());
      parts.push_back(clone(ctx, parcel));
    }
    geos::GeomPtr all = ctx.collection(GEOS_GEOMETRYCOLLECTION, std::move(parts));
    geos::GeomPtr merged = ctx.own(GEOSUnaryUnion_r(h, all.get()), "union of parcels");
    const double covered = geosArea(ctx, intersection(ctx, block, merged.get()).get());
    const double blockArea = blocks.area(b);
    coverage.blockArea += blockArea;
    coverage.gapArea += std::max(0.0, blockArea - covered);
    coverage.overlapArea += std::max(0.0, inBlock - covered);
    ++coverage.blocks;
  }
  ticker.finish();
  return coverage;
}

std::string landUseKey(const FieldValue& value) {
  if (const auto* code = std::get_if<std::int64_t>(&value))
    return std::string(landUseName(landUseFromCode(static_cast<int>(*code))));
  if (const auto* real = std::get_if<double>(&value))
    return std::string(landUseName(landUseFromCode(static_cast<int>(*real))));
  if (const auto* text = std::get_if<std::string>(&value)) {
    if (const auto use = parseLandUse(*text)) return std::string(landUseName(*use));
    std::string lowered = *text;
    std::transform(lowered.begin(), lowered.end(), lowered.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    // The vectorizer's "undeveloped" parcels are land without a use, as the grid's "unused" is.
    if (lowered == "undeveloped") return std::string(landUseName(LandUse::Unused));
    return lowered;
  }
  return "";
}

double landUseShareError(const std::map<std::string, double>& a, const std::map<std::string, double>& b) {
  auto total = [](const std::map<std::string, double>& m) {
    double s = 0.0;
    for (const auto& [use, area] : m) s += area;
    return s;
  };
  const double totalA = total(a), totalB = total(b);
  std::set<std::string> uses;
  for (const auto& [use, area] : a) uses.insert(use);
  for (const auto& [use, area] : b) uses.insert(use);
  double error = 0.0;
  for (const std::string& use : uses) {
    const auto ia = a.find(use), ib = b.find(use);
    const double shareA = totalA > 0.0 && ia != a.end() ? ia->second / totalA : 0.0;
    const double shareB = totalB > 0.0 && ib != b.end() ? ib->second / totalB : 0.0;
    error += std::abs(shareA - shareB);
  }
  return error;
}

}  // namespace urbanvec::evaluate
