// City shrinking (spec pueyo-urban-data.md part B; issue 19): a smaller street network that keeps the
// landmarks, the important streets and their arrangement. shrinkCity runs the thesis's steps in order
// (pipeline in shrink.cpp) on plain data; the app layer reads OSM and .osmi files into ShrinkInput.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/shrink/city.hpp"
#include "urbanvec/shrink/measures.hpp"
#include "urbanvec/shrink/shrink_options.hpp"

namespace urbanvec::shrink {

struct ShrunkWay {
  std::int64_t osmId = 0;  ///< negative for the new dead-end connectors (§B.6)
  std::string highway;
  std::string name;
  double importance = 0.0;  ///< impW (§B.4)
  std::string kind;         ///< important, selected, connector, dead_end_connector; full map: street
  LineString line;
};

struct ShrunkPlace {
  std::string placeId;
  std::int64_t osmId = 0;
  std::string name;
  double appearW = 0.0;
  Geometry geometry;  ///< Vec2, LineString or Polygon
};

struct SeamLine {
  int number = 0;  ///< removal order, from 1
  bool vertical = true;
  LineString line;  ///< pixel centres, original coordinates
};

/// Named figures of a run (counts per step, carving, and the measures), in a stable order.
struct ShrinkReport {
  std::vector<std::pair<std::string, double>> values;
  std::vector<std::string> notes;               ///< why seams could not be removed, and similar remarks
  double value(const std::string& name) const;  ///< NaN when absent
};

struct StepTime {
  std::string step;  ///< the thesis's Table 2 step names
  double seconds = 0.0;
};

struct ShrinkResult {
  std::vector<ShrunkWay> streets;      ///< the shrunk skeleton
  std::vector<ShrunkPlace> places;     ///< landmarks, same shapes, moved
  std::vector<ShrunkWay> fullStreets;  ///< every street of the cleaned city, deformed by the same seams
  std::vector<SeamLine> seams;
  ShrinkMeasures measures;
  ShrinkReport report;
  std::vector<std::string> warnings;
  std::vector<StepTime> timings;
};

/// Steps 0-8 of §B (B.2-B.11) and the measures. Throws InvalidInput when the city has no street,
/// InvalidOption for out-of-range options or more seams than the image has pixels minus one.
ShrinkResult shrinkCity(const ShrinkInput& input, const ShrinkOptions& options,
                        const Progress& progress = {});

}  // namespace urbanvec::shrink
