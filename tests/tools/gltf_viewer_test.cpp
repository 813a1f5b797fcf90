// tools/gltf-viewer/render.mjs, the Khronos glTF Sample Viewer as a headless float renderer, held
// to the glTF specification's BRDF computed here from its text, not from either renderer:
//   - a unit quad (base colour 0.5, metallic 0, roughness 1) lit straight on by one directional
//     light and seen by a camera straight on gives, in every pixel of its middle, glTF 2.0
//     Appendix B's dielectric_brdf = mix(diffuse_brdf, specular_brdf(roughness^2), F) with
//     F = 0.04 + 0.96 (1 - |V.H|)^5, D = a^2 / (pi ((N.H)^2 (a^2 - 1) + 1)^2) and the
//     height-correlated V = 1 / (2 (|N.V| sqrt(a^2 + (1 - a^2)(N.L)^2) + |N.L| sqrt(a^2 + (1 - a^2)(N.V)^2))),
//     times the light's illuminance (KHR_lights_punctual: intensity in lux) times N.L, with V
//     the pixel's own view direction; relative tolerance 1e-5 (SwiftShader's float32 shading and
//     the interpolated world position; measured: 2.3e-7 at worst over 484 pixels), and exposure
//     scales it exactly;
//   - the same quad with KHR_materials_sheen (colour 1, roughness 1) gives f_sheen + base x
//     min(1 - E(N.V), 1 - E(N.L)) (the KHR_materials_sheen README's albedo scaling), E read
//     bilinearly from an 8-bit table of the Charlie lobe's albedo integrated here by brute
//     force: this fails if the viewer renders sheen without the table (its 1.1.0 loader never
//     uploads it: E = 0, 18 % brighter) or with a wrong one; tolerance 0.5 % (an 8-bit entry
//     rounded the other way moves E by 1/255; measured: 2.8e-5 at worst over 484 pixels);
//   - one texture as both sheenColorTexture and sheenRoughnessTexture (SheenCloth's case): the
//     colour is the texel decoded by the sRGB curve (IEC 61966-2-1, computed here), which holds
//     only because scene_copy.mjs splits such a texture in two (the viewer alone reads it linear);
//   - a point light and a spot light with a range match KHR_lights_punctual's falloffs;
//   - the served table itself (sheen_lut.mjs) against that brute-force integral;
//   - background pixels are 0 and masked out; bad job files give one line and exit 2, a frame
//     that does not come within GLTF_VIEWER_TIMEOUT_S one line and exit 4, and no output.
// Skipped when Chromium, Node or the pinned npm package is absent (scripts/setup.sh --tests
// installs them). 22 s on the 2-core machine at load 5 (ctest -R gltf_viewer_test, 6 renders).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <sys/wait.h>
#include <vector>

#include <nlohmann/json.hpp>

#include "image_io.h"
#include "pfm_io.h"
#include "temp_dir.h"

