#include "urbanvec/vectorize/roads/road_output.hpp"

#include <algorithm>
#include <cstdint>
#include <tuple>

#include "urbanvec/core/geos.hpp"
#include "urbanvec/core/memory.hpp"
#include "urbanvec/core/planar_graph.hpp"
#include "urbanvec/vectorize/roads/road_graph_build.hpp"

namespace urbanvec::vectorize {

std::vector<LineString> simplifyTogether(const std::vector<LineString>& lines, double tolerance) {
  geos::Context ctx;
  geos::GeomPtr all = ctx.multiLineString(lines);
  geos::GeomPtr simple =
      ctx.own(GEOSTopologyPreserveSimplify_r(ctx.handle(), all.get(), tolerance), "road simplification");
  const int n = GEOSGetNumGeometries_r(ctx.handle(), simple.get());
  if (n != static_cast<int>(lines.size())) return lines;  // GEOS changed the structure: keep the originals
  std::vector<LineString> out;
  out.reserve(lines.size());
  for (int k = 0; k < n; ++k) {
    LineString l = ctx.coordinates(GEOSGetGeometryN_r(ctx.handle(), simple.get(), k));
    // Exact end nodes, so segments keep meeting at the very same coordinates.
    if (l.size() < 2) l = {lines[k].front(), lines[k].back()};
    l.front() = lines[k].front();
    l.back() = lines[k].back();
    out.push_back(std::move(l));
  }
  return out;
}

namespace {

const char* className(NodeType t) {
  switch (t) {
    case NodeType::Primary:
      return "primary";
    case NodeType::Secondary:
      return "secondary";
    case NodeType::Perimeter:
      return "perimeter";
  }
  return "secondary";
}

}  // namespace

RoadNetwork buildRoadNetwork(const RoadGraph& g) {
  RoadNetwork net;
  const size_t n = g.nodes.size();
  std::vector<std::int32_t> outId(n, -1);
  auto addEnd = [&](int i, NetworkNodeKind kind) {
    outId[i] = static_cast<std::int32_t>(net.nodes.size());
    net.nodes.push_back({g.nodes[i].p, kind, g.degree(i)});
  };
  for (size_t i = 0; i < n; ++i) {
    const RoadNode& v = g.nodes[i];
    if (!v.alive) continue;
    const int deg = g.degree(static_cast<int>(i));
    if (deg >= 3)
      addEnd(static_cast<int>(i), NetworkNodeKind::Intersection);
    else if (deg <= 1)
      addEnd(static_cast<int>(i), NetworkNodeKind::DeadEnd);
    else if (linkType(g, static_cast<int>(i), v.links[0]) != linkType(g, static_cast<int>(i), v.links[1]))
      addEnd(static_cast<int>(i), NetworkNodeKind::Connection);
  }
  // Segments are the chains of the road graph between ends (core/planar_graph line merging), in the
  // order a walk from every end would find them: by the (node, link slot) they leave first, then the
  // closed rings of degree-2 nodes by their lowest node.
  PlanarGraph planar;
  for (const RoadNode& v : g.nodes) planar.addNode(v.p);
  for (size_t i = 0; i < n; ++i)
    for (int j : g.nodes[i].links)
      if (static_cast<int>(i) < j) planar.addEdge(static_cast<int>(i), j);
  auto slotOf = [&](int from, int to) {
    const auto& links = g.nodes[from].links;
    return static_cast<int>(std::find(links.begin(), links.end(), to) - links.begin());
  };
  struct Walk {
    std::pair<int, int> key;  ///< (start node, link slot); rings: (lowest node, 0) after every path
    bool ring = false;
    std::vector<int> nodes;
  };
  std::vector<Walk> walks;
  const auto kept = [&](int i) { return outId[i] >= 0; };
  for (const std::vector<int>& chain : planar.chains(kept)) {
    Walk w;
    w.nodes = planar.chainNodes(chain, kept);
    const int first = w.nodes.front(), last = w.nodes.back();
    w.ring = outId[first] < 0;
    if (w.ring) {
      // A ring starts at its lowest node, towards that node's first link.
      w.nodes.pop_back();
      const auto low = std::min_element(w.nodes.begin(), w.nodes.end());
      std::rotate(w.nodes.begin(), low, w.nodes.end());
      if (w.nodes.size() > 1 && w.nodes[1] != g.nodes[w.nodes[0]].links[0])
        std::reverse(w.nodes.begin() + 1, w.nodes.end());
      w.nodes.push_back(w.nodes.front());
      w.key = {w.nodes.front(), 0};
    } else {
      const std::pair<int, int> forward{first, slotOf(first, w.nodes[1])};
      const std::pair<int, int> backward{last, slotOf(last, w.nodes[w.nodes.size() - 2])};
      if (backward < forward) std::reverse(w.nodes.begin(), w.nodes.end());
      w.key = std::min(forward, backward);
    }
    walks.push_back(std::move(w));
  }
  std::sort(walks.begin(), walks.end(),
            [](const Walk& a, const Walk& b) { return std::tie(a.ring, a.key) < std::tie(b.ring, b.key); });
  for (const Walk& w : walks) {
    const int start = w.nodes.front();
    if (w.ring) addEnd(start, NetworkNodeKind::Road);
    NetworkSegment seg;
    for (int i : w.nodes) seg.points.push_back(g.nodes[i].p);
    const NodeType cls = linkType(g, start, w.nodes[1]);
    seg.roadClass = cls == NodeType::Primary     ? RoadClass::Primary
                    : cls == NodeType::Perimeter ? RoadClass::Perimeter
                                                 : RoadClass::Secondary;
    seg.fromNode = outId[start];
    seg.toNode = outId[w.nodes.back()];
    net.segments.push_back(std::move(seg));
  }
  return net;
}

void simplifyRoadNetwork(RoadNetwork& net, double tolerance) {
  if (!(tolerance > 0) || net.segments.empty()) return;
  std::vector<LineString> lines;
  lines.reserve(net.segments.size());
  // Moved, not copied: simplifyTogether returns either the simplified lines or these.
  for (NetworkSegment& s : net.segments) lines.push_back(std::move(s.points));
  lines = simplifyTogether(lines, tolerance);
  for (size_t k = 0; k < lines.size(); ++k) net.segments[k].points = std::move(lines[k]);
  releaseFreedMemory();  // the simplifier's index: ~400 bytes per road vertex
}

std::vector<Layer> roadLayers(const RoadNetwork& net, const GridSpec& spec) {
  Layer roads;
  roads.name = "roads";
  roads.geometryType = GeometryType::LineString;
  roads.fields = {{"road_id", FieldType::Integer},
                  {"road_class", FieldType::String},
                  {"from_node", FieldType::Integer},
                  {"to_node", FieldType::Integer},
                  {"length", FieldType::Real}};
  Layer nodes;
  nodes.name = "road_nodes";
  nodes.geometryType = GeometryType::Point;
  nodes.fields = {
      {"node_id", FieldType::Integer}, {"kind", FieldType::String}, {"degree", FieldType::Integer}};
  static const char* const kinds[] = {"intersection", "dead_end", "connection", "road"};
  static const char* const classes[] = {"primary", "secondary", "perimeter"};
  for (size_t k = 0; k < net.nodes.size(); ++k) {
    Feature f;
    f.geometry = toWorld(net.nodes[k].position, spec);
    f.values = {static_cast<std::int64_t>(k) + 1, std::string(kinds[static_cast<int>(net.nodes[k].kind)]),
                static_cast<std::int64_t>(net.nodes[k].degree)};
    nodes.features.push_back(std::move(f));
  }
  for (size_t k = 0; k < net.segments.size(); ++k) {
    const NetworkSegment& s = net.segments[k];
    LineString world;
    world.reserve(s.points.size());
    for (const Vec2& p : s.points) world.push_back(toWorld(p, spec));
    Feature f;
    f.values = {static_cast<std::int64_t>(k) + 1, std::string(classes[static_cast<int>(s.roadClass)]),
                static_cast<std::int64_t>(s.fromNode) + 1, static_cast<std::int64_t>(s.toNode) + 1,
                length(world)};
    f.geometry = std::move(world);
    roads.features.push_back(std::move(f));
  }
  return {roads, nodes};
}

SimulatedCity simulatedCity(const Grid<std::uint8_t>& cells, const std::vector<SimBlock>& blocks,
                            const std::vector<SimParcel>& parcels) {
  SimulatedCity city;
  city.grid = Grid<LandUse>(cells.width, cells.height, LandUse::Unused);
  city.grid.frameDx = cells.frameDx;  // a window keeps the whole raster's frame (issue 22)
  city.grid.frameDy = cells.frameDy;
  for (size_t i = 0; i < cells.cells.size(); ++i)
    city.grid.cells[i] =
        cells.cells[i] < kLandUseClassCount ? static_cast<LandUse>(cells.cells[i]) : LandUse::Unused;
  auto cellOf = [&](std::int32_t i) { return GridCell{i % cells.width, i / cells.width}; };
  for (const SimBlock& b : blocks) {
    SimulatedBlock sb;
    sb.id = b.id;
    sb.internal = b.internal;
    sb.centre = b.center;
    for (std::int32_t i : b.patches) sb.cells.push_back(cellOf(i));
    for (int p : b.parcels) sb.parcelIds.push_back(parcels[p].id);
    city.blocks.push_back(std::move(sb));
  }
  for (const SimParcel& p : parcels) {
    SimulatedParcel sp;
    sp.id = p.id;
    sp.landUse = p.use;
    sp.centre = p.center;
    for (std::int32_t i : p.patches) sp.cells.push_back(cellOf(i));
    city.parcels.push_back(std::move(sp));
  }
  return city;
}

std::vector<Layer> rawGraphLayers(const RoadGraph& g, const GridSpec& spec, const std::string& prefix) {
  Layer links;
  links.name = prefix + "links";
  links.geometryType = GeometryType::LineString;
  links.fields = {{"link_id", FieldType::Integer},
                  {"from_node", FieldType::Integer},
                  {"to_node", FieldType::Integer},
                  {"link_class", FieldType::String}};
  Layer nodes;
  nodes.name = prefix + "nodes";
  nodes.geometryType = GeometryType::Point;
  nodes.fields = {{"node_id", FieldType::Integer},
                  {"node_type", FieldType::String},
                  {"degree", FieldType::Integer},
                  {"intersection", FieldType::Integer}};
  for (size_t i = 0; i < g.nodes.size(); ++i) {
    const RoadNode& v = g.nodes[i];
    if (!v.alive) continue;
    Feature f;
    f.geometry = toWorld(v.p, spec);
    f.values = {static_cast<std::int64_t>(i), std::string(className(v.type)),
                static_cast<std::int64_t>(v.links.size()), static_cast<std::int64_t>(v.intersection)};
    nodes.features.push_back(std::move(f));
    for (int j : v.links) {
      if (j < static_cast<int>(i)) continue;
      Feature l;
      l.geometry = LineString{toWorld(v.p, spec), toWorld(g.nodes[j].p, spec)};
      l.values = {static_cast<std::int64_t>(links.features.size()) + 1, static_cast<std::int64_t>(i),
                  static_cast<std::int64_t>(j), std::string(className(linkType(g, static_cast<int>(i), j)))};
      links.features.push_back(std::move(l));
    }
  }
  return {links, nodes};
}

}  // namespace urbanvec::vectorize
