// Reading and writing vector layers with OGR, converting to and from the plain types of core/layer.hpp.
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "urbanvec/core/layer.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/io/atomic_output.hpp"

namespace urbanvec::io {

struct VectorWriteOptions {
  std::string format;                               ///< OGR driver; empty = from the extension (GPKG default)
  std::vector<std::string> layerCreationOptions;    ///< NAME=VALUE, -lco
  std::vector<std::string> datasetCreationOptions;  ///< NAME=VALUE, -dsco
  std::string crsWkt;                               ///< CRS of every layer; empty = none
  std::map<std::string, std::string> layerStylesQml;  ///< layer name -> QGIS style (QML), GPKG only
  /// Also store io::defaultStyleFor(name) for standard layer names without an explicit style.
  bool defaultStyles = true;
};

/// The OGR driver for an output path: from -of if given, else from its extension.
std::string vectorFormatFor(const std::string& path, const std::string& requestedFormat);

/// Writes all layers to a new dataset at `path` (the caller makes it atomic). Throws urbanvec::Error.
void writeVectorDataset(const std::string& path, const std::vector<Layer>& layers,
                        const VectorWriteOptions& options);

/// A vector output taken before any work: the format and its creation options are checked, and the
/// name is locked and staged (AtomicOutput), so a bad -of/-lco fails at once, not after the work.
/// A format that holds one layer per file (Shapefile, GeoJSON, FlatGeobuf, CSV...) receiving several
/// layers writes a folder with one file (set) per layer; naming that folder like a file of the format
/// (`out.shp`) is refused.
class VectorOutput {
 public:
  /// `layerNames`: the layers the run will write (their names give a folder output's files).
  VectorOutput(std::string path, VectorWriteOptions options, std::vector<std::string> layerNames,
               OutputRules rules);
  /// Writes every layer into the staging place, in `crsWkt` when given (else the options' CRS).
  void write(const std::vector<Layer>& layers, const std::string& crsWkt = {});
  /// Moves the written files into place (AtomicOutput::commit).
  void commit(const Progress& progress = {});
  const std::string& format() const { return options_.format; }

 private:
  friend class LayerStream;
  /// The staging path of one layer's file when each layer has its own (layerPerFile_).
  std::string layerFile(const std::string& layer) const;
  std::string path_;
  VectorWriteOptions options_;
  bool layerPerFile_ = false;  ///< one dataset per layer inside a folder output
  std::string extension_;      ///< of each per-layer file, with the dot
  std::unique_ptr<AtomicOutput> output_;
};

class DatasetWriter;

/// Writes a run's layers into a VectorOutput one at a time, as the run makes each final, in the order
/// they come; each layer's features are freed once written. With `background`, a thread of its own
/// writes while the caller goes on computing; without, add() writes at once. Both make the same GDAL
/// calls in the same order, so the same file. Destroyed before finish() (the run failed or was
/// cancelled), it stops between two features and closes what it wrote, uncommitted; the VectorOutput
/// then removes its staging as before (destroy the stream first).
class LayerStream {
 public:
  LayerStream(VectorOutput& output, std::string crsWkt, bool background);
  ~LayerStream();
  LayerStream(const LayerStream&) = delete;
  LayerStream& operator=(const LayerStream&) = delete;

  /// Takes the next layer. Throws the error of an earlier layer's writing, if any.
  void add(Layer&& layer);
  /// Waits until every layer is written, then finishes the dataset (styles, commit). Throws
  /// urbanvec::Error when any writing failed. The output still needs VectorOutput::commit().
  void finish();

 private:
  void write(Layer& layer);
  void finishDatasets();
  void loop();

  VectorOutput& output_;
  VectorWriteOptions options_;              ///< the output's, with the CRS of this run
  std::unique_ptr<DatasetWriter> dataset_;  ///< the one dataset of a multi-layer format, once opened
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Layer> queue_;
  bool finishing_ = false;
  std::atomic<bool> stop_{false};
  std::exception_ptr error_;
};

struct VectorReadOptions {
  std::string targetCrs;  ///< reproject to this CRS (WKT or any user string GDAL accepts); empty = keep
  /// OGR SQL attribute filter (-where); empty = every feature. A filter OGR refuses is an InvalidOption.
  std::string where;
};

struct LayerRead {
  Layer layer;
  std::string crsWkt;  ///< the layer's CRS before any reprojection; empty when it has none
};

/// Names of the vector layers in a dataset; throws when it is missing or not a vector dataset.
std::vector<std::string> listVectorLayers(const std::string& path, const std::string& role);

/// Reads one layer (all fields, geometries as plain types), or nothing when the dataset has no layer
/// of that name. `role` names the input in messages.
std::optional<LayerRead> readVectorLayer(const std::string& path, const std::string& layerName,
                                         const std::string& role, const VectorReadOptions& options = {});

}  // namespace urbanvec::io