namespace gbl {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const fs::path kTool = fs::path(GBL_SOURCE_DIR) / "tools" / "gltf-viewer";
constexpr double kPi = 3.14159265358979323846;

struct TempDir : test::TempDir {
    TempDir() : test::TempDir("gbl_gltf_viewer_") { keep = std::getenv("GBL_KEEP_VIEWER") != nullptr; }
};

std::string quoted(const std::string& s) {
    std::string out = "'";
    for (char ch : s) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return out + "'";
}

#define REQUIRE_VIEWER()                                                                                       \
    do {                                                                                                       \
        if (!fs::exists("/usr/bin/chromium")) GTEST_SKIP() << "/usr/bin/chromium is absent (scripts/setup.sh --tests)"; \
        if (std::system("command -v node >/dev/null 2>&1") != 0) GTEST_SKIP() << "node is absent (scripts/setup.sh --tests)"; \
        if (!fs::exists(kTool / "node_modules/@khronosgroup/gltf-viewer/package.json"))                    \
            GTEST_SKIP() << "the Sample Viewer's npm package is not installed (scripts/setup.sh --tests)";   \
    } while (0)

struct ToolRun {
    int exitCode = -1;
    std::string stderrText;
};

ToolRun node(const fs::path& dir, const std::string& args, const std::string& env = "") {
    const fs::path err = dir / "stderr.txt";
    const int status = std::system((env + " node " + args + " > /dev/null 2> " + quoted(err.string())).c_str());
    ToolRun r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.stderrText = test::readFile(err);
    return r;
}

ToolRun render(const fs::path& dir, const json& job, const std::string& name = "job.json") {
    test::writeFile(dir / name, job.dump(1));
    return node(dir, quoted((kTool / "render.mjs").string()) + " " + quoted((dir / name).string()));
}

// A 2 x 2 quad in the z = 0 plane facing +Z, its buffer in a .bin file beside it (a relative URI,
// served from the model's folder). With `texture`, also TEXCOORD_0 and glTF texture 0 (that image,
// tex.png, the default sampler).
void writeQuad(const fs::path& dir, const json& material, const Image8* texture = nullptr) {
    const std::array<float, 12> pos = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const std::array<float, 12> nrm = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const std::array<uint16_t, 6> idx = {0, 1, 2, 0, 2, 3};
    const std::array<float, 8> uv = {0, 1, 1, 1, 1, 0, 0, 0};
    std::string bin(reinterpret_cast<const char*>(pos.data()), 48);
    bin += std::string(reinterpret_cast<const char*>(nrm.data()), 48);
    bin += std::string(reinterpret_cast<const char*>(idx.data()), 12);
    if (texture) bin += std::string(reinterpret_cast<const char*>(uv.data()), 32);
    test::writeFile(dir / "quad.bin", bin);
    json g = {{"asset", {{"version", "2.0"}}},
              {"scene", 0},
              {"scenes", {{{"nodes", {0}}}}},
              {"nodes", {{{"mesh", 0}}}},
              {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}, {"material", 0}}}}}}},
              {"materials", {material}},
              {"buffers", {{{"byteLength", 108}, {"uri", "quad.bin"}}}},
              {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                               {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
                               {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 12}}}},
              {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                              {"min", {-1, -1, 0}}, {"max", {1, 1, 0}}},
                             {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                             {{"bufferView", 2}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}}};
    if (material.contains("extensions")) g["extensionsUsed"] = {"KHR_materials_sheen"};
    if (texture) {
        writePng((dir / "tex.png").string(), *texture);
        g["buffers"][0]["byteLength"] = 140;
        g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 108}, {"byteLength", 32}});
        g["accessors"].push_back({{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}});
        g["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 3;
        g["textures"] = {{{"source", 0}}};
        g["images"] = {{{"uri", "tex.png"}}};
    }
    test::writeFile(dir / "quad.gltf", g.dump());
}

json baseMaterial() {
    return {{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}};
}

constexpr int kW = 64, kH = 36;
constexpr double kYfov = 0.8, kEyeZ = 3.0, kLux = 3.0;

json quadJob(double exposure = 1.0) {
    return {{"gltf", "quad.gltf"},
            {"width", kW},
            {"height", kH},
            {"camera", {{"camera_to_world", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, kEyeZ, 1}},
                        {"yfov", kYfov}, {"znear", 0.05}, {"zfar", 100.0}}},
            {"lights", {{{"type", "directional"}, {"color", {1, 1, 1}}, {"intensity", kLux}, {"direction", {0, 0, -1}}}}},
            {"exposure", exposure},
            {"ibl", nullptr},
            {"output", "viewer.pfm"}};
}

// Where the pixel centre's ray from the eye (0, 0, 3), looking down -Z, meets z = 0.
std::array<double, 2> hit(int x, int yTopDown) {
    const double t = std::tan(kYfov / 2);
    const double nx = (2.0 * (x + 0.5) / kW - 1.0) * t * double(kW) / kH;
    const double ny = (1.0 - 2.0 * (yTopDown + 0.5) / kH) * t;
    return {nx * kEyeZ, ny * kEyeZ};
}

