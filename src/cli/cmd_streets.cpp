// `urbanvec streets`: a street network grown from a tensor field inside a real boundary, around water
// and parks, following terrain and existing roads (issue 18; spec chen-streets.md).
#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "urbanvec/app/command.hpp"
#include "urbanvec/app/street_layers.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/core/landuse.hpp"
#include "urbanvec/io/atomic_output.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/layer_styles.hpp"
#include "urbanvec/io/raster_io.hpp"
#include "urbanvec/io/vector_io.hpp"
#include "urbanvec/streets/generate_streets.hpp"

namespace urbanvec {
namespace {

using app::option;
using app::Role;
using app::ValueType;

app::CommandSpec spec() {
  const streets::StreetsOptions d;
  app::CommandSpec s;
  s.name = "streets";
  s.summary = "Grows a street network from a tensor field inside a boundary, around water and parks.";
  s.description =
      "Designs a tensor field (Chen et al. 2008) from grid and radial elements (an OGR point layer with "
      "fields kind = grid|radial, angle in degrees counter-clockwise from east, size, decay; or a JSON file "
      "{\"elements\": [{\"kind\", \"x\", \"y\", \"angle\", \"size\", \"decay\"}]}), from polylines (existing "
      "roads with -roads, coastlines or rivers with -field-lines: each segment a regular element) and from a "
      "DEM (major roads follow contours, minor roads climb the gradient), blended with Eq. 3 "
      "exp(-d |p - p_i|^2) and smoothed. Traces major roads, then minor roads ending on them, along the "
      "field's two eigenvector families (interleaved seeding, RK4, d_sep / d_test separation, look-ahead "
      "joins into T-junctions), inside the -boundary polygon and out of -water; -parks and a -density raster "
      "widen the spacing. Every crossing is a node (GEOS). Writes the layers streets (class major/minor, "
      "highway primary/residential for gridify, length), street_nodes (degree) and blocks (faces inside "
      "the boundary, land_use), and with -water the water polygons (layer water), in the boundary's CRS (a "
      "geographic one is replaced by its UTM zone); "
      "-field writes the field as a 2-band raster (major direction in degrees, magnitude / median). "
      "Distances are in metres. The output does not depend on -threads. See docs/streets.md.";
  s.group = "Streets";
  s.positionals = {
      {"output", "Vector file to create (layers streets, street_nodes, blocks).", Role::OutputVector}};
  s.outputLayers = {"streets", "street_nodes", "blocks", "water"};
  auto& o = s.options;
  o.push_back(option("-boundary", ValueType::String, "<file>",
                     "Polygon layer (first layer) the streets grow in, e.g. from 'urbanvec boundary'.")
                  .withRole(Role::InputVector));
  o.push_back(option("-design", ValueType::String, "<file>",
                     "Design elements: a point layer (fields kind, angle, size, decay) or a .json file.")
                  .withRole(Role::InputFile));
  o.push_back(option("-design-layer", ValueType::String, "<name>", "Layer of -design; default the first."));
  o.push_back(option("-roads", ValueType::String, "<file>",
                     "Existing roads (line layer) whose segments shape the field and seed the major roads.")
                  .withRole(Role::InputVector));
  o.push_back(option("-keep-roads", ValueType::Flag, "",
                     "Keep the -roads (after -where) in the network, clipped to the boundary, and grow the "
                     "traced roads around them: minor roads end on them in T-junctions (spec 14, local "
                     "editing of an existing network)."));
  o.push_back(option("-roads-layer", ValueType::String, "<name>", "Layer of -roads; default the first."));
  o.push_back(
      option("-where", ValueType::String, "<expression>",
             "OGR SQL filter on -roads choosing the roads that shape the field (e.g. the main roads)."));
  o.push_back(option("-field-lines", ValueType::String, "<file>",
                     "Further polylines for the field (coastline, river, edges); polygons give their rings.")
                  .withRole(Role::InputVector));
  o.push_back(
      option("-boundary-field", ValueType::Flag, "", "The boundary's outline also shapes the field (§4.3)."));
  o.push_back(option("-water", ValueType::String, "<file>", "Water polygons: no street inside.")
                  .withRole(Role::InputVector));
  o.push_back(option("-water-where", ValueType::String, "<expression>", "OGR SQL filter on -water."));
  o.push_back(option("-water-layer", ValueType::String, "<name>", "Layer of -water; default the first."));
  o.push_back(option("-parks", ValueType::String, "<file>", "Park polygons: d_sep x -park-factor inside.")
                  .withRole(Role::InputVector));
  o.push_back(
      option("-dem", ValueType::String, "<file>", "Elevation raster in the output CRS covering the boundary.")
          .withRole(Role::InputRaster));
  o.push_back(option("-density", ValueType::String, "<file>",
                     "Population density raster in the output CRS: d_sep grows where it is low (§11).")
                  .withRole(Role::InputRaster));
  o.push_back(
      option("-field", ValueType::String, "<file>",
             "Also write the tensor field as a GeoTIFF: band 1 major direction (degrees ccw from east), "
             "band 2 magnitude / median magnitude.")
          .withRole(Role::OutputRaster));
  o.push_back(option("-dsep-major", ValueType::Real, "<metres>",
                     "Separation of major roads; default the spacing of the -roads (2 x land area / their "
                     "length on the land: a grid with as much road) up to " +
                         app::numberText(d.trace.majorDsep) + " and at least -dsep-floor, without -roads " +
                         app::numberText(d.trace.majorDsep) + "; printed unless -q.")
                  .withUnit("m")
                  .atLeast(1e-3));
  o.push_back(
      option("-dsep-minor", ValueType::Real, "<metres>",
             "Separation of minor roads; default -dsep-major x " + app::numberText(d.minorDsepRatio) + ".")
          .withUnit("m")
          .atLeast(1e-3));
  o.push_back(option("-dsep-floor", ValueType::Real, "<metres>",
                     "Least -dsep-major taken from the -roads spacing: finer roads (a full mapped network, a "
                     "fine grid) are traced at this spacing, with a warning. Not applied to a given "
                     "-dsep-major.")
                  .withUnit("m")
                  .byDefault(app::numberText(d.derivedDsepFloor))
                  .atLeast(1e-3));
  o.push_back(option("-dtest-ratio", ValueType::Real, "<ratio>",
                     "d_test / d_sep: a street stops this close to a parallel one.")
                  .byDefault(app::numberText(d.trace.dtestRatio)));
  o.push_back(option("-lookahead-ratio", ValueType::Real, "<ratio>",
                     "d_lookahead / d_sep: how far a stopped street looks for a street to join (T-junction).")
                  .byDefault(app::numberText(d.trace.lookaheadRatio))
                  .atLeast(0));
  o.push_back(option("-min-length-ratio", ValueType::Real, "<ratio>",
                     "Streets shorter than this x d_sep are dropped.")
                  .byDefault(app::numberText(d.trace.minLengthRatio))
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(
      option("-edge-seed-ratio", ValueType::Real, "<ratio>",
             "Seeds closer than this x the integration step to the boundary or the water are not used "
             "(a street seeded on the edge meets the one clipped there at a corner); 0 = off.")
          .byDefault(app::numberText(d.trace.edgeSeedRatio))
          .atLeast(0)
          .isAdvanced());
  o.push_back(option("-step", ValueType::Real, "<metres>", "Integration step; default half a field cell.")
                  .withUnit("m")
                  .atLeast(1e-3)
                  .isAdvanced());
  o.push_back(
      option("-field-cell", ValueType::Real, "<metres>", "Cell of the field grid; default d_sep_minor / 4.")
          .withUnit("m")
          .atLeast(1e-3)
          .isAdvanced());
  o.push_back(option("-decay-share", ValueType::Real, "<ratio>",
                     "Default decay of design elements: d = 1/sigma^2, sigma = this x the domain width (§5).")
                  .byDefault(app::numberText(d.field.decayRadiusShare))
                  .atLeast(1e-6)
                  .isAdvanced());
  o.push_back(option("-line-decay-ratio", ValueType::Real, "<ratio>",
                     "Decay radius of road / line elements as a multiple of d_sep_major.")
                  .byDefault(app::numberText(d.polylineDecayRatio))
                  .atLeast(1e-6)
                  .isAdvanced());
  o.push_back(option("-smooth", ValueType::Integer, "<iterations>",
                     "Laplacian smoothing iterations of the field (§6.1).")
                  .byDefault(std::to_string(d.field.smoothingIterations))
                  .atLeast(0)
                  .atMost(100000));
  o.push_back(
      option("-dem-weight", ValueType::Real, "<weight>", "Weight of the terrain term per unit slope (§4.4).")
          .byDefault(app::numberText(d.field.heightWeight))
          .atLeast(0));
  o.push_back(option("-park-factor", ValueType::Real, "<factor>", "d_sep multiplier inside parks (§11).")
                  .byDefault(app::numberText(d.trace.parkFactor))
                  .atLeast(1));
  o.push_back(option("-density-max-factor", ValueType::Real, "<factor>",
                     "d_sep where the density is 0, as a multiple of d_sep.")
                  .byDefault(app::numberText(d.trace.densityMaxFactor))
                  .atLeast(1));
  o.push_back(option("-noise", ValueType::Real, "<degrees>",
                     "Amplitude of the Perlin-noise rotation of the field (§7); 0 = none.")
                  .byDefault(app::numberText(d.field.noiseAmplitude * 180.0 / M_PI))
                  .withUnit("degrees")
                  .atLeast(0)
                  .atMost(90));
  o.push_back(option("-noise-wavelength", ValueType::Real, "<metres>",
                     "Wavelength of the noise; default 2 x -dsep-major.")
                  .withUnit("m")
                  .atLeast(1e-3)
                  .isAdvanced());
  // The shares of the graph noise and of stopping short: a value in [0, 1].
  auto share = [&](const char* name, const std::string& help, double byDefault) {
    o.push_back(option(name, ValueType::Real, "<share>", help)
                    .byDefault(app::numberText(byDefault))
                    .atLeast(0)
                    .atMost(1));
  };
  share("-delete-share",
        "Graph noise (§13.6): share of minor segments between crossings deleted (Halton-spread).",
        d.noise.fullShare);
  share("-cut-share", "Graph noise: share of minor segments cut back to a dead-end stub.",
        d.noise.partialShare);
  share("-bend-share",
        "Graph noise: share of minor segments deleted at a T-junction whose two other streets then meet at a "
        "turn of at least 45 degrees, so the street turns the corner there.",
        d.noise.bendShare);
  share("-stop-short-share",
        "Chance that an end of a minor road joining streets at both ends (T-junctions) stops d_test short "
        "instead, leaving a dead end (a cul-de-sac); one end per road at most, drawn from -seed; 0 = off.",
        d.trace.stopShortShare);
  o.push_back(option("-major-clearance-ratio", ValueType::Real, "<ratio>",
                     "A minor-road seed keeps this x d_sep_minor from the major roads of its family (the "
                     "full d_sep from minor ones): the major roads bound the regions minor roads fill (§12).")
                  .byDefault(app::numberText(d.trace.majorClearanceRatio))
                  .atLeast(0)
                  .atMost(1));
  o.push_back(option("-bow", ValueType::Real, "<ratio>",
                     "Curved streets: each traced street between two nodes bows sideways by a half sine of "
                     "up to this share of its chord (at most a quarter of the minor d_sep; drawn per street "
                     "from -seed; never onto another street or the boundary); 0 = straight.")
                  .byDefault(app::numberText(d.bow.ratio))
                  .atLeast(0)
                  .atMost(0.5));
  o.push_back(app::seedOption());
  o.push_back(option("-no-minor", ValueType::Flag, "", "Trace the major roads only."));
  o.push_back(
      option("-default-use", ValueType::String, "<class>",
             "Land use (gridify class name) of blocks that gridify's untagged-land rule leaves to its "
             "default: where the density is positive or not given and under half of the block's edge "
             "is residential (minor) streets.")
          .byDefault(d.defaultUse));
  o.push_back(
      option("-t_srs", ValueType::String, "<crs>", "Output CRS (projected, metres); default the boundary's.")
          .withRole(Role::Crs));
  o.push_back(option("-threads", ValueType::Integer, "<n>",
                     "Worker threads for the field (0 = all cores); the output does not depend on it.")
                  .byDefault("0")
                  .atLeast(0)
                  .isAdvanced());
  for (const app::OptionSpec& v : app::vectorOutputOptions()) o.push_back(v);
  s.examples = {
      "urbanvec streets -boundary boundary.gpkg -design design.gpkg streets.gpkg",
      "urbanvec streets -boundary city.gpkg -roads monaco.osm.pbf -roads-layer lines -where \"highway IN "
      "('primary','secondary')\" -water sea.gpkg -field field.tif streets.gpkg"};
  return s;
}

std::vector<streets::DesignElement> readDesign(const std::string& path, const std::string& layer,
                                               const std::string& crs) {
  std::vector<streets::DesignElement> out;
  auto kindOf = [&](const std::string& k) {
    std::string v = k;
    std::transform(v.begin(), v.end(), v.begin(), [](unsigned char c) { return std::tolower(c); });
    if (v == "grid" || v == "regular") return streets::ElementKind::Grid;
    if (v == "radial" || v == "center" || v == "centre") return streets::ElementKind::Radial;
    throw invalidInput("-design '" + path + "': unknown element kind '" + k + "' (grid or radial)");
  };
  const bool json = path.size() > 5 && path.substr(path.size() - 5) == ".json";
  if (json) {
    std::ifstream in(path);
    if (!in) throw invalidInput("-design '" + path + "' cannot be read");
    nlohmann::json doc;
    try {
      in >> doc;
      for (const auto& e : doc.at("elements")) {
        streets::DesignElement d;
        d.kind = kindOf(e.at("kind").get<std::string>());
        d.position = {e.at("x").get<double>(), e.at("y").get<double>()};
        d.angle = e.value("angle", 0.0) * M_PI / 180.0;
        d.size = e.value("size", d.kind == streets::ElementKind::Grid ? 1.0 : 100.0);
        d.decay = e.value("decay", 0.0);
        out.push_back(d);
      }
    } catch (const nlohmann::json::exception& e) {
      throw invalidInput("-design '" + path + "' is not a design file ({\"elements\": [...]}): " + e.what());
    }
    return out;
  }
  const app::LoadedLayer l = app::readLayer({path, layer, "", "-design"}, crs, false);
  const int kind = l.layer.fieldIndex("kind"), angle = l.layer.fieldIndex("angle");
  const int size = l.layer.fieldIndex("size"), decay = l.layer.fieldIndex("decay");
  if (kind < 0)
    throw invalidInput("-design '" + path + "': layer '" + l.layer.name + "' has no field 'kind'");
  auto number = [](const FieldValue& v, double fallback) {
    if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
    if (const auto* r = std::get_if<double>(&v)) return *r;
    if (const auto* s = std::get_if<std::string>(&v)) {
      try {
        return std::stod(*s);
      } catch (...) {
      }
    }
    return fallback;
  };
  for (const Feature& f : l.layer.features) {
    const auto* p = std::get_if<Vec2>(&f.geometry);
    if (!p) continue;
    streets::DesignElement d;
    const auto* k = std::get_if<std::string>(&f.values[static_cast<std::size_t>(kind)]);
    d.kind = kindOf(k ? *k : "");
    d.position = *p;
    if (angle >= 0) d.angle = number(f.values[static_cast<std::size_t>(angle)], 0.0) * M_PI / 180.0;
    d.size = d.kind == streets::ElementKind::Grid ? 1.0 : 100.0;
    if (size >= 0) d.size = number(f.values[static_cast<std::size_t>(size)], d.size);
    if (decay >= 0) d.decay = number(f.values[static_cast<std::size_t>(decay)], 0.0);
    out.push_back(d);
  }
  return out;
}

/// Reads a raster that must be in `crs`; `cover` (optional) is the extent it must cover.
Grid<float> readRaster(const std::string& path, const std::string& option, const std::string& crs,
                       GridSpec& spec, std::vector<std::uint8_t>* valid, const Vec2* lo, const Vec2* hi) {
  io::RasterInfo info;
  Grid<float> g = io::readRasterBand<float>(path, option + " raster", &info);
  spec = info.spec;
  if (spec.crsWkt.empty() || !io::sameCrs(spec.crsWkt, crs))
    throw invalidInput(option + " '" + path + "' is in " +
                       (spec.crsWkt.empty() ? "no CRS" : io::crsShortName(spec.crsWkt)) +
                       ", not the output CRS " + io::crsShortName(crs) + "; warp it first (gdalwarp -t_srs)");
  if (lo && hi) {
    const Vec2 a = spec.transform.pixelToWorld(0, 0),
               b = spec.transform.pixelToWorld(spec.width, spec.height);
    if (std::min(a.x, b.x) > lo->x || std::max(a.x, b.x) < hi->x || std::min(a.y, b.y) > lo->y ||
        std::max(a.y, b.y) < hi->y)
      throw invalidInput(option + " '" + path + "' (" + std::to_string(spec.width) + "x" +
                         std::to_string(spec.height) + " cells) does not cover the boundary");
  }
  if (valid) {
    valid->assign(g.cells.size(), 1);
    for (std::size_t i = 0; i < g.cells.size(); ++i)
      if (!std::isfinite(g.cells[i]) || (info.nodata && g.cells[i] == static_cast<float>(*info.nodata)))
        (*valid)[i] = 0;
  } else if (info.nodata) {
    for (float& v : g.cells)
      if (v == static_cast<float>(*info.nodata)) v = 0.0f;
  }
  return g;
}

void writeFieldRaster(const std::string& path, const streets::TensorField& field, const std::string& crs) {
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  const int w = field.width(), h = field.height();
  GDALDataset* ds = driver->Create(path.c_str(), w, h, 2, GDT_Float32, nullptr);
  if (!ds) throw ioError("cannot create -field raster '" + path + "'");
  const double c = field.cellSize();
  // Vertex (i, j) is the centre of pixel (i, h - 1 - j).
  double gt[6] = {field.origin().x - c / 2, c, 0, field.origin().y + (h - 0.5) * c, 0, -c};
  ds->SetGeoTransform(gt);
  if (!crs.empty()) ds->SetProjection(crs.c_str());
  const double median = std::max(field.medianMagnitude(), 1e-300);
  std::vector<float> angle(static_cast<std::size_t>(w) * h), mag(angle.size());
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const std::size_t k = static_cast<std::size_t>(h - 1 - j) * w + i;
      const streets::Tensor& t = field.at(i, j);
      angle[k] = static_cast<float>(t.angle() * 180.0 / M_PI);
      mag[k] = static_cast<float>(t.magnitude() / median);
    }
  CPLErr e1 = ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, w, h, angle.data(), w, h, GDT_Float32, 0, 0);
  CPLErr e2 = ds->GetRasterBand(2)->RasterIO(GF_Write, 0, 0, w, h, mag.data(), w, h, GDT_Float32, 0, 0);
  ds->GetRasterBand(1)->SetDescription("major direction (degrees ccw from east)");
  ds->GetRasterBand(2)->SetDescription("magnitude / median magnitude");
  GDALClose(ds);
  if (e1 != CE_None || e2 != CE_None) throw ioError("cannot write -field raster '" + path + "'");
}

void run(const app::ParsedArgs& args, app::CommandContext& ctx) {
  const std::string outputPath = args.positionals()[0];
  if (!args.given("-boundary")) throw invalidOption("-boundary is required: the polygon the streets grow in");
  streets::StreetsOptions options;
  if (args.given("-dsep-floor")) options.derivedDsepFloor = args.real("-dsep-floor");
  // A pair given (or a -dsep-minor over the fixed default, without -roads) is checked before any
  // input is read; a -dsep-major derived from the -roads only after reading them.
  if (args.given("-dsep-minor") && (args.given("-dsep-major") || !args.given("-roads"))) {
    const double major = args.given("-dsep-major") ? args.real("-dsep-major") : options.trace.majorDsep;
    if (args.real("-dsep-minor") > major)
      throw invalidOption("-dsep-minor " + args.str("-dsep-minor") + " exceeds -dsep-major " +
                          (args.given("-dsep-major")
                               ? args.str("-dsep-major")
                               : app::numberText(major) + " (the default without -roads)"));
  }
  options.seed = static_cast<std::uint64_t>(args.integer("-seed"));
  options.bow.ratio = args.real("-bow");
  options.trace.stopShortShare = args.real("-stop-short-share");
  options.trace.majorClearanceRatio = args.real("-major-clearance-ratio");
  options.noise.fullShare = args.real("-delete-share");
  options.noise.partialShare = args.real("-cut-share");
  options.noise.bendShare = args.real("-bend-share");
  options.field.noiseAmplitude = args.real("-noise") * M_PI / 180.0;
  if (args.given("-noise-wavelength")) options.field.noiseWavelength = args.real("-noise-wavelength");
  options.trace.dtestRatio = args.real("-dtest-ratio");
  if (!(options.trace.dtestRatio > 0.0) || options.trace.dtestRatio > 1.0)
    throw invalidOption("-dtest-ratio " + args.str("-dtest-ratio") +
                        ": d_test must be > 0 and at most d_sep (ratio in (0, 1])");
  options.trace.lookaheadRatio = args.real("-lookahead-ratio");
  options.trace.minLengthRatio = args.real("-min-length-ratio");
  options.trace.edgeSeedRatio = args.real("-edge-seed-ratio");
  if (args.given("-step")) options.trace.step = args.real("-step");
  if (args.given("-field-cell")) options.field.cellSize = args.real("-field-cell");
  options.field.decayRadiusShare = args.real("-decay-share");
  options.polylineDecayRatio = args.real("-line-decay-ratio");
  options.field.smoothingIterations = static_cast<int>(args.integer("-smooth"));
  options.field.heightWeight = args.real("-dem-weight");
  options.trace.parkFactor = args.real("-park-factor");
  options.trace.densityMaxFactor = args.real("-density-max-factor");
  options.trace.minorRoads = !args.flag("-no-minor");
  options.defaultUse = args.str("-default-use");
  if (!parseLandUse(options.defaultUse) || isRoad(*parseLandUse(options.defaultUse)))
    throw invalidOption("-default-use '" + options.defaultUse +
                        "' is not a land-use class (residential, commercial, "
                        "industrial, park, reserved, unused)");
  const int threads = static_cast<int>(args.integer("-threads"));
  options.field.threads =
      threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

  io::VectorWriteOptions write;
  if (args.has("-of")) write.format = args.str("-of");
  write.layerCreationOptions = args.values("-lco");
  write.datasetCreationOptions = args.values("-dsco");
  write.layerStylesQml["streets"] = io::categorizedQml(
      "class", io::SymbolKind::Line,
      {{"major", "Major road", "200,90,40,255"}, {"minor", "Minor road", "90,90,90,255"}}, 0.5);
  write.layerStylesQml["street_nodes"] = io::singleSymbolQml(io::SymbolKind::Marker, "40,40,40,255", 1.0);
  write.layerStylesQml["blocks"] =
      io::categorizedQml("land_use", io::SymbolKind::Fill, io::landUseCategories(), 0.1);
  std::vector<std::string> layerNames{"streets", "street_nodes", "blocks"};
  if (args.given("-water")) layerNames.push_back("water");
  io::VectorOutput output(outputPath, write, layerNames,
                          io::OutputRules{args.flag("-overwrite"), false, {}, ctx.inputs});
  std::optional<io::AtomicOutput> fieldOut;
  if (args.given("-field"))
    fieldOut.emplace(args.str("-field"), io::OutputRules{args.flag("-overwrite"), false, {}, ctx.inputs});

  // The boundary fixes the CRS (its UTM zone when geographic, or -t_srs).
  std::string target;
  if (args.given("-t_srs")) {
    target = io::crsToWkt(args.str("-t_srs"), "-t_srs");
    if (!io::isProjectedInMetres(target))
      throw invalidOption("-t_srs " + args.str("-t_srs") + " is not a projected CRS in metres");
  }
  const app::LoadedLayer boundaryLayer = app::readLayer({args.str("-boundary"), "", "", "-boundary"}, target);
  const std::string crs = boundaryLayer.crsWkt;
  if (crs.empty())
    throw invalidInput("-boundary '" + args.str("-boundary") +
                       "' has no CRS; streets needs a projected CRS in metres");
  if (!io::isProjectedInMetres(crs))
    throw invalidInput("-boundary '" + args.str("-boundary") + "' is in " + io::crsShortName(crs) +
                       ": streets needs a projected CRS in metres (give -t_srs)");
  streets::StreetsInput input;
  input.boundary = app::polygonsOf(boundaryLayer.layer, "-boundary '" + args.str("-boundary") + "'");
  auto optionalLayer = [&](const char* opt, const char* layerOpt, const char* whereOpt) {
    return app::readLayer({args.str(opt), layerOpt && args.given(layerOpt) ? args.str(layerOpt) : "",
                           whereOpt && args.given(whereOpt) ? args.str(whereOpt) : "", opt},
                          crs, false);
  };
  if (args.given("-design")) {
    input.design =
        readDesign(args.str("-design"), args.given("-design-layer") ? args.str("-design-layer") : "", crs);
    if (input.design.empty())
      throw invalidInput("-design '" + args.str("-design") + "' holds no design element");
  }
  std::vector<LineString> roads;
  if (args.given("-roads")) {
    roads = app::linesOf(optionalLayer("-roads", "-roads-layer", "-where").layer);
    input.fieldLines = roads;
    if (input.fieldLines.empty())
      throw invalidInput("-roads '" + args.str("-roads") + "' holds no line" +
                         (args.given("-where") ? " where " + args.str("-where") : ""));
    if (args.flag("-keep-roads")) input.existingRoads = input.fieldLines;
  }
  if (args.flag("-keep-roads") && !args.given("-roads"))
    throw invalidOption("-keep-roads needs -roads: it keeps those roads in the network");
  if (args.given("-field-lines")) {
    const std::vector<LineString> more = app::linesOf(optionalLayer("-field-lines", nullptr, nullptr).layer);
    input.fieldLines.insert(input.fieldLines.end(), more.begin(), more.end());
  }
  if (args.flag("-boundary-field"))
    for (const Polygon& p : input.boundary) input.fieldLines.push_back(p.outer);
  if (args.given("-water")) {
    const app::LoadedLayer w = optionalLayer("-water", "-water-layer", "-water-where");
    input.water = app::polygonsOf(w.layer, "-water '" + args.str("-water") + "'");
  }
  if (args.given("-parks"))
    input.parks = app::polygonsOf(optionalLayer("-parks", nullptr, nullptr).layer,
                                  "-parks '" + args.str("-parks") + "'");
  Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}, hi = lo * -1.0;
  for (const Polygon& p : input.boundary)
    for (const Vec2& v : p.outer)
      lo = {std::min(lo.x, v.x), std::min(lo.y, v.y)}, hi = {std::max(hi.x, v.x), std::max(hi.y, v.y)};
  if (args.given("-dem")) {
    streets::HeightMap dem;
    dem.heights = readRaster(args.str("-dem"), "-dem", crs, dem.spec, &dem.valid, &lo, &hi);
    input.dem = std::move(dem);
  }
  if (args.given("-density")) {
    GridSpec spec;
    input.density = readRaster(args.str("-density"), "-density", crs, spec, nullptr, nullptr, nullptr);
    input.densitySpec = spec;
  }
  // d_sep: given, or the spacing of the roads that shape the field (their scale, not a fixed one).
  std::string dsepSource = args.given("-dsep-major") ? "given" : "default";
  if (args.given("-dsep-major")) {
    options.trace.majorDsep = args.real("-dsep-major");
  } else if (!roads.empty()) {
    // At most the fixed default: a few lines given to shape the field are not a network, and their
    // spacing (2 A / L) would leave a city of them almost without streets. At least the floor: a
    // full mapped network would otherwise be traced again at its own, far finer, spacing.
    const double spacing = streets::roadSpacing(roads, input.boundary, input.water);
    if (spacing > 0.0 && spacing < options.trace.majorDsep) {
      options.trace.majorDsep = spacing;
      dsepSource = "from the -roads spacing";
      if (spacing < options.derivedDsepFloor) {
        options.trace.majorDsep = options.derivedDsepFloor;
        dsepSource = "the -roads spacing " + app::numberText(spacing) + " m raised to -dsep-floor";
        ctx.warn("the -roads are " + app::numberText(spacing) + " m apart, closer than -dsep-floor " +
                 app::numberText(options.derivedDsepFloor) +
                 " m: the major roads are traced at the floor (give -dsep-major to choose)");
      }
    }
  }
  options.trace.minorDsep =
      args.given("-dsep-minor") ? args.real("-dsep-minor") : options.minorDsepRatio * options.trace.majorDsep;
  if (options.trace.minorDsep > options.trace.majorDsep)  // only a derived -dsep-major gets here
    throw invalidOption("the -dsep-major derived from the -roads spacing, " +
                        app::numberText(options.trace.majorDsep) + " m, is below -dsep-minor " +
                        args.str("-dsep-minor") + "; give -dsep-major");
  if (!ctx.quiet && ctx.out)
    *ctx.out << "dsep-major: " << app::numberText(options.trace.majorDsep) << " m (" << dsepSource
             << "), dsep-minor: " << app::numberText(options.trace.minorDsep) << " m\n";

