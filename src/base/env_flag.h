#pragma once
// GBL_* switches read from the environment: a variable set to anything but "" or "0" is on.
#include <cstdlib>
#include <cstring>
#include <optional>

namespace gbl {

// Unset or empty: nullopt; "0": false; anything else: true.
inline std::optional<bool> envChoice(const char* name) {
    const char* v = std::getenv(name);
    if (!v || !*v) return std::nullopt;
    return std::strcmp(v, "0") != 0;
}

inline bool envFlag(const char* name) { return envChoice(name).value_or(false); }

// A number: unset or empty: nullopt; else strtol's reading of it (0 where there is no number).
// The caller checks the range.
inline std::optional<long> envLong(const char* name) {
    const char* v = std::getenv(name);
    if (!v || !*v) return std::nullopt;
    return std::strtol(v, nullptr, 10);
}

}  // namespace gbl
