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

}  // namespace gbl
