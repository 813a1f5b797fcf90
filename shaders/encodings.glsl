// gbufferlab encoding primitives, GLSL 450 include file (no #version).
// Mirrored line for line in src/encodings.{h,cpp} (namespace gbl::enc) with the same names.
//
// Contract (why GPU and CPU agree to the bit):
// - Encoders map floats to integer codes and quantise with floor(x * s + 0.5), s = 2^bits - 1,
//   never round() / packUnorm*. They use only + - * / sqrt abs min max floor clamp and integer
//   ops, whose results IEEE 754 fixes exactly (llvmpipe: divps/sqrtps; C++: -ffp-contract=off).
//   Float intermediates of encoders are `precise` so that no driver reassociates or fuses them.
//   (quantizeDepth24 is the one exception: an exact float split, see there.) Checked once on
//   lavapipe (llvmpipe 15): 37.7M codes from every encoder bit-identical to the C++ mirror.
// - Decoders map codes to floats; they are compared with a tolerance (lavapipe: <= 1 ulp).
// - Inputs are finite; NaN is not expected (clamp of NaN is undefined in GLSL).
// Error bounds in the family files below were measured by tests/encoding/encodings_test.cpp (exhaustive where <= 16 bits per
// code, otherwise millions of random inputs); see `gbufferlab encodings` for mean / p99 / max.

#ifndef GBL_ENCODINGS_GLSL
#define GBL_ENCODINGS_GLSL

// The families, in dependency order (each uses only those before it); section numbers as in
// src/encoding/encodings.h.
#include "codec_tables.glsl"      // where the 8-bit tables below are read from
#include "scalar_encodings.glsl"  // 1-3. fixed point, small floats, 8-bit sRGB
#include "normal_encodings.glsl"  // 4. unit normals
#include "color_encodings.glsl"   // 5-8. colour transforms, chroma checkerboard, roughness maps, UE4 specular colour, depth
#include "engine_encodings.glsl"  // 8. packings of shipped engines

// zeux/niagara's emissive-to-albedo ratio and dithered octahedral normals.
#include "niagara_encodings.glsl"

#endif  // GBL_ENCODINGS_GLSL