// The angles at the quad's point (px, py, 0) under the eye, with N = L = +Z: V from the point to the
// eye, H between V and L.
struct HeadOn {
    double NdotV, NdotH, VdotH;
};
HeadOn headOn(double px, double py) {
    const double vx = -px, vy = -py, vz = kEyeZ, vl = std::sqrt(vx * vx + vy * vy + vz * vz);
    const double NdotV = vz / vl;
    const double hx = vx / vl, hy = vy / vl, hz = NdotV + 1.0, hl = std::sqrt(hx * hx + hy * hy + hz * hz);
    return {NdotV, hz / hl, (hx * vx / vl + hy * vy / vl + hz * NdotV) / hl};
}

struct Frame {
    Image rgb;
    std::vector<unsigned char> mask;  // rows top to bottom
};

Frame readFrame(const fs::path& dir) {
    Frame f;
    f.rgb = readPfm((dir / "viewer.pfm").string());
    const std::string pgm = test::readFile(dir / "viewer.mask.pgm");
    const std::string header = "P5\n" + std::to_string(kW) + " " + std::to_string(kH) + "\n255\n";
    EXPECT_EQ(pgm.substr(0, header.size()), header);
    EXPECT_EQ(pgm.size(), header.size() + size_t(kW * kH));
    f.mask.assign(pgm.begin() + std::min(header.size(), pgm.size()), pgm.end());
    f.mask.resize(size_t(kW * kH));
    return f;
}

// glTF 2.0 Appendix B, dielectric (metallic 0): mix(diffuse_brdf, specular_brdf(a), F).
double gltfDielectricBrdf(double baseColor, double roughness, double NdotL, double NdotV, double NdotH, double VdotH) {
    const double a = roughness * roughness, a2 = a * a;
    const double F = 0.04 + 0.96 * std::pow(1.0 - std::fabs(VdotH), 5.0);
    const double D = a2 / (kPi * std::pow(NdotH * NdotH * (a2 - 1.0) + 1.0, 2.0));
    const double Vis = 1.0 / (2.0 * (NdotV * std::sqrt(a2 + (1.0 - a2) * NdotL * NdotL) +
                                     NdotL * std::sqrt(a2 + (1.0 - a2) * NdotV * NdotV)));
    return (1.0 - F) * baseColor / kPi + F * Vis * D;
}

// KHR_materials_sheen README: Charlie D (alphaG = r^2, as the Sample Viewer and Filament take it;
// the README writes alphaG = r, the same at r = 1, the roughness used here) and Conty & Kulla's
// visibility with the README's lambda fit.
double charlieLambda(double cosTheta, double alphaG) {
    const double s = (1 - alphaG) * (1 - alphaG);
    auto l = [&](double x) {
        auto mix = [&](double a, double b) { return a + (b - a) * s; };
        return mix(21.5473, 25.3245) / (1 + mix(3.82987, 3.32435) * std::pow(x, mix(0.19823, 0.16801))) +
               mix(-1.97760, -1.27393) * x + mix(-4.32054, -4.85967);
    };
    return std::fabs(cosTheta) < 0.5 ? std::exp(l(cosTheta)) : std::exp(2 * l(0.5) - l(1 - cosTheta));
}
double sheenBrdf(double r, double NdotL, double NdotV, double NdotH) {
    const double alphaG = std::max(r, 1e-6) * std::max(r, 1e-6);
    const double sin2h = std::max(1 - NdotH * NdotH, 0.0);
    const double D = (2 + 1 / alphaG) * std::pow(sin2h, 0.5 / alphaG) / (2 * kPi);
    const double V = 1 / ((1 + charlieLambda(NdotV, alphaG) + charlieLambda(NdotL, alphaG)) * 4 * NdotV * NdotL);
    return D * std::clamp(V, 0.0, 1.0);  // the viewer clamps V to [0, 1] (its brdf.glsl, V_Sheen)
}

// E(mu, r) = integral of sheenBrdf N.L over the hemisphere, by brute force: a uniform grid in
// (cos theta_L, phi) over the whole circle, no symmetry used (sheen_lut.mjs integrates over
// t = sqrt(N.L) and half the circle).
double sheenAlbedoBrute(double mu, double r, int n = 1024) {
    const double vx = std::sqrt(1 - mu * mu), vz = mu;
    double sum = 0;
    for (int a = 0; a < n; ++a) {
        const double cl = (a + 0.5) / n, sl = std::sqrt(1 - cl * cl);
        for (int b = 0; b < 2 * n; ++b) {
            const double phi = (b + 0.5) / (2 * n) * 2 * kPi;
            const double hx = vx + sl * std::cos(phi), hy = sl * std::sin(phi), hz = vz + cl;
            const double NdotH = hz / std::sqrt(hx * hx + hy * hy + hz * hz);
            sum += sheenBrdf(r, cl, mu, NdotH) * cl;
        }
    }
    return sum * (1.0 / n) * (2 * kPi / (2 * n));
}

