// The gridify pipeline (issue 2 §2): grid frame, land use, water, roads, truth blocks, parcels,
// population, truth layers. Every rule is stated in docs/gridify.md.
#include "urbanvec/gridify/gridify.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <sstream>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/gridify/blocks.hpp"
#include "urbanvec/gridify/parcels.hpp"
#include "urbanvec/gridify/polygon_raster.hpp"
#include "urbanvec/gridify/road_raster.hpp"
#include "urbanvec/gridify/vector_ops.hpp"
#include "urbanvec/gridify/water.hpp"

namespace urbanvec::gridify {

namespace {

constexpr double kMinBlockArea = 1.0;  // m²: slivers from noding are not blocks

void grow(Extent& e, const Vec2& p, bool& first) {
  if (first) {
    e = {p.x, p.y, p.x, p.y};
    first = false;
    return;
  }
  e.minX = std::min(e.minX, p.x);
  e.minY = std::min(e.minY, p.y);
  e.maxX = std::max(e.maxX, p.x);
  e.maxY = std::max(e.maxY, p.y);
}

std::string formatNumber(double v) {
  std::ostringstream s;
  s.precision(15);
  s << v;
  return s.str();
}

/// Converts between world coordinates and pixel coordinates (row down) of the grid.
struct Frame {
  double minX, maxY, cell;
  int width, height;
  Vec2 toPixel(const Vec2& w) const { return {(w.x - minX) / cell, (maxY - w.y) / cell}; }
  LineString toWorld(const LineString& pixels) const {
    LineString out;
    out.reserve(pixels.size());
    for (const Vec2& p : pixels) out.push_back({minX + p.x * cell, maxY - p.y * cell});
    return out;
  }
  LineString toPixel(const LineString& line) const {
    LineString out;
    out.reserve(line.size());
    for (const Vec2& p : line) out.push_back(toPixel(p));
    return out;
  }
  Polygon toPixel(const Polygon& p) const {
    Polygon out{toPixel(p.outer), {}};
    for (const Ring& h : p.holes) out.holes.push_back(toPixel(h));
    return out;
  }
  MultiPolygon toPixel(const MultiPolygon& mp) const {
    MultiPolygon out;
    for (const Polygon& p : mp) out.push_back(toPixel(p));
    return out;
  }
  std::vector<Cell> cells(const MultiPolygon& world) const {
    std::vector<Cell> out;
    cellsInside(toPixel(world), width, height, out);
    return out;
  }
  /// The cell holding a world point, or (-1, -1) outside the grid.
  Cell cellAt(const Vec2& w) const {
    const Vec2 p = toPixel(w);
    const int c = static_cast<int>(std::floor(p.x)), r = static_cast<int>(std::floor(p.y));
    if (c < 0 || r < 0 || c >= width || r >= height) return {-1, -1};
    return {c, r};
  }
};

/// A point inside a building footprint (for the cell of small buildings and for parcel lookup).
Vec2 pointOnSurface(const geos::Context& ctx, const MultiPolygon& shape) {
  geos::GeomPtr g = validPolygons(ctx, shape);
  if (GEOSisEmpty_r(ctx.handle(), g.get()) == 1)
    return shape.empty() || shape[0].outer.empty() ? Vec2{} : shape[0].outer[0];
  geos::GeomPtr p = ctx.own(GEOSPointOnSurface_r(ctx.handle(), g.get()), "point on surface");
  double x = 0.0, y = 0.0;
  GEOSGeomGetX_r(ctx.handle(), p.get(), &x);
  GEOSGeomGetY_r(ctx.handle(), p.get(), &y);
  return {x, y};
}

LandUse majorityUse(const Grid<std::uint8_t>& base, const std::vector<Cell>& cells) {
  std::array<std::size_t, kLandUseClassCount> counts{};
  for (const Cell& c : cells) ++counts[base.at(c.first, c.second)];
  LandUse best = LandUse::Unused;
  std::size_t bestCount = 0;
  for (int k = 0; k < kLandUseClassCount; ++k) {
    const LandUse u = static_cast<LandUse>(k);
    if (!isDeveloped(u) && u != LandUse::Reserved) continue;
    if (counts[k] > bestCount) {
      best = u;
      bestCount = counts[k];
    }
  }
  return best;
}

Layer makeGridInfo(const GridSpec& spec, double cellSize, const std::string& crsName) {
  Layer info;
  info.name = "grid_info";
  info.geometryType = GeometryType::None;
  info.fields = {{"cell_size", FieldType::Real},
                 {"width", FieldType::Integer},
                 {"height", FieldType::Integer},
                 {"geotransform", FieldType::String},
                 {"crs", FieldType::String}};
  std::string gt;
  for (int i = 0; i < 6; ++i) gt += (i ? " " : "") + formatNumber(spec.transform.c[i]);
  info.features.push_back(
      {std::monostate{}, {cellSize, std::int64_t{spec.width}, std::int64_t{spec.height}, gt, crsName}});
  return info;
}

/// Issue 20: the blocks (faces of the network) with no land-use polygon take the use their buildings,
/// bounding streets or the default suggest (untagged_land.hpp) on their cells that nothing else
/// claims.
void inferUntaggedLand(const CityData& city, const Frame& frame, const std::vector<TruthBlock>& blocks,
                       const RoadRaster& roads, const Grid<std::uint8_t>& wet,
                       const Grid<std::uint8_t>& tagged, const std::vector<Vec2>& buildingPoint,
                       const std::vector<LandUse>& buildingUse, const GridifyOptions& options,
                       Grid<std::uint8_t>& base, GridifyResult& result) {
  if (!options.untagged.enabled || blocks.empty()) return;
  Grid<std::int32_t> blockOf(frame.width, frame.height, 0);
  std::vector<BlockEvidence> evidence(blocks.size());
  std::vector<std::vector<Cell>> blockCells(blocks.size());
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    evidence[b].external = blocks[b].external;
    for (const Cell& c : frame.cells(MultiPolygon{blocks[b].shape})) {
      if (roads.classes.at(c.first, c.second) || wet.at(c.first, c.second)) continue;
      blockOf.at(c.first, c.second) = static_cast<std::int32_t>(b + 1);
      blockCells[b].push_back(c);
      ++evidence[b].cells;
      evidence[b].taggedCells += tagged.at(c.first, c.second);
    }
  }
  for (std::size_t i = 0; i < city.buildings.size(); ++i) {
    const Cell c = frame.cellAt(buildingPoint[i]);
    if (c.first < 0 || !blockOf.at(c.first, c.second)) continue;
    evidence[blockOf.at(c.first, c.second) - 1].buildingArea[buildingUse[i]] +=
        area(city.buildings[i].footprint);
  }
  // Bounding streets: every half cell along a rasterized centreline, the blocks in the 3x3 cells
  // around it get that piece of street.
  std::vector<std::int32_t> seen;
  for (std::size_t r = 0; r < city.roads.size(); ++r) {
    if (!roads.rasterized[r]) continue;
    const LineString line = frame.toPixel(city.roads[r].centreline);
    for (std::size_t k = 1; k < line.size(); ++k) {
      const double len = distance(line[k - 1], line[k]);
      const int steps = std::max(1, static_cast<int>(std::ceil(len / 0.5)));
      for (int s = 0; s < steps; ++s) {
        const Vec2 p = line[k - 1] + (line[k] - line[k - 1]) * ((s + 0.5) / steps);
        const int col = static_cast<int>(std::floor(p.x)), row = static_cast<int>(std::floor(p.y));
        seen.clear();
        for (int dr = -1; dr <= 1; ++dr)
          for (int dc = -1; dc <= 1; ++dc)
            if (blockOf.inside(col + dc, row + dr))
              if (const std::int32_t b = blockOf.at(col + dc, row + dr))
                if (std::find(seen.begin(), seen.end(), b) == seen.end()) seen.push_back(b);
        for (std::int32_t b : seen)
          evidence[b - 1].streetLength[city.roads[r].sourceClass] += len / steps * frame.cell;
      }
    }
  }
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const auto [use, rule] = inferUntaggedUse(evidence[b], options.untagged);
    if (!use) continue;
    result.untaggedByBuildings += rule == UntaggedRule::Buildings;
    result.untaggedByStreets += rule == UntaggedRule::Streets;
    result.untaggedByDefault += rule == UntaggedRule::Default;
    for (const Cell& c : blockCells[b])
      if (base.at(c.first, c.second) == static_cast<std::uint8_t>(LandUse::Unused)) {
        base.at(c.first, c.second) = static_cast<std::uint8_t>(*use);
        ++result.inferredCells;
      }
  }
}

}  // namespace

