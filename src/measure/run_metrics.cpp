#include "run_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "error.h"
#include "flip.h"
#include "significance.h"
#include "host_profile.h"
#include "pair_memo.h"
#include "parallel_invoke.h"
#include "tone_map.h"

namespace gbl {
namespace {

void checkSize(const Image& image, int width, int height, const char* what) {
    if (image.empty()) return;
    if (image.width != width || image.height != height || image.channels < 1 ||
        image.pixels.size() != image.pixelCount() * size_t(image.channels))
        throwUserError(std::string("compare: ") + what + " is " + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + " but the render is " + std::to_string(width) + "x" +
                       std::to_string(height) + "; every image of a run must have the render's size");
}

void checkSurface(const SurfaceImages& s, int width, int height, const char* side) {
    const std::string prefix(side);
    const std::pair<const Image*, const char*> images[] = {
        {&s.normal, "normal"},       {&s.baseColor, "base colour"}, {&s.diffuseColor, "diffuse colour"},
        {&s.specularColor, "specular colour"}, {&s.roughness, "roughness"}, {&s.metallic, "metallic"},
        {&s.occlusion, "occlusion"}, {&s.emissive, "emissive"},     {&s.depth, "depth"},
        {&s.viewDepth, "view depth"}, {&s.coat, "coat"}, {&s.coatRoughness, "coat roughness"},
        {&s.coatNormal, "coat normal"}, {&s.sheenColor, "sheen colour"}, {&s.sheenRoughness, "sheen roughness"},
        {&s.anisotropyStrength, "anisotropy strength"}, {&s.anisotropyDirection, "anisotropy direction"}};
    for (const auto& [image, name] : images) checkSize(*image, width, height, (prefix + " " + name).c_str());
    if (s.coverage.size() != size_t(width) * size_t(height))
        throwUserError("compare: the " + prefix + " coverage mask has " + std::to_string(s.coverage.size()) +
                       " entries for " + std::to_string(size_t(width) * size_t(height)) +
                       " pixels; give one byte per pixel");
}

bool usable(const Image& a, const Image& b, int channels, const char* what) {
    if (a.empty() || b.empty()) return false;
    if (a.channels < channels || b.channels < channels)
        throwUserError(std::string("compare: ") + what + " needs " + std::to_string(channels) +
                       " channels but the images have " + std::to_string(a.channels) + " and " +
                       std::to_string(b.channels));
    return true;
}

// Runs errorAt(i, ok, sq) for every measured pixel, pools the results by class and writes the
// per-pixel value into `map` (0 where not measured). sq: summed squared channel error (colours).
// The samples stream into one pool in pixel order with their class (ClassStatsPool: each class
// gets the statistics of its own samples, as summarize() of them would give).
template <class ErrorAt>
AttributeMetrics measure(const Mask& measured, const Mask& metal, Image* map, bool color, ErrorAt&& errorAt) {
    const size_t n = measured.size();
    size_t both = 0;
    for (uint8_t m : measured) both += m ? 1 : 0;
    ClassStatsPool pool(both);
    double sqAll = 0.0, sqMetal = 0.0, sqDielectric = 0.0;  // colour: summed squared RGB error
    size_t skipped = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!measured[i]) continue;
        bool ok = true;
        double sq = 0.0;
        const double e = errorAt(i, ok, sq);
        if (!ok) {
            ++skipped;
            continue;
        }
        if (map) map->pixels[i] = float(e);
        pool.add(e, metal[i] != 0);
        sqAll += sq;
        (metal[i] ? sqMetal : sqDielectric) += sq;
    }
    const std::array<ScalarStats, 3> stats = pool.finish();  // dielectric, metal, all
    auto finish = [&](const ScalarStats& st, double sq) {
        ClassStats c;
        c.error = st;
        if (color && st.count > 0) c.rmse = std::sqrt(sq / (3.0 * double(st.count)));
        return c;
    };
    AttributeMetrics m;
    m.all = finish(stats[2], sqAll);
    m.metal = finish(stats[1], sqMetal);
    m.dielectric = finish(stats[0], sqDielectric);
    m.skipped = skipped;
    return m;
}


