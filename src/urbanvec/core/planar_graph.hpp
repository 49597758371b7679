// One planar graph for every module that works on street networks and their faces (issue 16): nodes
// with positions, undirected edges carrying polylines, a rotation system (each node's edges in
// clockwise order) and the queries the modules share — noding of a line soup, degrees, half-edge face
// walks, connected components, A* shortest paths and line merging through degree-2 nodes.
//
// Guarantees: every query is deterministic and depends only on node and edge ids and their order
// (no hashing of pointers, no unordered iteration), so callers get the same faces, chains and paths
// on every run. Coordinates are whatever frame the caller uses (metres or cells); y points up.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec {

class PlanarGraph {
 public:
  struct Node {
    Vec2 p;
    /// Incident edge ids; in rotation order (clockwise from north) after sortRotations() or
    /// setRotation().
    std::vector<int> edges;
  };
  struct Edge {
    int a = -1;
    int b = -1;
    /// From node a's position to node b's, both included (two points for a straight edge).
    LineString line;
  };

  /// Half-edges: 2e runs along edge e from a to b, 2e + 1 from b to a.
  static int halfEdge(int edge, bool reversed) { return 2 * edge + (reversed ? 1 : 0); }
  static int edgeOf(int halfEdge) { return halfEdge / 2; }
  int origin(int halfEdge) const;
  int target(int halfEdge) const;

  struct Face {
    std::vector<int> halfEdges;  ///< in walk order, the face on their left
    /// Twice the signed area enclosed by the walk along the edges' polylines: positive for a bounded
    /// face (counter-clockwise), negative for a component's outer face, about zero around a tree.
    double twiceSignedArea = 0.0;
  };

  int addNode(const Vec2& p);
  /// Adds an edge a-b (a != b); an empty line means the straight segment between the nodes.
  int addEdge(int a, int b, LineString line = {});

  std::size_t nodeCount() const { return nodes_.size(); }
  std::size_t edgeCount() const { return edges_.size(); }
  const Node& node(int n) const { return nodes_[static_cast<std::size_t>(n)]; }
  const Edge& edge(int e) const { return edges_[static_cast<std::size_t>(e)]; }
  int degree(int n) const { return static_cast<int>(node(n).edges.size()); }
  /// The end of edge e that is not n.
  int otherEnd(int e, int n) const { return edge(e).a == n ? edge(e).b : edge(e).a; }

  /// Orders each node's edges clockwise from due north by the direction in which they leave the node
  /// (their polyline's first segment from that end); ties keep the lower edge id first.
  void sortRotations();
  /// Sets a node's rotation explicitly (the same edges, in the caller's clockwise order).
  void setRotation(int n, std::vector<int> edgesClockwise);

  /// Every face of the embedding, by the leftmost-turn walk: from half-edge u->v the walk continues
  /// with the edge that follows v->u clockwise around v. Faces come in the order of their first
  /// half-edge, taking nodes by id and each node's outgoing half-edges in rotation order — so for a
  /// component, the first face found is the one left of its lowest node's first edge.
  std::vector<Face> faces() const;
  /// The faces with each connected component's outline first, as the cadastre circuits need it
  /// ("outline is entry 0"): per component in order, its outer face — the face through its lowest
  /// node (least y, then x) with the least signed area — then every other face in faces() order. The
  /// walk closes on half-edges, so an outline through a cut vertex (a figure eight) stays one face.
  std::vector<Face> facesOutlineFirst() const;
  /// The bounded faces (twiceSignedArea > minTwiceArea), in the order faces() gives them.
  std::vector<Face> boundedFaces(double minTwiceArea = 1e-12) const;
  /// Each face's nodes, one per half-edge origin.
  std::vector<int> faceNodes(const Face& face) const;
  /// The face's outline: its half-edges' polylines joined (closed ring).
  Ring faceRing(const Face& face) const;

  /// Component id per node (0, 1, ... in order of each component's lowest node id); isolated nodes are
  /// components of their own.
  std::vector<int> components(int* count = nullptr) const;

  /// The cheapest path of edges from `from` to `to` (A*): `cost(edge)` >= 0; `heuristic(node)` a
  /// lower bound of the cost from node to `to` (default 0: Dijkstra). Ties go to the lower node id.
  /// Empty optional when `to` cannot be reached; an empty path when from == to.
  std::optional<std::vector<int>> shortestPath(int from, int to, const std::function<double(int)>& cost,
                                               const std::function<double(int)>& heuristic = {}) const;
  /// Straight-line length of every edge's polyline, the usual A* cost; pair with euclideanHeuristic.
  double edgeLength(int e) const;
  std::function<double(int)> euclideanHeuristic(int to) const;

  /// Line merging: maximal chains of edges through nodes of degree 2 (and not in `keepNode`, which
  /// marks nodes a chain must end at, e.g. a change of road class). A cycle of degree-2 nodes is one
  /// chain starting at its lowest edge. Chains come in order of their lowest edge id.
  std::vector<std::vector<int>> chains(const std::function<bool(int)>& keepNode = {}) const;
  /// The nodes along a chain (one more than its edges), from its first edge's free end. A chain of two
  /// edges between the same two nodes (a ring off one node) starts at the node the chain ends at (degree
  /// other than 2, or in `keepNode`: pass the same `keepNode` as to chains()); a ring of degree-2 nodes
  /// starts at its first edge's first node, as chains() walks it.
  std::vector<int> chainNodes(const std::vector<int>& chain,
                              const std::function<bool(int)>& keepNode = {}) const;
  /// The polyline of a chain, from the first of its chainNodes() (same `keepNode`).
  LineString chainLine(const std::vector<int>& chain, const std::function<bool(int)>& keepNode = {}) const;

  /// Nodes a line soup: lines are cut where they cross or touch (GEOS), coordinates are snapped to a
  /// grid of `tolerance` (0 = exact noding), and pieces meeting at a point share a node. Pieces
  /// shorter than the tolerance vanish. Nodes are numbered by (x, y), edges by their first node.
  static PlanarGraph fromLines(const std::vector<LineString>& lines, double tolerance = 0.0);

 private:
  std::vector<Node> nodes_;
  std::vector<Edge> edges_;
  /// Position of each half-edge's edge in its origin's rotation (rebuilt on demand).
  mutable std::vector<int> rotationIndex_;
  mutable bool rotationIndexValid_ = false;
  void buildRotationIndex() const;
  /// The half-edge leaving node n through edge e.
  int outgoing(int n, int e) const { return halfEdge(e, edge(e).a != n); }
};

}  // namespace urbanvec
