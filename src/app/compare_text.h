#pragma once
// compare's numbers as text, the same in its progress lines and on the console's table.
#include <cmath>
#include <cstdio>
#include <string>

namespace gbl::compare {

// "52.3 dB", or "inf" for identical images.
inline std::string formatPsnr(double db) {
    if (std::isinf(db)) return "inf";
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.1f dB", db);
    return buf;
}

}  // namespace gbl::compare