Extent cityExtent(const CityData& city) {
  Extent e;
  bool first = true;
  for (const CityRoad& r : city.roads)
    for (const Vec2& p : r.centreline) grow(e, p, first);
  for (const CityBuilding& b : city.buildings)
    for (const Polygon& p : b.footprint)
      for (const Vec2& v : p.outer) grow(e, v, first);
  for (const CityArea& a : city.areas)
    for (const Polygon& p : a.shape)
      for (const Vec2& v : p.outer) grow(e, v, first);
  return first ? Extent{} : e;
}

GridSpec gridFrame(const CityData& city, const GridifyOptions& options) {
  if (!(options.cellSize > 0.0) || !std::isfinite(options.cellSize))
    throw invalidOption("-tr: the cell size must be a positive number of metres, not " +
                        formatNumber(options.cellSize));
  const double cs = options.cellSize;
  Extent box;
  if (options.extent) {
    box = *options.extent;
  } else {
    box = cityExtent(city);
    if (box.empty()) throw invalidInput("the input holds no road, building or land-use feature to grid");
    box.minX = std::floor(box.minX / cs) * cs;
    box.minY = std::floor(box.minY / cs) * cs;
    box.maxX = std::ceil(box.maxX / cs) * cs;
    box.maxY = std::ceil(box.maxY / cs) * cs;
  }
  const double w = std::round((box.maxX - box.minX) / cs), h = std::round((box.maxY - box.minY) / cs);
  if (!(w >= 1.0) || !(h >= 1.0))
    throw invalidOption("-te: the extent " + formatNumber(box.minX) + " " + formatNumber(box.minY) + " " +
                        formatNumber(box.maxX) + " " + formatNumber(box.maxY) + " holds no cell of " +
                        formatNumber(cs) + " m");
  if (w * h > 2.0e8)
    throw invalidOption("-tr: " + formatNumber(w) + " x " + formatNumber(h) + " cells is too many");
  GridSpec spec;
  spec.width = static_cast<int>(w);
  spec.height = static_cast<int>(h);
  spec.transform.c = {box.minX, cs, 0.0, box.maxY, 0.0, -cs};
  spec.crsWkt = city.crsWkt;
  return spec;
}

