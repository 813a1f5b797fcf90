#pragma once
// The encodings' exact 8-bit tables (encodings.h: kSrgbDecode, kSrgbEncodeThresholds,
// kCryGlossRoughness, kCryGlossEncodeThresholds, kGamma22Decode, kGamma22EncodeThresholds,
// kSrgbFastHdrpEncodeThresholds; engine_encodings.h: kKz2PowerRoughness,
// kKz2PowerEncodeThresholds) as one array of floats, in the order and at the offsets of shaders/codec_tables.glsl: what the
// renderer uploads as the storage buffer its G-buffer pass (set 0) and G-buffer readers (lighting
// and decode passes, set 1) take the tables from, at binding kCodecTablesBinding. Why a buffer and not the
// shaders' constant arrays: codec_tables.glsl (llvmpipe's JIT compile of constant arrays indexed
// at run time). Each table takes 256 floats; a 255-entry threshold table ends with one 0 of
// padding that no search reads.
#include <cstdint>
#include <vector>

namespace gbl::enc {

// In set 0 of the G-buffer pass (after kBestFitTableBinding) and set 1 of its readers (the
// target-read set: after any target's binding).
inline constexpr uint32_t kCodecTablesBinding = 16;
inline constexpr uint32_t kCodecTableSrgbDecode = 0;
inline constexpr uint32_t kCodecTableSrgbEncode = 256;
inline constexpr uint32_t kCodecTableCryGlossDecode = 512;
inline constexpr uint32_t kCodecTableCryGlossEncode = 768;
inline constexpr uint32_t kCodecTableGamma22Decode = 1024;
inline constexpr uint32_t kCodecTableGamma22Encode = 1280;
inline constexpr uint32_t kCodecTableSrgbFastHdrpEncode = 1536;
inline constexpr uint32_t kCodecTableKz2PowerDecode = 1792;
inline constexpr uint32_t kCodecTableKz2PowerEncode = 2048;
inline constexpr uint32_t kCodecTableFloats = 2304;

// kCodecTableFloats floats: the nine tables at the offsets above.
const std::vector<float>& codecTableFloats();

}  // namespace gbl::enc
