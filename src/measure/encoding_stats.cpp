#include "encoding_stats.h"

#include "color_difference.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include <nlohmann/json.hpp>

#include "encodings.h"
#include "niagara_encodings.h"
#include "error.h"

namespace gbl {

namespace {

using glm::vec3;

const EncodingInfo& requireEncoding(std::string_view name, int bits, AttributeKind kind) {
    const EncodingInfo* info = findEncoding(name);
    if (!info)
        throwUserError("unknown encoding '" + std::string(name) + "' (known: " + knownEncodingNames() + ")");
    if (!encodingBitsValid(*info, bits))
        throwUserError("encoding '" + info->name + "': bits " + std::to_string(bits) + " outside " +
                       std::to_string(info->minBits) + ".." + std::to_string(info->maxBits));
    if (info->kind != kind)
        throwUserError("encoding '" + info->name + "' is a " + attributeKindName(info->kind) + " encoding, not " +
                       attributeKindName(kind));
    return *info;
}

struct Summary {
    double mean = 0.0, p99 = 0.0, max = 0.0;
};

Summary summarize(std::vector<double>& v) {
    Summary s;
    if (v.empty()) return s;
    double sum = 0.0;
    for (double x : v) {
        sum += x;
        s.max = std::max(s.max, x);
    }
    s.mean = sum / double(v.size());
    size_t k = std::min(v.size() - 1, size_t(std::ceil(0.99 * double(v.size()))) - 1);
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
    s.p99 = v[k];
    return s;
}

double uniform01(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

vec3 toVec3(glm::dvec3 d) { return vec3(float(d.x), float(d.y), float(d.z)); }

double maxAbsDiff(vec3 a, vec3 b) {
    return std::max({std::fabs(double(a.x) - double(b.x)), std::fabs(double(a.y) - double(b.y)),
                     std::fabs(double(a.z) - double(b.z))});
}

// A float -> float transform on top of unorm: (to code domain, back).
vec3 unormRoundTrip3(vec3 c, unsigned bits) {
    return vec3(enc::dequantizeUnorm(enc::quantizeUnorm(c.x, bits), bits),
                enc::dequantizeUnorm(enc::quantizeUnorm(c.y, bits), bits),
                enc::dequantizeUnorm(enc::quantizeUnorm(c.z, bits), bits));
}

std::vector<glm::vec3> syntheticImage(int width, int height, std::mt19937_64& rng) {
    const int block = 16;
    int bw = (width + block - 1) / block, bh = (height + block - 1) / block;
    std::vector<vec3> blocks(size_t(bw) * size_t(bh));
    for (vec3& b : blocks) b = vec3(float(uniform01(rng)), float(uniform01(rng)), float(uniform01(rng)));
    std::vector<vec3> img(size_t(width) * size_t(height));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float u = float(x) / float(std::max(1, width - 1)), v = float(y) / float(std::max(1, height - 1));
            vec3 ramp(u, v, 1.0f - 0.5f * (u + v));
            img[size_t(y) * size_t(width) + size_t(x)] =
                blocks[size_t(y / block) * size_t(bw) + size_t(x / block)] * 0.75f + ramp * 0.25f;
        }
    return img;
}

}  // namespace

// ---- colour science ------------------------------------------------------------------------

// One CIEDE2000 in the project: the metrics module's (src/image/color_difference.h), tested against
// Sharma, Wu & Dalal's 34 published pairs.
glm::dvec3 linearSrgbToLab(glm::dvec3 c) {
    const Lab lab = gbl::linearSrgbToLab(c.x, c.y, c.z);
    return {lab.L, lab.a, lab.b};
}

double deltaE2000(glm::dvec3 lab1, glm::dvec3 lab2) {
    return gbl::deltaE2000(Lab{lab1.x, lab1.y, lab1.z}, Lab{lab2.x, lab2.y, lab2.z});
}

double angleDegrees(glm::dvec3 a, glm::dvec3 b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * (180.0 / std::numbers::pi);
}

glm::dvec3 uniformSphere(double u, double v) {
    double z = 1.0 - 2.0 * u;
    double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    double phi = 2.0 * std::numbers::pi * v;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// ---- round trips -----------------------------------------------------------------------------

glm::vec3 roundTripNormal(std::string_view name, int bits, glm::vec3 n, glm::ivec2 pixel) {
    const EncodingInfo& info = requireEncoding(name, bits, AttributeKind::Normal);
    unsigned b = unsigned(bits);
    if (info.name == "normal_xyz") return enc::decodeNormalXyz(enc::encodeNormalXyz(n, b), b);
    if (info.name == "normal_bestfit") return enc::decodeNormalBestFit(enc::encodeNormalBestFit(n));
    if (info.name == "normal_xy_zsign") return enc::decodeNormalXyZSign(enc::encodeNormalXyZSign(n, b), b);
    if (info.name == "normal_spheremap") return enc::decodeNormalSpheremap(enc::encodeNormalSpheremap(n, b), b);
    if (info.name == "normal_stereographic")
        return enc::decodeNormalStereographic(enc::encodeNormalStereographic(n, b), b);
    if (info.name == "normal_octahedral") return enc::decodeNormalOctahedral(enc::encodeNormalOctahedral(n, b), b);
    if (info.name == "normal_octahedral_precise")
        return enc::decodeNormalOctahedralPrecise(enc::encodeNormalOctahedralPrecise(n, b), b);
    if (info.name == "normal_octahedral_bevy")
        return enc::decodeNormalOctahedralUnorm(enc::encodeNormalOctahedralBevy(n, b), b);
    if (info.name == "normal_octahedral_unity")
        return enc::decodeNormalOctahedralUnorm(enc::encodeNormalOctahedralUnity(n, b), b);
    if (info.name == "normal_octahedral_hdrp")
        return enc::decodeNormalOctahedralUnorm(enc::encodeNormalOctahedralHdrp(n, b), b);
    if (info.name == "normal_octahedral_dithered")
        return enc::decodeNormalOctahedralUnorm(enc::encodeNormalOctahedralDithered(n, b, pixel), b);
    // No sign bit: over the whole sphere, the half facing away (z < 0) comes back mirrored.
    if (info.name == "normal_xy_float16") return enc::decodeNormalXyFloat16(enc::encodeNormalXyFloat16(n));
    // HDRP's anisotropy: the tangent n stored against a normal perpendicular to it (read back
    // exactly, as a decoded normal would be), strength 1; the decode is an axis, so its sign is
    // taken from n (the direction metric measures the angle between lines).
    if (info.name == "anisotropy_angle_hdrp") {
        const glm::vec3 axis = std::fabs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
        const glm::vec3 normal = glm::normalize(glm::cross(n, axis));
        const glm::vec3 d = enc::decodeAnisotropyHdrp(enc::encodeAnisotropyHdrp(n, 1.0f, normal), normal);
        return glm::dot(d, n) < 0.0f ? -d : d;
    }
    // UE's bottom normal: n stored against a coat normal 10 degrees from it (a coat over a
    // normal-mapped base; the delta saturates for bottoms far from the top), read back exactly.
    if (info.name == "normal_octahedral_delta_ue") {
        const glm::vec3 axis = std::fabs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
        const glm::vec3 side = glm::normalize(glm::cross(n, axis));
        const glm::vec3 top = glm::normalize(n * 0.98480775f + side * 0.17364818f);  // cos, sin 10 deg
        return enc::decodeNormalOctahedralDeltaUe(enc::encodeNormalOctahedralDeltaUe(n, top, b), top, b);
    }
    throwUserError("encoding '" + info.name + "' has no normal round trip");
}

// Y through quantizeUnorm, chroma through quantizeChroma (the YCbCr family's midpoint quantiser).
glm::vec3 chromaRoundTrip3(glm::vec3 t, unsigned b) {
    return glm::vec3(enc::dequantizeUnorm(enc::quantizeUnorm(t.x, b), b),
                     enc::dequantizeChroma(enc::quantizeChroma(t.y, b), b),
                     enc::dequantizeChroma(enc::quantizeChroma(t.z, b), b));
}

glm::vec3 roundTripColor(std::string_view name, int bits, glm::vec3 c) {
    const EncodingInfo& info = requireEncoding(name, bits, AttributeKind::Color);
    unsigned b = unsigned(bits);
    if (info.name == "srgb8")
        return vec3(enc::decodeSrgb8(enc::encodeSrgb8(c.x)), enc::decodeSrgb8(enc::encodeSrgb8(c.y)),
                    enc::decodeSrgb8(enc::encodeSrgb8(c.z)));
    if (info.name == "ycbcr") return enc::yCbCrToRgb(chromaRoundTrip3(enc::rgbToYCbCr(c), b));
    if (info.name == "ycbcr_sqrt") return enc::yCbCrSqrtToRgb(chromaRoundTrip3(enc::rgbToYCbCrSqrt(c), b));
    if (info.name == "ycocg") return enc::yCoCgToRgb(unormRoundTrip3(enc::rgbToYCoCg(c), b));
    if (info.name == "luma") return vec3(enc::dequantizeUnorm(enc::quantizeUnorm(enc::lumaBt601(c), b), b));
    if (info.name == "gamma22")
        return vec3(enc::decodeGamma22(enc::encodeGamma22(c.x)), enc::decodeGamma22(enc::encodeGamma22(c.y)),
                    enc::decodeGamma22(enc::encodeGamma22(c.z)));
    if (info.name == "srgb8_fast_hdrp")
        return vec3(enc::decodeSrgb8FastHdrp(enc::encodeSrgb8FastHdrp(c.x)), enc::decodeSrgb8FastHdrp(enc::encodeSrgb8FastHdrp(c.y)),
                    enc::decodeSrgb8FastHdrp(enc::encodeSrgb8FastHdrp(c.z)));
    if (info.name == "float11_11_10")
        return vec3(enc::decodeFloat11(enc::encodeFloat11(c.x)), enc::decodeFloat11(enc::encodeFloat11(c.y)),
                    enc::decodeFloat10(enc::encodeFloat10(c.z)));
    if (info.name == "rgb9e5") return enc::decodeRgb9e5(enc::encodeRgb9e5(c));
    // Emissive alone (the tag only replaces an exact 0, which reads back 0).
    if (info.name == "float11_11_10_hdrp_ao_tag")
        return enc::decodeFloat111110HdrpAoTag(enc::encodeFloat111110HdrpAoTag(c, 1.0f));
    if (info.name == "emissive_albedo_ratio")
        return enc::decodeEmissiveAlbedoRatio(enc::encodeEmissiveAlbedoRatio(c, c, b), b, c);
    throwUserError("encoding '" + info.name + "' has no single-value colour round trip (it reads neighbours)");
}

float roundTripScalar(std::string_view name, int bits, float x) {
    const EncodingInfo& info = requireEncoding(name, bits, AttributeKind::Scalar);
    unsigned b = unsigned(bits);
    if (info.name == "unorm") return enc::dequantizeUnorm(enc::quantizeUnorm(x, b), b);
    if (info.name == "snorm") return enc::dequantizeSnorm(enc::quantizeSnorm(x, b), b);
    if (info.name == "float16") return enc::decodeFloat16(enc::encodeFloat16(x));
    if (info.name == "float11") return enc::decodeFloat11(enc::encodeFloat11(x));
    if (info.name == "float10") return enc::decodeFloat10(enc::encodeFloat10(x));
    if (info.name == "float32") return enc::decodeFloat32(enc::encodeFloat32(x));
    if (info.name == "depth24") return enc::dequantizeDepth24(enc::quantizeDepth24(x));
    if (info.name == "gloss")
        return enc::roughnessFromGloss(enc::dequantizeUnorm(enc::quantizeUnorm(enc::glossFromRoughness(x), b), b));
    if (info.name == "smoothness_cry")
        return enc::roughnessFromSmoothnessCry(
            enc::dequantizeUnorm(enc::quantizeUnorm(enc::smoothnessFromRoughnessCry(x), b), b));
    if (info.name == "cry_gloss_power") return enc::decodeCryGlossPower(enc::encodeCryGlossPower(x));
    if (info.name == "kz2_log_power") return enc::decodeKz2LogPower(enc::encodeKz2LogPower(x));
    if (info.name == "unorm_round_even") return enc::dequantizeUnorm(enc::quantizeUnormRoundEven(x, b), b);
    if (info.name == "coat_roughness_bevy") return enc::decodeCoatRoughnessBevy(enc::encodeCoatRoughnessBevy(x, b), b);
    if (info.name == "unorm_signed") return enc::dequantizeUnormSigned(enc::quantizeUnormSigned(x, b), b);
    if (info.name == "unorm_sqrt") return enc::decodeUnormSqrt(enc::encodeUnormSqrt(x));
    if (info.name == "reflectance_bevy_webgl2")
        return enc::specularFromReflectanceBevyWebgl2(
            enc::dequantizeUnorm(enc::quantizeUnorm(enc::reflectanceFromSpecular(x), b), b));
    if (info.name == "reflectance")
        return enc::specularFromReflectance(
            enc::dequantizeUnorm(enc::quantizeUnorm(enc::reflectanceFromSpecular(x), b), b));
    throwUserError("encoding '" + info.name + "' has no scalar round trip");
}

std::vector<glm::vec3> roundTripChromaCheckerboard(std::string_view name, int bits, const std::vector<glm::vec3>& rgb,
                                                   int width, int height) {
    const EncodingInfo& info = requireEncoding(name, bits, AttributeKind::Color);
    bool ycocg = info.name == "ycocg_checkerboard";
    if (!ycocg && info.name != "ycbcr_checkerboard")
        throwUserError("encoding '" + info.name + "' is not a checkerboard encoding");
    if (width <= 0 || height <= 0 || rgb.size() != size_t(width) * size_t(height))
        throwUserError("roundTripChromaCheckerboard: image size does not match width*height");
    unsigned b = unsigned(bits);
    // Encode: each pixel keeps (Y, one chroma), as the G-buffer would store them.
    std::vector<glm::vec2> stored(rgb.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            size_t i = size_t(y) * size_t(width) + size_t(x);
            vec3 t = ycocg ? enc::rgbToYCoCg(rgb[i]) : enc::rgbToYCbCr(rgb[i]);
            float chroma = enc::chromaForPixel(glm::ivec2(x, y), glm::vec2(t.y, t.z));
            stored[i] = glm::vec2(enc::dequantizeUnorm(enc::quantizeUnorm(t.x, b), b),
                                  ycocg ? enc::dequantizeUnorm(enc::quantizeUnorm(chroma, b), b)
                                        : enc::dequantizeChroma(enc::quantizeChroma(chroma, b), b));
        }
    // Mirrored borders (-1 -> 1, n -> n-2) keep the checkerboard parity of the missing neighbour.
    auto mirror = [](int i, int n) { return n == 1 ? 0 : i < 0 ? -i : i >= n ? 2 * n - 2 - i : i; };
    auto at = [&](int x, int y) {
        return stored[size_t(mirror(y, height)) * size_t(width) + size_t(mirror(x, width))];
    };
    std::vector<vec3> out(rgb.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            glm::vec2 c = at(x, y), px = at(x + 1, y), nx = at(x - 1, y), py = at(x, y + 1), ny = at(x, y - 1);
            glm::vec2 ch = enc::reconstructChroma(glm::ivec2(x, y), c.x, c.y, glm::vec4(px.x, nx.x, py.x, ny.x),
                                                  glm::vec4(px.y, nx.y, py.y, ny.y));
            vec3 t(c.x, ch.x, ch.y);
            out[size_t(y) * size_t(width) + size_t(x)] = ycocg ? enc::yCoCgToRgb(t) : enc::yCbCrToRgb(t);
        }
    return out;
}

// ---- measurement -----------------------------------------------------------------------------

EncodingStats measureEncoding(std::string_view name, int bits, int samples, std::uint64_t seed) {
    const EncodingInfo* info = findEncoding(name);
    if (!info) throwUserError("unknown encoding '" + std::string(name) + "' (known: " + knownEncodingNames() + ")");
    requireEncoding(name, bits, info->kind);
    if (samples <= 0) throwUserError("encoding stats: samples must be > 0 (got " + std::to_string(samples) + ")");
    EncodingStats s;
    s.encoding = info->name;
    s.bits = bits;
    s.totalBits = encodingTotalBits(*info, bits);
    s.kind = info->kind;
    s.samples = samples;
    std::mt19937_64 rng(seed);
    std::vector<double> err(size_t(samples), 0.0);
    std::vector<double> de;
    if (info->kind == AttributeKind::Normal) {
        s.domain = info->reads == "coat_normal" ? "uniform unit sphere, under a coat normal 10 deg away"
                                                : "uniform unit sphere";
        s.unit = "deg";
        for (size_t i = 0; i < err.size(); ++i) {
            double& e = err[i];
            double u = uniform01(rng), v = uniform01(rng);
            glm::dvec3 n = uniformSphere(u, v);
            // Sample i at pixel (i mod 256, i / 256): the dithered encodings' noise varies over them.
            vec3 d = roundTripNormal(info->name, bits, toVec3(n), glm::ivec2(int(i % 256), int(i / 256)));
            e = angleDegrees(n, glm::dvec3(d));
        }
    } else if (info->kind == AttributeKind::Color) {
        s.unit = "abs";
        s.hasDeltaE = true;
        de.resize(size_t(samples));
        std::vector<vec3> in, out;
        if (info->needsNeighbours) {
            int w = std::max(1, int(std::ceil(std::sqrt(double(samples)))));
            int h = std::max(1, (samples + w - 1) / w);
            s.domain = "synthetic image " + std::to_string(w) + "x" + std::to_string(h) +
                       ": 16x16 random flat blocks, 3:1 with a smooth ramp";
            in = syntheticImage(w, h, rng);
            out = roundTripChromaCheckerboard(info->name, bits, in, w, h);
            in.resize(size_t(samples));
            out.resize(size_t(samples));
        } else {
            s.domain = "uniform [0,1]^3, linear sRGB";
            in.resize(size_t(samples));
            out.resize(size_t(samples));
            for (size_t i = 0; i < in.size(); ++i) {
                in[i] = vec3(float(uniform01(rng)), float(uniform01(rng)), float(uniform01(rng)));
                out[i] = roundTripColor(info->name, bits, in[i]);
            }
        }
        for (size_t i = 0; i < in.size(); ++i) {
            err[i] = maxAbsDiff(in[i], out[i]);
            de[i] = deltaE2000(linearSrgbToLab(glm::dvec3(in[i])), linearSrgbToLab(glm::dvec3(out[i])));
        }
    } else {
        bool snorm = info->name == "snorm";
        s.domain = snorm ? "uniform [-1,1]" : "uniform [0,1]";
        s.unit = "abs";
        for (double& e : err) {
            double u = uniform01(rng);
            float x = float(snorm ? 2.0 * u - 1.0 : u);
            e = std::fabs(double(roundTripScalar(info->name, bits, x)) - double(x));
        }
    }
    Summary a = summarize(err);
    s.meanError = a.mean;
    s.p99Error = a.p99;
    s.maxError = a.max;
    if (s.hasDeltaE) {
        Summary d = summarize(de);
        s.meanDeltaE = d.mean;
        s.p99DeltaE = d.p99;
        s.maxDeltaE = d.max;
    }
    return s;
}

std::vector<EncodingStats> measureAllEncodings(int samples, std::uint64_t seed) {
    std::vector<EncodingStats> all;
    for (const EncodingInfo& e : listEncodings()) all.push_back(measureEncoding(e.name, e.defaultBits, samples, seed));
    return all;
}

std::string formatEncodingStatsTable(const std::vector<EncodingStats>& stats) {
    std::string out;
    char line[256];
    std::snprintf(line, sizeof line, "%-26s %4s %5s %-6s %4s %11s %11s %11s %9s %9s %9s\n", "encoding", "bits", "total",
                  "kind", "unit", "mean", "p99", "max", "dE00 mean", "dE00 p99", "dE00 max");
    out += line;
    for (const EncodingStats& s : stats) {
        std::snprintf(line, sizeof line, "%-26s %4d %5d %-6s %4s %11.4g %11.4g %11.4g", s.encoding.c_str(), s.bits,
                      s.totalBits, attributeKindName(s.kind), s.unit.c_str(), s.meanError, s.p99Error, s.maxError);
        out += line;
        if (s.hasDeltaE) {
            std::snprintf(line, sizeof line, " %9.4f %9.4f %9.4f", s.meanDeltaE, s.p99DeltaE, s.maxDeltaE);
            out += line;
        }
        out += "\n";
    }
    return out;
}

nlohmann::json encodingStatsToJson(const EncodingStats& s) {
    nlohmann::json j = {{"encoding", s.encoding}, {"bits", s.bits},       {"total_bits", s.totalBits},
                        {"kind", attributeKindName(s.kind)},           {"samples", s.samples},
                        {"domain", s.domain},     {"unit", s.unit},       {"mean", s.meanError},
                        {"p99", s.p99Error},      {"max", s.maxError}};
    if (s.hasDeltaE) j["delta_e2000"] = {{"mean", s.meanDeltaE}, {"p99", s.p99DeltaE}, {"max", s.maxDeltaE}};
    return j;
}

nlohmann::json encodingStatsToJson(const std::vector<EncodingStats>& stats) {
    nlohmann::json j = nlohmann::json::array();
    for (const EncodingStats& s : stats) j.push_back(encodingStatsToJson(s));
    return j;
}

}  // namespace gbl
