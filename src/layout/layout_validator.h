#pragma once
// The layout validator's checks (layout_validate.cpp: the layout as a whole; layout_validate_fields.cpp:
// one field, and the bits of one target). Internal to gbl_layout.
#include <string>
#include <string_view>
#include <vector>

#include "encoding_registry.h"
#include "layout.h"

namespace gbl::layout_validation {

inline constexpr int kMaxColorTargets = 8;  // Vulkan's guaranteed maxColorAttachments (and lavapipe's)

inline std::string squote(std::string_view s) { return "'" + std::string(s) + "'"; }
inline std::string bitsText(int n) { return std::to_string(n) + (n == 1 ? " bit" : " bits"); }
inline std::string lineText(FilePlace p) { return "line " + std::to_string(p.line); }

class Validator {
public:
    Validator(const Layout& layout, std::vector<LayoutDiagnostic>& out) : layout_(layout), out_(out) {}
    void run();

private:
    void error(FilePlace place, std::string message);
    // Number of codes a field's encoding produces for its attribute.
    static int expectedCodes(const Field& f, const EncodingInfo* enc);
    // Why `enc` cannot hold `attr` ("" when it can).
    static std::string unsuitable(const EncodingInfo& enc, const AttributeInfo& attr);
    // Everything about one field that does not involve other fields. `channels` is the target's
    // (or the stencil's) channel list, `format` its name for messages.
    void checkField(const Field& f, const std::vector<Channel>& channels, const std::string& format);
    // Bits of one target (or the stencil): total fits, no two codes share a bit.
    void checkPacking(const std::vector<Field>& fields, const std::vector<Channel>& channels, int totalBits,
                      const std::string& where, const std::string& format, FilePlace place);
    void checkTargets();
    void checkStencil();
    // An encoding that reads another attribute of the pixel (emissive_albedo_ratio reads
    // base_color) decodes from that attribute's decoded value: it must be stored in a field that
    // comes before this one (an earlier target, or earlier in the same target), as readGBuffer
    // and the CPU codec decode fields in layout order.
    void checkReads();
    void checkStoredOnce();
    // The selector and the conditional fields (layouts/README.md, "Shading models: the selector").
    void checkSelector();
    FilePlace fallbackTablePlace() const;
    void checkRequired();
    // What each derived fallback reads.
    static std::vector<Attribute> inputsOf(FallbackKind k);
    void checkFallbacks();
    // [clear]: declared, listing every shading or geometry attribute stored in a colour target and
    // only those (extras hold their declared `value` in every pixel, cleared ones included): what a
    // pixel without geometry holds is part of the layout, never a default.
    // [space]: the space normals are stored in is declared, never assumed (issue 11 item 4), and a
    // stored position's space too; a position space without a stored position is an error.
    void checkSpace();
    void checkClear();
    // The attribute a field's encoding stores besides its own (EncodingInfo::carries), else its own.
    static Attribute carriedBy(const Field& f);
    void checkPipeline();

    const Layout& layout_;
    std::vector<LayoutDiagnostic>& out_;
};

}  // namespace gbl::layout_validation
