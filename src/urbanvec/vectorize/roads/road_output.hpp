// Conversion of the road graph after B6 to the part 1 -> part 2 interface (road_network.hpp) and to
// the `roads` and `road_nodes` layers of CONVENTIONS.md ("Vector output of vectorize"): one
// LineString per segment between intersections, dead ends or road-class changes, so segments meet
// exactly at shared nodes.
#pragma once

#include <string>
#include <vector>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/layer.hpp"
#include "urbanvec/vectorize/roads/road_graph.hpp"
#include "urbanvec/vectorize/roads/road_network.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

/// GEOS topology-preserving simplification of all lines at once: ends kept exactly, no new crossings
/// among them. Returns the lines unchanged when GEOS changes their number.
std::vector<LineString> simplifyTogether(const std::vector<LineString>& lines, double tolerance);

/// The segments and segment-end nodes of the graph, internal frame. A node ends segments when its
/// degree is not 2 or its two links carry different classes; rings of degree-2 nodes start at their
/// lowest node (kind Road).
RoadNetwork buildRoadNetwork(const RoadGraph& graph);

/// The segments simplified together (pw) with GEOS's topology-preserving simplifier, which keeps their
/// end nodes and adds no crossings. Does nothing for tolerance <= 0.
void simplifyRoadNetwork(RoadNetwork& network, double tolerance);

/// `roads` (road_id, road_class, from_node, to_node, length in CRS units) and `road_nodes` (node_id,
/// kind, degree) in world coordinates. Ids are 1-based indices into the network's vectors.
std::vector<Layer> roadLayers(const RoadNetwork& network, const GridSpec& spec);

/// The raster-side data of part 2 (road_network.hpp SimulatedCity) from A2-A5 results.
SimulatedCity simulatedCity(const Grid<std::uint8_t>& cells, const std::vector<SimBlock>& blocks,
                            const std::vector<SimParcel>& parcels);

/// Every link as its own two-point LineString (link_id, from_node, to_node, link_class) plus every
/// node (node_id, node_type, degree, intersection): the raw graph after a stage, for -debug-stages.
std::vector<Layer> rawGraphLayers(const RoadGraph& graph, const GridSpec& spec, const std::string& prefix);

}  // namespace urbanvec::vectorize