TEST(GltfViewer, LambertQuadMatchesTheSpecificationsBrdf) {
    REQUIRE_VIEWER();
    TempDir dir;
    writeQuad(dir.path, baseMaterial());
    const ToolRun run = render(dir.path, quadJob());
    ASSERT_EQ(run.exitCode, 0) << run.stderrText;
    EXPECT_EQ(run.stderrText, "");
    const Frame f = readFrame(dir.path);
    ASSERT_EQ(f.rgb.width, kW);
    ASSERT_EQ(f.rgb.height, kH);
    int checked = 0, background = 0;
    double worst = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const auto [px, py] = hit(x, y);
            const unsigned char m = f.mask[size_t(y) * kW + x];
            if (std::max(std::fabs(px), std::fabs(py)) > 1.1) {  // clear of the quad's edge
                EXPECT_EQ(m, 0) << x << "," << y;
                for (int c = 0; c < 3; ++c) EXPECT_EQ(f.rgb.at(x, y, c), 0.0f) << x << "," << y;
                ++background;
                continue;
            }
            if (std::max(std::fabs(px), std::fabs(py)) > 0.8) continue;
            EXPECT_EQ(m, 255) << x << "," << y;
            const auto [NdotV, NdotH, VdotH] = headOn(px, py);
            const double expected = gltfDielectricBrdf(0.5, 1.0, 1.0, NdotV, NdotH, VdotH) * kLux * 1.0;
            for (int c = 0; c < 3; ++c) {
                const double rel = std::fabs(f.rgb.at(x, y, c) / expected - 1.0);
                worst = std::max(worst, rel);
                EXPECT_LT(rel, 1e-5) << "pixel " << x << "," << y << " channel " << c << ": viewer " << f.rgb.at(x, y, c)
                                     << ", glTF Appendix B " << expected;
            }
            ++checked;
        }
    EXPECT_GT(checked, 300);
    EXPECT_GT(background, 500);
    std::printf("Lambert quad: %d pixels within %.2g of Appendix B (relative)\n", checked, worst);

    // Exposure is a plain factor on the linear radiance.
    const ToolRun twice = render(dir.path, quadJob(2.0));
    ASSERT_EQ(twice.exitCode, 0) << twice.stderrText;
    const Frame g = readFrame(dir.path);
    for (size_t i = 0; i < f.rgb.pixels.size(); ++i) ASSERT_EQ(g.rgb.pixels[i], 2.0f * f.rgb.pixels[i]) << i;
}