GridifyResult gridify(const CityData& city, const GridifyOptions& options, const Progress& progress) {
  if (!(options.floorAreaPerPerson > 0.0))
    throw invalidOption("-floor-area-per-person must be positive, not " +
                        formatNumber(options.floorAreaPerPerson));
  GridifyResult result;
  result.spec = gridFrame(city, options);
  const GridSpec& spec = result.spec;
  const double cs = options.cellSize;
  Extent box{spec.transform.c[0], spec.transform.c[3] - spec.height * cs,
             spec.transform.c[0] + spec.width * cs, spec.transform.c[3]};
  const bool withLandCover = !city.landCover.cells.empty();
  if (withLandCover && (city.landCover.width != spec.width || city.landCover.height != spec.height))
    throw internalError("the land cover (" + std::to_string(city.landCover.width) + " x " +
                        std::to_string(city.landCover.height) + " cells) is not on the grid (" +
                        std::to_string(spec.width) + " x " + std::to_string(spec.height) + " cells)");
  const Frame frame{box.minX, box.maxY, cs, spec.width, spec.height};
  geos::Context ctx;
  reportProgress(progress, 0.0, "land use");

  // Base land use: areas, the largest first so that smaller areas inside them win.
  Grid<std::uint8_t> base(spec.width, spec.height, static_cast<std::uint8_t>(LandUse::Unused));
  Grid<std::uint8_t> wet(spec.width, spec.height, 0);
  Grid<std::uint8_t> tagged(spec.width, spec.height, 0);  // cells under a land-use polygon
  std::vector<std::size_t> order(city.areas.size());
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> areaSize(city.areas.size());
  for (std::size_t i = 0; i < city.areas.size(); ++i) areaSize[i] = area(city.areas[i].shape);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return areaSize[a] > areaSize[b]; });
  std::vector<MultiPolygon> waterShapes = city.water;
  for (std::size_t i : order) {
    const CityArea& a = city.areas[i];
    if (a.use == LandUse::Water) {
      waterShapes.push_back(a.shape);
      continue;
    }
    if (isRoad(a.use)) continue;
    for (const Cell& c : frame.cells(a.shape)) {
      tagged.at(c.first, c.second) = 1;
      if (a.use != LandUse::Unused) base.at(c.first, c.second) = static_cast<std::uint8_t>(a.use);
    }
  }
  // A land-cover raster (already on the grid, issue 20) gives its developed classes to the cells no
  // land-use polygon covers; buildings standing there take its class, as they take a polygon's.
  if (withLandCover)
    for (std::size_t k = 0; k < base.cells.size(); ++k) {
      const LandUse cover = static_cast<LandUse>(city.landCover.cells[k]);
      if (tagged.cells[k] || !(isDeveloped(cover) || cover == LandUse::Reserved)) continue;
      base.cells[k] = static_cast<std::uint8_t>(cover);
      ++result.landCoverCells;
    }
  reportProgress(progress, 0.1, "water");

  // Water: polygons and the sea side of the coastline, clipped to the grid.
  MultiPolygon sea = seaFromCoastline(city.coastlines, box);
  if (!sea.empty()) waterShapes.push_back(sea);
  std::vector<MultiPolygon> waterClipped;
  for (const MultiPolygon& shape : waterShapes) {
    MultiPolygon clipped = clipPolygons(ctx, shape, box);
    if (clipped.empty()) continue;
    for (const Cell& c : frame.cells(clipped)) wet.at(c.first, c.second) = 1;
    waterClipped.push_back(std::move(clipped));
  }
  reportProgress(progress, 0.2, "buildings");

  // Buildings: their own class, else the area they stand in, else the default.
  std::vector<LandUse> buildingUse(city.buildings.size());
  std::vector<Vec2> buildingPoint(city.buildings.size());
  std::vector<MultiPolygon> footprints(city.buildings.size());
  for (std::size_t i = 0; i < city.buildings.size(); ++i) {
    const CityBuilding& b = city.buildings[i];
    footprints[i] = b.footprint;
    buildingPoint[i] = pointOnSurface(ctx, b.footprint);
    LandUse use = options.defaultBuildingUse;
    if (b.use) {
      use = *b.use;
    } else {
      const Cell c = frame.cellAt(buildingPoint[i]);
      if (c.first >= 0) {
        const LandUse around = static_cast<LandUse>(base.at(c.first, c.second));
        if (isDeveloped(around) || around == LandUse::Reserved) use = around;
      }
    }
    buildingUse[i] = use;
    std::vector<Cell> cells = frame.cells(b.footprint);
    if (cells.empty()) {
      const Cell c = frame.cellAt(buildingPoint[i]);
      if (c.first >= 0) cells.push_back(c);
    }
    for (const Cell& c : cells) base.at(c.first, c.second) = static_cast<std::uint8_t>(use);
  }
  reportProgress(progress, 0.3, "roads");

  // Roads.
  std::vector<PixelRoad> pixelRoads;
  for (const CityRoad& r : city.roads) pixelRoads.push_back({frame.toPixel(r.centreline), r.roadClass});
  RoadRasterOptions roadOptions;
  roadOptions.mergeGapCells = options.mergeGapCells;
  RoadRaster roads = rasterizeRoads(pixelRoads, spec.width, spec.height, roadOptions);
  result.roadsMerged = roads.adjustments;
  reportProgress(progress, 0.45, "blocks");

  Layer roadLayer;
  roadLayer.name = "roads";
  roadLayer.geometryType = GeometryType::LineString;
  roadLayer.fields = {{"road_id", FieldType::Integer},
                      {"road_class", FieldType::String},
                      {"source_class", FieldType::String},
                      {"name", FieldType::String},
                      {"length", FieldType::Real}};
  MultiLineString rasterizedLines;
  std::vector<double> curbOffsets;  // metres from each rasterized line to its curbs
  for (std::size_t i = 0; i < city.roads.size(); ++i) {
    if (!roads.rasterized[i]) continue;
    const CityRoad& r = city.roads[i];
    MultiLineString parts;
    for (const LineString& clipped : clipLine(ctx, r.centreline, box))
      for (const LineString& onGrid :
           partsOnRoadCells(frame.toPixel(clipped), roads.classes, options.truthRoadReachCells))
        parts.push_back(frame.toWorld(onGrid));
    if (parts.empty()) continue;
    ++result.roadsRasterized;
    const std::string cls = r.roadClass == LandUse::PrimaryRoad ? "primary" : "secondary";
    const double curbCells =
        r.roadClass == LandUse::PrimaryRoad ? options.truthCurbPrimaryCells : options.truthCurbSecondaryCells;
    for (LineString& part : parts) {
      rasterizedLines.push_back(part);
      curbOffsets.push_back(curbCells * cs);
      const double len = length(part);
      roadLayer.features.push_back(
          {std::move(part),
           {static_cast<std::int64_t>(roadLayer.features.size() + 1), cls, r.sourceClass, r.name, len}});
    }
  }

  // Faces of the noded network minus water hold the derived parcels; the truth blocks are the land
  // between their curbs.
  std::vector<TruthBlock> blocks = roadBlocks(rasterizedLines, box, waterClipped, kMinBlockArea);
  const std::vector<TruthBlock> truthBlocks =
      curbBlocks(blocks, rasterizedLines, curbOffsets, box, kMinBlockArea);
  inferUntaggedLand(city, frame, blocks, roads, wet, tagged, buildingPoint, buildingUse, options, base,
                    result);
  reportProgress(progress, 0.6, "parcels");

  // Parcels: given ones clipped to the grid, or a tessellation of the blocks.
  struct Candidate {
    MultiPolygon shape;
    std::optional<LandUse> use;
    std::optional<double> population;
    std::string sourceId;
  };
  std::vector<Candidate> candidates;
  if (!city.parcels.empty()) {
    for (const CityParcel& p : city.parcels) {
      MultiPolygon clipped = clipPolygons(ctx, p.shape, box, kMinBlockArea);
      if (!clipped.empty()) candidates.push_back({std::move(clipped), p.use, p.population, p.sourceId});
    }
  } else {
    Tessellation tess = tessellateBlocks(blocks, footprints, options.parcelReach);
    for (TessellatedParcel& t : tess.parcels)
      candidates.push_back({std::move(t.shape), buildingUse[t.building], std::nullopt, ""});
    // A block without buildings is one parcel when it has a land use.
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      if (tess.blockBuilt[i]) continue;
      MultiPolygon shape{blocks[i].shape};
      const LandUse use = majorityUse(base, frame.cells(shape));
      if (use != LandUse::Unused) candidates.push_back({std::move(shape), use, std::nullopt, ""});
    }
  }

  // Rasterize parcels (later ones win), then keep those with cells, numbered 1..n.
  Grid<std::int32_t> provisional(spec.width, spec.height, 0);
  std::vector<std::vector<Cell>> candidateCells(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    for (const Cell& c : frame.cells(candidates[i].shape)) {
      if (roads.classes.at(c.first, c.second) || wet.at(c.first, c.second)) continue;
      provisional.at(c.first, c.second) = static_cast<std::int32_t>(i + 1);
    }
  }
  for (int r = 0; r < spec.height; ++r)
    for (int c = 0; c < spec.width; ++c)
      if (const std::int32_t id = provisional.at(c, r)) candidateCells[id - 1].emplace_back(c, r);
  std::vector<std::int32_t> newId(candidates.size(), 0);
  result.parcelIds = Grid<std::int32_t>(spec.width, spec.height, 0);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidateCells[i].empty()) continue;
    newId[i] = static_cast<std::int32_t>(result.parcels.size() + 1);
    ParcelRecord rec;
    rec.id = newId[i];
    rec.cells = static_cast<std::int64_t>(candidateCells[i].size());
    rec.use = candidates[i].use ? *candidates[i].use : majorityUse(base, candidateCells[i]);
    if (rec.use == LandUse::Water || isRoad(rec.use)) rec.use = LandUse::Unused;
    result.parcels.push_back(rec);
    for (const Cell& c : candidateCells[i]) result.parcelIds.at(c.first, c.second) = newId[i];
  }
  reportProgress(progress, 0.8, "population");

  // Population: the parcel's field, else its residential buildings' floor area / floor area per person.
  std::vector<double> estimated(result.parcels.size(), 0.0);
  for (std::size_t i = 0; i < city.buildings.size(); ++i) {
    if (buildingUse[i] != LandUse::Residential) continue;
    const Cell c = frame.cellAt(buildingPoint[i]);
    if (c.first < 0) continue;
    const std::int32_t id = result.parcelIds.at(c.first, c.second);
    if (id == 0) continue;
    const double levels = city.buildings[i].levels.value_or(options.defaultLevels);
    estimated[id - 1] += area(city.buildings[i].footprint) * levels / options.floorAreaPerPerson;
  }
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!newId[i]) continue;
    ParcelRecord& rec = result.parcels[newId[i] - 1];
    rec.population = candidates[i].population ? *candidates[i].population : estimated[rec.id - 1];
  }

  // Final rasters: roads, then water, then the parcel's class, then the base land use.
  result.landUse = Grid<std::uint8_t>(spec.width, spec.height, 0);
  result.density = Grid<float>(spec.width, spec.height, 0.0f);
  for (std::size_t k = 0; k < result.landUse.cells.size(); ++k) {
    std::uint8_t v = base.cells[k];
    const std::int32_t id = result.parcelIds.cells[k];
    if (id > 0) {
      const ParcelRecord& rec = result.parcels[id - 1];
      if (rec.use != LandUse::Unused) v = static_cast<std::uint8_t>(rec.use);
      result.density.cells[k] = static_cast<float>(rec.population / static_cast<double>(rec.cells));
    }
    if (wet.cells[k]) v = static_cast<std::uint8_t>(LandUse::Water);
    if (roads.classes.cells[k]) v = roads.classes.cells[k];
    result.landUse.cells[k] = v;
  }
  reportProgress(progress, 0.9, "truth");

  // Truth layers.
  Layer blockLayer;
  blockLayer.name = "blocks";
  blockLayer.geometryType = GeometryType::Polygon;
  blockLayer.fields = {
      {"block_id", FieldType::Integer}, {"kind", FieldType::String}, {"area", FieldType::Real}};
  for (const TruthBlock& b : truthBlocks)
    blockLayer.features.push_back({b.shape,
                                   {static_cast<std::int64_t>(blockLayer.features.size() + 1),
                                    std::string(b.external ? "external" : "internal"), area(b.shape)}});
  Layer parcelLayer;
  parcelLayer.name = "parcels";
  parcelLayer.geometryType = GeometryType::MultiPolygon;
  parcelLayer.fields = {{"parcel_id", FieldType::Integer}, {"land_use", FieldType::String},
                        {"population", FieldType::Real},   {"cells", FieldType::Integer},
                        {"area", FieldType::Real},         {"source_id", FieldType::String}};
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!newId[i]) continue;
    const ParcelRecord& rec = result.parcels[newId[i] - 1];
    parcelLayer.features.push_back({candidates[i].shape,
                                    {std::int64_t{rec.id}, std::string(landUseName(rec.use)), rec.population,
                                     rec.cells, area(candidates[i].shape), candidates[i].sourceId}});
  }
  Layer waterLayer;
  waterLayer.name = "water";
  waterLayer.geometryType = GeometryType::MultiPolygon;
  waterLayer.fields = {{"water_id", FieldType::Integer}};
  if (!waterClipped.empty()) {
    geos::GeomPtr wetUnion = unionPolygons(ctx, waterClipped);
    MultiPolygon all = ctx.toPolygons(wetUnion.get());
    if (!all.empty()) waterLayer.features.push_back({all, {std::int64_t{1}}});
  }
  result.truth.push_back(std::move(roadLayer));
  result.truth.push_back(std::move(blockLayer));
  result.truth.push_back(std::move(parcelLayer));
  result.truth.push_back(std::move(waterLayer));
  result.truth.push_back(makeGridInfo(spec, cs, ""));
  reportProgress(progress, 1.0, "done");
  return result;
}

}  // namespace urbanvec::gridify
