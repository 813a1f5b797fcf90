#include "tone_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "parallel_for.h"

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

// The 8-bit code of a display value y in [0,1], as every writer of 8-bit images computes it:
// floor(linearToSrgb(y) * 255 + 0.5).
unsigned char srgbByteDirect(float y) { return static_cast<unsigned char>(std::floor(linearToSrgb(y) * 255.0f + 0.5f)); }

// The same code without the pow: the 255 places where it steps up. srgbByteDirect is monotone
// non-decreasing over the floats in [0,1] (linearToSrgb's curve is increasing; its pow segment
// is evaluated in double, where consecutive float inputs are ~2^29 double ulps apart, far more
// than glibc pow's 0.52-ulp error, and every later step -- x 1.055, - 0.055, rounding to float,
// x 255, + 0.5, floor -- is a correctly rounded, hence monotone, operation; checked exhaustively
// over all 1,065,353,217 floats in [0,1] when this was written, and at every step and bucket by
// tone_map_test). So code(y) = the number of steps at or below y, found from the code of y's
// bucket of width 1/4096 (at most ~0.8 steps per bucket: the curve's slope x 255 / 4096 is
// largest at the knee) and a short walk up: 3-4 ns a channel instead of ~25.
struct SrgbByteSteps {
    float step[257];               // step[k]: smallest float y with code(y) >= k; step[256] = +inf
    unsigned char bucket[4097];    // code(i / 4096)
    SrgbByteSteps() {
        step[0] = 0.0f;
        step[256] = std::numeric_limits<float>::infinity();
        uint32_t lo = 0;  // bit patterns of non-negative floats are ordered as the floats
        uint32_t one;
        const float oneF = 1.0f;
        std::memcpy(&one, &oneF, sizeof one);
        auto code = [](uint32_t bits) {
            float y;
            std::memcpy(&y, &bits, sizeof y);
            return int(srgbByteDirect(y));
        };
        for (int k = 1; k <= 255; ++k) {  // bisection: the smallest bits in [lo, one] with code >= k
            uint32_t a = lo, b = one;
            while (a < b) {
                const uint32_t m = a + (b - a) / 2;
                if (code(m) >= k) b = m;
                else a = m + 1;
            }
            std::memcpy(&step[k], &a, sizeof a);
            lo = a;
        }
        for (int i = 0; i <= 4096; ++i) bucket[i] = srgbByteDirect(float(i) / 4096.0f);
    }
    // y in [0,1] (acesFilmNarkowicz's range).
    unsigned char code(float y) const {
        int c = bucket[int(y * 4096.0f)];  // exact scaling by a power of two
        while (y >= step[c + 1]) ++c;
        return static_cast<unsigned char>(c);
    }
};

const SrgbByteSteps& srgbByteSteps() {
    static const SrgbByteSteps steps;
    return steps;
}

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

// The 8-bit tone map, store(index, code) for every RGB value, in pixel bands on every core (each
// value is computed alone, so the split does not change it).
template <class Store>
void toneMapBytes(const Image& hdr, float exposure, Store&& store) {
    checkInput(hdr, exposure);
    const SrgbByteSteps& steps = srgbByteSteps();
    const size_t n = hdr.pixelCount(), channels = size_t(hdr.channels);
    const int threads = int(std::clamp<size_t>(n / (size_t(1) << 16), 1, size_t(hardwareThreads())));
    parallelFor(int64_t(n), threads, [&](int64_t begin, int64_t end) {
        for (size_t p = size_t(begin); p < size_t(end); ++p)
            for (size_t c = 0; c < 3; ++c) {
                const float linear = hdr.pixels[p * channels + (channels == 1 ? 0 : c)];
                store(p * 3 + c, steps.code(acesFilmNarkowicz(linear * exposure)));
            }
    });
}

}  // namespace

unsigned char srgbByte(float display) {
    return srgbByteSteps().code(display > 0.0f ? std::min(display, 1.0f) : 0.0f);  // NaN -> 0, as linearToSrgb
}

Image8 toneMapToSrgb8(const Image& hdr, float exposure) {
    Image8 out{hdr.width, hdr.height, 3, std::vector<unsigned char>(hdr.pixelCount() * 3)};
    toneMapBytes(hdr, exposure, [&](size_t i, unsigned char code) { out.pixels[i] = code; });
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
    float asFloat[256];
    for (int b = 0; b < 256; ++b) asFloat[b] = float(b) / 255.0f;
    toneMapBytes(hdr, exposure, [&](size_t i, unsigned char code) { out.pixels[i] = asFloat[code]; });
    return out;
}

Image toneMapToSrgbFloat(const Image& hdr, float exposure) {
    Image out(hdr.width, hdr.height, 3);
    toneMapEach(hdr, exposure, [&](size_t p, int c, float encoded) { out.pixels[p * 3 + size_t(c)] = encoded; });
    return out;
}

}  // namespace gbl