// KHR_lights_punctual README: a point or spot light's illuminance at distance d is
// intensity / d^2, windowed by max(min(1 - (d / range)^4, 1), 0) when range > 0 ("Range
// Property"); a spot's by the squared ramp saturate(cd * scale + offset)^2 with
// scale = 1 / max(0.001, cos(inner) - cos(outer)), offset = -cos(outer) scale ("Inner and Outer
// Cone Angles" reference code), cd = the cosine between the spot's direction and light-to-point.
TEST(GltfViewer, PointAndSpotLightsMatchKhrLightsPunctual) {
    REQUIRE_VIEWER();
    TempDir dir;
    writeQuad(dir.path, baseMaterial());
    struct Light {
        std::array<double, 3> pos, dir;
        double intensity, range, inner, outer;
        bool spot;
    };
    const std::vector<Light> lights = {{{0.5, 0.3, 1.5}, {0, 0, 0}, 2.0, 0.0, 0, 0, false},
                                       {{-0.3, -0.2, 2.0}, {0.1, 0.05, -1.0}, 4.0, 2.5, 0.15, 0.4, true}};
    json job = quadJob();
    job["lights"] = json::array();
    for (const Light& l : lights) {
        json j = {{"type", l.spot ? "spot" : "point"}, {"color", {1, 1, 1}}, {"intensity", l.intensity},
                  {"position", l.pos}, {"range", l.range}};
        if (l.spot) j.update({{"direction", l.dir}, {"inner_cone_angle", l.inner}, {"outer_cone_angle", l.outer}});
        job["lights"].push_back(j);
    }
    const ToolRun run = render(dir.path, job);
    ASSERT_EQ(run.exitCode, 0) << run.stderrText;
    const Frame f = readFrame(dir.path);
    int checked = 0;
    double worst = 0, worstAbs = 0, peak = 0;
    std::vector<double> expectedAt(size_t(kW * kH), -1.0);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const auto [px, py] = hit(x, y);
            if (std::max(std::fabs(px), std::fabs(py)) > 0.9) continue;
            const std::array<double, 3> v = {-px, -py, kEyeZ};
            const double vl = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            const double NdotV = v[2] / vl;
            double expected = 0;
            for (const Light& l : lights) {
                const std::array<double, 3> toL = {l.pos[0] - px, l.pos[1] - py, l.pos[2]};
                const double d = std::sqrt(toL[0] * toL[0] + toL[1] * toL[1] + toL[2] * toL[2]);
                const std::array<double, 3> L = {toL[0] / d, toL[1] / d, toL[2] / d};
                double e = l.intensity / (d * d);
                if (l.range > 0) e *= std::clamp(1 - std::pow(d / l.range, 4), 0.0, 1.0);
                if (l.spot) {
                    const double dl = std::sqrt(l.dir[0] * l.dir[0] + l.dir[1] * l.dir[1] + l.dir[2] * l.dir[2]);
                    const double cd = -(l.dir[0] * L[0] + l.dir[1] * L[1] + l.dir[2] * L[2]) / dl;
                    const double scale = 1 / std::max(0.001, std::cos(l.inner) - std::cos(l.outer));
                    e *= std::pow(std::clamp(cd * scale - std::cos(l.outer) * scale, 0.0, 1.0), 2);
                }
                std::array<double, 3> h = {L[0] + v[0] / vl, L[1] + v[1] / vl, L[2] + NdotV};
                const double hl = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                const double NdotH = h[2] / hl, VdotH = (h[0] * v[0] + h[1] * v[1] + h[2] * v[2]) / (hl * vl);
                expected += gltfDielectricBrdf(0.5, 1.0, L[2], NdotV, NdotH, VdotH) * e * L[2];
            }
            expectedAt[size_t(y) * kW + x] = expected;
            peak = std::max(peak, expected);
            ++checked;
        }
    // Not float precision here: SwiftShader's normalize and pow are approximate (measured against
    // this double-precision evaluation: the point light alone 3.3e-4 relative at worst, 1.3e-4
    // median, always low; the spot's ramp, steep at its cone edge (1 / (cos 0.15 - cos 0.4) = 14.8
    // per unit of cosine), turns a ~1e-4 error of the cosine into 4e-5 of the peak there). So:
    // 1e-3 relative plus 1e-4 of the frame's peak. A wrong falloff (1/d instead of 1/d^2, no range
    // window, a linear instead of squared ramp, a cone twice as wide) is off by far more.
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const double expected = expectedAt[size_t(y) * kW + x];
            if (expected < 0) continue;
            const double got = f.rgb.at(x, y, 1);
            EXPECT_NEAR(got, expected, 1e-3 * expected + 1e-4 * peak) << "pixel " << x << "," << y;
            worstAbs = std::max(worstAbs, std::fabs(got - expected) / peak);
            if (expected > 0.05 * peak) worst = std::max(worst, std::fabs(got / expected - 1));
        }
    EXPECT_GT(checked, 500);
    std::printf("point + spot: %d pixels; worst %.2g relative (above 5 %% of the peak), %.2g of the peak absolute\n",
                checked, worst, worstAbs);
}

