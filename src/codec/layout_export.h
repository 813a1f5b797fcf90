#pragma once
// `gbufferlab layouts export`: a layout as one self-contained HLSL or GLSL file an engine includes
// (docs/export.md). It holds a Surface struct in engine units, an encode to the values each render
// target of the layout's REAL format receives (float4 for UNORM / SNORM / sRGB / float targets,
// uint for UINT ones), a decode from those values (and the 4 neighbours where the layout
// reconstructs checkerboard chroma), the encoding helpers it needs and nothing else, and a header
// comment with the bit map, formats, clear values, what is derived and the provenance.
//
// One source of truth: the helpers are the declarations of shaders/*_encodings.glsl that the
// renderer compiles (export_glsl_library.h), and the per-field codes and bit places come from the
// generator of the renderer's wiring (wiring_field_codegen.h), so the exported encode packs the
// same words as writeGBuffer and the CPU mirror (tests/codec/layout_export_gpu_test.cpp).
//
// Every identifier the file declares starts with gbl_ (layout text never becomes an identifier
// except through exportIdentifier), and layout text reaches it only inside // comments, made
// printable ASCII by glslCommentText.
#include <string>
#include <vector>

#include "export_glsl_library.h"
#include "layout.h"

namespace gbl {

enum class ExportLanguage { Glsl, Hlsl };

struct ExportOptions {
    ExportLanguage language = ExportLanguage::Glsl;
    // A compute entry point `main`: surfaces from a buffer, encode, decode, both written back
    // (the float layout of exportSurfaceMembers; docs/export.md).
    bool kernel = false;
    // The 8-bit tables as select trees (default) or const arrays (export_glsl_library.h).
    exporting::ExportTables tables = exporting::ExportTables::Selects;
};

// One member of the exported Surface struct, in declaration order.
struct ExportMember {
    std::string name;      // "baseColor", "shadingModelId"
    Attribute attribute{};
    int components = 1;
    bool isUint = false;   // integer extras
    bool stored = true;    // false: derived by decode from a fallback, ignored by encode
    int firstFloat = 0;    // its first float in the kernel's buffers
    std::vector<double> defaultValue;  // extras: the layout's declared value (else empty: 0)
};

std::vector<ExportMember> exportSurfaceMembers(const Layout& layout);
// Floats per surface in the kernel's input (the members, then 1 = covered, 0 = no geometry) and
// output (the decoded members, then 4 words per target: a float target's values as float bits).
int exportKernelInputFloats(const Layout& layout);
int exportKernelOutputWords(const Layout& layout);
// The prefix of every name the file declares for this layout: "gbl_" + the name with every
// character outside [A-Za-z0-9] as '_' (no "__": GLSL reserves it).
std::string exportPrefix(const Layout& layout);
std::string exportIdentifier(const std::string& text);
// Whether encode takes the pixel (checkerboard chroma, dithering) and decode the 4 neighbours.
bool exportEncodeTakesPixel(const Layout& layout);
bool exportDecodeReconstructs(const Layout& layout);
bool exportUsesBestFitTable(const Layout& layout);

// The scale k with which float(code) * k is the value a UNORM channel of `bits` bits (or, signed,
// an SNORM one: scale 2^(bits-1) - 1) receives: float(code) * k * (2^bits - 1) lies in
// [code, code + 0.25) for every code, whether the product rounds to nearest or towards zero, so
// the hardware's conversion (round to nearest, or truncate) gives back exactly `code`.
float exportNormScale(int bits, bool isSigned);

// Throws std::runtime_error when the encodings' GLSL cannot be read.
std::string exportLayout(const Layout& layout, const ExportOptions& options, const exporting::ShaderFileReader& read);
// The same with the encodings' library read once (a caller that exports many layouts: the mutant
// and fuzz tests; reading and splitting the shader files is most of an export's time).
std::string exportLayout(const Layout& layout, const ExportOptions& options, const exporting::GlslLibrary& library);

}  // namespace gbl
