#pragma once
// The text of a small layout file for a test, built from its parts as the layout language writes
// them: the header, [depth], the [[target]]s or [ids], then (with targets) [fallback], [space] and
// [clear]. [fallback] holds the usual value of every attribute that no field stores, unless told
// otherwise; a test's own text is what it states, the rest is this file's.
#include <string>
#include <utility>
#include <vector>

namespace gbl::test {

// `source = ...` of a layout written for a test.
inline constexpr const char* kTestSource = R"({ engine = "none", talk = "unit test", year = 2024 })";
inline constexpr const char* kHdrpSource = R"({ engine = "Unity HDRP", talk = "unit test", year = 2021 })";

// A [[target]] (without its header line): name, format and fields, each field an inline table
// without its braces ("attribute = \"normal\", encoding = ..., at = [...]").
std::string targetText(const std::string& name, const std::string& format, const std::vector<std::string>& fields);

// HDRP's G-buffer targets (Lit.hlsl's EncodeIntoGBuffer, through gbufferlab's HDRP encodings):
// GBuffer1 the normal buffer with perceptual roughness, GBuffer2 fresnel0 through FastLinearToSRGB,
// GBuffer3 emissive with the AO tag.
std::string hdrpGBuffer1();
std::string hdrpGBuffer2();
std::string hdrpGBuffer3();

class LayoutText {
public:
    LayoutText(std::string name, std::string title, std::string source = kTestSource,
               std::string pipeline = "deferred-shading");

    // [depth]'s lines (by default: format = "D32_SFLOAT").
    LayoutText& depth(std::string lines);
    // Adds a target: targetText(...), or the text of one.
    LayoutText& target(std::string text);
    LayoutText& target(const std::string& name, const std::string& format, const std::vector<std::string>& fields);
    // [ids]'s lines: a visibility buffer's.
    LayoutText& ids(std::string lines);
    // A fallback's value (TOML), replacing the usual one or added after the others.
    LayoutText& fallback(const std::string& attribute, const std::string& value);
    // No fallback for `attribute` (one that an encoding stores beside another).
    LayoutText& noFallback(const std::string& attribute);
    // The fallbacks written in this order (the others after them, as they were): the order a
    // layout's diagnostics follow.
    LayoutText& fallbackOrder(const std::vector<std::string>& attributes);
    // [space]'s lines (by default: normal = "world", up = "y").
    LayoutText& space(std::string lines);
    // Adds a line to [clear] (by default: the normal (0, 0, 1) and roughness 1).
    LayoutText& clear(const std::string& line);

    std::string text() const;
    operator std::string() const { return text(); }

private:
    std::string name_, title_, source_, pipeline_;
    std::string depth_ = "format = \"D32_SFLOAT\"\n";
    std::vector<std::string> targets_;
    std::string ids_;
    std::vector<std::pair<std::string, std::string>> fallbacks_;
    std::string space_ = "normal = \"world\"\nup = \"y\"\n";
    std::string clear_ = "normal = [0.0, 0.0, 1.0]\nroughness = 1.0\n";
};

}  // namespace gbl::test