// The 8-bit table as the viewer samples it: texel centres (i + 0.5) / 32, bilinear, clamp to edge.
struct SheenTable {
    std::vector<double> e;  // 8-bit values / 255, [row = roughness][col = N.V]
    double at(double mu, double r) const {
        auto coord = [](double v) { return std::clamp(v * 32 - 0.5, 0.0, 31.0); };
        const double fx = coord(mu), fy = coord(r);
        const int x0 = int(fx), y0 = int(fy), x1 = std::min(x0 + 1, 31), y1 = std::min(y0 + 1, 31);
        const double tx = fx - x0, ty = fy - y0;
        auto v = [&](int x, int y) { return e[size_t(y) * 32 + x]; };
        return (v(x0, y0) * (1 - tx) + v(x1, y0) * tx) * (1 - ty) + (v(x0, y1) * (1 - tx) + v(x1, y1) * tx) * ty;
    }
};

TEST(GltfViewer, SheenQuadUsesTheSheenAlbedoTable) {
    REQUIRE_VIEWER();
    TempDir dir;
    json material = baseMaterial();
    material["extensions"] = {{"KHR_materials_sheen", {{"sheenColorFactor", {1.0, 1.0, 1.0}}, {"sheenRoughnessFactor", 1.0}}}};
    writeQuad(dir.path, material);
    const ToolRun run = render(dir.path, quadJob());
    ASSERT_EQ(run.exitCode, 0) << run.stderrText;
    const Frame f = readFrame(dir.path);
    // The pixels below see N.V >= 0.9, so only the table's last row (roughness 31.5/32, reached
    // by clamping at r = 1) and its last columns matter; those entries by brute force, 8-bit.
    SheenTable table;
    table.e.assign(32 * 32, -1.0);
    for (int col = 27; col < 32; ++col) table.e[31 * 32 + col] = std::round(sheenAlbedoBrute((col + 0.5) / 32, 31.5 / 32, 512) * 255) / 255;
    int checked = 0;
    double worst = 0, withoutTable = 1;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const auto [px, py] = hit(x, y);
            if (std::max(std::fabs(px), std::fabs(py)) > 0.8) continue;
            const auto [NdotV, NdotH, VdotH] = headOn(px, py);
            if (NdotV < 0.9) continue;
            const double base = gltfDielectricBrdf(0.5, 1.0, 1.0, NdotV, NdotH, VdotH);
            const double scaling = std::min(1 - table.at(NdotV, 1.0), 1 - table.at(1.0, 1.0));
            const double expected = (sheenBrdf(1.0, 1.0, NdotV, NdotH) + base * scaling) * kLux;
            const double rel = std::fabs(f.rgb.at(x, y, 0) / expected - 1.0);
            worst = std::max(worst, rel);
            withoutTable = std::min(withoutTable, std::fabs((sheenBrdf(1.0, 1.0, NdotV, NdotH) + base) * kLux / expected - 1.0));
            EXPECT_LT(rel, 5e-3) << "pixel " << x << "," << y << ": viewer " << f.rgb.at(x, y, 0) << ", expected " << expected;
            ++checked;
        }
    EXPECT_GT(checked, 200);
    EXPECT_GT(withoutTable, 0.1) << "the check must tell a viewer without the table (E = 0) apart";
    std::printf("sheen quad: %d pixels within %.2g (relative); without the table they would be %.0f %% off\n", checked,
                worst, 100 * withoutTable);
}

