#pragma once
// The layouts of the source tree (layouts/*.toml) as the tests read them: from
// GBL_SOURCE_LAYOUT_DIR, whatever GBL_LAYOUT_DIR says.
#include <filesystem>
#include <string>
#include <vector>

#include "layout.h"

namespace gbl::test {

std::filesystem::path shippedLayoutDir();
// layouts/<name>.toml
Layout shippedLayout(const std::string& name);
// Every shipped layout, in the order of their names.
std::vector<Layout> shippedLayouts();
// The shipped layouts that store attributes: all but the visibility buffers (their ids:
// tests/render/visibility_test.cpp).
std::vector<Layout> shippedAttributeLayouts();
// The tests' own layouts (tests/layout/data/<name>.toml): shading-models, a selector's.
std::filesystem::path testLayoutDir();
Layout testLayout(const std::string& name);
// shading-models with HDRP's shape of fallbacks (fresnel0 under its standard feature, metallic under
// anisotropy, each derived where the other is stored): metallic held under anisotropic and
// clear_coat, a target E holding specular_color under default and cloth, metallic =
// "from_specular_color" beside specular_color = "ue4".
Layout selectorLayoutDerivingEachOther();

}  // namespace gbl::test