Image* mapOrNull(RunErrorMaps* maps, Image RunErrorMaps::*member, int width, int height, bool wanted) {
    if (!maps || !wanted) return nullptr;
    Image& image = maps->*member;
    image = Image(width, height, 1);
    return &image;
}

// Per-pixel CIEDE2000 values already computed for another colour attribute (`ref`, `test`): a
// pixel whose pair is bit for bit that attribute's pair takes its value (pixelDeltaE is a pure
// function of the bits, as pair_memo.h relies on) instead of computing it again.
struct KnownDeltaE {
    const Image* ref = nullptr;
    const Image* test = nullptr;
    const std::vector<double>* value = nullptr;  // per pixel, where measured
};

bool sameBits(const float* x, const float* y) { return std::memcmp(x, y, 3 * sizeof(float)) == 0; }

// `record`: when set, receives each measured pixel's value (for a later KnownDeltaE).
AttributeMetrics colorAttribute(const Image& ref, const Image& test, const Mask& measured, const Mask& metal,
                                Image* map, const char* what, std::vector<double>* record = nullptr,
                                const KnownDeltaE* known = nullptr) {
    if (!usable(ref, test, 3, what)) return {};
    const size_t rc = size_t(ref.channels), tc = size_t(test.channels);
    if (record) record->resize(measured.size());
    PairMemo<double> memo;
    return measure(measured, metal, map, true, [&](size_t i, bool& ok, double& sq) {
        const float* a = &ref.pixels[i * rc];
        const float* b = &test.pixels[i * tc];
        for (int c = 0; c < 3; ++c) {
            const double d = double(b[c]) - double(a[c]);
            sq += d * d;
        }
        double e = 0.0;
        if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) {
            e = 0.0;  // common (stored exactly); saves the costly path
        } else if (known && sameBits(a, &known->ref->pixels[i * size_t(known->ref->channels)]) &&
                   sameBits(b, &known->test->pixels[i * size_t(known->test->channels)])) {
            e = (*known->value)[i];
        } else {
            e = memo.get(a, b, pixelDeltaE);  // pairs repeat (pair_memo.h)
        }
        ok = std::isfinite(e);
        if (record) (*record)[i] = e;
        return e;
    });
}

// Base and diffuse colour in one task. Diffuse = base (1 - metallic) is the base colour itself
// wherever metallic is 0 on both sides (every dielectric, in most layouts), so most diffuse pixels
// take the base colour's value (KnownDeltaE); the rest compute theirs. Each is the value the
// attribute alone would give: the same numbers, about 40 % less of the two attributes' time.
void baseAndDiffuseColor(const SurfaceImages& reference, const SurfaceImages& test, const Mask& measured,
                         const Mask& metal, Image* baseMap, Image* diffuseMap, AttributeMetrics& base,
                         AttributeMetrics& diffuse) {
    std::vector<double> baseValues;
    base = colorAttribute(reference.baseColor, test.baseColor, measured, metal, baseMap, "base colour", &baseValues);
    const bool reuse = !reference.baseColor.empty() && !test.baseColor.empty();
    const KnownDeltaE known{&reference.baseColor, &test.baseColor, &baseValues};
    diffuse = colorAttribute(reference.diffuseColor, test.diffuseColor, measured, metal, diffuseMap, "diffuse colour",
                             nullptr, reuse ? &known : nullptr);
}

AttributeMetrics scalarAttribute(const Image& ref, const Image& test, const Mask& measured, const Mask& metal,
                                 Image* map, const char* what) {
    if (!usable(ref, test, 1, what)) return {};
    const size_t rc = size_t(ref.channels), tc = size_t(test.channels);
    return measure(measured, metal, map, false, [&](size_t i, bool& ok, double&) {
        const double e = std::abs(double(test.pixels[i * tc]) - double(ref.pixels[i * rc]));
        ok = std::isfinite(e);
        return e;
    });
}

