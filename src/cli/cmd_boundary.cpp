// `urbanvec boundary`: a realistic city boundary from 2-D Perlin noise (Wijgerse 2007; issue 7,
// spec wijgerse-boundary.md).
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <string>

#include "urbanvec/app/command.hpp"
#include "urbanvec/boundary/generate_boundary.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/io/atomic_output.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/vector_io.hpp"

namespace urbanvec {
namespace {

using app::option;
using app::Role;
using app::ValueType;

std::string text(double v, const char* format = "%g") {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

/// Sensible bounds of the placement options, in map units: a pixel from a millimetre to 10 km, an
/// image centre within 100 000 km of the CRS origin (projected coordinates stay well below), so
/// the written coordinates stay finite and keep sub-pixel precision.
constexpr double kMinCellSize = 1e-3;
constexpr double kMaxCellSize = 1e4;
constexpr double kMaxCoordinate = 1e8;
/// Larger than any image: 8192² pixels of kMaxCellSize.
constexpr double kMaxSuburbArea = 1e16;

app::CommandSpec spec() {
  const boundary::BoundaryOptions d;
  app::CommandSpec s;
  s.name = "boundary";
  s.summary = "Generates a realistic city boundary from two-dimensional Perlin noise (Wijgerse 2007).";
  s.description =
      "Sums Perlin noise layers 2^l x 2^l, mixes in a radial slope O = (c1 (1 - D^n) + c2 I) / (c1 + c2) "
      "with "
      "c1 = 1 - c2, thresholds at the requested fill ratio (only above the highest rim value, else new "
      "noise), "
      "traces the outline of the largest island and measures its realism: structured-walk fractal dimension "
      "1.18 < D_R < 1.28 with |a| <= 0.02916 and sigma <= 0.02, and enclosed-area ratio >= 6.35 %. "
      "Unrealistic "
      "boundaries are regenerated up to -max-tries times. The polygon is the outline of the city's pixels "
      "(holes filled); the metrics measure the thesis's chain through the boundary pixels' centres. Without "
      "-cellsize/-center/-a_srs it is in pixel units with y upwards. Layer 'boundary' holds one feature "
      "(Polygon, or MultiPolygon with -suburbs). See docs/boundary.md.";
  s.group = "City boundaries";
  s.positionals = {{"output",
                    "Vector file to create (GeoPackage unless -of or the extension says otherwise).",
                    Role::OutputVector}};
  auto& o = s.options;
  o.push_back(option("-size", ValueType::Integer, "<pixels>", "Width and height of the noise image.")
                  .byDefault(std::to_string(d.noise.size))
                  .withUnit("pixels")
                  .atLeast(16)
                  .atMost(8192));
  o.push_back(
      option("-layers", ValueType::String, "<start>-<end>",
             "Perlin layers: layer l is a 2^l x 2^l grid; 0 <= start <= end <= log2(size). The thesis "
             "recommends 2-9, 3-9, 4-9 or 5-9 for 512 pixels.")
          .byDefault(std::to_string(d.noise.startLayer) + "-" + std::to_string(d.noise.endLayer)));
  o.push_back(option("-slope", ValueType::Choice, "<n>", "Slope shape: 1 linear cone, 2 quadratic dome.")
                  .oneOf({"1", "2"})
                  .byDefault(text(d.transform.slopeExponent)));
  o.push_back(
      option("-c2", ValueType::Real, "<weight>",
             "Weight of the noise against the slope (c1 = 1 - c2): low values give near-circles, high "
             "values scattered islands.")
          .byDefault(text(d.transform.noiseWeight))
          .atLeast(0)
          .atMost(1));
  o.push_back(
      option(
          "-fill", ValueType::Real, "<ratio>",
          "Minimum share of the image to fill, strictly between 0 and 1 (the thesis recommends 0.20-0.40).")
          .byDefault(text(d.threshold.minimumFill)));
  o.push_back(
      option("-persistence", ValueType::Real, "<ratio>",
             "Weight ratio between successive noise layers (0.5 is the thesis's Eq. 2.23, which gives too "
             "smooth boundaries; see docs/boundary.md).")
          .byDefault(text(d.noise.persistence))
          .atLeast(0.01)
          .atMost(1)
          .isAdvanced());
  o.push_back(app::seedOption());
  o.back().atMost(4294967295.0);
  o.push_back(option("-max-tries", ValueType::Integer, "<N>",
                     "Noise images to generate at most; later tries use seeds derived from -seed.")
                  .byDefault(std::to_string(d.maxTries))
                  .atLeast(1)
                  .atMost(1000000));
  o.push_back(
      option("-validate", ValueType::Flag, "", "Regenerate until the boundary is realistic (the default)."));
  o.push_back(
      option("-no-validate", ValueType::Flag, "",
             "Only regenerate when the threshold falls below the rim; keep the first boundary found."));
  o.push_back(
      option("-skip", ValueType::Integer, "<s>",
             "Structured walk from every s-th vertex only (1 = exact; the thesis's 15 is within 0.0025).")
          .byDefault(std::to_string(d.realism.walk.skip))
          .atLeast(1)
          .isAdvanced());
  o.push_back(
      option("-cellsize", ValueType::Real, "<size>",
             "Ground size of a pixel in map units: the linear unit of -a_srs (metres for most projected "
             "CRSs, US feet for some); default 1, i.e. pixel units.")
          .withUnit("map units")
          .atLeast(kMinCellSize)
          .atMost(kMaxCellSize));
  o.push_back(option("-center", ValueType::Real, "<x> <y>",
                     "Where the image centre lands, in map units; default: the image's lower-left corner at "
                     "(0, 0).")
                  .values(2)
                  .withUnit("map units")
                  .atLeast(-kMaxCoordinate)
                  .atMost(kMaxCoordinate));
  o.push_back(option("-a_srs", ValueType::String, "<crs>", "CRS of the output (projected, e.g. EPSG:32633).")
                  .withRole(Role::Crs));
  o.push_back(option("-suburbs", ValueType::Real, "<area>",
                     "Also keep the other islands covering at least this area (in square map units, i.e. "
                     "-cellsize squared; square pixels without -cellsize) as suburbs: the feature becomes a "
                     "MultiPolygon.")
                  .withUnit("square map units")
                  .atLeast(0)
                  .atMost(kMaxSuburbArea));
  for (const app::OptionSpec& v : app::vectorOutputOptions()) o.push_back(v);
  s.examples = {
      "urbanvec boundary city.gpkg",
      "urbanvec boundary -fill 0.3 -seed 42 -cellsize 20 -center 455000 5550000 -a_srs EPSG:32633 city.gpkg",
      "urbanvec boundary -layers 4-9 -c2 0.3 -suburbs 20000 -seed 7 town.gpkg"};
  s.outputLayers = {"boundary"};
  return s;
}

void parseLayers(const std::string& value, boundary::PerlinOptions& noise) {
  const size_t dash = value.find('-');
  const auto bad = [&] {
    return invalidOption("-layers must be <start>-<end> with 0 <= start <= end <= " +
                         std::to_string(boundary::maxLayerFor(noise.size)) + " (log2 of -size " +
                         std::to_string(noise.size) + "), got '" + value + "'");
  };
  if (dash == std::string::npos || dash == 0 || dash + 1 >= value.size()) throw bad();
  try {
    size_t used = 0;
    noise.startLayer = std::stoi(value.substr(0, dash), &used);
    if (used != dash) throw bad();
    noise.endLayer = std::stoi(value.substr(dash + 1), &used);
    if (used != value.size() - dash - 1) throw bad();
  } catch (const std::logic_error&) {
    throw bad();
  }
  if (noise.startLayer < 0 || noise.startLayer > noise.endLayer ||
      noise.endLayer > boundary::maxLayerFor(noise.size))
    throw bad();
}

/// Pixel frame (x right, y down, pixel centres at +0.5) to the output frame (y up).
struct Placement {
  double cellSize = 1.0;
  Vec2 centre;
  double half = 0.0;  ///< half the image size, in pixels
  Vec2 operator()(const Vec2& p) const {
    return {centre.x + (p.x - half) * cellSize, centre.y - (p.y - half) * cellSize};
  }
};

Polygon place(const Polygon& polygon, const Placement& at) {
  Polygon out;
  for (const Vec2& p : polygon.outer) out.outer.push_back(at(p));
  for (const Ring& hole : polygon.holes) {
    out.holes.emplace_back();
    for (const Vec2& p : hole) out.holes.back().push_back(at(p));
  }
  return out;
}

FieldValue optionalReal(bool present, double value) {
  return present && std::isfinite(value) ? FieldValue(value) : FieldValue(std::monostate{});
}

void run(const app::ParsedArgs& args, app::CommandContext& ctx) {
  boundary::BoundaryOptions options;
  options.noise.size = static_cast<int>(args.integer("-size"));
  parseLayers(args.str("-layers"), options.noise);
  options.noise.persistence = args.real("-persistence");
  options.transform.slopeExponent = args.real("-slope");
  options.transform.noiseWeight = args.real("-c2");
  options.threshold.minimumFill = args.real("-fill");
  if (!(options.threshold.minimumFill > 0.0 && options.threshold.minimumFill < 1.0))
    throw invalidOption("-fill must lie strictly between 0 and 1, got " + args.str("-fill"));
  options.seed = static_cast<boundary::PerlinSeed>(args.integer("-seed"));
  options.maxTries = static_cast<int>(args.integer("-max-tries"));
  if (args.flag("-validate") && args.flag("-no-validate"))
    throw invalidOption("-validate and -no-validate contradict each other; give one of them");
  options.validate = !args.flag("-no-validate");
  options.realism.walk.skip = static_cast<int>(args.integer("-skip"));

  Placement placement;
  placement.half = options.noise.size / 2.0;
  placement.cellSize = args.given("-cellsize") ? args.real("-cellsize") : 1.0;
  if (args.given("-center")) {
    const std::vector<std::string> c = args.values("-center");
    placement.centre = {std::stod(c[0]), std::stod(c[1])};
  } else {
    placement.centre = {placement.half * placement.cellSize, placement.half * placement.cellSize};
  }
  if (args.given("-suburbs"))
    options.suburbMinimumPixels = args.real("-suburbs") / (placement.cellSize * placement.cellSize);

  io::VectorWriteOptions write;
  write.format = io::vectorFormatFor(args.positionals()[0], args.has("-of") ? args.str("-of") : "");
  write.layerCreationOptions = args.values("-lco");
  write.datasetCreationOptions = args.values("-dsco");
  if (args.given("-a_srs")) {
    write.crsWkt = io::crsToWkt(args.str("-a_srs"), "-a_srs");
    if (io::isGeographic(write.crsWkt))
      throw invalidOption(
          "-a_srs " + args.str("-a_srs") +
          " is geographic; the boundary is laid out in -cellsize units and needs a projected CRS");
  }
  const std::string outputPath = args.positionals()[0];
  io::VectorOutput output(outputPath, write, {"boundary"},
                          io::OutputRules{args.flag("-overwrite"), false, {}, ctx.inputs});
  if (write.crsWkt.empty())
    ctx.warn("no -a_srs: the boundary is written without a CRS" +
             std::string(args.given("-cellsize") ? "" : ", in pixel units") +
             "; give -a_srs, -cellsize and -center to place it on the map");
  const boundary::BoundaryResult result =
      boundary::generateBoundary(options, subProgress(ctx.progress, 0.0, 0.95));
  const boundary::BoundaryAttempt& kept = result.attempt;
  const shape::ShapeMetrics& metrics = *kept.metrics;
  const bool measured = metrics.regression.has_value();
  const bool valid = kept.realistic();

  MultiPolygon parts{place(result.city, placement)};
  for (const Polygon& p : result.suburbs) parts.push_back(place(p, placement));
  const bool multi = args.given("-suburbs");

  Layer layer;
  layer.name = "boundary";
  layer.geometryType = multi ? GeometryType::MultiPolygon : GeometryType::Polygon;
  layer.fields = {{"fractal_dimension", FieldType::Real},
                  {"slope_a", FieldType::Real},
                  {"sigma", FieldType::Real},
                  {"enclosed_area_ratio", FieldType::Real},
                  {"fill_ratio", FieldType::Real},
                  {"valid", FieldType::Integer},
                  {"seed", FieldType::Integer},
                  {"tries", FieldType::Integer}};
  Feature feature;
  if (multi)
    feature.geometry = parts;
  else
    feature.geometry = parts.front();
  feature.values = {optionalReal(measured, measured ? metrics.regression->comparableDimension : 0.0),
                    optionalReal(measured, measured ? metrics.regression->slope : 0.0),
                    optionalReal(measured, measured ? metrics.regression->sigma : 0.0),
                    FieldValue(metrics.enclosed.ratio),
                    FieldValue(kept.fillRatio),
                    FieldValue(static_cast<std::int64_t>(valid ? 1 : 0)),
                    FieldValue(static_cast<std::int64_t>(kept.seed)),
                    FieldValue(static_cast<std::int64_t>(result.tries))};
  layer.features.push_back(std::move(feature));
  reportProgress(ctx.progress, 0.96, "writing");
  output.write({layer});
  output.commit(ctx.progress);
  reportProgress(ctx.progress, 1.0, "done");

  const std::string dimension = measured ? "D_R " + text(metrics.regression->comparableDimension, "%.3f") +
                                               " (a " + text(metrics.regression->slope, "%.4f") + ", sigma " +
                                               text(metrics.regression->sigma, "%.4f") + ")"
                                         : "no fractal dimension (outline too short)";
  if (!valid && options.validate)
    ctx.warn("no realistic boundary in " + std::to_string(result.tries) + " tr" +
             (result.tries == 1 ? "y" : "ies") + "; wrote the last one (" + dimension +
             ", enclosed-area ratio " + text(metrics.enclosed.ratio, "%.3f") +
             "); raise -max-tries or use the recommended -layers/-c2");
  if (!ctx.quiet && ctx.out)
    *ctx.out << "boundary: " << dimension << ", enclosed-area ratio " << text(metrics.enclosed.ratio, "%.3f")
             << ", fill " << text(kept.fillRatio, "%.3f") << ", " << (valid ? "realistic" : "not realistic")
             << ", seed " << kept.seed << ", " << result.tries << " tr" << (result.tries == 1 ? "y" : "ies")
             << (result.suburbs.empty() ? "" : ", " + std::to_string(result.suburbs.size()) + " suburbs")
             << "\n";
}

const bool registered = app::registerCommand(spec(), run);

}  // namespace
}  // namespace urbanvec
