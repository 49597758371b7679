// `urbanvec street-metrics`: orientation entropy and order, node-degree shares, circuity, median edge
// length and intersection density of any line layer (issue 18 "Street-network metrics").
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

#include "urbanvec/app/command.hpp"
#include "urbanvec/app/street_layers.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/io/atomic_output.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/vector_io.hpp"
#include "urbanvec/streets/polygon_index.hpp"
#include "urbanvec/streets/street_metrics.hpp"

namespace urbanvec {
namespace {

using app::option;
using app::Role;
using app::ValueType;

app::CommandSpec spec() {
  const streets::StreetMetricOptions d;
  app::CommandSpec s;
  s.name = "street-metrics";
  s.summary =
      "Measures a street network: orientation entropy and order, node degrees, circuity, edge length.";
  s.description =
      "Nodes the lines of a layer (every crossing becomes a node, GEOS), merges edges through degree-2 nodes "
      "into simplified edges, and prints Boeing's indicators as OSMnx 1.2.3 computes them: "
      "orientation_entropy (nats, over 36 bins of 10 degrees centred on 0, 10, ... degrees, both bearings "
      "of each simplified edge's straight line), orientation_order 1 - ((H - ln 4) / (ln 36 - ln 4))^2, "
      "share_deadend / share_3way / share_4way of the nodes, average_degree, circuity (sum of edge lengths "
      "/ sum of end-to-end distances), median_edge_length (m), intersection_density (nodes of degree >= 2 "
      "per km^2), edges and nodes. With -area only nodes inside the polygons and edges with both ends "
      "inside count (degrees stay those of the whole network) and the density uses the polygons' area; "
      "else the convex hull of the nodes. A geographic layer is measured in its UTM zone. The optional "
      "output holds the nodes with their degree. See docs/streets.md.";
  s.group = "Streets";
  s.positionals = {
      {"input", "Vector dataset with a line layer (streets, OSM lines, vectorize roads).", Role::InputVector},
      {"output", "Vector file to create with the nodes (layer street_nodes, field degree).",
       Role::OutputVector, true}};
  s.outputLayers = {"street_nodes"};
  auto& o = s.options;
  o.push_back(
      option("-layer", ValueType::String, "<name>", "Line layer to measure; default the first layer."));
  o.push_back(option(
      "-where", ValueType::String, "<expression>",
      "OGR SQL attribute filter choosing the streets, e.g. \"highway IN ('primary','residential')\"."));
  o.push_back(
      option("-area", ValueType::String, "<file>",
             "Polygon layer (first layer) the measures are restricted to; its area gives the density.")
          .withRole(Role::InputVector));
  o.push_back(option("-json", ValueType::String, "<file>", "Also writes the figures as JSON to this file.")
                  .withRole(Role::OutputFile));
  o.push_back(option("-min-edge-length", ValueType::Real, "<metres>",
                     "Edges shorter than this are left out of the orientation histogram (OSMnx min_length).")
                  .byDefault(app::numberText(d.minEdgeLength))
                  .withUnit("m")
                  .atLeast(0));
  o.push_back(
      option("-t_srs", ValueType::String, "<crs>",
             "Measure in this projected CRS in metres; default the layer's (UTM for a geographic one).")
          .withRole(Role::Crs));
  for (const app::OptionSpec& v : app::vectorOutputOptions()) o.push_back(v);
  s.examples = {
      "urbanvec street-metrics streets.gpkg",
      "urbanvec street-metrics -layer lines -where \"highway IS NOT NULL\" -json m.json monaco.osm.pbf",
      "urbanvec street-metrics -area interior.gpkg -json m.json streets.gpkg nodes.gpkg"};
  return s;
}

std::string jsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream s;
  s << std::setprecision(10) << v;
  return s.str();
}

void run(const app::ParsedArgs& args, app::CommandContext& ctx) {
  const std::string input = args.positionals()[0];
  const bool hasOutput = args.positionals().size() > 1;
  streets::StreetMetricOptions options;
  options.minEdgeLength = args.real("-min-edge-length");

  std::optional<io::VectorOutput> output;
  if (hasOutput) {
    io::VectorWriteOptions write;
    if (args.has("-of")) write.format = args.str("-of");
    write.layerCreationOptions = args.values("-lco");
    write.datasetCreationOptions = args.values("-dsco");
    output.emplace(args.positionals()[1], write, std::vector<std::string>{"street_nodes"},
                   io::OutputRules{args.flag("-overwrite"), false, {}, ctx.inputs});
  }
  std::optional<io::AtomicOutput> json;
  if (args.given("-json"))
    json.emplace(args.str("-json"), io::OutputRules{args.flag("-overwrite"), false, {}, ctx.inputs});

  std::string target;
  if (args.given("-t_srs")) {
    target = io::crsToWkt(args.str("-t_srs"), "-t_srs");
    if (!io::isProjectedInMetres(target))
      throw invalidOption("-t_srs " + args.str("-t_srs") + " is not a projected CRS in metres");
  }
  app::LayerRequest request{input, args.given("-layer") ? args.str("-layer") : "",
                            args.given("-where") ? args.str("-where") : "", "input"};
  app::LoadedLayer loaded = app::readLayer(request, target);
  if (!loaded.crsWkt.empty() && !io::isProjectedInMetres(loaded.crsWkt))
    throw invalidInput("layer '" + loaded.layer.name + "' of '" + input + "' is in " +
                       io::crsShortName(loaded.crsWkt) + ", not a projected CRS in metres; give -t_srs");
  if (loaded.crsWkt.empty())
    ctx.warn("layer '" + loaded.layer.name + "' has no CRS: lengths are in its coordinate units");
  const std::vector<LineString> lines = app::linesOf(loaded.layer);
  if (lines.empty())
    throw invalidInput("layer '" + loaded.layer.name + "' of '" + input + "' holds no line" +
                       (request.where.empty() ? "" : " where " + request.where));
  std::optional<MultiPolygon> area;
  if (args.given("-area")) {
    app::LoadedLayer a = app::readLayer({args.str("-area"), "", "", "-area"}, loaded.crsWkt, false);
    area = app::polygonsOf(a.layer, "-area '" + args.str("-area") + "'");
  }

  reportProgress(ctx.progress, 0.0, "noding");
  const streets::SimplifiedNetwork net = streets::simplifyNetwork(lines, options);
  reportProgress(ctx.progress, 0.6, "measuring");
  const streets::StreetMetrics m = streets::measureNetwork(net, options, area);

  const std::vector<std::pair<std::string, double>> figures = {
      {"orientation_entropy", m.orientationEntropy},
      {"orientation_order", m.orientationOrder},
      {"share_deadend", m.shareDeadEnd},
      {"share_3way", m.share3Way},
      {"share_4way", m.share4Way},
      {"average_degree", m.averageDegree},
      {"circuity", m.circuity},
      {"median_edge_length", m.medianEdgeLength},
      {"intersection_density", m.intersectionDensity},
      {"edges", static_cast<double>(m.edges)},
      {"nodes", static_cast<double>(m.nodes)}};

  if (output) {
    Layer nodes;
    nodes.name = "street_nodes";
    nodes.geometryType = GeometryType::Point;
    nodes.fields = {{"node_id", FieldType::Integer}, {"degree", FieldType::Integer}};
    std::optional<streets::PolygonIndex> inside;
    if (area) inside.emplace(*area);
    std::int64_t id = 0;
    for (int n : net.nodes) {
      const Vec2 p = net.graph.node(n).p;
      if (inside && !inside->contains(p)) continue;
      nodes.features.push_back({p, {++id, static_cast<std::int64_t>(net.graph.degree(n))}});
    }
    output->write({nodes}, loaded.crsWkt);
  }
  reportProgress(ctx.progress, 1.0, "done");
  if (json) {
    {
      std::ofstream out(json->tempPath(), std::ios::binary);
      out << "{\n";
      for (std::size_t i = 0; i < figures.size(); ++i)
        out << "  \"" << figures[i].first << "\": " << jsonNumber(figures[i].second)
            << (i + 1 < figures.size() ? ",\n" : "\n");
      out << "}\n";
      out.flush();
      if (!out) throw ioError("cannot write -json output '" + json->path() + "'");
    }
    json->commit(ctx.progress);
  }
  if (output) output->commit(ctx.progress);
  std::fflush(stdout);
  if (!ctx.quiet && ctx.out)
    for (const auto& [key, value] : figures) *ctx.out << key << ": " << jsonNumber(value) << "\n";
}

const bool registered = app::registerCommand(spec(), run);

}  // namespace
}  // namespace urbanvec
