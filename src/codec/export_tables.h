#pragma once
// The encodings' exact 8-bit tables (sRGB, gamma 2.2, CryEngine's gloss, HDRP's fast sRGB: const
// float arrays in shaders/*_encodings.glsl) as `layouts export` writes them: functions that select
// the entry's bits from uvec4 constants, and each binary search over a threshold table unrolled so
// that its step k selects among the 2^k entries that step can reach.
//
// Why: a const array indexed at run time is lowered by lavapipe (Mesa 22.3) into an if-else ladder
// over every element at every lookup (nir_lower_indirect_derefs on function temporaries; a global
// `const` array is also copied into a local one at every call), and LLVM then takes minutes on a
// shader with a few sRGB encodes (granite's export kernel: over 15 minutes on the loaded 2-core
// machine, 26 s with the array a mutable global). A tree of selects over the same words is straight
// code: the kernel compiles in about 3 s there (28 Nov 2026, load 7). The values are the same bits
// (tests/codec/export_tables_test.cpp reads the trees back against the C++ twin tables).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "export_glsl_library.h"

namespace gbl::exporting {

// The values of `const float NAME[N] = float[N](...);` (parsed as glslang does: decimal to double,
// then to float); nullopt when `code` is not such a declaration.
struct ConstFloatTable {
    std::string name;
    std::vector<float> values;
};
std::optional<ConstFloatTable> parseConstFloatTable(const std::string& code);

// Rewrites, in place: every const float table used by a binary search of the encodings' shape
// (lo = 0, hi = 255, 8 steps) into `float NAME(uint step, uint j)` and the searches into their
// unrolled form; every other const float table into `float NAME(uint i)`, its `NAME[e]` uses into
// `NAME(e)`. Declarations it does not recognise are left as they are.
void rewriteCodecTables(std::vector<GlslDeclaration>& declarations);

// The entry of a 255-entry threshold table that step `step` (0..7) of the unrolled search reads
// when the count so far is c: index (c >> (8 - step)) * 2^(8 - step) + 2^(7 - step) - 1.
inline uint32_t searchStepEntry(uint32_t step, uint32_t j) {
    return j * (256u >> step) + (128u >> step) - 1u;
}

}  // namespace gbl::exporting
