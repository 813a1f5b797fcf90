#pragma once
// The encodings' GLSL (shaders/*_encodings.glsl, the files shaders/encodings.glsl includes) as a
// library of top-level declarations, for `gbufferlab layouts export`: the export emits the very
// text the renderer compiles (one source of truth), but only the declarations an exported layout
// reaches, renamed with a gbl_ prefix (an engine's own octEncode or quantizeUnorm cannot clash),
// each behind its own include guard (two exported layouts can share one shader), and, for HLSL,
// translated token by token (translateGlslToHlsl).
//
// What is not carried over: include guards and #include lines, GBL_CODEC_TABLE (no table buffer:
// the 8-bit tables become select trees, export_tables.h), and resource declarations (the best-fit
// normal table's buffer: the export declares its own, per language).
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace gbl::exporting {

struct GlslDeclaration {
    std::string name;     // the declared identifier (function, constant or #define)
    std::string comment;  // the // comment block right above it ("" when none)
    std::string code;     // the declaration itself, GBL_CODEC_TABLE already resolved
    bool isConstant = false;  // a global `const` (HLSL needs `static const`)
    bool isDefine = false;
    std::set<std::string> uses;  // identifiers it names (any, not only declarations)
};

// Reads one shader file by name ("encodings.glsl"); nullopt when missing.
using ShaderFileReader = std::function<std::optional<std::string>(const std::string&)>;

// How the export writes the encodings' 8-bit tables (export_tables.h): as select trees over
// uvec4 constants (the default: straight code that every driver compiles fast, about 255 selects
// per lookup), or as the shader source has them, const float arrays and 8-step binary searches
// (up to 8 loads per lookup, from constant memory on a GPU; minutes to compile on lavapipe).
enum class ExportTables { Selects, Arrays };

class GlslLibrary {
public:
    // The families encodings.glsl includes, in its order. Throws std::runtime_error naming the
    // file when one cannot be read.
    explicit GlslLibrary(const ShaderFileReader& read);

    // The declarations `roots` reach (transitively), in source order, with the tables as `tables`.
    std::vector<const GlslDeclaration*> closure(const std::set<std::string>& roots,
                                                ExportTables tables = ExportTables::Selects) const;
    const std::vector<GlslDeclaration>& declarations(ExportTables tables = ExportTables::Selects) const {
        return tables == ExportTables::Selects ? decls_ : source_;
    }

private:
    std::vector<GlslDeclaration> decls_;   // the tables rewritten (rewriteCodecTables)
    std::vector<GlslDeclaration> source_;  // as the shader files have them
};

// Splits one GLSL file into its top-level declarations (comments kept with the declaration they
// precede); preprocessor guards, #include lines and `layout(...)` resource blocks are dropped.
std::vector<GlslDeclaration> splitGlslDeclarations(const std::string& text);

// Every identifier of `code` outside comments.
std::set<std::string> identifiersOf(const std::string& code);

// `code` with each identifier in `names` replaced by prefix + identifier (comments too).
std::string prefixIdentifiers(const std::string& code, const std::set<std::string>& names, const std::string& prefix);

// GLSL 450 (the subset the encodings and the export's generated code use) as HLSL: vector and
// array types and their constructors (a one-argument vector constructor becomes a cast, which
// HLSL splats), bit casts (floatBitsToUint -> asuint ...), fract, mix, global `const`.
std::string translateGlslToHlsl(const std::string& code);

}  // namespace gbl::exporting
