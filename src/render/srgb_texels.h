#pragma once
// sRGB-encoded 8-bit texels decoded exactly, to half floats, before the GPU sees them.
//
// Why not R8G8B8A8_SRGB: lavapipe's sampler decodes sRGB with an approximation, up to 2.6 % off
// IEC 61966-2-1 in the dark codes (measured 2026-12-08 against the exact curve, a glTF quad of 8
// codes lit head-on: code 3 +2.6 %, 10 +2.5 %, 30 -1.9 %, 100 +0.67 %; the Khronos glTF Sample
// Viewer on SwiftShader within 1e-5 above code 10), which shifted every textured base colour and
// emissive of the float reference (docs/crosscheck.md). Decoded here in double precision and stored
// as R16G16B16A16_SFLOAT (relative rounding <= 2^-11, 4.9e-4 of a 2^-10 step: 2.4e-4), filtered and
// mip-mapped in linear space as the specification's sRGB sampling defines it.
#include <cstdint>
#include <vector>

namespace gbl {

// IEC 61966-2-1's decode of an 8-bit code: c / 12.92 for c <= 0.04045, else ((c + 0.055) / 1.055)^2.4.
double srgbCodeToLinear(uint8_t code);

// A positive float (at least 2^-14, at most 65504) as the nearest IEEE 754 half (ties to even); 0 as 0.
uint16_t halfOfPositive(double x);

// RGBA8 texels (sRGB RGB, linear alpha) as RGBA16F bits: 4 halves a texel, in order.
std::vector<uint16_t> decodeSrgbTexels(const uint8_t* rgba, size_t texels);

}  // namespace gbl
