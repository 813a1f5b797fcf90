#include "gpu_evaluator.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include "error.h"
#include "eval_device.h"
#include "gpu_flip.h"
#include "histogram.h"
#include "metrics.h"

namespace gbl {

using namespace evaluate;

namespace {

// Result offsets of the reductions (eval_device reduce), one submission per run.
constexpr uint32_t kImageFields = 15, kImageAt = 0;
constexpr uint32_t kAttrs = 8, kPerAttr = 11, kAttrFields = kAttrs * kPerAttr + 5, kAttrAt = 96;
constexpr uint32_t kFlipFields = 5, kFlipAt = 200, kHdrFlipAt = 210;
constexpr int kTile = 8;

std::array<uint32_t, 4> maskOf(std::initializer_list<uint32_t> fields) {
    std::array<uint32_t, 4> m{};
    for (uint32_t f : fields) m[f / 32] |= 1u << (f % 32);
    return m;
}

Image8 toImage8(const uint32_t* packed, uint32_t w, uint32_t h) {
    Image8 out{int(w), int(h), 3, std::vector<unsigned char>(size_t(w) * h * 3)};
    for (size_t i = 0; i < size_t(w) * h; ++i) {
        const uint32_t v = packed[i];
        out.pixels[i * 3 + 0] = uint8_t(v);
        out.pixels[i * 3 + 1] = uint8_t(v >> 8);
        out.pixels[i * 3 + 2] = uint8_t(v >> 16);
    }
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

struct GpuEvaluator::State {
    State(const VulkanContext& ctx, uint32_t w, uint32_t h) : device(ctx, w, h), flip(device) {}
    EvalDevice device;
    GpuFlip flip;
    DeviceRender reference;
    float exposure = 1.0f;
    float floorY = 1e-6f;
    bool noise = false;
    const Image* noiseSource = nullptr;
    FlipExposureRange hdrRange;
};

GpuEvaluator::GpuEvaluator(const VulkanContext& ctx, uint32_t width, uint32_t height)
    : s_(std::make_unique<State>(ctx, width, height)) {}

GpuEvaluator::~GpuEvaluator() = default;

namespace {
void checkRender(const DeviceRender& r, uint32_t w, uint32_t h, const char* what) {
    if (!r.hdr || r.hdr->extent.width != w || r.hdr->extent.height != h)
        throwUserError(std::string("GPU evaluation: the ") + what + " render is missing or not " + std::to_string(w) +
                       "x" + std::to_string(h) + "; every image of a run must have the render's size");
    for (const GpuImage* s : r.surfaces)
        if (s && (s->extent.width != w || s->extent.height != h))
            throwUserError(std::string("GPU evaluation: the ") + what + " surfaces are not " + std::to_string(w) + "x" +
                           std::to_string(h));
}
}  // namespace

void GpuEvaluator::setReference(const DeviceRender& reference, float exposure, const Image* noise) {
    State& s = *s_;
    EvalDevice& d = s.device;
    checkRender(reference, d.width, d.height, "reference");
    if (s.reference.hdr == reference.hdr && s.reference.surfaces == reference.surfaces && s.exposure == exposure &&
        s.noiseSource == noise)
        return;
    s.noiseSource = noise;
    s.reference = reference;
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
        d.reduce(cmd, kImageFields, maskOf({2, 3}), kImageAt);
    });
    const double* r = d.result();
    s.floorY = float(std::max(1e-2 * (r[6] > 0.0 ? r[5] / r[6] : 0.0), 1e-6));
    s.hdrRange = s.flip.exposureRange();
}

RunMetrics GpuEvaluator::evaluate(const DeviceRender& test, const GpuEvalOptions& o) {
    State& s = *s_;
    EvalDevice& d = s.device;
    if (!s.reference.hdr) throw std::logic_error("GpuEvaluator::evaluate before setReference");
    checkRender(test, d.width, d.height, "layout's");
    const bool attributes = test.surfaces[0] && s.reference.surfaces[0];
    const size_t n = size_t(d.width) * d.height;
    d.bindImages(*s.reference.hdr, *test.hdr, attributes ? s.reference.surfaces.data() : nullptr,
                 attributes ? test.surfaces.data() : nullptr);
    const bool images = o.images != nullptr;
    if (images) d.ensureOut8();
    const uint32_t tw = (d.width + kTile - 1) / kTile, th = (d.height + kTile - 1) / kTile;
    const bool crops = images && o.cropSize > 0 && o.cropCount > 0;
    if (crops) d.ensureTiles(size_t(tw) * th);

    // 1: image errors and attributes (the test's surfaces are read only here).
    d.ctx.submitAndWait([&](VkCommandBuffer cmd) {
        d.clearHistograms(cmd);
        Push img;
        img.flags = (images ? 1u : 0u) | (s.noise ? 2u : 0u);
        img.f0 = s.exposure, img.f1 = o.amplification > 0.0f ? o.amplification : 8.0f;
        img.f2 = o.heatMax > 0.0f ? o.heatMax : 0.1f, img.f3 = s.floorY;
        img.u[0] = kNoise;
        d.dispatch(cmd, Pass::Image, img);
        d.reduce(cmd, kImageFields, maskOf({2, 3}), kImageAt);
        if (attributes) {
            Push a;
            d.dispatch(cmd, Pass::Attributes, a);
            std::array<uint32_t, 4> mask{};
            for (uint32_t k = 0; k < kAttrs; ++k)
                for (uint32_t c = 0; c < 2; ++c) {
                    const uint32_t f = k * kPerAttr + c * 5 + 3;
                    mask[f / 32] |= 1u << (f % 32);
                }
            d.reduce(cmd, kAttrFields, mask, kAttrAt);
        }
        if (crops) {
            Push t;
            t.u[0] = kTile;
            t.f3 = s.floorY;
            d.dispatch(cmd, Pass::Tiles, t);
        }
    });
    // 2: the normal-error picture, scaled to the run's p99 normal error.
    if (images && attributes) {
        const double* nd = d.result() + kAttrAt;  // normal: dielectric fields, then metal
        std::vector<uint32_t> both(kHistBins);
        for (uint32_t b = 0; b < kHistBins; ++b)
            both[b] = d.histogram(kHistAttributes)[b] + d.histogram(kHistAttributes + 1)[b];
        const double p99 = histogramQuantile(both, 0.99, std::max(nd[3], nd[8]));
        d.ctx.submitAndWait([&](VkCommandBuffer cmd) {
            Push p;
            p.mode = 1;
            p.f0 = s.exposure;
            p.f1 = std::max(o.normalMinScaleDeg, float(p99));
            d.dispatch(cmd, Pass::Attributes, p);
        });
    }
    if (attributes) {
        d.bindImages(*s.reference.hdr, *test.hdr, s.reference.surfaces.data(), nullptr);
        if (o.surfacesDone) o.surfacesDone();
    }
    // 3: LDR- and HDR-FLIP, on planes that exist only for this.
    s.flip.allocate();
    d.ctx.submitAndWait([&](VkCommandBuffer cmd) {
        s.flip.ldr(cmd, s.exposure);
        Push fs;
        fs.flags = 2u | (images ? 1u : 0u);
        fs.u[0] = kFlipMap, fs.u[1] = kHistFlip;
        d.dispatch(cmd, Pass::FlipStats, fs);
        d.reduce(cmd, kFlipFields, {}, kFlipAt);
        if (o.hdrFlip) {
            s.flip.hdr(cmd, s.hdrRange);
            Push hs;
            hs.u[0] = kHdrFlipMap;
            d.dispatch(cmd, Pass::FlipStats, hs);
            d.reduce(cmd, kFlipFields, {}, kHdrFlipAt);
        }
    });
    s.flip.release();

    RunMetrics m;
    const double* r = d.result();
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
    if (o.hdrFlip) {
        e.hdrFlipMean = r[kHdrFlipAt] / nd;
        e.hdrFlipComputed = true;
        e.hdrFlipExposures = s.hdrRange.count;
    }
    auto cls = [&](const double* c, double flipSum) {  // c: pixels, rel, d^2, noise
        ClassImageErrors k;
        k.pixels = size_t(c[0]);
        if (k.pixels) {
            k.relLuminanceMean = c[1] / c[0];
            k.rmseLinear = std::sqrt(c[2] / (3.0 * c[0]));
            k.flipMean = flipSum / c[0];
            if (s.noise) k.referenceNoise = c[3] / c[0];
        }
        return k;
    };
    if (attributes) {
        e.dielectric = cls(r + 7, f[1]);
        e.metal = cls(r + 11, f[3]);
        const double all[4] = {r[7] + r[11], r[8] + r[12], r[9] + r[13], r[10] + r[14]};
        e.covered = cls(all, f[1] + f[3]);

        const double* a = r + kAttrAt;
        AttributeMetrics* out[kAttrs] = {&m.normal, &m.baseColor, &m.diffuseColor, &m.specularColor,
                                         &m.roughness, &m.metallic, &m.occlusion, &m.depth};
        for (uint32_t k = 0; k < kAttrs; ++k) {
            const bool colour = k >= 1 && k <= 3;
            const double* dl = a + k * kPerAttr;  // dielectric
            const double* mt = dl + 5;            // metal
            std::span<const uint32_t> hd{d.histogram(kHistAttributes + 2 * k), kHistBins};
            std::span<const uint32_t> hm{d.histogram(kHistAttributes + 2 * k + 1), kHistBins};
            std::vector<uint32_t> both(kHistBins);
            for (uint32_t b = 0; b < kHistBins; ++b) both[b] = hd[b] + hm[b];
            const double merged[5] = {dl[0] + mt[0], dl[1] + mt[1], dl[2] + mt[2], std::max(dl[3], mt[3]), dl[4] + mt[4]};
            out[k]->dielectric = classStats(dl, hd, colour);
            out[k]->metal = classStats(mt, hm, colour);
            out[k]->all = classStats(merged, both, colour);
            out[k]->skipped = size_t(dl[10]);
        }
        const double* c = a + kAttrs * kPerAttr;
        m.coverage.pixels = n;
        m.coverage.both = size_t(c[0]);
        m.coverage.referenceOnly = size_t(c[1]);
        m.coverage.testOnly = size_t(c[2]);
        m.coverage.metal = size_t(c[3]);
        m.coverage.dielectric = size_t(c[4]);
    }

    if (images) {
        GpuErrorImages& out = *o.images;
        out.render = toImage8(d.out8(kOutRender), d.width, d.height);
        out.reference = toImage8(d.out8(kOutReference), d.width, d.height);
        out.difference = toImage8(d.out8(kOutDifference), d.width, d.height);
        out.heat = toImage8(d.out8(kOutHeat), d.width, d.height);
        out.flip = toImage8(d.out8(kOutFlip), d.width, d.height);
        out.normal = attributes ? toImage8(d.out8(kOutNormal), d.width, d.height) : Image8{};
        out.worst.clear();
        if (crops) {
            Image tiles(int(tw), int(th), 1);
            std::memcpy(tiles.pixels.data(), d.tiles(), size_t(tw) * th * 4);
            const int size = std::min({o.cropSize, int(d.width), int(d.height)});
            const int tileWindow = std::max(1, size / kTile);
            for (Crop c : findWorstRegions(tiles, tileWindow, o.cropCount)) {
                c.size = std::min({tileWindow * kTile, int(d.width), int(d.height)});
                c.x = std::min(c.x * kTile, int(d.width) - c.size);
                c.y = std::min(c.y * kTile, int(d.height) - c.size);
                out.worst.push_back(c);
            }
        }
        d.releaseOut8();
    }
    return m;
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
}

UploadedRender::~UploadedRender() {
    destroyImage(ctx, hdr);
    for (GpuImage& s : surfaces) destroyImage(ctx, s);
}

DeviceRender UploadedRender::view() const {
    DeviceRender r;
    r.hdr = &hdr;
    if (hasSurfaces)
        for (size_t k = 0; k < 4; ++k) r.surfaces[k] = &surfaces[k];
    return r;
}

}  // namespace gbl
