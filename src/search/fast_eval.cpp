#include "fast_eval.h"

#include <algorithm>
#include <cmath>

#include "cpu_codec.h"
#include "error.h"
#include "flip.h"
#include "metrics.h"
#include "normal_space.h"
#include "pair_memo.h"
#include "tone_map.h"

namespace gbl::search {

const char* objectiveName(Objective o) {
    switch (o) {
        case Objective::Flip: return "flip";
        case Objective::Psnr: return "psnr";
        default: return "attributes";
    }
}

Objective parseObjective(const std::string& text) {
    if (text == "flip") return Objective::Flip;
    if (text == "psnr") return Objective::Psnr;
    if (text == "attributes") return Objective::Attributes;
    throwUserError("--objective '" + text + "': unknown objective (known: flip, psnr, attributes)");
}

std::vector<glm::vec3> positionsFromDepth(const std::vector<float>& depth, int width, int height,
                                          const glm::mat4& invViewProj) {
    std::vector<glm::vec3> out(depth.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            // lighting_pass.comp.glsl worldPositionFromDepth.
            const glm::vec2 ndc = (glm::vec2(float(x), float(y)) + 0.5f) / glm::vec2(float(width), float(height)) * 2.0f - 1.0f;
            const glm::vec4 w = invViewProj * glm::vec4(ndc, depth[i], 1.0f);
            out[i] = glm::vec3(w) / w.w;
        }
    return out;
}

namespace {
// A window depth in the other Z convention: gbufferlab's reversed Z is z' = w - z
// (computeCameraMatrices), so d' = 1 - d, rounded once to float32.
float otherZConvention(float d) { return float(1.0 - double(d)); }
}  // namespace

float quantizeDepth(float d, bool referenceReversedZ, const Depth& depth) {
    const bool flip = depth.reversedZ != referenceReversedZ;
    if (depth.floatDepth) {
        if (!flip) return d;
        // The other convention stores 1 - d as a float32, read back as 1 - stored.
        return otherZConvention(otherZConvention(d));
    }
    const double steps = std::ldexp(1.0, depth.depthBits) - 1.0;
    const double own = flip ? 1.0 - double(d) : double(d);
    const double stored = std::nearbyint(std::clamp(own, 0.0, 1.0) * steps) / steps;
    return float(flip ? 1.0 - stored : stored);
}

struct FastEvaluator::Prepared {
    Image referenceHdr;
    Image referenceSrgb;
    std::unique_ptr<LdrFlipReference> flip;
};

FastEvaluator::FastEvaluator(std::vector<EvalView> views, std::vector<ShadeLight> lights, const IblMaps& ibl,
                             Objective objective, float exposure)
    : views_(std::move(views)), lights_(std::move(lights)), ibl_(ibl), objective_(objective), exposure_(exposure) {
    for (EvalView& v : views_) {
        v.shade.position = positionsFromDepth(v.depth, v.shade.width, v.shade.height, v.invViewProj);
        for (DepthVariant& d : v.depthVariants)
            d.position = positionsFromDepth(d.depth, v.shade.width, v.shade.height, d.invViewProj);
        auto p = std::make_unique<Prepared>();
        p->referenceHdr = reshade(v.shade, v.shade.covered, v.reference, v.shade.position, lights_, ibl_, nullptr, 0);
        p->referenceSrgb = toneMapToSrgb8AsFloat(p->referenceHdr, exposure_);
        p->flip = std::make_unique<LdrFlipReference>(p->referenceSrgb);  // every objective: FLIP is on the front
        prepared_.push_back(std::move(p));
    }
}

FastEvaluator::~FastEvaluator() = default;

const Image& FastEvaluator::referenceHdr(size_t v) const { return prepared_[v]->referenceHdr; }

Image FastEvaluator::renderLayout(const Layout& layout, size_t vi, int threads) const {
    return renderImpl(layout, vi, threads, nullptr);
}

namespace {
void addAttributeErrors(const std::vector<Surface>& reference, const std::vector<Surface>& decoded,
                        const std::vector<uint8_t>& covered, Evaluation& e);
}  // namespace

FrameCompression FastEvaluator::compressWords(const Layout& layout, size_t v, int threads) const {
    FrameCompression f;
    renderImpl(layout, v, threads, nullptr, &f);
    return f;
}

Image FastEvaluator::renderImpl(const Layout& layout, size_t vi, int threads, Evaluation* errors,
                                FrameCompression* compression) const {
    if (layout.pipeline != Pipeline::DeferredShading)
        throwUserError("layout '" + layout.name + "': the fast evaluation models deferred shading only");
    const EvalView& v = views_[vi];
    const int w = v.shade.width, h = v.shade.height;
    const size_t n = size_t(w) * size_t(h);
    const StoredSpace normalSpace = layout.space.normal;
    const bool storesPosition = layout.stores(Attribute::Position);
    // What this layout's depth format sees: the reference rendered with it when there is such a
    // variant; else the D32 depth quantised as the format would hold it.
    const DepthVariant* variant = nullptr;
    for (const DepthVariant& d : v.depthVariants)
        if (d.format == layout.depth.format && d.reversedZ == layout.depth.reversedZ) variant = &d;
    const std::vector<Surface>& input = variant ? variant->surfaces : v.reference;
    const std::vector<uint8_t>& covered = variant ? variant->covered : v.shade.covered;
    std::vector<glm::vec3> quantized;
    if (!variant && !(layout.depth.floatDepth && layout.depth.reversedZ == v.depthReversedZ)) {
        std::vector<float> depth(n);
        for (size_t i = 0; i < n; ++i) depth[i] = quantizeDepth(v.depth[i], v.depthReversedZ, layout.depth);
        quantized = positionsFromDepth(depth, w, h, v.invViewProj);
    }
    const std::vector<glm::vec3>& positions =
        variant ? variant->position : quantized.empty() ? v.shade.position : quantized;
    // A stored window depth (Bevy on WebGL2) in the layout's own Z convention, as the G-buffer pass
    // writes gl_FragCoord.z: a variant's depth is in it already; the D32 reference's is in the
    // reference's convention (the other one is 1 - d here: quantizeDepth).
    const bool storesDepth = layout.stores(Attribute::Depth);
    const bool flipDepth = !variant && layout.depth.reversedZ != v.depthReversedZ;
    auto ownDepth = [&](size_t i) {
        const float d = variant ? variant->depth[i] : v.depth[i];
        return flipDepth ? otherZConvention(d) : d;
    };

    // Into the stored space (normal_space.h), as the G-buffer pass does before writeGBuffer;
    // pixels without geometry hold the layout's clear values.
    const Surface clear = clearSurface(layout);
    // Per-thread scratch: a candidate's 10 MB of Surfaces are not allocated (and page-faulted) anew
    // every time (perf: 5 % of a search at 480x270 went to fresh pages).
    thread_local std::vector<Surface> stored, decoded;
    thread_local CpuGBuffer gbuffer;
    stored.resize(n);
    for (size_t i = 0; i < n; ++i) {
        if (!covered[i]) {
            stored[i] = clear;
            continue;
        }
        Surface s = input[i];
        s.normal = directionToStored(s.normal, normalSpace, v.view);
        s.coatNormal = directionToStored(s.coatNormal, normalSpace, v.view);  // the layers' directions too
        s.anisotropyDirection = directionToStored(s.anisotropyDirection, normalSpace, v.view);
        if (storesPosition) s.position = pointToStored(positions[i], layout.space.position, v.view);
        if (storesDepth) s.position = glm::vec3(0.0f, 0.0f, ownDepth(i));
        stored[i] = s;
    }
    CpuCodec codec(layout, CpuCodecOptions{std::max(threads, 1)});
    gbuffer.covered = covered;
    codec.encode(stored, w, h, gbuffer);
    if (compression) {
        *compression = compressFrame(layout, gbuffer.targetWords, uint32_t(w), uint32_t(h));
        return Image{};
    }
    codec.decode(gbuffer, decoded);
    std::vector<glm::vec3> storedPositions;
    if (storesPosition) storedPositions.resize(n);
    for (size_t i = 0; i < n; ++i) {
        decoded[i].normal = directionFromStored(decoded[i].normal, normalSpace, v.view);
        decoded[i].coatNormal = directionFromStored(decoded[i].coatNormal, normalSpace, v.view);
        decoded[i].anisotropyDirection = directionFromStored(decoded[i].anisotropyDirection, normalSpace, v.view);
        if (storesPosition) storedPositions[i] = pointFromStored(decoded[i].position, layout.space.position, v.view);
    }
    if (storesDepth) {  // the lighting rebuilds position from the decoded depth (lighting_pass.comp.glsl)
        std::vector<float> depth(n);
        for (size_t i = 0; i < n; ++i) {
            const float d = decoded[i].position.z;
            depth[i] = flipDepth ? otherZConvention(d) : d;
        }
        storedPositions = positionsFromDepth(depth, w, h, variant ? variant->invViewProj : v.invViewProj);
    }
    if (errors) addAttributeErrors(input, decoded, covered, *errors);
    const Fallback* emissive = layout.findFallback(Attribute::Emissive);
    const bool forward = emissive && emissive->kind == FallbackKind::Forward;
    return reshade(v.shade, covered, decoded, storesPosition || storesDepth ? storedPositions : positions, lights_, ibl_,
                   forward ? &input : nullptr, std::max(threads, 1));
}

Evaluation FastEvaluator::evaluate(const Layout& layout) const { return evaluate(layout, 1); }

namespace {

// The decoded Surfaces against the reference's, over covered pixels, added to `e` as means: the
// per-pixel errors of compare (run_metrics.h: normal angle, CIEDE2000 of the colours, absolute
// scalars) and the `attributes` objective's weighted sum (fast_eval.h). CIEDE2000 is memoised on
// the exact bits of each pair (pair_memo.h: the values are those of the unmemoised formula) and
// skipped where the colours are equal; diffuse colour takes base colour's value where both sides'
// diffuse equals their base (metallic 0), as compare does. Per-thread memos: a pair's value never
// changes, so they stay valid from one candidate to the next.
void addAttributeErrors(const std::vector<Surface>& reference, const std::vector<Surface>& decoded,
                        const std::vector<uint8_t>& covered, Evaluation& e) {
    thread_local PairMemo<double> baseMemo, diffuseMemo, specularMemo;
    auto deltaE = [](PairMemo<double>& memo, const glm::vec3& a, const glm::vec3& b) {
        if (a == b) return 0.0;
        const double v = memo.get(&a.x, &b.x, pixelDeltaE);
        return std::isfinite(v) ? v : 0.0;
    };
    double normal = 0.0, base = 0.0, diffuse = 0.0, specular = 0.0, rough = 0.0, metal = 0.0, occl = 0.0, attr = 0.0;
    size_t count = 0, normalCount = 0;
    for (size_t i = 0; i < reference.size(); ++i) {
        if (!covered[i]) continue;
        const Surface& a = reference[i];
        const Surface& b = decoded[i];
        bool ok = true;
        const double angle = normalAngleDeg(&a.normal.x, &b.normal.x, ok);
        if (ok) normal += angle, ++normalCount;
        const double baseDe = deltaE(baseMemo, a.baseColor, b.baseColor);
        base += baseDe;
        diffuse += a.diffuseColor == a.baseColor && b.diffuseColor == b.baseColor
                       ? baseDe
                       : deltaE(diffuseMemo, a.diffuseColor, b.diffuseColor);
        specular += deltaE(specularMemo, a.specularColor, b.specularColor);
        const double dr = std::abs(double(a.roughness) - double(b.roughness));
        rough += dr;
        metal += std::abs(double(a.metallic) - double(b.metallic));
        occl += std::abs(double(a.occlusion) - double(b.occlusion));
        const glm::vec3 dd = glm::abs(a.diffuseColor - b.diffuseColor);
        const glm::vec3 ds = glm::abs(a.specularColor - b.specularColor);
        attr += angle / 10.0 + double(dd.x + dd.y + dd.z) / 3.0 + 4.0 * double(ds.x + ds.y + ds.z) / 3.0 + dr;
        ++count;
    }
    if (!count) return;
    const double n = double(count);
    e.normalDeg += normalCount ? normal / double(normalCount) : 0.0;
    e.baseColorDe += base / n;
    e.diffuseColorDe += diffuse / n;
    e.specularColorDe += specular / n;
    e.roughness += rough / n;
    e.metallic += metal / n;
    e.occlusion += occl / n;
    e.attributes += attr / n;
}

// The mean of a FLIP map: flipStats' mean, without the sorts its quantiles need (7 % of a search).
double meanOf(const Image& map) {
    double sum = 0.0;
    for (float v : map.pixels) sum += double(v);
    return map.pixels.empty() ? 0.0 : sum / double(map.pixels.size());
}

// imageErrorStats(..., PsnrPeak::One, 3).psnr without its p99 sort: 10 log10(1 / MSE) over the
// RGB samples; identical images count as 100 dB.
double psnrOne(const Image& a, const Image& b) {
    double sum = 0.0;
    const size_t n = a.pixelCount();
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = double(b.pixels[i * size_t(b.channels) + size_t(c)]) - double(a.pixels[i * size_t(a.channels) + size_t(c)]);
            sum += d * d;
        }
    const double mse = sum / double(n * 3);
    return mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : 100.0;
}

}  // namespace

Evaluation FastEvaluator::evaluate(const Layout& layout, int threads) const {
    Evaluation e;
    double flip = 0.0, psnr = 0.0;
    for (size_t vi = 0; vi < views_.size(); ++vi) {
        const Prepared& p = *prepared_[vi];
        const Image hdr = renderImpl(layout, vi, threads, &e);
        const Image srgb = toneMapToSrgb8AsFloat(hdr, exposure_);
        psnr += psnrOne(p.referenceSrgb, srgb);
        flip += meanOf(p.flip->compare(srgb));
    }
    const double nv = double(views_.size());
    e.psnr = psnr / nv;
    e.flip = flip / nv;
    for (double* m : {&e.attributes, &e.normalDeg, &e.baseColorDe, &e.diffuseColorDe, &e.specularColorDe,
                      &e.roughness, &e.metallic, &e.occlusion})
        *m /= nv;
    e.error = objective_ == Objective::Flip ? e.flip : objective_ == Objective::Psnr ? -e.psnr : e.attributes;
    return e;
}

}  // namespace gbl::search