// The layers' attribute errors (run_metrics.h "Material layers"): each over the measured pixels
// whose reference carries its layer (`bits`: layerBitsAt where measured).
void layerAttributes(const SurfaceImages& reference, const SurfaceImages& test, const Mask& measured,
                     const std::vector<uint8_t>& bits, const Mask& metal, LayerMetrics& out,
                     std::vector<std::function<void()>>& tasks) {
    auto over = [&](uint8_t bit) {
        auto mask = std::make_shared<Mask>(measured.size(), 0);
        for (size_t i = 0; i < measured.size(); ++i) (*mask)[i] = measured[i] && (bits[i] & bit) ? 1 : 0;
        return mask;
    };
    // Built up front (cheap), shared by the tasks of one layer.
    std::shared_ptr<Mask> coated = over(kCarriesCoat), sheen = over(kCarriesSheen), aniso = over(kCarriesAnisotropy);
    tasks.push_back([&, coated] {
        out[LayerAttribute::Coat] = scalarAttribute(reference.coat, test.coat, *coated, metal, nullptr, "coat");
        out[LayerAttribute::CoatRoughness] = scalarAttribute(reference.coatRoughness, test.coatRoughness, *coated, metal,
                                                             nullptr, "coat roughness");
        if (!usable(reference.coatNormal, test.coatNormal, 3, "coat normal") ||
            !usable(reference.normal, test.normal, 3, "normal"))
            return;
        const size_t rc = size_t(reference.normal.channels), tc = size_t(test.normal.channels);
        out[LayerAttribute::CoatNormal] = measure(*coated, metal, nullptr, false, [&](size_t i, bool& ok, double&) {
            const float* r = effectiveCoatNormal(&reference.coatNormal.pixels[i * 3], &reference.normal.pixels[i * rc]);
            const float* t = effectiveCoatNormal(&test.coatNormal.pixels[i * 3], &test.normal.pixels[i * tc]);
            return normalAngleDeg(r, t, ok);
        });
    });
    tasks.push_back([&, sheen] {
        out[LayerAttribute::SheenColor] =
            colorAttribute(reference.sheenColor, test.sheenColor, *sheen, metal, nullptr, "sheen colour");
        out[LayerAttribute::SheenRoughness] = scalarAttribute(reference.sheenRoughness, test.sheenRoughness, *sheen,
                                                              metal, nullptr, "sheen roughness");
    });
    tasks.push_back([&, aniso] {
        out[LayerAttribute::AnisotropyStrength] = scalarAttribute(reference.anisotropyStrength, test.anisotropyStrength,
                                                                  *aniso, metal, nullptr, "anisotropy strength");
        if (!usable(reference.anisotropyDirection, test.anisotropyDirection, 3, "anisotropy direction") ||
            !usable(reference.normal, test.normal, 3, "normal"))
            return;
        const size_t rc = size_t(reference.normal.channels), tc = size_t(test.normal.channels);
        out[LayerAttribute::AnisotropyDirection] = measure(*aniso, metal, nullptr, false, [&](size_t i, bool& ok, double&) {
            return anisotropyDirectionErrorDeg(&reference.anisotropyDirection.pixels[i * 3],
                                               &reference.normal.pixels[i * rc],
                                               &test.anisotropyDirection.pixels[i * 3], &test.normal.pixels[i * tc], ok);
        });
    });
}

