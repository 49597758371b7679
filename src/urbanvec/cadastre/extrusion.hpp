// LoD1 extrusion of building elements (spec pueyo-urban-data.md §A.8): prisms with triangulated roofs
// and floors, written as Wavefront OBJ and CityJSON 1.1.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "urbanvec/cadastre/cadastre.hpp"

namespace urbanvec::cadastre {

/// Triangles of a polygon with holes (CGAL constrained Delaunay triangulation, inside faces only), as
/// indices into the polygon's vertices taken ring by ring (outer first, closing points excluded), each
/// counter-clockwise.
std::vector<std::array<int, 3>> triangulatePolygon(const Polygon& polygon);

struct Mesh {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside
  std::vector<int> triangleObject;            ///< building index per triangle
};

/// One closed prism per polygon part of every building with height > 0 (0-floor elements, the
/// courtyards, make none, §A.8): floor at z = 0, roof at the height, two triangles per facade edge.
/// Every edge of a prism is shared by exactly two of its triangles (watertight) and normals point out.
Mesh extrudeBuildings(const std::vector<BuildingOut>& buildings);

/// Wavefront OBJ text: coordinates relative to `origin` (written in a comment), one object per building,
/// one facet normal per triangle.
std::string objText(const Mesh& mesh, const std::array<double, 2>& origin, const std::string& crsName);

/// CityJSON 1.1: one Building per element with height > 0 (LoD1 Solid: floor, roof and facade
/// surfaces, holes kept), attributes floors, floors_below, measuredHeight, label, block_id.
/// `epsg` > 0 fills metadata.referenceSystem.
std::string cityJsonText(const std::vector<BuildingOut>& buildings, int epsg);

}  // namespace urbanvec::cadastre
