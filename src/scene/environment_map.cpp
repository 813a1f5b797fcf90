#include "environment_map.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "error.h"
#include "file_io.h"
#include "image_io.h"
#include "memory_budget.h"

namespace gbl {
namespace {
constexpr float kPi = 3.14159265358979323846f;
}

// Equirectangular convention (identical in shaders/environment_map.glsl; keep them in step):
// world space is right-handed, +Y up, and the camera's default view is down -Z.
//   u = 0.5 + atan2(d.x, -d.z) / (2 pi)   -> u = 0.5 straight ahead (-Z), 0.75 at +X, 0.25 at -X,
//                                            0 / 1 behind (+Z), where the map's seam is
//   v = acos(clamp(d.y, -1, 1)) / pi      -> v = 0 at +Y (image row 0 is "up"), 1 at -Y
// `direction` must be unit length (atan2 does not care, acos does).
glm::vec2 directionToEquirectUv(glm::vec3 direction) {
    const float u = 0.5f + std::atan2(direction.x, -direction.z) / (2.0f * kPi);
    const float v = std::acos(std::clamp(direction.y, -1.0f, 1.0f)) / kPi;
    return {u, v};
}

// The exact inverse: phi = (u - 0.5) 2 pi around +Y from -Z towards +X, theta = v pi from +Y.
glm::vec3 equirectUvToDirection(glm::vec2 uv) {
    const float phi = (uv.x - 0.5f) * (2.0f * kPi);
    const float theta = uv.y * kPi;
    const float sinTheta = std::sin(theta);
    return {sinTheta * std::sin(phi), std::cos(theta), -sinTheta * std::cos(phi)};
}

// Texel (i, j) covers u in [i/W, (i+1)/W): its centre is at (i + 0.5) / W, as for a GPU sampler
// with repeat in u and clamp-to-edge in v; so CPU and GPU lookups agree.
glm::vec3 sampleEquirect(const Image& image, glm::vec3 direction) {
    const glm::vec2 uv = directionToEquirectUv(direction);
    if (image.empty() || !std::isfinite(uv.x) || !std::isfinite(uv.y)) return glm::vec3(0.0f);  // NaN in: no light
    const float x = uv.x * float(image.width) - 0.5f;
    const float y = uv.y * float(image.height) - 0.5f;
    const float x0f = std::floor(x), y0f = std::floor(y);
    const float fx = x - x0f, fy = y - y0f;
    const auto wrapX = [&](long i) { return int(((i % image.width) + image.width) % image.width); };
    const auto clampY = [&](long j) { return int(std::clamp(j, 0L, long(image.height - 1))); };
    const int xa = wrapX(long(x0f)), xb = wrapX(long(x0f) + 1);
    const int ya = clampY(long(y0f)), yb = clampY(long(y0f) + 1);
    const auto texel = [&](int tx, int ty) {
        if (image.channels < 3) return glm::vec3(image.at(tx, ty, 0));
        return glm::vec3(image.at(tx, ty, 0), image.at(tx, ty, 1), image.at(tx, ty, 2));
    };
    const glm::vec3 top = texel(xa, ya) * (1.0f - fx) + texel(xb, ya) * fx;
    const glm::vec3 bottom = texel(xa, yb) * (1.0f - fx) + texel(xb, yb) * fx;
    return top * (1.0f - fy) + bottom * fy;
}

void validateEnvironmentImage(const Image& image, const std::string& source) {
    const std::string size = std::to_string(image.width) + "x" + std::to_string(image.height);
    if (image.width != 2 * image.height || image.height <= 0)
        throwUserError(source + ": environment map is " + size +
                       "; an equirectangular map must be 2:1 (e.g. 1024x512)");
    if (image.height < 4)
        throwUserError(source + ": environment map is " + size +
                       "; an equirectangular map must be 2:1 and at least 8x4 (e.g. 1024x512)");
    if (image.channels < 1 || image.pixels.size() != image.pixelCount() * size_t(image.channels))
        throwUserError(source + ": environment map " + size + " has " + std::to_string(image.pixels.size()) +
                       " values for " + std::to_string(image.channels) + " channels; the image is inconsistent");
    // A NaN, Inf or clearly negative texel poisons every integral taken over the map (irradiance,
    // prefilter), so it is refused, not clamped: the user should know their map is broken. Tiny
    // negatives (lossy-compression ringing, see kEnvironmentRingingTolerance) pass, to be clamped.
    // Finite but huge values (3.4e38, an RGBE exponent of 255) overflow those integrals to Inf and
    // the renders to NaN, so values above kEnvironmentMaxValue are refused the same way.
    size_t bad = 0, first = 0;
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        const float value = image.pixels[i];
        if (std::isfinite(value) && value >= -kEnvironmentRingingTolerance && value <= kEnvironmentMaxValue) continue;
        if (bad++ == 0) first = i;
    }
    if (bad == 0) return;
    static const char* kChannelNames[] = {"R", "G", "B", "A"};
    const size_t channel = first % size_t(image.channels);
    const size_t pixel = first / size_t(image.channels);
    const std::string channelName = image.channels == 1 ? "Y"
                                    : image.channels <= 4 ? kChannelNames[channel]
                                                          : std::to_string(channel);
    char valueText[32];
    std::snprintf(valueText, sizeof valueText, "%.9g", double(image.pixels[first]));
    throwUserError(source + ": environment map has " + std::to_string(bad) +
                   " invalid values (NaN, Inf, below -1/64 or above 1e9); the first is at x=" + std::to_string(pixel % size_t(image.width)) +
                   ", y=" + std::to_string(pixel / size_t(image.width)) + ", channel " + channelName + ", value " +
                   std::string(valueText) + "; fix the map (e.g. clamp to [0, 1e9]) and export it again");
}

size_t clampEnvironmentRinging(Image& image) {
    size_t clamped = 0;
    for (float& value : image.pixels)
        if (value < 0.0f && value >= -kEnvironmentRingingTolerance) {
            value = 0.0f;
            ++clamped;
        }
    return clamped;
}

EnvironmentMap loadEnvironmentMap(const std::string& path) {
    // Beside the image (12 bytes a pixel), the map's texture on the device and its mips (16 bytes
    // and a third more) and the importance-sampling tables (a float a pixel, twice): checked from
    // the header, before the file is decoded.
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".hdr" && ext != ".exr") return {path, readEnvironmentFile(path)};  // refuses it, naming the fix
    const ImageFileInfo info = probeImageFile(path);
    requireMemory(double(info.width) * double(info.height) * (12.0 + 16.0 * 4.0 / 3.0 + 8.0),
                  escapeText(path) + ": an environment map of " + std::to_string(info.width) + "x" +
                      std::to_string(info.height) + " pixels",
                  "give a smaller map (e.g. 4096x2048 is plenty for the IBL), or raise GBL_MEMORY_BUDGET");
    EnvironmentMap map{path, readEnvironmentFile(path)};
    registerInput(path);  // no output may replace it (file_io.h)
    validateEnvironmentImage(map.image, path);
    map.clampedNegativeTexels = clampEnvironmentRinging(map.image);
    return map;
}

}  // namespace gbl
