#pragma once

namespace urbanvec {
/// The library's version, e.g. "0.1.0".
constexpr const char* kVersion = URBANVEC_VERSION;
}  // namespace urbanvec
