#pragma once
// HDR -> display. The tone map is stated so images are comparable across runs:
// exposure scale, then the ACES filmic fit by Krzysztof Narkowicz (2016), then the exact sRGB
// transfer function, then 8-bit quantisation with floor(x * 255 + 0.5).
#include "image.h"

namespace gbl {

float acesFilmNarkowicz(float x);
float linearToSrgb(float linear);   // exact piecewise sRGB OETF, x in [0,1]
float srgbToLinear(float encoded);  // exact inverse

// The 8-bit code of a display-referred linear value in [0,1] (clamped; NaN -> 0):
// floor(linearToSrgb(display) * 255 + 0.5), found from the curve's 255 steps (no pow).
unsigned char srgbByte(float display);
// RGB(A) float -> RGB 8-bit, with the tone map above. Alpha is dropped.
Image8 toneMapToSrgb8(const Image& hdr, float exposure = 1.0f);
// What toneMapToSrgb8 writes, read back as a PNG reader does: byte / 255.0f (float division).
// The report's tone-mapped metrics and LDR-FLIP are computed on this, so they equal what
// `gbufferlab diff` (or any tool) computes from the written PNGs.
Image toneMapToSrgb8AsFloat(const Image& hdr, float exposure = 1.0f);
// The report viewer's HDR preview (report.html's exposure control): each linear channel as
// log2, kPreviewLog2Min..kPreviewLog2Max mapped to 0..255 (floor(255 t + 0.5); values at or
// below 2^kPreviewLog2Min, and non-finite ones, give 0). 28 stops in 8 bits: 0.11-stop steps,
// a preview only -- render.exr holds the exact values.
inline constexpr float kPreviewLog2Min = -12.0f;
inline constexpr float kPreviewLog2Max = 16.0f;
Image8 logEncodeForPreview(const Image& hdr);
// The same tone map kept in float (display-referred, sRGB-encoded, in [0,1]).
Image toneMapToSrgbFloat(const Image& hdr, float exposure = 1.0f);

}  // namespace gbl
