#pragma once
// Measures what one encoding loses, Cigolle-style: encode + decode N samples through the C++
// mirror (src/encoding/encodings.h) and report mean / p99 / max error (`gbufferlab encodings`).
//
// Sample domains (fixed-seed std::mt19937_64, doubles from the top 53 bits):
//   normals: uniform on the unit sphere (Archimedes: z = 1 - 2u, phi = 2 pi v, r = sqrt(1 - z^2)),
//            error = angle between input and decoded direction, in degrees (atan2(|a x b|, a.b)
//            in double);
//   colours: uniform in [0,1]^3, read as linear sRGB; error = max abs channel error, plus
//            CIEDE2000 (Sharma, Wu, Dalal 2005) between the CIELAB (D65) of input and output;
//            the checkerboard encodings need neighbours and are measured on a synthetic image
//            instead: 16x16-pixel flat blocks of random colour blended 3:1 with a smooth ramp;
//   scalars: uniform in [0,1] (snorm: [-1,1]); error = abs difference.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "encoding_registry.h"

namespace gbl {

struct EncodingStats {
    std::string encoding;
    int bits = 0;          // bits per code
    int totalBits = 0;     // per encoded value (codeCount * bits + extraBits)
    AttributeKind kind = AttributeKind::Scalar;
    int samples = 0;
    std::string domain;    // what was sampled
    std::string unit;      // "deg" (normals) or "abs"
    double meanError = 0.0;
    double p99Error = 0.0;
    double maxError = 0.0;
    bool hasDeltaE = false;  // colours only: CIEDE2000
    double meanDeltaE = 0.0;
    double p99DeltaE = 0.0;
    double maxDeltaE = 0.0;
};

// Throws UserError for an unknown name or bits outside the registry's range.
EncodingStats measureEncoding(std::string_view name, int bits, int samples = 1 << 20, std::uint64_t seed = 1);

// Every registered encoding at its default bits.
std::vector<EncodingStats> measureAllEncodings(int samples = 1 << 20, std::uint64_t seed = 1);

// A fixed-width text table, one row per entry, with a header line.
std::string formatEncodingStatsTable(const std::vector<EncodingStats>& stats);

// {"encoding":..., "bits":..., "total_bits":..., "kind":..., "samples":..., "domain":...,
//  "unit":..., "mean":..., "p99":..., "max":..., and for colours "delta_e2000": {mean,p99,max}}.
nlohmann::json encodingStatsToJson(const EncodingStats& stats);
nlohmann::json encodingStatsToJson(const std::vector<EncodingStats>& stats);

// Encode + decode one value through the C++ mirror. Kind must match (normal / colour / scalar);
// the checkerboard colour encodings have no single-value round trip (throw). `pixel` feeds the
// dithered encodings' noise (normal_octahedral_dithered). emissive_albedo_ratio round-trips rgb as
// an emissive whose albedo is rgb itself (the hue it keeps), decoded with that exact albedo.
glm::vec3 roundTripNormal(std::string_view name, int bits, glm::vec3 n, glm::ivec2 pixel = {0, 0});
glm::vec3 roundTripColor(std::string_view name, int bits, glm::vec3 rgb);
float roundTripScalar(std::string_view name, int bits, float x);

// Checkerboard encodings over a whole image (row-major, width*height); missing neighbours at the
// borders are fetched mirrored (x = -1 reads x = 1), which keeps the checkerboard parity.
std::vector<glm::vec3> roundTripChromaCheckerboard(std::string_view name, int bits, const std::vector<glm::vec3>& rgb,
                                                   int width, int height);

// Colour science for the colour errors.
glm::dvec3 linearSrgbToLab(glm::dvec3 rgb);             // CIELAB, D65 white, sRGB primaries
double deltaE2000(glm::dvec3 lab1, glm::dvec3 lab2);     // CIEDE2000, kL = kC = kH = 1
double angleDegrees(glm::dvec3 a, glm::dvec3 b);         // in [0, 180]
glm::dvec3 uniformSphere(double u, double v);            // u, v in [0,1)

}  // namespace gbl
