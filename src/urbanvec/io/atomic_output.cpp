#include "urbanvec/io/atomic_output.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>
#include <system_error>
#include <thread>

#include "urbanvec/core/error.hpp"

namespace fs = std::filesystem;

namespace urbanvec::io {

namespace {

std::atomic<bool> gCommitted{false};

std::optional<struct stat> statOf(const std::string& path) {
  struct stat s {};
  if (::stat(path.c_str(), &s) != 0) return std::nullopt;
  return s;
}

bool sameFile(const struct stat& a, const struct stat& b) {
  return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

bool processAlive(long pid) {
  if (pid <= 0) return false;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

void sleepMs(long ms) {
  if (ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(ms));
}

/// Side files GDAL and QGIS keep beside a file they opened (statistics, histograms): stale once the
/// file is replaced, so they go with it.
const char* const kSidecarSuffixes[] = {".aux.xml"};

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

long faultSetting(const char* name) {
  const char* env = std::getenv("URBANVEC_FAULT");
  if (!env || !*env) return 0;
  std::stringstream in(env);
  std::string item;
  const std::string key = std::string(name) + "=";
  while (std::getline(in, item, ','))
    if (item.rfind(key, 0) == 0) return std::strtol(item.c_str() + key.size(), nullptr, 10);
  return 0;
}

bool anyOutputCommitted() {
  return gCommitted;
}

void removePath(const std::string& path) {
  std::error_code ec;
  fs::remove_all(path, ec);
}

AtomicOutput::AtomicOutput(std::string path, bool overwrite)
    : AtomicOutput(std::move(path), OutputRules{overwrite, false, {}, {}}) {}

AtomicOutput::AtomicOutput(std::string path, OutputRules rules)
    : path_(std::move(path)), rules_(std::move(rules)) {
  what_ = rules_.isFolder ? "output folder" : "output file";
  if (path_.empty()) throw invalidOption("the " + what_ + " name is empty");
  while (rules_.isFolder && path_.size() > 1 && path_.back() == '/') path_.pop_back();
  const fs::path target(path_);
  fs::path parent = target.parent_path();
  if (parent.empty()) parent = ".";
  parent_ = parent.string();
  std::error_code ec;
  if (!fs::exists(parent, ec))
    throw ioError("cannot write " + what_ + " '" + path_ + "': folder '" + parent_ + "' does not exist");
  if (!fs::is_directory(parent, ec))
    throw ioError("cannot write " + what_ + " '" + path_ + "': '" + parent_ + "' is not a folder");
  if (::access(parent_.c_str(), W_OK) != 0)
    throw ioError("cannot write " + what_ + " '" + path_ + "': folder '" + parent_ + "' is not writable");
  checkInputs();
  if (fs::exists(target, ec) && rules_.isFolder != fs::is_directory(target, ec))
    throw ioError(what_ + " '" + path_ + "' exists and is " +
                  (rules_.isFolder ? "not a folder" : "a folder"));
  // Staging and lock live in the real folder the output lands in: inside an existing output folder
  // (which may be a symlink to another file system, where a rename from beside it would fail), else
  // in the output's parent. Resolved paths make `g` and a symlink to it share one lock.
  const bool insideFolder = rules_.isFolder && fs::is_directory(target, ec);
  const fs::path real = fs::weakly_canonical(insideFolder ? target : parent, ec);
  workDir_ = ec ? (insideFolder ? target : parent).string() : real.string();
  baseName_ = insideFolder ? fs::path(workDir_).filename().string() : target.filename().string();
  if (baseName_.empty() || baseName_ == "." || baseName_ == "..") baseName_ = "output";
  takeLock();
  try {
    checkExisting();
    removeStaleTemporaries();
    const fs::path base(baseName_);
    const std::string staging =
        (fs::path(workDir_) /
         ("." + base.stem().string() + ".tmp-" + std::to_string(::getpid()) + base.extension().string()))
            .string();
    removePath(staging);
    if (!fs::create_directory(staging, ec))
      throw ioError("cannot create the temporary folder '" + staging + "': " + ec.message());
    stagingDir_ = staging;
    tempPath_ = rules_.isFolder ? stagingDir_ : (fs::path(stagingDir_) / target.filename()).string();
  } catch (...) {
    releaseLock();  // no destructor runs for a constructor that throws
    throw;
  }
}

void AtomicOutput::releaseLock() {
  if (lockFd_ < 0) return;
  ::unlink(lockPath_.c_str());
  ::close(lockFd_);
  lockFd_ = -1;
}

void AtomicOutput::checkInputs() const {
  const fs::path target(path_);
  const fs::path root = rules_.isFolder ? target : fs::path(parent_);
  std::vector<std::string> written;
  if (!rules_.isFolder) written.push_back(path_);
  for (const std::string& e : rules_.entries) written.push_back((root / e).string());
  std::error_code ec;
  const fs::path folderReal = rules_.isFolder ? fs::weakly_canonical(target, ec) : fs::path();
  for (const std::string& input : rules_.inputs) {
    if (input.empty() || input.rfind("/vsi", 0) == 0) continue;
    const std::optional<struct stat> in = statOf(input);
    if (!in) continue;
    for (const std::string& w : written)
      if (const std::optional<struct stat> out = statOf(w); out && sameFile(*in, *out))
        throw invalidInput(what_ + " '" + path_ + "' would replace the input '" + input +
                           "'; choose another output name");
    if (!rules_.isFolder) continue;
    // A folder output never holds an input: the input's folder chain must not reach the output.
    if (const std::optional<struct stat> out = statOf(path_); out && sameFile(*in, *out))
      throw invalidInput(what_ + " '" + path_ + "' is the input '" + input + "'; choose another folder");
    const fs::path inputReal = fs::weakly_canonical(input, ec);
    if (ec || folderReal.empty()) continue;
    for (fs::path p = inputReal.parent_path(); !p.empty(); p = p.parent_path()) {
      if (p == folderReal)
        throw invalidInput(what_ + " '" + path_ + "' holds the input '" + input +
                           "'; write the output to another folder");
      if (p == p.parent_path()) break;
    }
  }
}

void AtomicOutput::checkExisting() const {
  std::error_code ec;
  if (!rules_.isFolder) {
    if (fs::exists(path_, ec) && !rules_.overwrite)
      throw ioError(what_ + " '" + path_ + "' already exists; use -overwrite to replace it");
  } else if (!fs::exists(path_, ec)) {
    return;
  }
  if (rules_.overwrite) return;
  const fs::path root = rules_.isFolder ? fs::path(path_) : fs::path(parent_);
  std::vector<std::string> present;
  for (const std::string& e : rules_.entries)
    if (fs::exists(root / e, ec) && (rules_.isFolder || (root / e).string() != path_)) present.push_back(e);
  if (present.empty()) return;
  if (rules_.isFolder)
    throw ioError(what_ + " '" + path_ + "' already holds " + joinNames(present) +
                  "; use -overwrite to replace them (other files in the folder are kept)");
  throw ioError(what_ + " '" + path_ + "' would replace " + joinNames(present) +
                " beside it; use -overwrite");
}

void AtomicOutput::takeLock() {
  lockPath_ = (fs::path(workDir_) / ("." + baseName_ + ".lock")).string();
  for (int attempt = 0; attempt < 10; ++attempt) {
    const int fd = ::open(lockPath_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      throw ioError("cannot write " + what_ + " '" + path_ + "': cannot create '" + lockPath_ + "' (" +
                    std::strerror(errno) + ")");
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      char buffer[32] = {};
      const ssize_t n = ::pread(fd, buffer, sizeof buffer - 1, 0);
      ::close(fd);
      const long pid = n > 0 ? std::strtol(buffer, nullptr, 10) : 0;
      throw ioError(what_ + " '" + path_ + "' is being written by another run" +
                    (pid > 0 ? " (process " + std::to_string(pid) + ")" : std::string()) +
                    "; wait for it to finish or choose another output name");
    }
    // The holder before us may have removed the lock file between our open and our lock: then the
    // lock we hold is on a file nobody else sees, so take the name again.
    struct stat held {};
    const std::optional<struct stat> current = statOf(lockPath_);
    if (::fstat(fd, &held) == 0 && current && sameFile(held, *current)) {
      const std::string pid = std::to_string(::getpid()) + "\n";
      if (::ftruncate(fd, 0) == 0 && ::pwrite(fd, pid.data(), pid.size(), 0) < 0) {
        // The PID only improves another run's message; the lock holds without it.
      }
      lockFd_ = fd;
      return;
    }
    ::close(fd);
  }
  throw ioError("cannot lock " + what_ + " '" + path_ + "': its lock file '" + lockPath_ +
                "' keeps changing");
}

void AtomicOutput::removeStaleTemporaries() const {
  const fs::path target(baseName_);
  const std::string prefix = "." + target.stem().string() + ".tmp-";
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(workDir_, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    size_t end = prefix.size();
    while (end < name.size() && std::isdigit(static_cast<unsigned char>(name[end]))) ++end;
    if (end == prefix.size() ||
        name.compare(end, target.extension().string().size(), target.extension().string()))
      continue;
    const long pid = std::strtol(name.substr(prefix.size(), end - prefix.size()).c_str(), nullptr, 10);
    if (pid != ::getpid() && !processAlive(pid)) removePath(entry.path().string());
  }
}

AtomicOutput::~AtomicOutput() {
  if (!stagingDir_.empty()) removePath(stagingDir_);
  releaseLock();
}

void AtomicOutput::commit(const Progress& progress) {
  reportProgress(progress, 0.0, "writing");
  if (const long delay = faultSetting("commit-delay-ms")) sleepMs(delay);
  std::error_code ec;
  const bool folderIsNew = rules_.isFolder && !fs::exists(path_, ec);
  if (folderIsNew) {
    fs::rename(stagingDir_, path_, ec);
    if (ec) throw ioError("cannot write " + what_ + " '" + path_ + "': " + ec.message());
    stagingDir_.clear();
  } else {
    const fs::path root = rules_.isFolder ? fs::path(path_) : fs::path(parent_);
    std::vector<std::string> staged;
    for (const fs::directory_entry& entry : fs::directory_iterator(stagingDir_, ec))
      staged.push_back(entry.path().filename().string());
    std::sort(staged.begin(), staged.end());
    for (const std::string& name : staged) {
      const fs::path dest = root / name;
      if (!fs::exists(dest, ec)) continue;
      if (!rules_.overwrite)
        throw ioError("cannot write " + what_ + " '" + path_ + "': '" + dest.string() +
                      "' appeared while this run was working; use -overwrite to replace it");
      if (fs::is_directory(dest, ec) != fs::is_directory(fs::path(stagingDir_) / name, ec))
        throw ioError("cannot write " + what_ + " '" + path_ + "': '" + dest.string() + "' is " +
                      (fs::is_directory(dest, ec) ? "a folder" : "not a folder"));
    }
    // Replaced entries go aside first, so a failure part-way can put every one of them back.
    const fs::path aside = fs::path(stagingDir_) / ".replaced";
    fs::create_directory(aside, ec);
    std::vector<std::pair<fs::path, fs::path>> movedAside;  // original place, place aside
    std::vector<fs::path> movedIn;
    auto rollBack = [&](const std::string& why) {
      std::error_code ignored;
      for (const fs::path& p : movedIn) fs::remove_all(p, ignored);
      for (const auto& [original, kept] : movedAside) fs::rename(kept, original, ignored);
      throw ioError("cannot write " + what_ + " '" + path_ + "': " + why + "; the previous files were kept");
    };
    int asideCount = 0;
    auto moveAside = [&](const fs::path& original) {
      const fs::path kept = aside / std::to_string(asideCount++);
      fs::rename(original, kept, ec);
      if (ec) rollBack("cannot move '" + original.string() + "' aside (" + ec.message() + ")");
      movedAside.emplace_back(original, kept);
    };
    // A file being replaced is first hard-linked aside, so the rename onto it is one atomic step
    // (no moment without the old or the new file) and a rollback can still bring it back.
    auto keepAside = [&](const fs::path& original) {
      const fs::path kept = aside / std::to_string(asideCount);
      if (fs::is_regular_file(original, ec) && ::link(original.c_str(), kept.c_str()) == 0) {
        ++asideCount;
        movedAside.emplace_back(original, kept);
        return;
      }
      moveAside(original);  // a folder, or a file system without hard links
    };
    auto isStaged = [&](const std::string& name) {
      return std::find(staged.begin(), staged.end(), name) != staged.end();
    };
    for (const std::string& name : staged) {
      const fs::path dest = root / name;
      if (fs::exists(dest, ec)) keepAside(dest);
      for (const char* suffix : kSidecarSuffixes) {
        const fs::path sidecar = root / (name + suffix);
        if (fs::exists(sidecar, ec) && !isStaged(name + suffix)) moveAside(sidecar);
      }
      fs::rename(fs::path(stagingDir_) / name, dest, ec);
      if (ec) rollBack("cannot move '" + name + "' into place (" + ec.message() + ")");
      movedIn.push_back(dest);
    }
    // Files of the previous output that this run did not write (a .prj of an output now without CRS,
    // a layer not written this time) would describe the new one wrongly: they go too.
    for (const std::string& name : rules_.entries)
      if (!isStaged(name) && fs::exists(root / name, ec)) moveAside(root / name);
  }
  gCommitted = true;
  if (const long delay = faultSetting("after-commit-delay-ms")) sleepMs(delay);
}

}  // namespace urbanvec::io