  const streets::StreetNetwork net = streets::generateStreets(input, options, ctx.progress);
  if (net.streets.empty())
    ctx.warn(
        "no street could be traced (water or parks cover the boundary, or the boundary is smaller than "
        "d_sep): the layers are empty");

  Layer streetsLayer{"streets",
                     GeometryType::LineString,
                     {{"street_id", FieldType::Integer},
                      {"class", FieldType::String},
                      {"highway", FieldType::String},
                      {"source", FieldType::String},
                      {"length", FieldType::Real}},
                     {}};
  std::int64_t id = 0;
  for (const streets::StreetEdge& e : net.streets) {
    const bool existing = e.level == streets::StreetLevel::Existing;
    const bool major = existing || e.level == streets::StreetLevel::Major;
    streetsLayer.features.push_back(
        {e.line,
         {++id, std::string(major ? "major" : "minor"), std::string(major ? "primary" : "residential"),
          std::string(existing ? "existing" : "traced"), length(e.line)}});
  }
  Layer nodesLayer{"street_nodes",
                   GeometryType::Point,
                   {{"node_id", FieldType::Integer}, {"degree", FieldType::Integer}},
                   {}};
  id = 0;
  for (const streets::StreetNode& n : net.nodes)
    nodesLayer.features.push_back({n.p, {++id, static_cast<std::int64_t>(n.degree)}});
  Layer blocksLayer{
      "blocks",
      GeometryType::Polygon,
      {{"block_id", FieldType::Integer}, {"land_use", FieldType::String}, {"area", FieldType::Real}},
      {}};
  id = 0;
  for (const streets::Block& b : net.blocks)
    blocksLayer.features.push_back({b.shape, {++id, b.landUse, area(b.shape)}});
  std::vector<Layer> layers{streetsLayer, nodesLayer, blocksLayer};
  if (!input.water.empty()) {
    // The water the streets avoided, so that gridify (default -water-layer water) sees it too.
    Layer water{"water", GeometryType::Polygon, {{"water_id", FieldType::Integer}}, {}};
    id = 0;
    for (const Polygon& p : input.water) water.features.push_back({p, {++id}});
    layers.push_back(std::move(water));
  }
  output.write(layers, crs);
  if (fieldOut) writeFieldRaster(fieldOut->tempPath(), net.field, crs);
  if (fieldOut) fieldOut->commit(ctx.progress);
  output.commit(ctx.progress);
  if (!ctx.quiet && ctx.out)
    *ctx.out << "streets: " << net.streets.size() << " streets (" << net.tracedLines << " traced lines, "
             << net.stats.lookaheadJoins << " look-ahead joins), " << net.nodes.size() << " nodes, "
             << net.blocks.size() << " blocks\n";
}

const bool registered = app::registerCommand(spec(), run);

}  // namespace
}  // namespace urbanvec