double luminance(const float* p, int channels) {
    if (channels < 3) return p[0];
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// The denominator's floor of relativeLuminanceError: 1e-2 x the reference's mean luminance
// (non-positive pixels count as 0, non-finite ones are left out), at least 1e-6.
double relativeLuminanceFloor(const Image& ref) {
    double sum = 0.0;
    size_t finite = 0;
    for (size_t i = 0; i < ref.pixelCount(); ++i) {
        const double y = luminance(&ref.pixels[i * size_t(ref.channels)], ref.channels);
        if (std::isfinite(y) && y > 0.0) sum += y;
        finite += std::isfinite(y) ? 1 : 0;
    }
    return std::max(1e-2 * (finite ? sum / double(finite) : 0.0), 1e-6);
}

// Pixel i of relativeLuminanceError, as its image stores it (float; NaN where not finite).
float relativeLuminanceAt(const Image& ref, const Image& test, size_t i, double floor) {
    const double yr = luminance(&ref.pixels[i * size_t(ref.channels)], ref.channels);
    const double yt = luminance(&test.pixels[i * size_t(test.channels)], test.channels);
    const double e = std::abs(yt - yr) / std::max(std::isfinite(yr) ? yr : 0.0, floor);
    return std::isfinite(e) ? float(e) : std::numeric_limits<float>::quiet_NaN();
}

Image relativeLuminanceErrorImage(const Image& ref, const Image& test, double floor) {
    Image out(ref.width, ref.height, 1);
    for (size_t i = 0; i < ref.pixelCount(); ++i) out.pixels[i] = relativeLuminanceAt(ref, test, i, floor);
    return out;
}

}  // namespace

Image relativeLuminanceError(const Image& ref, const Image& test) {
    if (ref.width != test.width || ref.height != test.height)
        throwUserError("relative luminance error: reference is " + std::to_string(ref.width) + "x" +
                       std::to_string(ref.height) + " but test is " + std::to_string(test.width) + "x" +
                       std::to_string(test.height));
    return relativeLuminanceErrorImage(ref, test, relativeLuminanceFloor(ref));
}

PreparedReference::PreparedReference(const Image& referenceHdr, float exposure_)
    : hdr(&referenceHdr),
      exposure(exposure_),
      srgb(std::make_shared<const Image>(toneMapToSrgb8AsFloat(referenceHdr, exposure_))),
      flip(*srgb),
      luminanceFloor(relativeLuminanceFloor(referenceHdr)) {}

RunMetrics computeRunMetrics(const SurfaceImages& reference, const SurfaceImages& test, const Image& referenceHdr,
                             const Image& testHdr, float exposure) {
    return computeRunMetrics(reference, test, referenceHdr, testHdr, exposure, RunMetricsOptions{});
}

