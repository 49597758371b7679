// Outputs are written into a hidden staging folder beside the target and moved into place on success,
// so a failed, cancelled or killed run never leaves a half-written or clobbered output, and never
// touches a file it does not write (CONVENTIONS.md "The command"; issue 15).
#pragma once

#include <string>
#include <vector>

#include "urbanvec/core/progress.hpp"

namespace urbanvec::io {

/// What a run may do to the place it writes.
struct OutputRules {
  bool overwrite = false;  ///< replace entries that exist (only those this run writes)
  /// The output is a folder holding `entries`; other files in an existing folder are left alone.
  bool isFolder = false;
  /// Names this run writes: in the folder, or beside a file output (a multi-file format's side
  /// files, e.g. out.shx next to out.shp). Checked before any work; the file output's own name is
  /// implied. Entries found only when moving into place are still never replaced without overwrite.
  std::vector<std::string> entries;
  /// Paths the run reads: the output never replaces one, and a folder output is never one of them
  /// (same file compared by device and inode, so symlinks and hard links count).
  std::vector<std::string> inputs;
};

/// Takes an output name for this run: checks that it may be written (before any work), locks it
/// against other runs writing the same name, removes temporaries that killed runs left, and stages
/// everything in a hidden folder `.<stem>.tmp-<pid><ext>` that commit() moves into place.
class AtomicOutput {
 public:
  AtomicOutput(std::string path, OutputRules rules);
  AtomicOutput(std::string path, bool overwrite);
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;
  /// Removes the staging folder unless commit() succeeded, and releases the name.
  ~AtomicOutput();

  /// Where to write: for a file output a path with the target's name inside the staging folder (a
  /// driver may add side files beside it); for a folder output the staging folder itself.
  const std::string& tempPath() const { return tempPath_; }
  const std::string& path() const { return path_; }
  /// The point of no return: reports progress one last time (so a cancellation still removes
  /// everything), then moves every staged entry into place, replacing only same-named entries.
  void commit(const Progress& progress = {});

 private:
  void checkInputs() const;
  void checkExisting() const;
  void takeLock();
  void releaseLock();
  void removeStaleTemporaries() const;

  std::string path_;
  OutputRules rules_;
  std::string what_;        ///< "output file" or "output folder", for messages
  std::string parent_;      ///< folder holding the target
  std::string workDir_;     ///< real folder holding the staging folder and the lock
  std::string baseName_;    ///< name the staging folder and the lock are derived from
  std::string stagingDir_;  ///< hidden folder beside (or inside) the target
  std::string tempPath_;
  std::string lockPath_;
  int lockFd_ = -1;
};

/// True once any AtomicOutput of this process has been moved into place: from then on an interrupt
/// no longer undoes the run (the app finishes and reports success).
bool anyOutputCommitted();

/// Removes a file or a folder tree; ignores errors.
void removePath(const std::string& path);

/// Test hooks read from the environment variable URBANVEC_FAULT, a comma-separated list of
/// `name=value`: `write-fail-after=N` (the vector writer fails after N features),
/// `write-delay-ms=N` (sleeps before each layer is written), `commit-delay-ms=N` (sleeps between the
/// last progress check and the move into place), `after-commit-delay-ms=N` (sleeps after it). They
/// let the tests exercise failures and signals at each phase of writing; unset, they cost nothing.
long faultSetting(const char* name);

}  // namespace urbanvec::io
