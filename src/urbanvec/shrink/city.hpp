// The plain data of the shrinking pipeline (spec pueyo-urban-data.md §B.1, §C.1): a city of nodes and
// street ways already projected to metres, and the important places of the .osmi file (or of an
// importance layer) resolved to those nodes. The app layer builds it from OSM; the algorithm never sees
// a file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec::shrink {

struct CityNode {
  std::int64_t osmId = 0;  ///< OSM node id; negative for nodes the pipeline or the app created
  Vec2 p;                  ///< projected position, metres
  /// False when the node lies outside the download bounds (§B.1.1 `bounds`), for §B.2 cleaning.
  bool inBounds = true;
};

/// A street: one OSM way with a `highway` tag (§B.1.1). The thesis never merges ways (§B.4 [INFERENCE]).
struct CityWay {
  std::int64_t osmId = 0;
  std::vector<int> nodes;  ///< indices into City::nodes, in way order
  std::string highway;
  std::string name;
};

struct City {
  std::vector<CityNode> nodes;  ///< street nodes and the nodes of important non-street places
  std::vector<CityWay> streets;
};

/// An important place of the .osmi file (§B.1.2) with its members resolved.
struct Place {
  std::string id;  ///< the .osmi place id (or the importance layer's feature id)
  std::string name;
  std::int64_t osmId = 0;  ///< OSM id of its first member (0 when drawn by hand)
  double appearW = 1.0;    ///< [0, 1], 1 = most important
  /// Streets that are members (by OSM way id): important directly (§B.4).
  std::vector<std::int64_t> streetIds;
  /// Non-street elements (buildings, squares, rivers, points): node sequences into City::nodes; one
  /// node is a point, first == last a polygon, else a line (§B.7).
  std::vector<std::vector<int>> shapes;
  std::vector<std::int64_t> shapeIds;  ///< OSM id of each shape's element (0 when drawn by hand)
  /// `function=bounding` (or `boundary`): the closed node ring of the area (§B.1.2); streets with a
  /// node inside get the place's weight (§B.3 task 2). Empty for other places.
  std::vector<int> boundingRing;
};

struct ShrinkInput {
  City city;
  std::vector<Place> places;
};

}  // namespace urbanvec::shrink
