// Errors raised by the library. Only the app layer catches them and maps them to exit codes
// (CONVENTIONS.md "Library shape").
#pragma once

#include <stdexcept>
#include <string>

namespace urbanvec {

enum class ErrorKind {
  InvalidInput,   ///< an input file or its content is unusable
  InvalidOption,  ///< an option value is out of range or inconsistent
  Io,             ///< reading or writing failed (permissions, disk, driver)
  Internal        ///< a bug: an invariant of the library did not hold
};

/// An error with a full sentence naming the file/option/value at fault.
class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& sentence) : std::runtime_error(sentence), kind_(kind) {}
  ErrorKind kind() const noexcept { return kind_; }

 private:
  ErrorKind kind_;
};

/// Thrown when a progress callback returned false.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled by the user") {}
};

inline Error invalidInput(const std::string& s) { return Error(ErrorKind::InvalidInput, s); }
inline Error invalidOption(const std::string& s) { return Error(ErrorKind::InvalidOption, s); }
inline Error ioError(const std::string& s) { return Error(ErrorKind::Io, s); }
inline Error internalError(const std::string& s) { return Error(ErrorKind::Internal, s); }

}  // namespace urbanvec
