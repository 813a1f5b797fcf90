#include "cpu_codec.h"

#include <algorithm>
#include <stdexcept>

#include "cpu_codec_kernels.h"
#include "cpu_codec_plan.h"
#include "parallel_for.h"

namespace gbl {

namespace {

// Below this many pixels per thread, starting threads costs more than it saves.
constexpr int64_t kMinPixelsPerThread = 16384;

int bandCount(int threads, int width, int height) {
    const int64_t pixels = int64_t(width) * int64_t(height);
    return int(std::max<int64_t>(1, std::min<int64_t>({threads, height, pixels / kMinPixelsPerThread})));
}

}  // namespace

namespace {
codec::CodecPlan planAtFrame(const Layout& layout, uint32_t frameIndex) {
    codec::CodecPlan plan = codec::compilePlan(layout);
    for (codec::TargetPlan& t : plan.targets)
        for (codec::FieldPlan& f : t.encodeFields)
            if (f.ditherPerFrame) f.frameIndex = frameIndex;
    return plan;
}
}  // namespace

CpuCodec::CpuCodec(const Layout& layout, CpuCodecOptions options)
    : plan_(std::make_shared<const codec::CodecPlan>(planAtFrame(layout, options.frameIndex))),
      threads_(options.threads > 0 ? options.threads : hardwareThreads()) {}

CpuGBuffer CpuCodec::encode(const std::vector<Surface>& surfaces, int width, int height) const {
    CpuGBuffer g;
    encode(surfaces, width, height, g);
    return g;
}

void CpuCodec::encode(const std::vector<Surface>& surfaces, int width, int height, CpuGBuffer& out) const {
    if (width < 0 || height < 0 || surfaces.size() != size_t(width) * size_t(height))
        throw std::invalid_argument("encodeGBuffer: surfaces do not match width * height");
    const codec::CodecPlan& plan = *plan_;
    const size_t pixels = surfaces.size();
    out.width = width;
    out.height = height;
    // Every word is written below, so resize (not assign): reused memory is not cleared first.
    out.targetWords.resize(plan.targets.size());
    std::vector<uint32_t*> targets, material;
    for (size_t t = 0; t < plan.targets.size(); ++t) {
        out.targetWords[t].resize(pixels * size_t(plan.targets[t].words));
        targets.push_back(out.targetWords[t].data());
    }
    out.materialWords.resize(size_t(plan.materialTargets));
    for (std::vector<uint32_t>& m : out.materialWords) {
        m.resize(pixels * 4);
        material.push_back(m.data());
    }
    const codec::WordViews views{targets.data(), material.data()};
    parallelFor(height, bandCount(threads_, width, height), [&](int64_t y0, int64_t y1) {
        codec::encodeRows(plan, surfaces.data(), width, int(y0), int(y1), views);
    });
}

std::vector<Surface> CpuCodec::decode(const CpuGBuffer& gbuffer) const {
    std::vector<Surface> out;
    decode(gbuffer, out);
    return out;
}

namespace {

// The word views of `g`, checked against the plan: throws std::invalid_argument when they do not fit.
struct CheckedViews {
    std::vector<const uint32_t*> targets, material;
    codec::ConstWordViews views;
};
CheckedViews checkedViews(const codec::CodecPlan& plan, const CpuGBuffer& g) {
    const size_t pixels = size_t(std::max(g.width, 0)) * size_t(std::max(g.height, 0));
    bool fits = g.targetWords.size() == plan.targets.size() && int(g.materialWords.size()) == plan.materialTargets;
    for (size_t t = 0; fits && t < plan.targets.size(); ++t)
        fits = g.targetWords[t].size() == pixels * size_t(plan.targets[t].words);
    for (size_t m = 0; fits && m < g.materialWords.size(); ++m) fits = g.materialWords[m].size() == pixels * 4;
    fits = fits && (g.covered.empty() || g.covered.size() == pixels);
    if (!fits) throw std::invalid_argument("decodeGBuffer: the G-buffer's words do not match its layout and size");
    CheckedViews c;
    for (const std::vector<uint32_t>& w : g.targetWords) c.targets.push_back(w.data());
    for (const std::vector<uint32_t>& w : g.materialWords) c.material.push_back(w.data());
    c.views = {c.targets.data(), c.material.data(), g.covered.empty() ? nullptr : g.covered.data()};
    return c;
}

}  // namespace

void CpuCodec::decode(const CpuGBuffer& g, std::vector<Surface>& out) const {
    const codec::CodecPlan& plan = *plan_;
    const CheckedViews c = checkedViews(plan, g);
    out.resize(size_t(std::max(g.width, 0)) * size_t(std::max(g.height, 0)));
    parallelFor(g.height, bandCount(threads_, g.width, g.height), [&](int64_t y0, int64_t y1) {
        codec::decodeRows(plan, c.views, g.width, g.height, int(y0), int(y1), out.data() + size_t(y0) * size_t(g.width));
    });
}

void CpuCodec::decodeRows(const CpuGBuffer& g, int y0, int y1, Surface* out) const {
    if (y0 < 0 || y1 > g.height || y0 > y1) throw std::invalid_argument("CpuCodec::decodeRows: rows outside the image");
    const CheckedViews c = checkedViews(*plan_, g);
    codec::decodeRows(*plan_, c.views, g.width, g.height, y0, y1, out);
}

bool CpuCodec::decodes() const { return plan_->decodeError == nullptr; }

Surface clearSurface(const Layout& layout) {
    Surface s;
    float* f = reinterpret_cast<float*>(&s);
    for (int k = 0; k < int(sizeof(Surface) / sizeof(float)); ++k) f[k] = 0.0f;
    for (const ClearValue& c : layout.clears) {
        if (attributeInfo(c.attribute).cls == AttributeClass::Extra) continue;
        const int at = codec::surfaceOffset(c.attribute);
        for (size_t i = 0; i < c.value.size(); ++i) f[at + int(i)] = float(c.value[i]);
    }
    return s;
}

std::vector<std::array<uint32_t, 4>> clearWords(const Layout& layout) {
    const CpuGBuffer g = CpuCodec(layout, {1}).encode(std::vector<Surface>(2, clearSurface(layout)), 2, 1);
    std::vector<std::array<uint32_t, 4>> out(layout.targets.size(), std::array<uint32_t, 4>{0, 0, 0, 0});
    for (size_t t = 0; t < layout.targets.size(); ++t) {
        const size_t words = g.targetWords[t].size() / 2;
        for (size_t i = 0; i < words && i < 4; ++i) out[t][i] = g.targetWords[t][i];
    }
    return out;
}

CpuGBuffer encodeGBuffer(const Layout& layout, const std::vector<Surface>& surfaces, int width, int height) {
    return CpuCodec(layout).encode(surfaces, width, height);
}

std::vector<Surface> decodeGBuffer(const Layout& layout, const CpuGBuffer& gbuffer) {
    return CpuCodec(layout).decode(gbuffer);
}

}  // namespace gbl
