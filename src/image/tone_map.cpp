#include "tone_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gbl {

// Narkowicz's fit of the ACES RRT+ODT: x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), saturated.
// The curve reaches 1 at x ~ 7.24 and is clamped beyond; returning 1 early for x >= 8 gives the
// same value without overflowing x*x for huge inputs. NaN and negatives map to 0 (black), so a
// broken pixel is visible as a hole rather than undefined 8-bit output.
float acesFilmNarkowicz(float x) {
    if (!(x > 0.0f)) return 0.0f;
    if (x >= 8.0f) return 1.0f;
    const float y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
    return std::clamp(y, 0.0f, 1.0f);
}

// IEC 61966-2-1 piecewise curve, evaluated in double so the float result is correctly rounded
// (the round trip tests hold to float precision).
float linearToSrgb(float linear) {
    const double x = std::clamp(double(linear), 0.0, 1.0);  // NaN -> fails both compares below
    if (!(x > 0.0031308)) return float(std::isnan(x) ? 0.0 : 12.92 * x);
    return float(1.055 * std::pow(x, 1.0 / 2.4) - 0.055);
}

float srgbToLinear(float encoded) {
    const double e = std::clamp(double(encoded), 0.0, 1.0);
    if (!(e > 0.04045)) return float(std::isnan(e) ? 0.0 : e / 12.92);
    return float(std::pow((e + 0.055) / 1.055, 2.4));
}

namespace {

void checkInput(const Image& hdr, float exposure) {
    if (hdr.channels != 1 && hdr.channels < 3)
        throw std::invalid_argument("tone map: image has " + std::to_string(hdr.channels) + " channels; need 1, 3 or 4");
    if (hdr.pixels.size() != hdr.pixelCount() * size_t(hdr.channels))
        throw std::invalid_argument("tone map: inconsistent image size");
    if (!std::isfinite(exposure) || exposure < 0.0f)
        throw std::invalid_argument("tone map: exposure must be finite and >= 0");
}

// Runs `store(pixelIndex, channel, encoded)` for each RGB value of the tone-mapped image.
template <class Store>
void toneMapEach(const Image& hdr, float exposure, Store&& store) {
    checkInput(hdr, exposure);
    for (size_t p = 0; p < hdr.pixelCount(); ++p)
        for (int c = 0; c < 3; ++c) {
            const float linear = hdr.pixels[p * size_t(hdr.channels) + size_t(hdr.channels == 1 ? 0 : c)];
            store(p, c, linearToSrgb(acesFilmNarkowicz(linear * exposure)));
        }
}

}  // namespace

Image8 toneMapToSrgb8(const Image& hdr, float exposure) {
    Image8 out{hdr.width, hdr.height, 3, std::vector<unsigned char>(hdr.pixelCount() * 3)};
    toneMapEach(hdr, exposure, [&](size_t p, int c, float encoded) {
        out.pixels[p * 3 + size_t(c)] = static_cast<unsigned char>(std::floor(encoded * 255.0f + 0.5f));
    });
    return out;
}

Image8 logEncodeForPreview(const Image& hdr) {
    Image8 out{hdr.width, hdr.height, 3, std::vector<unsigned char>(hdr.pixelCount() * 3)};
    const int channels = hdr.channels;
    for (size_t p = 0; p < hdr.pixelCount(); ++p)
        for (int c = 0; c < 3; ++c) {
            const float x = hdr.pixels[p * size_t(channels) + size_t(channels >= 3 ? c : 0)];
            float t = 0.0f;
            if (std::isfinite(x) && x > 0.0f)
                t = std::clamp((std::log2(x) - kPreviewLog2Min) / (kPreviewLog2Max - kPreviewLog2Min), 0.0f, 1.0f);
            out.pixels[p * 3 + size_t(c)] = static_cast<unsigned char>(std::floor(t * 255.0f + 0.5f));
        }
    return out;
}

Image toneMapToSrgb8AsFloat(const Image& hdr, float exposure) {
    Image out(hdr.width, hdr.height, 3);
    toneMapEach(hdr, exposure, [&](size_t p, int c, float encoded) {
        const auto byte = static_cast<unsigned char>(std::floor(encoded * 255.0f + 0.5f));
        out.pixels[p * 3 + size_t(c)] = float(byte) / 255.0f;
    });
    return out;
}

Image toneMapToSrgbFloat(const Image& hdr, float exposure) {
    Image out(hdr.width, hdr.height, 3);
    toneMapEach(hdr, exposure, [&](size_t p, int c, float encoded) { out.pixels[p * 3 + size_t(c)] = encoded; });
    return out;
}

}  // namespace gbl
