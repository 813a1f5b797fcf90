#pragma once
// The comparison's metrics computed on the device, where the render is (issue 14 item 1): from
// the reference's and a test's HDR images and decoded surfaces, still in device memory, compute
// passes produce every number of measure/run_metrics.h's RunMetrics and the report's 8-bit error
// images. Only scalars, histograms and 8-bit images come back to the host. measure/ stays the
// CPU oracle (tests/evaluate/gpu_evaluator_test.cpp holds the two to stated tolerances).
//
// Where the GPU results differ from the CPU oracle, and by how much at most:
//  * Sums are in double (per invocation, then a second pass in record order): as the CPU's.
//  * p99 and medians come from histograms (histogram.h): within 2^-10 relative of the exact
//    nearest-rank value (0 stays exactly 0); maxima are exact.
//  * Per-pixel maths is float (the CPU uses double for CIEDE2000, normal angles and the sRGB
//    curve): an 8-bit tone-mapped value can differ by one step where the CPU's value lies within
//    float rounding of a rounding boundary.
//  * FLIP: the same kernels and filter order in float; means agree to 1e-4 (gpu_evaluator_test).
//  * Worst regions are found on 8 x 8 tiles (corners on multiples of 8).
//
// A frame can be evaluated in bands of rows (issue 14: 4K in bounded memory), each band's images
// holding its rows and a halo (EvalBand). The planes and 8-bit buffers then hold maxImageRows
// rows; the host keeps, whole-frame, only the 8-bit images and what they need (State::Run in
// evaluator_state.h: 19-22 bytes per pixel with images, none without). A banded run equals the
// whole-frame evaluate() of the same images:
//  * counts, maxima, histograms (so p99, medians) exactly; double sums to 1e-12 relative (the
//    bands change their order of summation only);
//  * FLIP per pixel bit for bit when every band's halo is at least flipHaloRows() rows (or
//    reaches the frame's edge): its filters clamp at the band image's edges, which are then only
//    ever the frame's;
//  * the 8-bit images byte for byte: the normal-error picture is mapped at the last band, when
//    the whole frame's p99 is known; the heat map and relative errors use the luminance floor of
//    the reference bands (1e-2 x their mean luminance, a sum in another order: it may differ
//    from setReference's by a float ulp; the tests assert equality on the default scene);
//  * the worst-region crops, when every band's firstRow is a multiple of 8 (required with crops:
//    a tile then never straddles two bands; compare's bands are multiples of 8 rows).
// The reference's noise (setReference's `noise`) is not supported in bands.
#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "image.h"
#include "run_metrics.h"
#include "vk_resources.h"
#include "worst_regions.h"

