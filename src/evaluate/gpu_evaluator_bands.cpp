// GpuEvaluator's banded calls (gpu_evaluator.h): the reference's statistics and a run over bands
// of rows, each band's images holding its rows and a halo (issue 14: 4K in bounded memory). The
// passes are the whole-frame ones (evaluator_state.h), run on the band's images with the counted
// rows restricted to the band's own (EvalDevice::setView); what they reduce is folded on the host
// band after band, the histograms add up on the device over the run, and the 8-bit images and
// tiles come back band by band into whole-frame host images.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "evaluator_state.h"
#include "histogram.h"

namespace gbl {

using namespace evaluate;

namespace {

[[noreturn]] void misuse(const std::string& what) { throw std::logic_error("GpuEvaluator bands: " + what); }

// A band that continues the frame at `nextRow` and fits the planes and the frame.
void checkBand(const EvalDevice& d, const EvalBand& b, uint32_t nextRow) {
    const auto str = [](uint32_t v) { return std::to_string(v); };
    if (b.rows == 0) misuse("a band of 0 rows");
    if (b.firstRow != nextRow)
        misuse("band at row " + str(b.firstRow) + ", expected " + str(nextRow) +
               " (bands cover the frame once, top to bottom)");
    if (uint64_t(b.firstRow) + b.rows > d.height)
        misuse("band rows " + str(b.firstRow) + "+" + str(b.rows) + " pass the frame's " + str(d.height));
    if (b.imageRows > d.planeRows)
        misuse("band image of " + str(b.imageRows) + " rows; the evaluator holds " + str(d.planeRows));
    if (b.imageFirstRow > b.firstRow || uint64_t(b.firstRow) + b.rows > uint64_t(b.imageFirstRow) + b.imageRows ||
        uint64_t(b.imageFirstRow) + b.imageRows > d.height)
        misuse("the band's images (rows " + str(b.imageFirstRow) + "+" + str(b.imageRows) +
               ") do not hold its rows " + str(b.firstRow) + "+" + str(b.rows) + " within the frame");
}

// Fields [at, at + fields) of the band's reduction folded into the run's: sums added, maxima
// kept (`first`: the run's first band, copied).
void fold(double* run, const double* band, uint32_t at, uint32_t fields, const FieldMask& maxMask, bool first) {
    for (uint32_t f = at; f < at + fields; ++f) {
        const uint32_t k = f - at;
        const bool isMax = (maxMask[k / 32] >> (k % 32)) & 1u;
        run[f] = first ? band[f] : isMax ? std::max(run[f], band[f]) : run[f] + band[f];
    }
}

// Rows [first, first + rows) of a width-wide host plane into the frame vector at frame row `to`.
void copyRows(const float* plane, uint32_t width, uint32_t first, uint32_t rows, std::vector<float>& frame, uint32_t to) {
    std::memcpy(frame.data() + size_t(to) * width, plane + size_t(first) * width, size_t(rows) * width * 4);
}

Image8 frameImage(uint32_t w, uint32_t h) { return Image8{int(w), int(h), 3, std::vector<unsigned char>(size_t(w) * h * 3)}; }

}  // namespace

// ---- The reference's statistics -----------------------------------------------------------------

void GpuEvaluator::beginReferenceBands(float exposure) {
    State& s = *s_;
    if (s.run.active) misuse("beginReferenceBands during a run");
    s.reference = {};
    s.referenceSerials = {};
    s.noise = false;
    s.noiseSource = nullptr;
    s.statsReady = false;
    s.exposure = exposure;
    s.referenceBands = {};
    s.referenceBands.active = true;
    s.referenceBands.luminance.assign(size_t(s.device.width) * s.device.height, 0.0f);
}

void GpuEvaluator::addReferenceBand(const DeviceRender& reference, const EvalBand& band) {
    State& s = *s_;
    EvalDevice& d = s.device;
    State::ReferenceBands& rb = s.referenceBands;
    if (!rb.active) misuse("addReferenceBand before beginReferenceBands");
    checkBand(d, band, rb.nextRow);
    checkRender(reference, d.width, band.imageRows, "reference band's");
    const uint32_t counted = band.firstRow - band.imageFirstRow;
    const float* y = d.hostPlane(kBandOut);
    d.bindImages(*reference.hdr, *reference.hdr, nullptr, nullptr);
    d.setView(band.imageRows, counted, band.rows);
    d.ctx.submitAndWait([&](VkCommandBuffer cmd) {
        // The floor's sums (setReference's pass), then the luminance for the exact median.
        Push p;
        p.f0 = s.exposure;
        p.f3 = 1.0f;
        d.dispatch(cmd, Pass::Image, p);
        d.reduce(cmd, kImageFields, imageMaxMask(), kImageAt);
        Push l;
        l.mode = 2;
        l.u[0] = kBandOut;
        d.dispatch(cmd, Pass::Luminance, l);
        d.reduce(cmd, 1, maskOf({0}), kRefLuminanceAt);
    });
    d.setWholeFrameView();
    const double* r = d.result();
    rb.sumY += r[5];
    rb.countY += r[6];
    rb.maxY = std::max(rb.maxY, r[kRefLuminanceAt]);
    copyRows(y, d.width, counted, band.rows, rb.luminance, band.firstRow);
    rb.nextRow += band.rows;
}

void GpuEvaluator::endReferenceBands() {
    State& s = *s_;
    State::ReferenceBands& rb = s.referenceBands;
    if (!rb.active) misuse("endReferenceBands before beginReferenceBands");
    if (rb.nextRow != s.device.height)
        misuse("the reference bands end at row " + std::to_string(rb.nextRow) + " of " + std::to_string(s.device.height));
    // As setReference: 1e-2 x the reference's mean luminance, at least 1e-6.
    s.floorY = float(std::max(1e-2 * (rb.countY > 0.0 ? rb.sumY / rb.countY : 0.0), 1e-6));
    s.hdrRange = GpuFlip::exposureRange(rb.luminance, rb.maxY);
    rb = {};
    s.device.releasePlane(kBandOut);
    s.statsReady = true;
}

// ---- A run ---------------------------------------------------------------------------------------

void GpuEvaluator::beginRun(const GpuEvalOptions& options) {
    State& s = *s_;
    EvalDevice& d = s.device;
    if (s.noise) misuse("the reference's noise is not supported in bands (setReference with noise)");
    if (!s.statsReady || s.referenceBands.active) misuse("beginRun before the reference's statistics (endReferenceBands)");
    State::Run& run = s.run;
    run = {};
    run.active = true;
    run.options = options;
    run.options.surfacesDone = nullptr;
    run.pass = errorPassSettings(options, s.exposure, s.floorY);
    if (run.pass.images) {
        d.ensureOut8();
        for (Image8* im : {&run.images.render, &run.images.reference, &run.images.difference, &run.images.heat,
                           &run.images.flip})
            *im = frameImage(d.width, d.height);
    }
    const uint32_t tw = (d.width + kTile - 1) / kTile;
    if (run.pass.crops) {
        d.ensureTiles(size_t(tw) * ((d.planeRows + kTile - 1) / kTile));
        run.tiles = Image(int(tw), int((d.height + kTile - 1) / kTile), 1);
    }
    s.flip.allocate();
    d.ctx.submitAndWait([&](VkCommandBuffer cmd) { d.clearHistograms(cmd); });
}

void GpuEvaluator::addBand(const DeviceRender& reference, const DeviceRender& test, const EvalBand& band) {
    State& s = *s_;
    EvalDevice& d = s.device;
    State::Run& run = s.run;
    if (!run.active) misuse("addBand before beginRun");
    checkBand(d, band, run.nextRow);
    checkRender(reference, d.width, band.imageRows, "reference band's");
    checkRender(test, d.width, band.imageRows, "layout's band");
    const bool attributes = test.surfaces[0] && reference.surfaces[0];
    const bool layers = attributes && test.layers[0] && reference.layers[0];
    if (run.bands == 0) run.pass.attributes = attributes, run.pass.layers = layers;
    else if (attributes != run.pass.attributes) misuse("surfaces in some bands of a run only");
    else if (layers != run.pass.layers) misuse("layers in some bands of a run only");
    if (run.pass.crops && band.firstRow % kTile != 0)
        misuse("with crops every band starts on a multiple of " + std::to_string(kTile) + " rows (row " +
               std::to_string(band.firstRow) + ")");
    const bool normalImage = run.pass.images && attributes;
    const uint32_t counted = band.firstRow - band.imageFirstRow;
    const float* angles = normalImage ? d.hostPlane(kBandOut) : nullptr;
    d.bindImages(*reference.hdr, *test.hdr, attributes ? reference.surfaces.data() : nullptr,
                 attributes ? test.surfaces.data() : nullptr, layers ? reference.layers.data() : nullptr,
                 layers ? test.layers.data() : nullptr);
    d.setView(band.imageRows, counted, band.rows);
    d.ctx.submitAndWait([&](VkCommandBuffer cmd) {
        recordErrorPasses(cmd, d, run.pass);
        if (normalImage) {  // what mode 1 would map, kept until the whole frame's p99 is known
            Push p;
            p.mode = 2;
            p.f0 = s.exposure;
            p.u[0] = kBandOut;
            d.dispatch(cmd, Pass::Attributes, p);
        }
        recordFlipPasses(cmd, d, s.flip, s.exposure, run.pass.images, run.options.hdrFlip, s.hdrRange, layers);
    });
    d.setWholeFrameView();

    const bool first = run.bands == 0;
    double* acc = run.result.data();
    const double* r = d.result();
    fold(acc, r, kImageAt, kImageFields, imageMaxMask(), first);
    if (attributes) fold(acc, r, kAttrAt, kAttrFields, attributeMaxMask(), first);
    if (layers) {
        fold(acc, r, kLayerAt, kLayerFields, layerMaxMask(), first);
        fold(acc, r, kLayerFlipAt, kLayerFlipFields, {}, first);
    }
    fold(acc, r, kFlipAt, kFlipFields, {}, first);
    if (run.options.hdrFlip) fold(acc, r, kHdrFlipAt, kFlipFields, {}, first);
    if (run.pass.images) {
        const size_t at = size_t(counted) * d.width;
        GpuErrorImages& im = run.images;
        unpackRows(d.out8(kOutRender) + at, band.rows, im.render, band.firstRow);
        unpackRows(d.out8(kOutReference) + at, band.rows, im.reference, band.firstRow);
        unpackRows(d.out8(kOutDifference) + at, band.rows, im.difference, band.firstRow);
        unpackRows(d.out8(kOutHeat) + at, band.rows, im.heat, band.firstRow);
        unpackRows(d.out8(kOutFlip) + at, band.rows, im.flip, band.firstRow);
    }
    if (normalImage) {
        if (first) run.normalAngles.assign(size_t(d.width) * d.height, 0.0f);
        copyRows(angles, d.width, counted, band.rows, run.normalAngles, band.firstRow);
    }
    if (run.pass.crops) {  // the band's tile rows: whole tiles, as firstRow is a multiple of 8
        const size_t tw = size_t(run.tiles.width), rows = (band.rows + kTile - 1) / kTile;
        std::memcpy(run.tiles.pixels.data() + size_t(band.firstRow / kTile) * tw, d.tiles(), rows * tw * 4);
    }
    run.nextRow += band.rows;
    ++run.bands;

    // The last band: the whole frame's histograms are in, so the normal-error picture's scale is
    // known; map every row while this band's images (bound, though the mapping reads none) live.
    if (normalImage && run.nextRow == d.height) {
        const float scale = normalImageScale(acc, d, run.options.normalMinScaleDeg);
        run.images.normal = frameImage(d.width, d.height);
        for (uint32_t row = 0; row < d.height; row += d.planeRows) {
            const uint32_t rows = std::min(d.planeRows, d.height - row);
            std::memcpy(d.hostPlane(kBandOut), run.normalAngles.data() + size_t(row) * d.width, size_t(rows) * d.width * 4);
            d.setView(rows, 0, rows);
            d.ctx.submitAndWait([&](VkCommandBuffer cmd) {
                Push p;
                p.f1 = scale;
                p.u[0] = kBandOut;
                d.dispatch(cmd, Pass::NormalMap, p);
            });
            d.setWholeFrameView();
            unpackRows(d.out8(kOutNormal), rows, run.images.normal, row);
        }
        run.normalAngles = {};
    }
}

RunMetrics GpuEvaluator::finishRun() {
    State& s = *s_;
    EvalDevice& d = s.device;
    State::Run& run = s.run;
    if (!run.active) misuse("finishRun before beginRun");
    if (run.nextRow != d.height)
        misuse("the run's bands end at row " + std::to_string(run.nextRow) + " of " + std::to_string(d.height));
    const RunMetrics m = assembleMetrics(run.result.data(), d, size_t(d.width) * d.height, run.pass.attributes,
                                         run.options.hdrFlip, false, s.hdrRange, run.pass.layers);
    if (run.pass.images) {
        GpuErrorImages& out = *run.options.images;
        out = std::move(run.images);
        out.worst.clear();
        if (run.pass.crops)
            out.worst = worstCrops(run.tiles, d.width, d.height, run.options.cropSize, run.options.cropCount);
    }
    s.flip.release();
    d.releaseOut8();
    d.releasePlane(kBandOut);
    run = {};
    return m;
}

}  // namespace gbl
