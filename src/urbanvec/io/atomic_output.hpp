// Outputs are written under a temporary name beside the target and renamed on success, so a failed
// or killed run never leaves a half-written or clobbered output (CONVENTIONS.md "The command").
#pragma once

#include <string>

namespace urbanvec::io {

class AtomicOutput {
 public:
  /// Checks up front that `path` may be written: its folder exists and is writable, and it does not
  /// exist unless `overwrite`. `what` names the output in messages ("output file", "output folder").
  AtomicOutput(std::string path, bool overwrite, bool isDirectory = false);
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;
  /// Removes the temporary output unless commit() succeeded.
  ~AtomicOutput();

  /// Where to write: same folder and extension as the target, hidden name.
  const std::string& tempPath() const { return tempPath_; }
  const std::string& path() const { return path_; }
  /// Moves the temporary output onto the target (replacing it when overwriting).
  void commit();

 private:
  std::string path_;
  std::string tempPath_;
  bool overwrite_;
  bool isDirectory_;
  bool committed_ = false;
};

/// Removes a file or a folder tree; ignores errors.
void removePath(const std::string& path);

}  // namespace urbanvec::io
