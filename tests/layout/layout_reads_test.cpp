// The layout language's cross-attribute encodings (issue 15, niagara): an encoding that reads
// another attribute of the pixel (emissive_albedo_ratio reads base_color) is accepted only when
// that attribute is stored in a field before it; otherwise one error at the encoding's
// file:line:col names the field, the attribute it reads and the fix.
#include "layout_test_support.h"

using namespace gbl;
using namespace gbl::layout_test;

namespace {

// kValid's 3:3:2 base colour in rt0.a, plus a second target whose r holds emissive as the ratio.
const std::string kRatioTarget = R"(
[[target]]
name = "rt1"
format = "R8G8B8A8_UNORM"
field = [
  { attribute = "emissive", encoding = "emissive_albedo_ratio", at = "r" },
]
)";

std::string withRatio() {
    std::string t = edit(kValid, "emissive = 0.0\n", "");
    t = edit(t, "\n[fallback]", kRatioTarget + "\n[fallback]");
    return edit(t, "base_color = 0.0\n", "base_color = 0.0\nemissive = 0.0\n");
}

}  // namespace

TEST(LayoutReads, RatioAfterItsBaseColourIsValid) {
    const auto diags = checkLayout(withRatio(), kFile);
    EXPECT_TRUE(diags.empty()) << joined(diags);
}

TEST(LayoutReads, RatioWithoutBaseColourNamesTheFieldAndTheFix) {
    // base_color no longer stored: a fallback gives it, but the ratio needs the stored value.
    std::string t = edit(withRatio(), "  { attribute = \"base_color\", encoding = \"unorm\", at = [\"a[0:2]\", \"a[3:5]\", \"a[6:7]\"] },\n", "");
    t = edit(t, "base_color = 0.0\n", "");
    t = edit(t, "[fallback]\n", "[fallback]\nbase_color = 0.5\n");
    expectOnlyError(t, placeOf(t, "\"emissive_albedo_ratio\""),
                    {"encoding 'emissive_albedo_ratio' of 'emissive' reads 'base_color'",
                     "the layout does not store", "store base_color in a field before 'emissive'"});
}

TEST(LayoutReads, RatioBeforeItsBaseColourIsRefused) {
    // The ratio's target first: readGBuffer would decode emissive before base_color.
    std::string t = withRatio();
    const size_t rt1 = t.find("[[target]]\nname = \"rt1\"");
    ASSERT_NE(rt1, std::string::npos);
    const std::string block = t.substr(rt1, t.find("\n[fallback]") - rt1);
    t.erase(rt1, block.size());
    t = edit(t, "[[target]]\nname = \"rt0\"", block + "\n[[target]]\nname = \"rt0\"");
    expectOnlyError(t, placeOf(t, "\"emissive_albedo_ratio\""),
                    {"reads 'base_color', which is stored after it", "an earlier target"});
}

TEST(LayoutReads, RatioStoresEmissiveOnly) {
    std::string t = edit(kValid, "encoding = \"unorm\", at = [\"a[0:2]\", \"a[3:5]\", \"a[6:7]\"]",
                         "encoding = \"emissive_albedo_ratio\", at = \"a\"");
    expectError(t, placeOf(t, "\"emissive_albedo_ratio\""),
                {"'emissive_albedo_ratio' stores emissive relative to base_color, not 'base_color'"});
}
