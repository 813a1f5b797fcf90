// sRGB texels decoded exactly to half floats (srgb_texels.h).
#include "srgb_texels.h"

#include <array>
#include <cmath>

namespace gbl {

double srgbCodeToLinear(uint8_t code) {
    const double c = double(code) / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

uint16_t halfOfPositive(double x) {
    if (x <= 0.0) return 0;
    int e = 0;
    const double m = std::frexp(x, &e);  // x = m 2^e, m in [0.5, 1): x = (2m) 2^(e-1)
    int exponent = e - 1 + 15;
    double fraction = std::nearbyint((2.0 * m - 1.0) * 1024.0);  // round to nearest, ties to even
    if (fraction >= 1024.0) {
        fraction = 0.0;
        ++exponent;
    }
    return uint16_t((exponent << 10) | int(fraction));
}

std::vector<uint16_t> decodeSrgbTexels(const uint8_t* rgba, size_t texels) {
    static const auto tables = [] {
        std::array<std::array<uint16_t, 256>, 2> t{};
        for (int i = 0; i < 256; ++i) {
            t[0][size_t(i)] = halfOfPositive(srgbCodeToLinear(uint8_t(i)));
            t[1][size_t(i)] = halfOfPositive(double(i) / 255.0);
        }
        return t;
    }();
    std::vector<uint16_t> out(texels * 4);
    for (size_t i = 0; i < texels * 4; ++i) out[i] = tables[(i & 3) == 3 ? 1 : 0][rgba[i]];
    return out;
}

}  // namespace gbl
