#include "urbanvec/io/atomic_output.hpp"

#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "urbanvec/core/error.hpp"

namespace fs = std::filesystem;

namespace urbanvec::io {

void removePath(const std::string& path) {
  std::error_code ec;
  fs::remove_all(path, ec);
}

AtomicOutput::AtomicOutput(std::string path, bool overwrite, bool isDirectory)
    : path_(std::move(path)), overwrite_(overwrite), isDirectory_(isDirectory) {
  const char* what = isDirectory_ ? "output folder" : "output file";
  if (path_.empty()) throw invalidOption(std::string("the ") + what + " name is empty");
  const fs::path target(path_);
  std::error_code ec;
  if (fs::exists(target, ec) && !overwrite_)
    throw ioError(std::string(what) + " '" + path_ + "' already exists; use -overwrite to replace it");
  if (fs::exists(target, ec) && isDirectory_ != fs::is_directory(target, ec))
    throw ioError(std::string(what) + " '" + path_ + "' exists and is " +
                  (isDirectory_ ? "not a folder" : "a folder"));
  fs::path parent = target.parent_path();
  if (parent.empty()) parent = ".";
  if (!fs::is_directory(parent, ec))
    throw ioError("cannot write " + std::string(what) + " '" + path_ + "': folder '" +
                  parent.string() + "' does not exist");
  if (::access(parent.c_str(), W_OK) != 0)
    throw ioError("cannot write " + std::string(what) + " '" + path_ + "': folder '" +
                  parent.string() + "' is not writable");
  const std::string hidden = "." + target.stem().string() + ".tmp-" + std::to_string(::getpid()) +
                             target.extension().string();
  tempPath_ = (parent / hidden).string();
  removePath(tempPath_);
  if (isDirectory_ && !fs::create_directory(tempPath_, ec))
    throw ioError("cannot create folder '" + tempPath_ + "': " + ec.message());
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) removePath(tempPath_);
}

void AtomicOutput::commit() {
  std::error_code ec;
  if (isDirectory_ && fs::exists(path_, ec)) {
    // rename() cannot replace a non-empty folder: move the old one aside, then delete it.
    const std::string old = tempPath_ + ".old";
    fs::rename(path_, old, ec);
    if (ec) throw ioError("cannot replace output folder '" + path_ + "': " + ec.message());
    fs::rename(tempPath_, path_, ec);
    if (ec) {
      fs::rename(old, path_);
      throw ioError("cannot write output folder '" + path_ + "': " + ec.message());
    }
    removePath(old);
  } else {
    fs::rename(tempPath_, path_, ec);
    if (ec) throw ioError("cannot write output '" + path_ + "': " + ec.message());
  }
  committed_ = true;
}

}  // namespace urbanvec::io
