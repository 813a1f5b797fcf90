#include "temporal_resolve.h"

#include <cmath>
#include <stdexcept>

namespace gbl {

double halton(unsigned index, unsigned base) {
    double result = 0.0, f = 1.0;
    for (unsigned i = index; i > 0; i /= base) {
        f /= double(base);
        result += f * double(i % base);
    }
    return result;
}

std::vector<JitterOffset> temporalJitter(int frames) {
    if (frames <= 1) return {JitterOffset{}};
    std::vector<JitterOffset> out;
    for (int k = 0; k < frames; ++k)
        out.push_back({float(halton(unsigned(k + 1), 2) - 0.5), float(halton(unsigned(k + 1), 3) - 0.5)});
    return out;
}

const char* resolveMethodName(ResolveMethod m) { return m == ResolveMethod::Mean ? "mean" : "exp"; }

void HdrResolve::add(const Image& frame) {
    if (frames_ == 0) {
        width_ = frame.width;
        height_ = frame.height;
        channels_ = frame.channels;
        sum_.assign(frame.pixels.begin(), frame.pixels.end());
        frames_ = 1;
        return;
    }
    if (frame.width != width_ || frame.height != height_ || frame.channels != channels_)
        throw std::invalid_argument("temporal resolve: the frames differ in size");
    const size_t n = sum_.size();
    if (method_ == ResolveMethod::Mean) {
        for (size_t i = 0; i < n; ++i) sum_[i] += double(frame.pixels[i]);
    } else {
        for (size_t i = 0; i < n; ++i) sum_[i] += kHistoryBlend * (double(frame.pixels[i]) - sum_[i]);
    }
    ++frames_;
}

Image HdrResolve::resolved() const {
    Image out(width_, height_, channels_);
    const double scale = method_ == ResolveMethod::Mean && frames_ > 0 ? double(frames_) : 1.0;
    for (size_t i = 0; i < sum_.size(); ++i) out.pixels[i] = float(sum_[i] / scale);
    return out;
}

namespace {
constexpr Image SurfaceImages::*kAttributes[] = {
    &SurfaceImages::normal,   &SurfaceImages::baseColor, &SurfaceImages::diffuseColor, &SurfaceImages::specularColor,
    &SurfaceImages::roughness, &SurfaceImages::metallic, &SurfaceImages::occlusion,    &SurfaceImages::emissive,
    &SurfaceImages::depth,    &SurfaceImages::viewDepth,
    // The layers (empty in a scene without them: no channel summed). Their directions are plain
    // means: the metrics measure them by angle, which does not depend on their length.
    &SurfaceImages::coat, &SurfaceImages::coatRoughness, &SurfaceImages::coatNormal, &SurfaceImages::sheenColor,
    &SurfaceImages::sheenRoughness, &SurfaceImages::anisotropyStrength, &SurfaceImages::anisotropyDirection};
}  // namespace

void SurfaceMean::add(const SurfaceImages& frame) {
    if (frames_ == 0) {
        width_ = frame.normal.width;
        height_ = frame.normal.height;
        coveredAll_ = frame.coverage;
        channels_.clear();
        for (Image SurfaceImages::*m : kAttributes) {
            const Image& image = frame.*m;
            Channel c;
            c.image = m;
            c.channels = image.channels;
            c.sum.assign(image.pixels.size(), 0.0);
            channels_.push_back(std::move(c));
        }
    } else if (frame.coverage.size() != coveredAll_.size()) {
        throw std::invalid_argument("temporal resolve: the frames' surfaces differ in size");
    }
    for (size_t p = 0; p < coveredAll_.size(); ++p) coveredAll_[p] = coveredAll_[p] && frame.coverage[p];
    for (Channel& c : channels_) {
        const Image& image = frame.*(c.image);
        if (image.pixels.size() != c.sum.size())
            throw std::invalid_argument("temporal resolve: the frames' surfaces differ in size");
        const bool normal = c.image == &SurfaceImages::normal;
        const size_t pixels = c.channels ? c.sum.size() / size_t(c.channels) : 0;
        for (size_t p = 0; p < pixels; ++p) {
            const float* v = &image.pixels[p * size_t(c.channels)];
            double scale = 1.0;
            if (normal) {  // unit normals, so that each frame weighs the same in the mean direction
                const double len = std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
                scale = len > 0.0 && std::isfinite(len) ? 1.0 / len : 0.0;
            }
            for (int k = 0; k < c.channels; ++k) c.sum[p * size_t(c.channels) + size_t(k)] += double(v[k]) * scale;
        }
    }
    ++frames_;
}

SurfaceImages SurfaceMean::mean() const {
    SurfaceImages out;
    out.coverage = coveredAll_;
    for (const Channel& c : channels_) {
        if (c.sum.empty()) continue;
        Image image(width_, height_, c.channels);
        const bool normal = c.image == &SurfaceImages::normal;
        const size_t pixels = c.sum.size() / size_t(c.channels);
        for (size_t p = 0; p < pixels; ++p) {
            if (!coveredAll_[p]) continue;
            const double* s = &c.sum[p * size_t(c.channels)];
            double scale = 1.0 / double(frames_);
            if (normal) {  // the normalised mean
                const double len = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
                scale = len > 0.0 ? 1.0 / len : 0.0;
            }
            for (int k = 0; k < c.channels; ++k) image.pixels[p * size_t(c.channels) + size_t(k)] = float(s[k] * scale);
        }
        out.*(c.image) = std::move(image);
    }
    return out;
}

}  // namespace gbl
