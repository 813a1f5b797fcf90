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

}  // namespace gbl::test
