// `urbanvec shrink`: city shrinking (issue 19; spec pueyo-urban-data.md part B) — a smaller street
// network that keeps the landmarks, the important streets and their arrangement.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "urbanvec/app/command.hpp"
#include "urbanvec/app/shrink_source.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/io/atomic_output.hpp"
#include "urbanvec/io/layer_styles.hpp"
#include "urbanvec/io/vector_io.hpp"
#include "urbanvec/shrink/shrink.hpp"

namespace urbanvec {
namespace {

using app::option;
using app::Role;
using app::ValueType;

app::CommandSpec spec() {
  const shrink::ShrinkOptions d;
  app::CommandSpec s;
  s.name = "shrink";
  s.summary = "Shrinks a city: fewer blocks between its landmarks, same landmarks, same arrangement.";
  s.description =
      "Pueyo's city shrinking (thesis ch. 4): from an OpenStreetMap file and an importance file (.osmi "
      "places with appearW, or a vector layer with an 'importance' field 0..1), keeps the streets of the "
      "landmarks and the top shF fraction of streets by importance, connects them (A*, dead ends within "
      "m segments), rasterises that skeleton, removes low-energy seams (seam carving with landmarks and "
      "intersections frozen) and moves every node back by the pixels it shifted. Outputs the shrunk "
      "streets, the landmarks (translated, same shape), the whole street map deformed the same way, the "
      "removed seams in original coordinates and a report with the error measures (area kept, landmark "
      "translation, order of landmark pairs, crossings, dead ends, orientation entropy, block areas). "
      "See docs/shrink.md.";
  s.group = "City shrinking";
  s.positionals = {
      {"osm", "OpenStreetMap file (.osm XML or .osm.pbf); in QGIS any layer of it.", Role::InputVector},
      {"importance", "Importance file: .osmi, or a vector layer with an 'importance' field.",
       Role::InputVector},
      {"output", "Vector file to create (GeoPackage).", Role::OutputVector}};
  s.outputLayers = {"streets",      "places", "place_lines",  "place_points",
                    "full_streets", "seams",  "shrink_report"};
  auto& o = s.options;
  o.push_back(option("-shf", ValueType::Real, "<fraction>", "shF: fraction of streets kept in the skeleton.")
                  .byDefault(app::numberText(d.selection.shrinkFactor)));
  o.push_back(option("-seams", ValueType::Integer, "<vertical> <horizontal>",
                     "Seams to remove: vertical (columns) and horizontal (rows) (imageSizeReduction).")
                  .values(2)
                  .byDefault(std::to_string(d.carving.verticalSeams) + " " +
                             std::to_string(d.carving.horizontalSeams)));
  o.push_back(
      option("-image-size", ValueType::Integer, "<pixels>", "imageSize: larger side of the skeleton image.")
          .byDefault(std::to_string(d.carving.imageSize))
          .withUnit("pixels"));
  o.push_back(option("-m-degree", ValueType::Integer, "<segments>",
                     "m-degree: most segments of a dead-end connection (the thesis's Firenze run uses 10).")
                  .byDefault(std::to_string(d.connection.mDegree)));
  o.push_back(
      option("-imp-dist-balance", ValueType::Real, "<alpha>",
             "impDistBalance: A* cost alpha*d/impW + (1-alpha)*d; 1 = importance only, 0 = distance only.")
          .byDefault(app::numberText(d.connection.impDistBalance)));
  o.push_back(option("-gray-dist-balance", ValueType::Real, "<beta>",
                     "grayDistBalance: energy = beta*inverted grey + (1-beta)*inverted distance field.")
                  .byDefault(app::numberText(d.carving.grayDistBalance)));
  o.push_back(option("-prox-str-threshold", ValueType::Real, "<metres>",
                     "proxStrThreshold: most distance from a landmark node to its indirect street "
                     "(the thesis's 0.00033 degrees of latitude).")
                  .byDefault(app::numberText(d.selection.proximityThreshold))
                  .withUnit("m")
                  .atLeast(0));
  o.push_back(
      option("-highway-weight", ValueType::String, "<highway>=<weight>",
             "Street-type weight (highwayWeights_d; strT = weight/10); defaults motorway=3 primary=2.5 "
             "secondary=2 tertiary=1.5 residential=1, other 0.5.")
          .many()
          .isAdvanced());
  o.push_back(option("-keep-unimportant-clusters", ValueType::Flag, "",
                     "Keep disconnected clusters without an important place (noImpClusters = False).")
                  .isAdvanced());
  o.push_back(option("-seam-order", ValueType::Choice, "<order>",
                     "Seam order: interleaved (vertical, horizontal, ...) or blocks (all vertical first).")
                  .oneOf({"blocks", "interleaved"})
                  .byDefault(d.carving.order == shrink::SeamOrder::Blocks ? "blocks" : "interleaved"));
  o.push_back(option("-freeze-landmarks", ValueType::Choice, "<mode>",
                     "Frozen landmark pixels: bbox (each element's pixel box: a pure translation) or nodes "
                     "(only node pixels, the thesis).")
                  .oneOf({"bbox", "nodes"})
                  .byDefault("bbox")
                  .isAdvanced());
  o.push_back(
      option("-translate-nodes-only", ValueType::Flag, "",
             "Back to vector as the thesis: move only the ways' nodes (no densified ways, no crossing "
             "guard); close ways can fold over each other (new crossings).")
          .isAdvanced());
  o.push_back(option("-threads", ValueType::Integer, "<n>",
                     "Threads of seam carving (0 = all cores); the output does not depend on it.")
                  .byDefault("0")
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-freeze-all-street-nodes", ValueType::Flag, "",
                     "Freeze every skeleton street node, so no street loses a node.")
                  .isAdvanced());
  o.push_back(
      option(
          "-keep-carved-nodes", ValueType::Flag, "",
          "Keep street nodes whose pixel a seam removes (moved onto the seam edge) instead of deleting them.")
          .isAdvanced());
  o.push_back(
      option("-keep-outside-bbox", ValueType::Flag, "",
             "Keep street nodes outside the file's download bounds (cleaning removes them by default).")
          .isAdvanced());
  o.push_back(
      option("-straighten", ValueType::Flag, "", "Re-straighten ways that were straight in the original."));
  o.push_back(option("-straight-tolerance", ValueType::Real, "<metres>",
                     "A way is straight when its interior nodes are within this distance of its chord.")
                  .byDefault(app::numberText(d.post.straightTolerance))
                  .withUnit("m")
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(
      option("-rotate", ValueType::String, "<degrees|auto>",
             "Rotation trick: rotate counter-clockwise before carving and back after; 'auto' aligns the "
             "dominant street bearing with the axes.")
          .byDefault("0"));
  o.push_back(
      option("-no-full-map", ValueType::Flag, "", "Do not deform the full street map (full_streets empty).")
          .isAdvanced());
  o.push_back(option("-importance-layer", ValueType::String, "<name>",
                     "Layer of a vector importance file; default every layer with the importance field.")
                  .isAdvanced());
  o.push_back(option("-importance-field", ValueType::String, "<name>",
                     "Importance field of a vector importance file.")
                  .byDefault("importance")
                  .isAdvanced());
  o.push_back(option("-t_srs", ValueType::String, "<crs>",
                     "Output CRS, projected in metres; default the UTM zone of the OSM data.")
                  .withRole(Role::Crs));
  o.push_back(option("-timings", ValueType::Flag, "", "Print the time of each step (thesis Table 2 names).")
                  .isAdvanced());
  for (const app::OptionSpec& v : app::vectorOutputOptions()) o.push_back(v);
  s.examples = {"urbanvec shrink -shf 0.15 -seams 100 100 city.osm.pbf places.osmi small.gpkg",
                "urbanvec shrink -shf 0.2 -seams 150 150 -rotate auto -straighten eixample.osm eixample.osmi "
                "small.gpkg"};
  return s;
}

std::string styleFor(const std::string& layer) {
  if (layer == "streets")
    return io::categorizedQml("kind", io::SymbolKind::Line,
                              {{"important", "important street", "200,30,30,255"},
                               {"selected", "selected street", "60,60,60,255"},
                               {"connector", "cluster connector", "30,90,200,255"},
                               {"dead_end_connector", "dead-end connector", "30,160,60,255"}},
                              0.6);
  if (layer == "full_streets") return io::singleSymbolQml(io::SymbolKind::Line, "170,170,170,255", 0.2);
  if (layer == "places") return io::singleSymbolQml(io::SymbolKind::Fill, "240,160,40,200", 0.26);
  if (layer == "place_lines") return io::singleSymbolQml(io::SymbolKind::Line, "240,160,40,255", 0.8);
  if (layer == "place_points") return io::singleSymbolQml(io::SymbolKind::Marker, "240,160,40,255");
  if (layer == "seams") return io::singleSymbolQml(io::SymbolKind::Line, "220,0,220,90", 0.1);
  return {};
}

Layer streetLayer(const std::string& name, const std::vector<shrink::ShrunkWay>& ways) {
  Layer layer;
  layer.name = name;
  layer.geometryType = GeometryType::LineString;
  layer.fields = {{"osm_id", FieldType::Integer},
                  {"highway", FieldType::String},
                  {"name", FieldType::String},
                  {"importance", FieldType::Real},
                  {"kind", FieldType::String}};
  for (const shrink::ShrunkWay& w : ways) {
    Feature f;
    f.geometry = w.line;
    f.values = {static_cast<std::int64_t>(w.osmId), w.highway,
                w.name.empty() ? FieldValue{} : FieldValue{w.name}, w.importance, w.kind};
    layer.features.push_back(std::move(f));
  }
  return layer;
}

void run(const app::ParsedArgs& args, app::CommandContext& ctx) {
  const std::string osmPath = args.positionals()[0];
  const std::string importancePath = args.positionals()[1];
  const std::string outputPath = args.positionals()[2];
  shrink::ShrinkOptions options;
  options.selection.shrinkFactor = args.real("-shf");
  // The default arrives as one "v h" text, a command-line value as two: split every value on blanks.
  std::vector<std::string> seams;
  for (const std::string& v : args.values("-seams")) {
    std::istringstream words(v);
    for (std::string word; words >> word;) seams.push_back(word);
  }
  if (seams.size() < 2) throw invalidOption("-seams needs two counts: <vertical> <horizontal>");
  auto seamCount = [&](const std::string& text) {
    try {
      size_t used = 0;
      const long v = std::stol(text, &used);
      if (used == text.size() && v >= 0 && v <= 1000000) return static_cast<int>(v);
    } catch (const std::exception&) {
    }
    throw invalidOption("-seams: '" + text + "' is not a seam count (a whole number >= 0)");
  };
  options.carving.verticalSeams = seamCount(seams.at(seams.size() - 2));
  options.carving.horizontalSeams = seamCount(seams.at(seams.size() - 1));
  options.carving.imageSize = static_cast<int>(args.integer("-image-size"));
  options.carving.threads = static_cast<int>(args.integer("-threads"));
  options.connection.mDegree = static_cast<int>(args.integer("-m-degree"));
  options.connection.impDistBalance = args.real("-imp-dist-balance");
  options.carving.grayDistBalance = args.real("-gray-dist-balance");
  options.selection.proximityThreshold = args.real("-prox-str-threshold");
  for (const std::string& kv : args.values("-highway-weight")) {
    const size_t eq = kv.find('=');
    char* end = nullptr;
    const double w = eq == std::string::npos ? NAN : std::strtod(kv.c_str() + eq + 1, &end);
    if (eq == std::string::npos || eq == 0 || !end || *end != '\0' || !(w >= 0.0))
      throw invalidOption("-highway-weight '" + kv + "': expected <highway>=<weight>, weight >= 0");
    options.selection.highwayWeights[kv.substr(0, eq)] = w;
  }
  options.connection.removeUnimportantClusters = !args.flag("-keep-unimportant-clusters");
  options.carving.order =
      args.str("-seam-order") == "blocks" ? shrink::SeamOrder::Blocks : shrink::SeamOrder::Interleaved;
  options.carving.landmarkFreeze = args.str("-freeze-landmarks") == "nodes"
                                       ? shrink::LandmarkFreeze::Nodes
                                       : shrink::LandmarkFreeze::BoundingBox;
  options.carving.freezeAllStreetNodes = args.flag("-freeze-all-street-nodes");
  options.carving.keepCarvedNodes = args.flag("-keep-carved-nodes");
  if (args.flag("-translate-nodes-only")) options.carving.densifySpacing = 0.0;
  options.cleaning.removeOutsideBounds = !args.flag("-keep-outside-bbox");
  options.post.straighten = args.flag("-straighten");
  options.post.straightTolerance = args.real("-straight-tolerance");
  options.post.fullMap = !args.flag("-no-full-map");
  const std::string rotate = args.str("-rotate");
  if (rotate == "auto") {
    options.post.autoRotate = true;
  } else {
    char* end = nullptr;
    options.post.rotationDegrees = std::strtod(rotate.c_str(), &end);
    if (end == rotate.c_str() || *end != '\0' || !std::isfinite(options.post.rotationDegrees))
      throw invalidOption("-rotate '" + rotate + "': expected an angle in degrees or 'auto'");
  }
  shrink::validate(options);

  io::VectorWriteOptions write;
  if (args.has("-of")) write.format = args.str("-of");
  write.layerCreationOptions = args.values("-lco");
  write.datasetCreationOptions = args.values("-dsco");
  for (const std::string& layer : spec().outputLayers)
    if (std::string qml = styleFor(layer); !qml.empty()) write.layerStylesQml[layer] = qml;
  io::OutputRules rules;
  rules.overwrite = args.flag("-overwrite");
  rules.inputs = ctx.inputs;
  io::VectorOutput output(outputPath, write, spec().outputLayers, rules);

  const auto start = std::chrono::steady_clock::now();
  app::ShrinkSourceOptions sourceOptions;
  if (args.given("-t_srs")) sourceOptions.targetCrs = args.str("-t_srs");
  if (args.given("-importance-layer")) sourceOptions.importanceLayer = args.str("-importance-layer");
  sourceOptions.importanceField = args.str("-importance-field");
  reportProgress(ctx.progress, 0.0, "reading");
  const app::ShrinkSource source = app::readShrinkSource(osmPath, importancePath, sourceOptions, ctx.warn);
  const double readSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const shrink::ShrinkResult result =
      shrink::shrinkCity(source.input, options, subProgress(ctx.progress, 0.1, 0.9));
  for (const std::string& w : result.warnings) ctx.warn(w);

  std::vector<Layer> layers;
  layers.push_back(streetLayer("streets", result.streets));
  Layer polygons, lines, points;
  polygons.name = "places", polygons.geometryType = GeometryType::Polygon;
  lines.name = "place_lines", lines.geometryType = GeometryType::LineString;
  points.name = "place_points", points.geometryType = GeometryType::Point;
  for (Layer* l : {&polygons, &lines, &points})
    l->fields = {{"place_id", FieldType::String},
                 {"osm_id", FieldType::Integer},
                 {"name", FieldType::String},
                 {"appear_w", FieldType::Real}};
  for (const shrink::ShrunkPlace& p : result.places) {
    Feature f;
    f.geometry = p.geometry;
    f.values = {p.placeId, static_cast<std::int64_t>(p.osmId),
                p.name.empty() ? FieldValue{} : FieldValue{p.name}, p.appearW};
    Layer& target = std::holds_alternative<Polygon>(p.geometry) ? polygons
                    : std::holds_alternative<Vec2>(p.geometry)  ? points
                                                                : lines;
    target.features.push_back(std::move(f));
  }
  layers.push_back(std::move(polygons));
  layers.push_back(std::move(lines));
  layers.push_back(std::move(points));
  layers.push_back(streetLayer("full_streets", result.fullStreets));
  Layer seamLayer;
  seamLayer.name = "seams";
  seamLayer.geometryType = GeometryType::LineString;
  seamLayer.fields = {{"seam", FieldType::Integer}, {"direction", FieldType::String}};
  for (const shrink::SeamLine& sl : result.seams)
    seamLayer.features.push_back(
        {sl.line,
         {static_cast<std::int64_t>(sl.number), std::string(sl.vertical ? "vertical" : "horizontal")}});
  layers.push_back(std::move(seamLayer));
  Layer report;
  report.name = "shrink_report";
  report.geometryType = GeometryType::None;
  Feature row;
  for (const auto& [name, value] : result.report.values) {
    report.fields.push_back({name, FieldType::Real});
    row.values.emplace_back(value);
  }
  report.fields.push_back({"ids_missing", FieldType::Integer});
  row.values.emplace_back(static_cast<std::int64_t>(source.missingIds));
  std::string notes;
  for (const std::string& n : result.report.notes) notes += (notes.empty() ? "" : "; ") + n;
  report.fields.push_back({"notes", FieldType::String});
  row.values.emplace_back(notes.empty() ? FieldValue{} : FieldValue{notes});
  report.features.push_back(std::move(row));
  layers.push_back(std::move(report));

  reportProgress(ctx.progress, 0.95, "writing");
  output.write(layers, source.crsWkt);
  output.commit(ctx.progress);
  if (!ctx.quiet && ctx.out) {
    const shrink::ShrinkReport& r = result.report;
    std::ostringstream line;
    line << "shrink: " << result.streets.size() << " skeleton streets of " << r.value("streets_clean") << ", "
         << result.places.size() << " landmark elements; image " << r.value("image_width") << "x"
         << r.value("image_height") << " -> " << r.value("final_width") << "x" << r.value("final_height")
         << "; area kept " << r.value("area_kept") << " (ideal " << r.value("area_ideal")
         << "); landmark deviation " << r.value("landmark_max_deviation") << " m; new crossings "
         << r.value("new_crossings") << "; new dead ends " << r.value("new_dead_ends") << "\n";
    *ctx.out << line.str();
    if (args.flag("-timings")) {
      *ctx.out << "timing read " << readSeconds << " s\n";
      double total = 0.0;
      for (const shrink::StepTime& t : result.timings) {
        *ctx.out << "timing " << t.step << " " << t.seconds << " s\n";
        total += t.seconds;
      }
      *ctx.out << "timing pipeline " << total << " s\n";
    }
  }
}

const bool registered = app::registerCommand(spec(), run);

}  // namespace
}  // namespace urbanvec
