#include "gpu_evaluator.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include "error.h"
#include "evaluator_state.h"
#include "flip_pipeline.h"
#include "histogram.h"
#include "host_profile.h"
#include "parallel_for.h"
#include "metrics.h"

namespace gbl {

namespace evaluate {

FieldMask maskOf(std::initializer_list<uint32_t> fields) {
    FieldMask m{};
    for (uint32_t f : fields) m[f / 32] |= 1u << (f % 32);
    return m;
}

FieldMask imageMaxMask() { return maskOf({2, 3}); }

FieldMask attributeMaxMask() {
    FieldMask mask{};
    for (uint32_t k = 0; k < kAttrs; ++k)
        for (uint32_t c = 0; c < 2; ++c) {
            const uint32_t f = k * kPerAttr + c * 5 + 3;
            mask[f / 32] |= 1u << (f % 32);
        }
    return mask;
}

FieldMask layerMaxMask() {
    FieldMask mask{};
    for (uint32_t k = 0; k < kLayerAttrs; ++k)
        for (uint32_t c = 0; c < 2; ++c) {
            const uint32_t f = k * kPerAttr + c * 5 + 3;
            mask[f / 32] |= 1u << (f % 32);
        }
    return mask;
}

void unpackRows(const uint32_t* packed, uint32_t rows, Image8& out, uint32_t row) {
    const size_t w = size_t(out.width), first = size_t(row) * w;
    for (size_t i = 0; i < size_t(rows) * w; ++i) {
        const uint32_t v = packed[i];
        unsigned char* px = &out.pixels[(first + i) * 3];
        px[0] = uint8_t(v);
        px[1] = uint8_t(v >> 8);
        px[2] = uint8_t(v >> 16);
    }
}

namespace {

// Rows in parallel: six of these per run at 4K were 0.1 s of one core's time.
Image8 toImage8(const uint32_t* packed, uint32_t w, uint32_t h) {
    Image8 out{int(w), int(h), 3, std::vector<unsigned char>(size_t(w) * h * 3)};
    parallelFor(h, 0, [&](int64_t begin, int64_t end) {
        unpackRows(packed + size_t(begin) * w, uint32_t(end - begin), out, uint32_t(begin));
    });
    return out;
}

// A class's statistics from its reduced fields (count, sum, sum of squares, max, colour d^2) and
// histogram; `colour`: the RMSE of linear RGB too.
ClassStats classStats(const double* f, std::span<const uint32_t> hist, bool colour) {
    ClassStats c;
    const double n = f[0];
    c.error.count = size_t(n);
    if (n <= 0.0) return c;
    c.error.mean = f[1] / n;
    c.error.rms = std::sqrt(f[2] / n);
    c.error.max = f[3];
    c.error.p99 = histogramQuantile(hist, 0.99, f[3]);
    if (colour) c.rmse = std::sqrt(f[4] / (3.0 * n));
    return c;
}

}  // namespace

ErrorPassSettings errorPassSettings(const GpuEvalOptions& o, float exposure, float floorY) {
    ErrorPassSettings s;
    s.images = o.images != nullptr;
    s.crops = s.images && o.cropSize > 0 && o.cropCount > 0;
    s.exposure = exposure;
    s.amplification = o.amplification > 0.0f ? o.amplification : 8.0f;
    s.heatMax = o.heatMax > 0.0f ? o.heatMax : 0.1f;
    s.floorY = floorY;
    return s;
}

void recordErrorPasses(VkCommandBuffer cmd, const EvalDevice& d, const ErrorPassSettings& s) {
    Push img;
    img.flags = (s.images ? 1u : 0u) | (s.noise ? 2u : 0u);
    img.f0 = s.exposure, img.f1 = s.amplification;
    img.f2 = s.heatMax, img.f3 = s.floorY;
    img.u[0] = kNoise;
    d.dispatch(cmd, Pass::Image, img);
    d.reduce(cmd, kImageFields, imageMaxMask(), kImageAt);
    if (s.attributes) {
        Push a;
        d.dispatch(cmd, Pass::Attributes, a);
        d.reduce(cmd, kAttrFields, attributeMaxMask(), kAttrAt);
    }
    if (s.layers) {
        Push l;
        l.flags = s.noise ? 2u : 0u;
        l.u[0] = kNoise;
        l.f3 = s.floorY;
        d.dispatch(cmd, Pass::Layers, l);
        d.reduce(cmd, kLayerFields, layerMaxMask(), kLayerAt);
    }
    if (s.crops) {
        Push t;
        t.u[0] = kTile;
        t.f3 = s.floorY;
        d.dispatch(cmd, Pass::Tiles, t);
    }
}

void recordFlipPasses(VkCommandBuffer cmd, const EvalDevice& d, GpuFlip& flip, float exposure, bool images,
                      bool hdrFlip, const FlipExposureRange& range, bool layers) {
    flip.ldr(cmd, exposure);
    Push fs;
    fs.flags = 2u | (images ? 1u : 0u);
    fs.u[0] = kFlipMap, fs.u[1] = kHistFlip;
    d.dispatch(cmd, Pass::FlipStats, fs);
    d.reduce(cmd, kFlipFields, {}, kFlipAt);
    if (layers) {
        Push ls;
        ls.mode = 1;
        ls.u[0] = kFlipMap;
        d.dispatch(cmd, Pass::Layers, ls);
        d.reduce(cmd, kLayerFlipFields, {}, kLayerFlipAt);
    }
    if (hdrFlip) {
        flip.hdr(cmd, range);
        Push hs;
        hs.u[0] = kHdrFlipMap;
        d.dispatch(cmd, Pass::FlipStats, hs);
        d.reduce(cmd, kFlipFields, {}, kHdrFlipAt);
    }
}

float normalImageScale(const double* result, const EvalDevice& d, float minDeg) {
    const double* nd = result + kAttrAt;  // normal: dielectric fields, then metal
    std::vector<uint32_t> both(kHistBins);
    for (uint32_t b = 0; b < kHistBins; ++b)
        both[b] = d.histogram(kHistAttributes)[b] + d.histogram(kHistAttributes + 1)[b];
    const double p99 = histogramQuantile(both, 0.99, std::max(nd[3], nd[8]));
    return std::max(minDeg, float(p99));
}

RunMetrics assembleMetrics(const double* r, const EvalDevice& d, size_t n, bool attributes, bool hdrFlip, bool noise,
                           const FlipExposureRange& range, bool layers) {
    RunMetrics m;
    const double nd = double(n);
    ShadedErrors& e = m.image;
    e.rmseLinear = std::sqrt(r[0] / (3.0 * nd));
    e.peakLinear = r[3] > 0.0 ? r[3] : 1.0;
    e.psnrLinear = psnrFromMse(r[0] / (3.0 * nd), e.peakLinear);
    e.meanAbs = r[1] / (3.0 * nd);
    e.maxAbs = r[2];
    e.p99Abs = histogramQuantile({d.histogram(kHistAbsLinear), kHistBins}, 0.99, r[2]);
    e.rmseToneMapped = std::sqrt(r[4] / (3.0 * nd));
    e.psnrToneMapped = psnrFromMse(r[4] / (3.0 * nd), 1.0);
    const double* f = r + kFlipAt;
    e.flipMean = f[0] / nd;
    e.flipMedian = histogramQuantile({d.histogram(kHistFlip), kHistBins}, 0.5, 1.0);
    if (hdrFlip) {
        e.hdrFlipMean = r[kHdrFlipAt] / nd;
        e.hdrFlipComputed = true;
        e.hdrFlipExposures = range.count;
    }
    auto cls = [&](const double* c, double flipSum) {  // c: pixels, rel, d^2, noise
        ClassImageErrors k;
        k.pixels = size_t(c[0]);
        if (k.pixels) {
            k.relLuminanceMean = c[1] / c[0];
            k.rmseLinear = std::sqrt(c[2] / (3.0 * c[0]));
            k.flipMean = flipSum / c[0];
            if (noise) k.referenceNoise = c[3] / c[0];
        }
        return k;
    };
    if (!attributes) return m;
    e.dielectric = cls(r + 7, f[1]);
    e.metal = cls(r + 11, f[3]);
    const double all[4] = {r[7] + r[11], r[8] + r[12], r[9] + r[13], r[10] + r[14]};
    e.covered = cls(all, f[1] + f[3]);

    // An attribute's three classes from its fields at `a` and its two histograms from `hist`.
    auto attribute = [&](const double* dl, uint32_t hist, bool colour) {
        const double* mt = dl + 5;  // dielectric, then metal
        std::span<const uint32_t> hd{d.histogram(hist), kHistBins};
        std::span<const uint32_t> hm{d.histogram(hist + 1), kHistBins};
        std::vector<uint32_t> both(kHistBins);
        for (uint32_t b = 0; b < kHistBins; ++b) both[b] = hd[b] + hm[b];
        const double merged[5] = {dl[0] + mt[0], dl[1] + mt[1], dl[2] + mt[2], std::max(dl[3], mt[3]), dl[4] + mt[4]};
        AttributeMetrics out;
        out.dielectric = classStats(dl, hd, colour);
        out.metal = classStats(mt, hm, colour);
        out.all = classStats(merged, both, colour);
        out.skipped = size_t(dl[10]);
        return out;
    };
    const double* a = r + kAttrAt;
    AttributeMetrics* out[kAttrs] = {&m.normal, &m.baseColor, &m.diffuseColor, &m.specularColor,
                                     &m.roughness, &m.metallic, &m.occlusion, &m.depth};
    for (uint32_t k = 0; k < kAttrs; ++k)
        *out[k] = attribute(a + k * kPerAttr, kHistAttributes + 2 * k, k >= 1 && k <= 3);
    if (layers) {
        const double* l = r + kLayerAt;
        LayerMetrics& lm = m.layers.emplace();
        for (uint32_t k = 0; k < kLayerAttrs; ++k)
            lm.byAttribute[k] = attribute(l + k * kPerAttr, kHistLayers + 2 * k, LayerAttribute(k) == LayerAttribute::SheenColor);
        auto& classes = e.layerClasses.emplace();
        for (size_t c = 0; c < kLayerClassCount; ++c)
            classes[c] = cls(l + kLayerAttrs * kPerAttr + 4 * c, r[kLayerFlipAt + c]);
    }
    const double* c = a + kAttrs * kPerAttr;
    m.coverage.pixels = n;
    m.coverage.both = size_t(c[0]);
    m.coverage.referenceOnly = size_t(c[1]);
    m.coverage.testOnly = size_t(c[2]);
    m.coverage.metal = size_t(c[3]);
    m.coverage.dielectric = size_t(c[4]);
    return m;
}

std::vector<Crop> worstCrops(const Image& tiles, uint32_t width, uint32_t height, int cropSize, int cropCount) {
    std::vector<Crop> worst;
    const int size = std::min({cropSize, int(width), int(height)});
    const int tileWindow = std::max(1, size / kTile);
    for (Crop c : findWorstRegions(tiles, tileWindow, cropCount)) {
        c.size = std::min({tileWindow * kTile, int(width), int(height)});
        c.x = std::min(c.x * kTile, int(width) - c.size);
        c.y = std::min(c.y * kTile, int(height) - c.size);
        worst.push_back(c);
    }
    return worst;
}

}  // namespace evaluate

using namespace evaluate;

uint32_t flipHaloRows() {
    const flip_pipeline::Kernels k = flip_pipeline::makeKernels(flipPixelsPerDegree());
    return uint32_t(std::max(k.csfRadius, k.featRadius));
}

GpuEvaluator::GpuEvaluator(const VulkanContext& ctx, uint32_t width, uint32_t height, uint32_t maxImageRows)
    : s_(std::make_unique<State>(ctx, width, height, maxImageRows)) {}

GpuEvaluator::~GpuEvaluator() = default;

void evaluate::checkRender(const DeviceRender& r, uint32_t w, uint32_t h, const char* what) {
    if (!r.hdr || r.hdr->extent.width != w || r.hdr->extent.height != h)
        throwUserError(std::string("GPU evaluation: the ") + what + " render is missing or not " + std::to_string(w) +
                       "x" + std::to_string(h) + "; every image of a run must have the render's size");
    for (const GpuImage* s : r.surfaces)
        if (s && (s->extent.width != w || s->extent.height != h))
            throwUserError(std::string("GPU evaluation: the ") + what + " surfaces are not " + std::to_string(w) + "x" +
                           std::to_string(h));
}

namespace {
void requireWholeFrames(const EvalDevice& d, const char* call) {
    if (d.planeRows < d.height)
        throw std::logic_error(std::string("GpuEvaluator::") + call + ": this evaluator's planes hold " +
                               std::to_string(d.planeRows) + " of " + std::to_string(d.height) +
                               " rows; use the banded calls");
}
}  // namespace

void GpuEvaluator::setReference(const DeviceRender& reference, float exposure, const Image* noise) {
    State& s = *s_;
    EvalDevice& d = s.device;
    requireWholeFrames(d, "setReference");
    checkRender(reference, d.width, d.height, "reference");
    std::array<uint64_t, 5> serials{reference.hdr->serial};
    for (size_t k = 0; k < 4; ++k) serials[k + 1] = reference.surfaces[k] ? reference.surfaces[k]->serial : 0;
    if (s.statsReady && s.referenceSerials == serials && s.exposure == exposure && s.noiseSource == noise) {
        s.reference = reference;  // the same images (their structs may have moved)
        return;
    }
    HostScope scope("evaluate: set reference (new view)");
    s.noiseSource = noise;
    s.reference = reference;
    s.referenceSerials = serials;
    s.exposure = exposure;
    s.noise = noise && !noise->empty();
    if (s.noise) {
        if (noise->width != int(d.width) || noise->height != int(d.height) || noise->channels != 1)
            throwUserError("GPU evaluation: the reference noise image must be 1 channel, " + std::to_string(d.width) +
                           "x" + std::to_string(d.height));
        d.uploadPlane(kNoise, noise->pixels.data());
    }
    // The relative luminance error's floor: 1e-2 x the reference's mean luminance (at least 1e-6).
    d.bindImages(*reference.hdr, *reference.hdr, nullptr, nullptr);
    d.ctx.submitAndWait([&](VkCommandBuffer cmd) {
        d.clearHistograms(cmd);
        Push p;
        p.f0 = exposure;
        p.f3 = 1.0f;
        d.dispatch(cmd, Pass::Image, p);
        d.reduce(cmd, kImageFields, imageMaxMask(), kImageAt);
    });
    const double* r = d.result();
    s.floorY = float(std::max(1e-2 * (r[6] > 0.0 ? r[5] / r[6] : 0.0), 1e-6));
    s.hdrRange = s.flip.exposureRange();
    s.statsReady = true;
}

RunMetrics GpuEvaluator::evaluate(const DeviceRender& test, const GpuEvalOptions& o) {
    State& s = *s_;
    EvalDevice& d = s.device;
    if (!s.reference.hdr) throw std::logic_error("GpuEvaluator::evaluate before setReference");
    requireWholeFrames(d, "evaluate");
    checkRender(test, d.width, d.height, "layout's");
    ErrorPassSettings pass = errorPassSettings(o, s.exposure, s.floorY);
    pass.noise = s.noise;
    pass.attributes = test.surfaces[0] && s.reference.surfaces[0];
    pass.layers = pass.attributes && test.layers[0] && s.reference.layers[0];
    const size_t n = size_t(d.width) * d.height;
    d.bindImages(*s.reference.hdr, *test.hdr, pass.attributes ? s.reference.surfaces.data() : nullptr,
                 pass.attributes ? test.surfaces.data() : nullptr, pass.layers ? s.reference.layers.data() : nullptr,
                 pass.layers ? test.layers.data() : nullptr);
    if (pass.images) d.ensureOut8();
    const uint32_t tw = (d.width + kTile - 1) / kTile, th = (d.height + kTile - 1) / kTile;
    if (pass.crops) d.ensureTiles(size_t(tw) * th);

    // 1: image errors and attributes (the test's surfaces are read only here).
    std::optional<HostScope> phase(std::in_place, "evaluate: errors and attributes");
    d.ctx.submitAndWait([&](VkCommandBuffer cmd) {
        d.clearHistograms(cmd);
        recordErrorPasses(cmd, d, pass);
    });
    // 2: the normal-error picture, scaled to the run's p99 normal error.
    phase.emplace("evaluate: normal-error image");
    if (pass.images && pass.attributes) {
        const float scale = normalImageScale(d.result(), d, o.normalMinScaleDeg);
        d.ctx.submitAndWait([&](VkCommandBuffer cmd) {
            Push p;
            p.mode = 1;
            p.f0 = s.exposure;
            p.f1 = scale;
            d.dispatch(cmd, Pass::Attributes, p);
        });
    }
    if (pass.attributes) {  // the reference's layers stay bound: the FLIP sums per layer class read them
        d.bindImages(*s.reference.hdr, *test.hdr, s.reference.surfaces.data(), nullptr,
                     pass.layers ? s.reference.layers.data() : nullptr, nullptr);
        if (o.surfacesDone) o.surfacesDone();
    }
    // 3: LDR- and HDR-FLIP, on planes that exist only for this.
    phase.emplace("evaluate: FLIP");
    s.flip.allocate();
    d.ctx.submitAndWait([&](VkCommandBuffer cmd) {
        recordFlipPasses(cmd, d, s.flip, s.exposure, pass.images, o.hdrFlip, s.hdrRange, pass.layers);
    });
    // Freed after every run: on a CPU device that is the 4K peak; on a GPU the context's
    // recycler (memory_recycler.h) hands the same blocks to the next run's planes.
    s.flip.release();

    phase.emplace("evaluate: assemble (histogram copy)");
    const RunMetrics m = assembleMetrics(d.result(), d, n, pass.attributes, o.hdrFlip, s.noise, s.hdrRange, pass.layers);
    phase.emplace("evaluate: 8-bit images and crops");
    if (pass.images) {
        GpuErrorImages& out = *o.images;
        out.render = out.reference = out.difference = out.heat = out.flip = out.normal = Image8{};
        out.packed = std::make_shared<PackedEvalImages>(d.ctx, d.width, d.height, d.detachOut8(), pass.attributes);
        if (!o.deferImages) out.unpack();
        out.worst.clear();
        if (pass.crops) {
            Image tiles(int(tw), int(th), 1);
            std::memcpy(tiles.pixels.data(), d.tiles(), size_t(tw) * th * 4);
            out.worst = worstCrops(tiles, d.width, d.height, o.cropSize, o.cropCount);
        }
    }
    return m;
}

// ---- The 8-bit images, packed and unpacked --------------------------------------------------------

PackedEvalImages::PackedEvalImages(const VulkanContext& ctx, uint32_t width, uint32_t height,
                                   std::vector<Buffer> buffers, bool normal)
    : ctx_(ctx), width_(width), height_(height), buffers_(std::move(buffers)), normal_(normal) {}

PackedEvalImages::~PackedEvalImages() {
    for (Buffer& b : buffers_) destroyBuffer(ctx_, b);
}

void GpuErrorImages::unpack() {
    if (!packed) return;
    const PackedEvalImages& p = *packed;
    auto image = [&](uint32_t slot) {
        return toImage8(static_cast<const uint32_t*>(p.buffers_.at(slot).mapped), p.width_, p.height_);
    };
    render = image(kOutRender);
    reference = image(kOutReference);
    difference = image(kOutDifference);
    heat = image(kOutHeat);
    flip = image(kOutFlip);
    normal = p.normal_ ? image(kOutNormal) : Image8{};
    packed.reset();
}

// ---- Host images onto the device ---------------------------------------------------------------

namespace {
GpuImage uploadRgba(const VulkanContext& ctx, int w, int h, const std::vector<float>& rgba) {
    ImageDesc desc;
    desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    desc.width = uint32_t(w);
    desc.height = uint32_t(h);
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    GpuImage image = createImage(ctx, desc);
    uploadImage(ctx, image, rgba.data(), rgba.size() * 4, VK_IMAGE_LAYOUT_GENERAL, false);
    return image;
}
float at(const Image& im, size_t i, int c) {
    if (im.empty()) return 0.0f;
    return im.pixels[i * size_t(im.channels) + size_t(std::min(c, im.channels - 1))];
}
}  // namespace

UploadedRender::UploadedRender(const VulkanContext& context, const Image& image, const SurfaceImages* s) : ctx(context) {
    const size_t n = image.pixelCount();
    if (image.channels < 3) throwUserError("GPU evaluation: a render needs 3 or 4 channels (RGB[A])");
    hasSurfaces = s != nullptr;
    if (s && s->coverage.size() != n)
        throwUserError("GPU evaluation: the coverage mask has " + std::to_string(s->coverage.size()) + " entries for " +
                       std::to_string(n) + " pixels; give one byte per pixel");
    std::vector<float> rgba(n * 4);
    for (size_t i = 0; i < n; ++i) {
        for (int k = 0; k < 3; ++k) rgba[i * 4 + size_t(k)] = at(image, i, k);
        rgba[i * 4 + 3] = s ? (s->coverage[i] ? 1.0f : 0.0f) : (image.channels >= 4 ? at(image, i, 3) : 1.0f);
    }
    hdr = uploadRgba(ctx, image.width, image.height, rgba);
    if (!s) return;
    const Image* rgb[4] = {&s->normal, &s->baseColor, &s->diffuseColor, &s->specularColor};
    const Image* alpha[4] = {&s->roughness, &s->metallic, &s->occlusion, &s->viewDepth};
    for (int k = 0; k < 4; ++k) {
        for (size_t i = 0; i < n; ++i) {
            for (int c = 0; c < 3; ++c) rgba[i * 4 + size_t(c)] = at(*rgb[k], i, c);
            rgba[i * 4 + 3] = at(*alpha[k], i, 0);
        }
        surfaces[size_t(k)] = uploadRgba(ctx, image.width, image.height, rgba);
    }
    hasLayers = s->hasLayers();
    if (!hasLayers) return;
    // decode_pass.comp.glsl's GBL_LAYERS images.
    const Image* layerRgb[4] = {&s->coatNormal, &s->sheenColor, &s->anisotropyDirection, &s->coatRoughness};
    const Image* layerAlpha[4] = {&s->coat, &s->sheenRoughness, &s->anisotropyStrength, nullptr};
    for (int k = 0; k < 4; ++k) {
        for (size_t i = 0; i < n; ++i) {
            for (int c = 0; c < 3; ++c)
                rgba[i * 4 + size_t(c)] = k == 3 ? (c == 0 ? at(*layerRgb[k], i, 0) : 0.0f) : at(*layerRgb[k], i, c);
            rgba[i * 4 + 3] = layerAlpha[k] ? at(*layerAlpha[k], i, 0) : 0.0f;
        }
        layers[size_t(k)] = uploadRgba(ctx, image.width, image.height, rgba);
    }
}

UploadedRender::~UploadedRender() {
    destroyImage(ctx, hdr);
    for (GpuImage& s : surfaces) destroyImage(ctx, s);
    for (GpuImage& l : layers) destroyImage(ctx, l);
}

DeviceRender UploadedRender::view() const {
    DeviceRender r;
    r.hdr = &hdr;
    if (hasSurfaces)
        for (size_t k = 0; k < 4; ++k) r.surfaces[k] = &surfaces[k];
    if (hasLayers)
        for (size_t k = 0; k < 4; ++k) r.layers[k] = &layers[k];
    return r;
}

}  // namespace gbl
