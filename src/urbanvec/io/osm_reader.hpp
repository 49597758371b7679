// Reading OpenStreetMap files (.osm XML, .osm.pbf, compressed XML) with libosmium into plain data that
// keeps what GDAL's OSM driver drops: the node ids of every way (shared nodes are the street topology
// the shrinking pipeline needs; spec pueyo-urban-data.md §B.1.1, §G "I/O"). See docs/shrink.md.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace urbanvec::io {

struct OsmNode {
  std::int64_t id = 0;
  double lon = 0.0;
  double lat = 0.0;
};

struct OsmWay {
  std::int64_t id = 0;
  std::vector<std::int64_t> refs;
  std::string highway;  ///< empty when the way has no highway tag
  std::string name;
};

struct OsmMember {
  char type = 'n';  ///< 'n', 'w' or 'r'
  std::int64_t ref = 0;
  std::string role;
};

struct OsmRelation {
  std::int64_t id = 0;
  std::string name;
  std::vector<OsmMember> members;
};

struct OsmData {
  bool hasBounds = false;  ///< the file's <bounds> (XML) or header bbox (PBF)
  double minLon = 0.0, minLat = 0.0, maxLon = 0.0, maxLat = 0.0;
  std::vector<OsmNode> nodes;  ///< sorted by id
  std::vector<OsmWay> ways;    ///< sorted by id
  std::vector<OsmRelation> relations;
  const OsmNode* node(std::int64_t id) const;  ///< nullptr when absent
  const OsmWay* way(std::int64_t id) const;
  const OsmRelation* relation(std::int64_t id) const;
};

/// Reads every node, way and relation. Throws an InvalidInput error naming `role` and the path for a
/// missing file, a file that is not OSM, or a broken one (XML errors give the line and column).
OsmData readOsmFile(const std::string& path, const std::string& role);

}  // namespace urbanvec::io