namespace {

// `release`: when set (it is `test`), emptied once the attribute metrics no longer need it.
// The inputs' sizes and channels, checked before any pixel is read.
void checkRunInputs(const SurfaceImages& reference, const SurfaceImages& test, const Image& referenceHdr,
                    const Image& testHdr, const RunMetricsOptions& options) {
    const int w = referenceHdr.width, h = referenceHdr.height;
    if (referenceHdr.empty() || referenceHdr.channels < 3)
        throwUserError("compare: the reference render needs 3 or 4 channels (RGB[A]) and pixels");
    if (testHdr.channels < 3) throwUserError("compare: the layout's render needs 3 or 4 channels (RGB[A])");
    checkSize(testHdr, w, h, "the layout's render");
    if (testHdr.empty()) throwUserError("compare: the layout's render is empty");
    checkSurface(reference, w, h, "reference");
    checkSurface(test, w, h, "layout's");
    const Image* noise = options.referenceNoise;
    if (noise && (noise->width != w || noise->height != h || noise->channels != 1))
        throw std::invalid_argument("computeRunMetrics: the reference noise image must be 1 channel, " +
                                    std::to_string(w) + "x" + std::to_string(h));
    const size_t n = referenceHdr.pixelCount();
    if (options.excluded && !options.excluded->empty() && options.excluded->size() != n)
        throw std::invalid_argument("computeRunMetrics: the excluded mask has " + std::to_string(options.excluded->size()) +
                                    " entries for " + std::to_string(n) + " pixels");
}

// What every metric of a run is over: the pixels both renders cover, less the excluded ones
// (RunMetricsOptions::excluded; `included` null when none is), their class (metal or dielectric),
// and the layers each one's reference carries (layer_classes.h; empty in a scene without them).
struct PixelClasses {
    Mask includedStorage;
    const Mask* included = nullptr;
    Mask measured, metal;
    std::vector<uint8_t> layerBits;
};

PixelClasses classifyPixels(const SurfaceImages& reference, const SurfaceImages& test, size_t n,
                            const RunMetricsOptions& options, bool layers, CoverageCounts& coverage) {
    PixelClasses p;
    if (options.excluded && !options.excluded->empty()) {
        p.includedStorage.resize(n);
        for (size_t i = 0; i < n; ++i) p.includedStorage[i] = (*options.excluded)[i] ? 0 : 1;
        p.included = &p.includedStorage;
    }
    p.measured.assign(n, 0);
    p.metal.assign(n, 0);
    const bool haveMetallic = !reference.metallic.empty();
    coverage.pixels = n;
    for (size_t i = 0; i < n; ++i) {
        if (p.included && !(*p.included)[i]) {
            ++coverage.excluded;
            continue;
        }
        const bool r = reference.coverage[i] != 0, t = test.coverage[i] != 0;
        if (r && t) {
            p.measured[i] = 1;
            ++coverage.both;
            const bool isMetal =
                haveMetallic && reference.metallic.pixels[i * size_t(reference.metallic.channels)] > 0.5f;
            p.metal[i] = isMetal ? 1 : 0;
            ++(isMetal ? coverage.metal : coverage.dielectric);
        } else if (r) {
            ++coverage.referenceOnly;
        } else if (t) {
            ++coverage.testOnly;
        }
    }
    if (layers) {
        p.layerBits.assign(n, 0);
        for (size_t i = 0; i < n; ++i)
            if (p.measured[i]) p.layerBits[i] = layerBitsAt(reference, i);
    }
    return p;
}

// One task per attribute (each fills its own fields and maps, exactly as alone: the results do
// not depend on the thread count).
void addAttributeTasks(const SurfaceImages& reference, const SurfaceImages& test, const PixelClasses& classes,
                       RunErrorMaps* maps, int w, int h, bool layers, RunMetrics& out,
                       std::vector<std::function<void()>>& tasks) {
    // The tasks run after this returns: the references below name the caller's objects, and the
    // values (w, h, maps) are captured by copy.
    const Mask& measured = classes.measured;
    const Mask& metal = classes.metal;
    const std::vector<uint8_t>& layerBits = classes.layerBits;
    if (layers) layerAttributes(reference, test, measured, layerBits, metal, out.layers.emplace(), tasks);
    if (usable(reference.normal, test.normal, 3, "normal")) tasks.push_back([&, w, h, maps] {
        const size_t rc = size_t(reference.normal.channels), tc = size_t(test.normal.channels);
        out.normal = measure(measured, metal, mapOrNull(maps, &RunErrorMaps::normalDeg, w, h, true), false,
                             [&](size_t i, bool& ok, double&) {
                                 return normalAngleDeg(&reference.normal.pixels[i * rc], &test.normal.pixels[i * tc], ok);
                             });
    });
    tasks.push_back([&, w, h, maps] {
        baseAndDiffuseColor(reference, test, measured, metal, mapOrNull(maps, &RunErrorMaps::baseColorDe, w, h, true),
                            mapOrNull(maps, &RunErrorMaps::diffuseColorDe, w, h, true), out.baseColor,
                            out.diffuseColor);
    });
    tasks.push_back([&, w, h, maps] {
        out.specularColor = colorAttribute(reference.specularColor, test.specularColor, measured, metal,
                                       mapOrNull(maps, &RunErrorMaps::specularColorDe, w, h, true), "specular colour");
    });
    tasks.push_back([&, w, h, maps] {
        out.roughness = scalarAttribute(reference.roughness, test.roughness, measured, metal,
                                    mapOrNull(maps, &RunErrorMaps::roughnessAbs, w, h, true), "roughness");
    });
    tasks.push_back([&, w, h, maps] {
        out.metallic = scalarAttribute(reference.metallic, test.metallic, measured, metal,
                                   mapOrNull(maps, &RunErrorMaps::metallicAbs, w, h, true), "metallic");
    });
    tasks.push_back([&, w, h, maps] {
        out.occlusion = scalarAttribute(reference.occlusion, test.occlusion, measured, metal,
                                    mapOrNull(maps, &RunErrorMaps::occlusionAbs, w, h, true), "occlusion");
    });
    if (usable(reference.viewDepth, test.viewDepth, 1, "view depth")) tasks.push_back([&, w, h, maps] {
        const size_t rc = size_t(reference.viewDepth.channels), tc = size_t(test.viewDepth.channels);
        out.depth = measure(measured, metal, mapOrNull(maps, &RunErrorMaps::depthRel, w, h, true), false,
                            [&](size_t i, bool& ok, double&) {
                                const double r = reference.viewDepth.pixels[i * rc];
                                const double t = test.viewDepth.pixels[i * tc];
                                const double e = std::abs(t - r) / r;
                                ok = r > 0.0 && std::isfinite(r) && std::isfinite(e);
                                return ok ? e : 0.0;
                            });
    });
}

// The image errors per material class (dielectric, metal, every covered pixel): relative
// luminance, linear RMSE, FLIP, and the reference's own noise where it has one (a ground truth).
// `rel` receives the whole relative-luminance map when `maps` asks for it.
void materialClassErrors(const Image& referenceHdr, const Image& testHdr, const Image& flip, const Image* noise,
                         const PixelClasses& classes, double floor, RunErrorMaps* maps, Image& rel, ShadedErrors& image) {
    const Mask& measured = classes.measured;
    const Mask& metal = classes.metal;
    const size_t n = referenceHdr.pixelCount();
    if (maps) rel = relativeLuminanceErrorImage(referenceHdr, testHdr, floor);
    struct Acc {
        size_t pixels = 0;
        double rel = 0.0, sq = 0.0, flip = 0.0, noise = 0.0;
    } acc[2];  // 0 dielectric, 1 metal
    const size_t rc = size_t(referenceHdr.channels), tc = size_t(testHdr.channels);
    for (size_t i = 0; i < n; ++i) {
        if (!measured[i]) continue;
        Acc& a = acc[metal[i] ? 1 : 0];
        ++a.pixels;
        const float r = maps ? rel.pixels[i] : relativeLuminanceAt(referenceHdr, testHdr, i, floor);
        a.rel += std::isfinite(r) ? r : 0.0;
        for (size_t c = 0; c < 3; ++c) {
            const double d = double(testHdr.pixels[i * tc + c]) - double(referenceHdr.pixels[i * rc + c]);
            a.sq += d * d;
        }
        a.flip += flip.pixels[i];
        if (noise) {
            const double y = luminance(&referenceHdr.pixels[i * rc], referenceHdr.channels);
            a.noise += double(noise->pixels[i]) / std::max(std::isfinite(y) ? y : 0.0, floor);
        }
    }
    auto finish = [&](const Acc& a) {
        ClassImageErrors e;
        e.pixels = a.pixels;
        if (a.pixels) {
            e.relLuminanceMean = a.rel / double(a.pixels);
            e.rmseLinear = std::sqrt(a.sq / double(3 * a.pixels));
            e.flipMean = a.flip / double(a.pixels);
            if (noise) e.referenceNoise = a.noise / double(a.pixels);
        }
        return e;
    };
    Acc all{acc[0].pixels + acc[1].pixels, acc[0].rel + acc[1].rel, acc[0].sq + acc[1].sq,
            acc[0].flip + acc[1].flip, acc[0].noise + acc[1].noise};
    image.dielectric = finish(acc[0]);
    image.metal = finish(acc[1]);
    image.covered = finish(all);
}

// The same sums over each layer class's pixels (a pixel may count in several), with FLIP's tile
// means per class for the significance test.
void layerClassErrors(const Image& referenceHdr, const Image& testHdr, const Image& flip, const Image* noise,
                      const PixelClasses& classes, double floor, ShadedErrors& image) {
    const Mask& measured = classes.measured;
    const std::vector<uint8_t>& layerBits = classes.layerBits;
    const size_t n = referenceHdr.pixelCount();
    std::array<ClassImageErrors, kLayerClassCount>& perClass = image.layerClasses.emplace();
    const size_t rc = size_t(referenceHdr.channels), tc = size_t(testHdr.channels);
    for (LayerClass c : kLayerClasses) {
        size_t pixels = 0;
        double relSum = 0.0, sq = 0.0, flipSum = 0.0, noiseSum = 0.0;
        Mask in(n, 0);
        for (size_t i = 0; i < n; ++i) {
            if (!measured[i] || !inLayerClass(layerBits[i], c)) continue;
            in[i] = 1;
            ++pixels;
            const float r = relativeLuminanceAt(referenceHdr, testHdr, i, floor);
            relSum += std::isfinite(r) ? r : 0.0;
            for (size_t k = 0; k < 3; ++k) {
                const double d = double(testHdr.pixels[i * tc + k]) - double(referenceHdr.pixels[i * rc + k]);
                sq += d * d;
            }
            flipSum += flip.pixels[i];
            if (noise) {
                const double y = luminance(&referenceHdr.pixels[i * rc], referenceHdr.channels);
                noiseSum += double(noise->pixels[i]) / std::max(std::isfinite(y) ? y : 0.0, floor);
            }
        }
        ClassImageErrors& e = perClass[size_t(c)];
        e.pixels = pixels;
        if (pixels) {
            e.relLuminanceMean = relSum / double(pixels);
            e.rmseLinear = std::sqrt(sq / double(3 * pixels));
            e.flipMean = flipSum / double(pixels);
            if (noise) e.referenceNoise = noiseSum / double(pixels);
            e.flipTiles = tileMeans(flip, kSignificanceTileColumns, kSignificanceTileRows, &in);
        }
    }
}

// The error maps the report's images are made from; the excluded pixels hold 0 in each.
void keepErrorMaps(RunErrorMaps& maps, const PreparedReference& prepared, Image&& testSrgb, Image&& flip, Image&& hdrFlip,
                   Image&& rel, const Image& referenceHdr, const Image& testHdr, PixelClasses&& classes) {
    const Mask* included = classes.included;
    const size_t n = referenceHdr.pixelCount();
    const int w = referenceHdr.width, h = referenceHdr.height;
    if (included) {  // no worst region among them
        for (Image* m : {&flip, &hdrFlip, &rel})
            if (!m->empty())
                for (size_t i = 0; i < n; ++i)
                    if (!(*included)[i]) m->pixels[i] = 0.0f;
    }
    maps.relLuminance = std::move(rel);
    maps.referenceSrgb = prepared.srgb;  // shared: outlives `local`
    maps.testSrgb = std::move(testSrgb);
    maps.flip = std::move(flip);
    maps.hdrFlip = std::move(hdrFlip);
    maps.absLinear = Image(w, h, 3);
    const size_t rc = size_t(referenceHdr.channels), tc = size_t(testHdr.channels);
    for (size_t i = 0; i < n; ++i)
        for (size_t c = 0; c < 3; ++c)
            maps.absLinear.pixels[i * 3 + c] =
                included && !(*included)[i] ? 0.0f : std::abs(testHdr.pixels[i * tc + c] - referenceHdr.pixels[i * rc + c]);
    maps.measured = std::move(classes.measured);
}

RunMetrics computeImpl(const SurfaceImages& reference, const SurfaceImages& test, const Image& referenceHdr,
                       const Image& testHdr, float exposure, const RunMetricsOptions& options,
                       SurfaceImages* release) {
    checkRunInputs(reference, test, referenceHdr, testHdr, options);
    const int w = referenceHdr.width, h = referenceHdr.height;
    RunMetrics out;
    RunErrorMaps* maps = options.maps;
    std::optional<HostScope> scope(std::in_place, "metrics: coverage");
    const bool layers = reference.hasLayers() && test.hasLayers();
    PixelClasses classes = classifyPixels(reference, test, referenceHdr.pixelCount(), options, layers, out.coverage);
    const Mask* included = classes.included;

    scope.emplace("metrics: attributes and image errors");
    std::vector<std::function<void()>> tasks;
    addAttributeTasks(reference, test, classes, maps, w, h, layers, out, tasks);
    // The shaded image, every pixel, RGB.
    tasks.push_back([&] {
        const ImageErrorStats linear = imageErrorStats(referenceHdr, testHdr, included, PsnrPeak::ReferenceMax, 3);
        out.image.rmseLinear = linear.rmse;
        out.image.psnrLinear = linear.psnr;
        out.image.peakLinear = linear.peak;
        out.image.maxAbs = linear.maxAbs;
        out.image.p99Abs = linear.p99Abs;
        out.image.meanAbs = linear.meanAbs;
    });
    const PreparedReference* prepared = options.prepared;
    if (prepared && (prepared->hdr != &referenceHdr || prepared->exposure != exposure))
        throw std::invalid_argument("computeRunMetrics: the prepared reference is of another image or exposure");
    std::optional<PreparedReference> local;
    if (!prepared) prepared = &local.emplace(referenceHdr, exposure);
    Image testSrgb = toneMapToSrgb8AsFloat(testHdr, exposure);
    tasks.push_back([&] {
        const double mse = included ? imageErrorStats(*prepared->srgb, testSrgb, included, PsnrPeak::One, 3).mse
                                    : meanSquaredError(*prepared->srgb, testSrgb, 3);  // imageErrorStats' mse
        out.image.rmseToneMapped = std::sqrt(mse);
        out.image.psnrToneMapped = psnrFromMse(mse, 1.0);
    });
    parallelInvoke(tasks);
    if (release) *release = SurfaceImages{};

    scope.emplace("metrics: FLIP");
    Image flip = prepared->flip.compare(testSrgb);
    Image hdrFlip;
    if (options.hdrFlip) {
        HdrFlipResult result = flipHdr(referenceHdr, testHdr);
        out.image.hdrFlipExposures = result.range.count;
        hdrFlip = std::move(result.flip);
        out.image.hdrFlipMean = flipStats(hdrFlip, included).mean;
        out.image.hdrFlipComputed = true;
    }

    // FLIP's statistics and the image errors per material class, side by side (both only read).
    scope.emplace("metrics: FLIP statistics and classes");
    Image rel;  // the whole map, for the heat map and the worst regions; else per pixel
    const double floor = prepared->luminanceFloor;
    tasks.clear();
    tasks.push_back([&] {
        const FlipStats fs = flipStats(flip, included);
        out.image.flipMean = fs.mean;
        out.image.flipMedian = fs.median;
        out.image.flipTiles = tileMeans(flip, kSignificanceTileColumns, kSignificanceTileRows, included);
    });
    tasks.push_back([&] {
        materialClassErrors(referenceHdr, testHdr, flip, options.referenceNoise, classes, floor, maps, rel, out.image);
    });
    if (layers) tasks.push_back([&] {
        layerClassErrors(referenceHdr, testHdr, flip, options.referenceNoise, classes, floor, out.image);
    });
    parallelInvoke(tasks);

    scope.emplace("metrics: maps");
    if (maps)
        keepErrorMaps(*maps, *prepared, std::move(testSrgb), std::move(flip), std::move(hdrFlip), std::move(rel),
                      referenceHdr, testHdr, std::move(classes));
    return out;
}

}  // namespace

RunMetrics computeRunMetrics(const SurfaceImages& reference, const SurfaceImages& test, const Image& referenceHdr,
                             const Image& testHdr, float exposure, const RunMetricsOptions& options) {
    return computeImpl(reference, test, referenceHdr, testHdr, exposure, options, nullptr);
}

RunMetrics computeRunMetrics(const SurfaceImages& reference, SurfaceImages&& test, const Image& referenceHdr,
                             const Image& testHdr, float exposure, const RunMetricsOptions& options) {
    return computeImpl(reference, test, referenceHdr, testHdr, exposure, options, &test);
}

}  // namespace gbl
