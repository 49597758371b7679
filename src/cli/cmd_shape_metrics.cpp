// `urbanvec shape-metrics`: the realism measures of Wijgerse (2007) for every polygon of a layer
// (issue 7; spec wijgerse-boundary.md §6-§8).
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "urbanvec/app/command.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/core/utm.hpp"
#include "urbanvec/io/atomic_output.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/vector_io.hpp"
#include "urbanvec/shape/shape_metrics.hpp"

namespace urbanvec {
namespace {

using app::option;
using app::Role;
using app::ValueType;

const char* const kMetricFields[] = {"fractal_dimension",   "slope_a",    "sigma",
                                     "enclosed_area_ratio", "base_chord", "valid"};

app::CommandSpec spec() {
  const shape::ShapeMetricOptions d;
  app::CommandSpec s;
  s.name = "shape-metrics";
  s.summary =
      "Measures how realistic polygons are as city boundaries: fractal dimension and enclosed-area ratio.";
  s.description =
      "For every polygon of a layer (urban extents, city boundaries, blocks, parcels...), walks its outer "
      "ring with "
      "chords l0 k^n, n = 0..scales-1 (structured walk, Batty & Longley), regresses the dimensions D_n "
      "against "
      "ln r_n and reads the comparable dimension D_R off the line; also computes the enclosed-area ratio "
      "A / (pi d^2 / 4) with d the largest diameter. 'valid' applies Wijgerse's rules: 1.18 < D_R < 1.28, "
      "|a| <= 0.02916, sigma <= 0.02 and ratio >= 0.0635. Lengths are in the layer's units, so a geographic "
      "layer "
      "needs -t_srs. Of a MultiPolygon the largest part is measured. The output is a copy of the layer with "
      "the "
      "fields fractal_dimension, slope_a, sigma, enclosed_area_ratio, base_chord and valid (existing fields "
      "of "
      "those names are replaced). See docs/boundary.md.";
  s.group = "City boundaries";
  s.positionals = {{"input", "Vector dataset with a polygon layer.", Role::InputVector},
                   {"output", "Vector file to create with a copy of the layer plus the metric fields.",
                    Role::OutputVector}};
  auto& o = s.options;
  o.push_back(option("-layer", ValueType::String, "<name>", "Layer to measure; default the first layer."));
  o.push_back(option("-t_srs", ValueType::String, "<crs>",
                     "Reproject to this CRS (in metres) before measuring; required for a geographic layer.")
                  .withRole(Role::Crs));
  o.push_back(option("-skip", ValueType::Integer, "<s>",
                     "Walk from every s-th vertex only (1 = exact; the thesis's 15 is within 0.0025).")
                  .byDefault(std::to_string(d.walk.skip))
                  .atLeast(1));
  o.push_back(option("-scales", ValueType::Integer, "<W>", "Number of chord lengths l0 k^n, n = 0..W-1.")
                  .byDefault(std::to_string(d.walk.scales))
                  .atLeast(3)
                  .atMost(64));
  o.push_back(option("-k", ValueType::Real, "<factor>", "Ratio between successive chord lengths.")
                  .byDefault(app::numberText(d.walk.scaleFactor))
                  .atLeast(1.01));
  o.push_back(
      option("-step", ValueType::Real, "<length>",
             "Base chord l0 in layer units; default the polygon's mean segment length (the thesis's rule), "
             "which depends on how densely it was digitised.")
          .atLeast(1e-12));
  o.push_back(
      option("-eval-at", ValueType::Real, "<length>",
             "Chord length at which D_R is read off the regression line; default each polygon's own mean "
             "chord (geometric mean of r_n). The boundary command uses 13.06 pixels (ln r = 2.5696).")
          .atLeast(1e-12)
          .isAdvanced());
  for (const app::OptionSpec& v : app::vectorOutputOptions()) o.push_back(v);
  s.examples = {"urbanvec shape-metrics boundary.gpkg boundary_metrics.gpkg",
                "urbanvec shape-metrics -layer urban_areas -t_srs EPSG:32633 -skip 1 extents.gpkg "
                "extents_metrics.gpkg"};
  return s;
}

/// The outer ring of the polygon to measure, or nothing for a non-polygonal or empty geometry.
const Ring* ringToMeasure(const Geometry& geometry) {
  if (const Polygon* p = std::get_if<Polygon>(&geometry)) return p->outer.empty() ? nullptr : &p->outer;
  if (const MultiPolygon* m = std::get_if<MultiPolygon>(&geometry)) {
    const Polygon* largest = nullptr;
    double best = -1.0;
    for (const Polygon& p : *m) {
      const double a = std::abs(signedArea(p.outer));
      if (!p.outer.empty() && a > best) best = a, largest = &p;
    }
    return largest ? &largest->outer : nullptr;
  }
  return nullptr;
}

/// Centre of the layer's bounding box, for the UTM suggestion.
bool layerCentre(const Layer& layer, Vec2& centre) {
  double minX = std::numeric_limits<double>::infinity(), minY = minX, maxX = -minX, maxY = -minX;
  for (const Feature& f : layer.features)
    if (const Ring* r = ringToMeasure(f.geometry))
      for (const Vec2& p : *r) {
        minX = std::min(minX, p.x), maxX = std::max(maxX, p.x);
        minY = std::min(minY, p.y), maxY = std::max(maxY, p.y);
      }
  if (!(minX <= maxX)) return false;
  centre = {(minX + maxX) / 2, (minY + maxY) / 2};
  return true;
}

void run(const app::ParsedArgs& args, app::CommandContext& ctx) {
  const std::string input = args.positionals()[0];
  const std::string outputPath = args.positionals()[1];
  shape::ShapeMetricOptions options;
  options.walk.skip = static_cast<int>(args.integer("-skip"));
  options.walk.scales = static_cast<int>(args.integer("-scales"));
  options.walk.scaleFactor = args.real("-k");
  if (args.given("-step")) options.walk.baseChord = args.real("-step");
  options.evaluationLogChord.reset();
  if (args.given("-eval-at")) options.evaluationLogChord = std::log(args.real("-eval-at"));

  std::string layerName;
  if (args.given("-layer")) {
    layerName = args.str("-layer");
  } else {
    const std::vector<std::string> layers = io::listVectorLayers(input, "input");
    if (layers.empty()) throw invalidInput("input '" + input + "' has no vector layer");
    layerName = layers.front();
  }
  io::VectorWriteOptions write;
  if (args.has("-of")) write.format = args.str("-of");
  write.layerCreationOptions = args.values("-lco");
  write.datasetCreationOptions = args.values("-dsco");
  io::VectorOutput output(outputPath, write, {layerName},
                          io::OutputRules{args.flag("-overwrite"), false, {}, ctx.inputs});
  io::VectorReadOptions read;
  if (args.given("-t_srs")) {
    const std::string wkt = io::crsToWkt(args.str("-t_srs"), "-t_srs");
    if (io::isGeographic(wkt))
      throw invalidOption("-t_srs " + args.str("-t_srs") +
                          " is geographic; shape metrics need lengths in metres");
    read.targetCrs = wkt;
  }
  std::optional<io::LayerRead> loaded = io::readVectorLayer(input, layerName, "input", read);
  if (!loaded) throw invalidInput("input '" + input + "' has no layer '" + layerName + "'");
  Layer& layer = loaded->layer;
  // GeoPackage stores "no CRS" as srs_id 0/-1, read back as "Undefined geographic/cartesian SRS".
  if (!loaded->crsWkt.empty() && io::crsShortName(loaded->crsWkt).rfind("Undefined", 0) == 0)
    loaded->crsWkt.clear();
  if (layer.geometryType != GeometryType::Polygon && layer.geometryType != GeometryType::MultiPolygon)
    throw invalidInput("layer '" + layerName + "' of '" + input +
                       "' does not hold polygons; shape-metrics measures polygon outlines");
  if (!loaded->crsWkt.empty() && io::isGeographic(loaded->crsWkt) && read.targetCrs.empty()) {
    std::string hint;
    Vec2 centre;
    if (layerCentre(layer, centre))
      hint = ", e.g. -t_srs EPSG:" + std::to_string(utmEpsgFor(centre.x, centre.y));
    throw invalidInput("layer '" + layerName + "' of '" + input + "' is in a geographic CRS (" +
                       io::crsShortName(loaded->crsWkt) + "); lengths and areas need metres: give -t_srs" +
                       hint);
  }
  if (loaded->crsWkt.empty() && read.targetCrs.empty())
    ctx.warn("layer '" + layerName + "' has no CRS: lengths are in its coordinate units");

  // Existing fields of the metric names are replaced, so measuring a measured layer works.
  std::vector<int> slot;
  for (const char* name : kMetricFields) {
    int index = layer.fieldIndex(name);
    const FieldType type = std::string(name) == "valid" ? FieldType::Integer : FieldType::Real;
    if (index < 0) {
      layer.fields.push_back({name, type});
      for (Feature& f : layer.features) f.values.emplace_back(std::monostate{});
      index = static_cast<int>(layer.fields.size()) - 1;
    } else {
      layer.fields[static_cast<size_t>(index)].type = type;
    }
    slot.push_back(index);
  }
  ProgressTicker ticker(ctx.progress, "measuring", layer.features.size());
  size_t measured = 0, realistic = 0, tooSmall = 0;
  for (Feature& f : layer.features) {
    ticker.tick();
    const Ring* ring = ringToMeasure(f.geometry);
    for (int i : slot) f.values[static_cast<size_t>(i)] = std::monostate{};
    if (!ring) continue;
    shape::ShapeMetrics m;
    try {
      m = shape::measureShape(*ring, options);
    } catch (const Error& e) {
      if (e.kind() != ErrorKind::InvalidInput) throw;
      continue;  // fewer than 3 distinct vertices: nothing to measure
    }
    ++measured;
    f.values[static_cast<size_t>(slot[3])] = m.enclosed.ratio;
    f.values[static_cast<size_t>(slot[4])] = m.walk.baseChord;
    f.values[static_cast<size_t>(slot[5])] = static_cast<std::int64_t>(m.realistic() ? 1 : 0);
    if (m.regression) {
      f.values[static_cast<size_t>(slot[0])] = m.regression->comparableDimension;
      f.values[static_cast<size_t>(slot[1])] = m.regression->slope;
      f.values[static_cast<size_t>(slot[2])] = m.regression->sigma;
    } else {
      ++tooSmall;
    }
    realistic += m.realistic() ? 1 : 0;
  }
  ticker.finish();
  if (tooSmall > 0)
    ctx.warn(
        std::to_string(tooSmall) + " polygon" + (tooSmall == 1 ? " has" : "s have") +
        " too few vertices for the chord lengths (fewer than 3 chords at the third scale): fractal_dimension "
        "is empty; try a smaller -step or fewer -scales");
  output.write({layer}, read.targetCrs.empty() ? loaded->crsWkt : read.targetCrs);
  output.commit(ctx.progress);
  if (!ctx.quiet && ctx.out)
    *ctx.out << "shape-metrics: " << measured << " of " << layer.features.size() << " features measured, "
             << realistic << " realistic as city boundaries\n";
}

const bool registered = app::registerCommand(spec(), run);

}  // namespace
}  // namespace urbanvec
