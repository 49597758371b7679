// Vector layers as plain data: what algorithms produce and the I/O layer writes with OGR.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec {

enum class GeometryType { None, Point, LineString, Polygon, MultiPolygon, MultiLineString };
enum class FieldType { Integer, Real, String };

struct FieldDef {
  std::string name;
  FieldType type = FieldType::String;
};

/// monostate is a null field.
using FieldValue = std::variant<std::monostate, std::int64_t, double, std::string>;

struct Feature {
  Geometry geometry;
  std::vector<FieldValue> values;  ///< one per field of the layer, in order
};

struct Layer {
  std::string name;
  GeometryType geometryType = GeometryType::None;
  std::vector<FieldDef> fields;
  std::vector<Feature> features;

  /// Index of a field, or -1.
  int fieldIndex(const std::string& field) const {
    for (size_t i = 0; i < fields.size(); ++i)
      if (fields[i].name == field) return static_cast<int>(i);
    return -1;
  }
};

/// Takes each output layer of a run as soon as it is final, in output order (a writer can store it
/// while the run goes on computing the next ones). It may throw (a failed write stops the run).
using LayerSink = std::function<void(Layer&&)>;

/// `sink`, or, when it is empty, a sink that appends each layer to `layers`.
inline LayerSink sinkOrAppend(const LayerSink& sink, std::vector<Layer>& layers) {
  if (sink) return sink;
  return [&layers](Layer&& layer) { layers.push_back(std::move(layer)); };
}

}  // namespace urbanvec
