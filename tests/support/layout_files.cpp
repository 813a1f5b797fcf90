#include "layout_files.h"

#include "layout_catalog.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

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

Layout selectorLayoutDerivingEachOther() {
    std::ifstream in(testLayoutDir() / "shading-models.toml");
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    auto replace = [&](const std::string& from, const std::string& to) {
        const size_t at = text.find(from);
        if (at == std::string::npos) throw std::logic_error("shading-models.toml has no '" + from + "'");
        text.replace(at, from.size(), to);
    };
    replace(R"({ attribute = "metallic",  encoding = "unorm", at = "r" },)",
            R"({ attribute = "metallic",  encoding = "unorm", at = "r", model = ["anisotropic", "clear_coat"] },)");
    replace("specular_color = \"ue4\"         #", "metallic = \"from_specular_color\"\nspecular_color = \"ue4\"         #");
    replace("[fallback]", "[[target]]\nname = \"E\"\nformat = \"R8G8B8A8_UNORM\"\nfield = [\n"
                          "  { attribute = \"specular_color\", encoding = \"unorm\", at = [\"r\", \"g\", \"b\"], "
                          "model = [\"default\", \"cloth\"] },\n]\n\n[fallback]");
    replace("occlusion = 1.0\n", "occlusion = 1.0\nspecular_color = 0.04\n");
    return parseLayout(text, "shading-models.toml");
}

}  // namespace gbl::test