// One texture as both sheenColorTexture (sRGB) and sheenRoughnessTexture (linear, alpha), as
// SheenCloth has it: the sheen colour must be the texel decoded by the sRGB curve. The viewer, left
// to itself, uploads the texture as linear because the roughness use binds it first
// (gltf-viewer.module.js:2196, :15515), so scene_copy.mjs gives the roughness use a texture of its
// own; without that the colour reads 128/255 = 0.502 instead of 0.216 and this fails (measured
// 2026-12-08: without the split all 484 pixels 1.4 % to 4.7 % off, matching the undecoded
// expectation to 1e-5; with it within 6.2e-6). Tolerance 2e-3: an 8-bit table entry rounded the
// other way moves a pixel by 0.216 x 0.5 / 255 of the base, 4e-4.
TEST(GltfViewer, TextureSharedByColourAndDataIsDecodedPerUse) {
    REQUIRE_VIEWER();
    TempDir dir;
    json material = baseMaterial();
    material["extensions"] = {{"KHR_materials_sheen",
                               {{"sheenColorFactor", {1.0, 1.0, 1.0}}, {"sheenRoughnessFactor", 1.0},
                                {"sheenColorTexture", {{"index", 0}}}, {"sheenRoughnessTexture", {{"index", 0}}}}}};
    Image8 tex;
    tex.width = 4, tex.height = 4, tex.channels = 4;
    for (int i = 0; i < 16; ++i) tex.pixels.insert(tex.pixels.end(), {128, 128, 128, 255});  // roughness 1 in alpha
    writeQuad(dir.path, material, &tex);
    const ToolRun run = render(dir.path, quadJob());
    ASSERT_EQ(run.exitCode, 0) << run.stderrText;
    const Frame f = readFrame(dir.path);
    // IEC 61966-2-1 of code 128, written from the standard's formula.
    const double c = 128.0 / 255.0, decoded = std::pow((c + 0.055) / 1.055, 2.4);
    SheenTable table;
    table.e.assign(32 * 32, -1.0);
    for (int col = 27; col < 32; ++col) table.e[31 * 32 + col] = std::round(sheenAlbedoBrute((col + 0.5) / 32, 31.5 / 32, 512) * 255) / 255;
    auto expected = [&](double s, double NdotV, double NdotH, double VdotH) {
        const double base = gltfDielectricBrdf(0.5, 1.0, 1.0, NdotV, NdotH, VdotH);
        const double scaling = std::min(1 - s * table.at(NdotV, 1.0), 1 - s * table.at(1.0, 1.0));
        return (s * sheenBrdf(1.0, 1.0, NdotV, NdotH) + base * scaling) * kLux;
    };
    int checked = 0;
    double worst = 0, undecoded = 1;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const auto [px, py] = hit(x, y);
            if (std::max(std::fabs(px), std::fabs(py)) > 0.8) continue;
            const auto [NdotV, NdotH, VdotH] = headOn(px, py);
            if (NdotV < 0.9) continue;
            const double want = expected(decoded, NdotV, NdotH, VdotH);
            const double rel = std::fabs(f.rgb.at(x, y, 0) / want - 1.0);
            worst = std::max(worst, rel);
            undecoded = std::min(undecoded, std::fabs(expected(c, NdotV, NdotH, VdotH) / want - 1.0));
            EXPECT_LT(rel, 2e-3) << "pixel " << x << "," << y << ": viewer " << f.rgb.at(x, y, 0) << ", expected " << want
                                 << " (sheen colour " << decoded << "; read undecoded, " << expected(c, NdotV, NdotH, VdotH) << ")";
            ++checked;
        }
    EXPECT_GT(checked, 200);
    EXPECT_GT(undecoded, 1e-2) << "the check must tell an undecoded sheen colour apart";
    std::printf("shared texture: %d pixels within %.2g (relative); read undecoded they would be %.1f %% off\n", checked, worst,
                100 * undecoded);
}

TEST(GltfViewer, ServedSheenTableMatchesABruteForceIntegral) {
    REQUIRE_VIEWER();
    TempDir dir;
    const std::string script = "import('" + (kTool / "sheen_lut.mjs").string() +
                               "').then(m => process.stderr.write(JSON.stringify(Array.from(m.sheenAlbedoTable()))))";
    const ToolRun run = node(dir.path, "-e " + quoted(script));
    ASSERT_EQ(run.exitCode, 0) << run.stderrText;
    const json values = json::parse(run.stderrText);
    ASSERT_EQ(values.size(), 32u * 32u);
    // Entries across the table; roughness from 0.14 (row 4) up, where a uniform grid converges
    // (below, the lobe hugs the horizon: sheen_lut.mjs's t = sqrt(N.L) nodes are there for it).
    for (const auto& [col, row] : std::vector<std::pair<int, int>>{{0, 31}, {3, 20}, {8, 8}, {15, 15}, {16, 4},
                                                                   {24, 12}, {31, 31}, {31, 6}, {10, 27}}) {
        const double mu = (col + 0.5) / 32, r = (row + 0.5) / 32;
        const double brute = sheenAlbedoBrute(mu, r);
        const double served = values[size_t(row) * 32 + col].get<double>();
        EXPECT_NEAR(served, brute, 1e-3 + 2e-3 * brute) << "N.V " << mu << ", roughness " << r;
    }
}

