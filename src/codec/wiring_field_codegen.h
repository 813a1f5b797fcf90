#pragma once
// Internal to codec/: the per-encoding GLSL of one field, used by wiring_codegen.cpp (which places
// the codes in a target's words and assembles writeGBuffer / readGBuffer). Split from it so that
// each file has one job: this one knows the encodings' GLSL names, that one the layout's bits.
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "layout.h"

namespace gbl::wiring {

// An unsigned GLSL literal ("12u").
inline std::string ulit(uint64_t v) { return std::to_string(v) + "u"; }

inline constexpr const char* kComp[] = {"x", "y", "z", "w"};

// The vector component (0 = x .. 3 = w) a channel of a target is read from.
int channelComponent(const Channel& c);
int attributeComponents(Attribute a);

// Colour transforms of the YCbCr family: forward, inverse; false for other encodings.
bool colorTransform(const std::string& enc, std::string& fwd, std::string& inv);
// The GLSL function that dequantises an encoding's chroma codes.
std::string chromaDequantize(const std::string& enc);

// Emits the encoder of a field: setup lines, returns one uint expression per code. An extra's
// value is the layout's constant, or, with extrasFromSurface (layouts export), the Surface member
// extraMemberName(attribute).
std::vector<std::string> emitEncodeField(std::ostream& o, const std::string& ind, const Field& f, const std::string& id,
                                         bool extrasFromSurface = false);
// The member an extra takes in an exported Surface: its name in camelCase ("shadingModelId").
std::string extraMemberName(Attribute a);
// Decoded value of a (non-checkerboard) field from its code expressions; "" for extras.
std::string decodeFieldExpr(const Field& f, const std::vector<std::string>& c);
// The GLSL statement that sets the attribute a field's encoding also stores (EncodingInfo::carries,
// e.g. "s.occlusion = ...;"), "" when it stores nothing else.
std::string decodeCarriedStatement(const Field& f, const std::vector<std::string>& c);

// Native formats: whether every code of `f` is one whole channel of `t` whose hardware encoding is
// the field's own; the floats the shader writes for them (emitNativeEncode) and the decoded value
// from the floats the hardware reads back (nativeDecodeExpr).
bool nativeField(const Target& t, const Field& f);
std::vector<std::string> emitNativeEncode(std::ostream& o, const std::string& ind, const Field& f, const std::string& id);
std::string nativeDecodeExpr(const Field& f, const std::vector<std::string>& u);

// Bit placement (wiring_codegen.cpp): `words[k] |= ...` lines that put `code` at its place in a
// target's words, and the expression that reads a code back from them.
void emitPlaceCode(std::ostream& o, const std::string& ind, const Target& t, const CodePlace& cp,
                   const std::string& words, const std::string& code);
std::string extractCode(const Target& t, const CodePlace& cp, const std::string& words);
std::string maskLit(int bits);
// The shading-model selector (layouts/README.md, "Shading models"), from the one statement of the
// encoder's rule (src/layout/shading_models.cpp), which the CPU codec's plan also reads:
// `uint <var> = 0u;` and one `if` per model the selector names, in reverse order of preference,
// so the pixel's model (ShadingModel's index) is the first whose layer the Surface `s` carries.
void emitModelPick(std::ostream& o, const std::string& ind, const Layout& layout, const std::string& var);
// The selector's code of the model in `var` ("var == 1u ? 4u : var == 2u ? 8u : 1u"; GLSL and HLSL).
std::string modelIdExpr(const Field& selector, const std::string& var);
// "((18u >> var) & 1u) != 0u": whether bit `var` of `mask` is set (a model or id in a set).
std::string maskTest(uint32_t mask, const std::string& var);

// `s.member = ...;` for a fallback (constant or derived; forward and material_pass as the renderer reads them).
void emitFallback(std::ostream& o, const Fallback& fb, const Layout& layout);

}  // namespace gbl::wiring
