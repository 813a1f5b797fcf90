#include "layout_files.h"

#include "layout_catalog.h"

namespace gbl::test {

std::filesystem::path shippedLayoutDir() { return GBL_SOURCE_LAYOUT_DIR; }

Layout shippedLayout(const std::string& name) { return loadLayoutFile(shippedLayoutDir() / (name + ".toml")); }

std::vector<Layout> shippedLayouts() {
    std::vector<Layout> v;
    for (const std::string& name : listLayoutNames(shippedLayoutDir())) v.push_back(shippedLayout(name));
    return v;
}

std::vector<Layout> shippedAttributeLayouts() {
    std::vector<Layout> v = shippedLayouts();
    std::erase_if(v, [](const Layout& l) { return l.pipeline == Pipeline::VisibilityBuffer; });
    return v;
}

std::filesystem::path testLayoutDir() { return shippedLayoutDir().parent_path() / "tests" / "layout" / "data"; }

Layout testLayout(const std::string& name) { return loadLayoutFile(testLayoutDir() / (name + ".toml")); }

}  // namespace gbl::test