TEST(GltfViewer, BadJobFilesGiveOneLineAndExit2) {
    REQUIRE_VIEWER();
    TempDir dir;
    writeQuad(dir.path, baseMaterial());
    struct Case {
        std::function<void(json&)> edit;
        std::string needle;
    };
    const std::vector<Case> cases = {
        {[](json& j) { j.erase("camera"); }, "camera: missing"},
        {[](json& j) { j["width"] = "64"; }, "width: \"64\" is not an integer"},
        {[](json& j) { j["camera"]["yfov"] = "wide"; }, "camera.yfov: not a finite number"},
        {[](json& j) { j["lights"][0]["type"] = "area"; }, "lights[0].type: \"area\" is not a light type"},
        {[](json& j) { j["lights"][0].erase("direction"); }, "lights[0].direction: missing"},
        {[](json& j) { j["gltf"] = "nowhere.gltf"; }, "gltf: " },
        {[](json& j) { j["ibl"] = {{"environment", "none.hdr"}, {"rotation_degrees", 90}, {"intensity", 1}}; }, "ibl.environment: "},
        {[](json& j) { j["exposure"] = 0; }, "exposure: 0 is not > 0"},
        {[](json& j) { j["output"] = "viewer.exr"; }, "output: viewer.exr does not end in .pfm"},
        {[](json& j) { j["colour"] = 1; }, "colour: unknown field"},
    };
    for (const Case& c : cases) {
        json job = quadJob();
        c.edit(job);
        const ToolRun run = render(dir.path, job, "bad.json");
        const std::string where = (dir.path / "bad.json").string();
        EXPECT_EQ(run.exitCode, 2) << c.needle << ": " << run.stderrText;
        EXPECT_EQ(std::count(run.stderrText.begin(), run.stderrText.end(), '\n'), 1) << run.stderrText;
        EXPECT_NE(run.stderrText.find(where), std::string::npos) << run.stderrText;
        EXPECT_NE(run.stderrText.find(c.needle), std::string::npos) << run.stderrText;
        EXPECT_FALSE(fs::exists(dir.path / "viewer.exr"));
    }
    // A missing model names the file that is not there; not JSON names the job file.
    json job = quadJob();
    job["gltf"] = "nowhere.gltf";
    EXPECT_NE(render(dir.path, job, "bad.json").stderrText.find((dir.path / "nowhere.gltf").string() + " does not exist"),
              std::string::npos);
    test::writeFile(dir.path / "broken.json", "{\"gltf\": ");
    const ToolRun broken = node(dir.path, quoted((kTool / "render.mjs").string()) + " " + quoted((dir.path / "broken.json").string()));
    EXPECT_EQ(broken.exitCode, 2);
    EXPECT_NE(broken.stderrText.find("broken.json: not JSON"), std::string::npos) << broken.stderrText;
    EXPECT_FALSE(fs::exists(dir.path / "viewer.pfm"));

    // A frame that does not come in time: exit 4, one line, no output (Chromium is ended).
    test::writeFile(dir.path / "slow.json", quadJob().dump());
    const ToolRun slow = node(dir.path, quoted((kTool / "render.mjs").string()) + " " + quoted((dir.path / "slow.json").string()),
                              "GLTF_VIEWER_TIMEOUT_S=0.2");
    EXPECT_EQ(slow.exitCode, 4) << slow.stderrText;
    EXPECT_NE(slow.stderrText.find("slow.json: the viewer gave no frame within 0.2 s"), std::string::npos) << slow.stderrText;
    EXPECT_EQ(std::count(slow.stderrText.begin(), slow.stderrText.end(), '\n'), 1) << slow.stderrText;
    EXPECT_FALSE(fs::exists(dir.path / "viewer.pfm"));
    EXPECT_FALSE(fs::exists(dir.path / "viewer.mask.pgm"));
}

}  // namespace
}  // namespace gbl
