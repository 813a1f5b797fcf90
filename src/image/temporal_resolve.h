#pragma once
// compare --temporal N: the sub-pixel jitter of N frames and their resolve into one image, as a
// temporal anti-aliasing (TAA) history converges with a still camera.
//
// Jitter: Halton(2, 3), as Unreal Engine's TAA (UE 5.3.2 SceneVisibility.cpp:4323-4324, also
// 4385-4386: SampleX = Halton(TemporalSampleIndex + 1, 2) - 0.5, SampleY = Halton(.., 3) - 0.5).
// Frame k (0-based) of a sequence of N > 1 is offset by (Halton(k + 1, 2) - 0.5, Halton(k + 1, 3)
// - 0.5) pixels: the image of the scene moves by that much right (x) and down (y), i.e. pixel
// (i, j) samples the scene at (i + 0.5 - dx, j + 0.5 - dy). A single frame (N = 1) is not jittered.
//
// Resolve: with a still camera and no reprojection, TAA's converged history is the uniform mean
// of the frames in linear HDR (ResolveMethod::Mean), accumulated in double: N identical frames
// resolve to that frame bit for bit (N x a float is exact in a double for N < 2^29, and the
// division rounds back to it). ResolveMethod::Exponential is the running history h_0 = frame 0,
// h_k = h_{k-1} + w (frame_k - h_{k-1}), w = kHistoryBlend. Memory does not grow with N: the
// accumulator holds one double image.
//
// Not modelled: motion and reprojection (a moving camera with history rejection), upscalers.
#include <cstddef>
#include <string>
#include <vector>

#include "image.h"
#include "surface_images.h"

namespace gbl {

// The radical inverse of `index` in `base` (index 1, base 2: 0.5; base 3: 1/3, 2/3, 1/9, ...).
double halton(unsigned index, unsigned base);

struct JitterOffset {
    float x = 0.0f, y = 0.0f;  // pixels, in [-0.5, 0.5)
};
// The N frames' offsets (above); N = 1: one zero offset.
std::vector<JitterOffset> temporalJitter(int frames);

enum class ResolveMethod { Mean, Exponential };
inline constexpr double kHistoryBlend = 0.1;  // weight of the current frame in the exponential history
const char* resolveMethodName(ResolveMethod m);  // "mean", "exp"

// Accumulates the HDR frames of one sequence; resolved() is the mean (or the exponential
// history), every channel (alpha = coverage: the covered fraction over the frames).
class HdrResolve {
public:
    explicit HdrResolve(ResolveMethod method) : method_(method) {}
    void add(const Image& frame);  // throws std::invalid_argument when sizes disagree
    Image resolved() const;
    int frames() const { return frames_; }

private:
    ResolveMethod method_;
    int width_ = 0, height_ = 0, channels_ = 0;
    int frames_ = 0;
    std::vector<double> sum_;  // Mean: the running sum; Exponential: the history
};

// Accumulates the decoded surfaces of one sequence; mean() is the temporal mean of each attribute
// over the pixels covered in every frame (normals: the normalised mean of the unit normals; colours,
// roughness, metallic, occlusion, emissive, depth and view depth: the arithmetic mean). Pixels not
// covered in every frame get coverage 0 and zero attributes. What a resolve approximately sees of
// the G-buffer (the lighting is not linear in it).
class SurfaceMean {
public:
    void add(const SurfaceImages& frame);
    SurfaceImages mean() const;
    int frames() const { return frames_; }

private:
    struct Channel {
        Image SurfaceImages::*image = nullptr;
        int channels = 0;
        std::vector<double> sum;  // empty: the attribute is absent from the frames
    };
    int frames_ = 0;
    int width_ = 0, height_ = 0;
    std::vector<Channel> channels_;
    std::vector<uint8_t> coveredAll_;
};

}  // namespace gbl
