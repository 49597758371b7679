// Reading the inputs of `urbanvec shrink`: an OSM file (libosmium, io/osm_reader) and an importance file
// (.osmi, io/osmi_reader, or any OGR layer with an `importance` field) into shrink::ShrinkInput,
// projected to metres (spec pueyo-urban-data.md §B.1; docs/shrink.md "Inputs").
#pragma once

#include <functional>
#include <string>

#include "urbanvec/shrink/city.hpp"

namespace urbanvec::app {

struct ShrinkSourceOptions {
  std::string targetCrs;        ///< -t_srs; empty = the UTM zone of the data's centre
  std::string importanceLayer;  ///< OGR importance input: layer name; empty = every layer with the field
  std::string importanceField = "importance";
};

struct ShrinkSource {
  shrink::ShrinkInput input;
  std::string crsWkt;
  int missingIds = 0;  ///< importance members not found in the OSM file
};

/// Throws urbanvec::Error (InvalidInput) naming the file: missing or unreadable files, malformed XML
/// (line and column), an appearW or importance outside 0..1 or not a number, a bounding place whose
/// nodes are not on its ways, an OSM file without nodes. Ids not in the OSM file are counted and
/// reported through `warn`.
ShrinkSource readShrinkSource(const std::string& osmPath, const std::string& importancePath,
                              const ShrinkSourceOptions& options,
                              const std::function<void(const std::string&)>& warn = {});

}  // namespace urbanvec::app