namespace gbl {

// One render on the device: its HDR image (RGBA32F, GENERAL, alpha 1 where geometry covers the
// pixel) and decoded surfaces (four RGBA32F images, GENERAL: normal + roughness, base colour +
// metallic, diffuse colour + occlusion, specular colour + view depth; render/decode_pass.h).
struct DeviceRender {
    const GpuImage* hdr = nullptr;
    std::array<const GpuImage*, 4> surfaces{};  // all set, or all null (no attribute metrics)
    // The material layers in a scene with them (decode_pass.comp.glsl's GBL_LAYERS images: coat
    // normal + coat, sheen colour + sheen roughness, anisotropy direction + strength, coat
    // roughness): all set, or all null (no layer metrics; RunMetrics::layers absent). Measured
    // when both sides have them and their surfaces.
    std::array<const GpuImage*, 4> layers{};
};

// The evaluator's 8-bit outputs of one run still in its host-visible buffers, packed (one uint per
// pixel), handed over by GpuEvalOptions::deferImages so that unpacking them (six 4K images: 0.14 s
// of the main thread on an H200) happens where the files are written. Destroying it returns the
// buffers (to the context's recycler on a GPU).
class PackedEvalImages {
public:
    PackedEvalImages(const VulkanContext& ctx, uint32_t width, uint32_t height, std::vector<Buffer> buffers, bool normal);
    ~PackedEvalImages();
    PackedEvalImages(const PackedEvalImages&) = delete;
    PackedEvalImages& operator=(const PackedEvalImages&) = delete;
    bool hasNormal() const { return normal_; }

private:
    friend struct GpuErrorImages;
    const VulkanContext& ctx_;
    uint32_t width_, height_;
    std::vector<Buffer> buffers_;  // evaluate::Out8Slot order
    bool normal_;
};

// What the report shows, as 8-bit RGB (untitled map bodies; report/error_images.h adds titles).
struct GpuErrorImages {
    Image8 render;      // the test's tone-mapped render (render.png)
    Image8 reference;   // the reference's, for the crops
    Image8 difference;  // min(1, k |test - reference|) of the tone-mapped images
    Image8 heat;        // relative luminance error over [0, heatMax]
    Image8 flip;        // LDR-FLIP over [0, 1]
    Image8 normal;      // normal angle over [0, max(normalMinScaleDeg, p99)], other pixels dimmed grey
    std::vector<Crop> worst;  // worst regions of the relative luminance error
    // With GpuEvalOptions::deferImages the Image8s above are empty and these hold them: unpack()
    // fills them (the same bytes as without deferral) and frees the buffers.
    std::shared_ptr<PackedEvalImages> packed;
    void unpack();
};

struct GpuEvalOptions {
    bool hdrFlip = true;
    GpuErrorImages* images = nullptr;  // when set, filled
    float heatMax = 0.10f;
    float amplification = 8.0f;
    float normalMinScaleDeg = 1.0f;
    int cropSize = 0;    // worst regions: window size (0: none)
    int cropCount = 3;
    // Leave the 8-bit images packed in `images->packed` (GpuErrorImages::unpack) instead of
    // unpacking them here; a later run's images go to new buffers meanwhile.
    bool deferImages = false;
    // Called once the test's surfaces are no longer read (after the attribute passes, before
    // FLIP allocates its planes): compare frees them there (peak memory at 4K).
    std::function<void()> surfacesDone;
};

// Rows of halo a band needs above and below so that FLIP (whose CSF and feature filters run side by
// side on the same input, so their radii do not add) sees every tap it would see in the whole frame:
// max(CSF radius, feature radius) at the evaluator's pixels per degree (flipPixelsPerDegree()).
uint32_t flipHaloRows();

// One band of a banded evaluation. The band's images (both renders) hold frame rows
// [imageFirstRow, imageFirstRow + imageRows) (the band and its halo, clamped to the frame); the
// rows that count, and that the 8-bit images and tiles receive, are [firstRow, firstRow + rows).
struct EvalBand {
    uint32_t imageFirstRow = 0, imageRows = 0;
    uint32_t firstRow = 0, rows = 0;
};

class GpuEvaluator {
public:
    // maxImageRows 0: whole frames only (evaluate/setReference, as now). Otherwise the planes hold
    // maxImageRows rows and the banded calls below are used (and evaluate/setReference only when
    // maxImageRows >= height; a std::logic_error otherwise).
    GpuEvaluator(const VulkanContext& ctx, uint32_t width, uint32_t height, uint32_t maxImageRows = 0);
    ~GpuEvaluator();
    GpuEvaluator(const GpuEvaluator&) = delete;
    GpuEvaluator& operator=(const GpuEvaluator&) = delete;

    // The reference every later run is measured against (kept by pointer: it must outlive its
    // use). noise: the reference's per-pixel noise (1 channel), uploaded once, or null.
    // Nothing is recomputed when called again with the same images, exposure and noise.
    void setReference(const DeviceRender& reference, float exposure, const Image* noise = nullptr);
    // Its working planes and 8-bit images are allocated for the call and freed before it returns.
    RunMetrics evaluate(const DeviceRender& test, const GpuEvalOptions& options);

    // The reference's statistics (luminance floor; HDR-FLIP exposure range, exact median included)
    // over bands that cover the frame once, top to bottom. Holds the frame's reference luminance
    // on the host (4 bytes per pixel) until endReferenceBands. Replaces setReference's reference.
    void beginReferenceBands(float exposure);
    void addReferenceBand(const DeviceRender& reference, const EvalBand& band);
    void endReferenceBands();
    // One run in bands, top to bottom, covering the frame once; options.images filled by finishRun
    // as evaluate() fills them (whole-frame 8-bit images, crops). options.surfacesDone unused.
    // Needs the reference's statistics (reference bands, or setReference without noise: noise
    // is a std::logic_error here). Misuse (bands out of order, overlapping, past the frame, more
    // rows than maxImageRows, a crop run's firstRow not a multiple of 8, surfaces in some bands
    // only) is a std::logic_error; images of the wrong size a UserError, as in evaluate().
    void beginRun(const GpuEvalOptions& options);
    void addBand(const DeviceRender& reference, const DeviceRender& test, const EvalBand& band);
    RunMetrics finishRun();

private:
    struct State;
    std::unique_ptr<State> s_;
};

// Uploads host images as a DeviceRender (tests, and runs whose render came back to the host).
// `hdr` RGB(A) float; `surfaces` optional (empty images: no surfaces).
struct UploadedRender {
    UploadedRender(const VulkanContext& ctx, const Image& hdr, const SurfaceImages* surfaces);
    ~UploadedRender();
    UploadedRender(const UploadedRender&) = delete;
    UploadedRender& operator=(const UploadedRender&) = delete;
    DeviceRender view() const;
    const VulkanContext& ctx;
    GpuImage hdr;
    std::array<GpuImage, 4> surfaces{};
    std::array<GpuImage, 4> layers{};  // when the surfaces have layers (SurfaceImages::hasLayers)
    bool hasSurfaces = false, hasLayers = false;
};

}  // namespace gbl
