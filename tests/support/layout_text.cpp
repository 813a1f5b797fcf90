#include "layout_text.h"

#include <algorithm>

namespace gbl::test {

std::string targetText(const std::string& name, const std::string& format, const std::vector<std::string>& fields) {
    std::string s = "name = \"" + name + "\"\nformat = \"" + format + "\"\nfield = [\n";
    for (const std::string& f : fields) s += "  { " + f + " },\n";
    return s + "]\n";
}

std::string hdrpGBuffer1() {
    return targetText("GBuffer1", "R8G8B8A8_UNORM",
                      {R"(attribute = "normal",    encoding = "normal_octahedral_hdrp", at = ["r + b[0:3]", "g + b[4:7]"])",
                       R"(attribute = "roughness", encoding = "unorm", at = "a")"});
}

std::string hdrpGBuffer2() {
    return targetText("GBuffer2", "R8G8B8A8_UNORM",
                      {R"(attribute = "specular_color", encoding = "srgb8_fast_hdrp", at = ["r", "g", "b"])"});
}

std::string hdrpGBuffer3() {
    return targetText("GBuffer3", "B10G11R11_UFLOAT_PACK32",
                      {R"(attribute = "emissive", encoding = "float11_11_10_hdrp_ao_tag", at = ["r", "g", "b"])"});
}

LayoutText::LayoutText(std::string name, std::string title, std::string source, std::string pipeline)
    : name_(std::move(name)), title_(std::move(title)), source_(std::move(source)), pipeline_(std::move(pipeline)) {
    fallbacks_ = {{"base_color", "0.5"},
                  {"metallic", "0.0"},
                  {"specular", "0.5"},
                  {"specular_color", "\"from_metallic\""},
                  {"diffuse_color", "\"from_base_color\""},
                  {"occlusion", "1.0"},
                  {"emissive", "0.0"}};
}

LayoutText& LayoutText::depth(std::string lines) {
    depth_ = std::move(lines);
    return *this;
}

LayoutText& LayoutText::target(std::string text) {
    targets_.push_back(std::move(text));
    return *this;
}

LayoutText& LayoutText::target(const std::string& name, const std::string& format, const std::vector<std::string>& fields) {
    return target(targetText(name, format, fields));
}

LayoutText& LayoutText::ids(std::string lines) {
    ids_ = std::move(lines);
    return *this;
}

LayoutText& LayoutText::fallback(const std::string& attribute, const std::string& value) {
    for (auto& [a, v] : fallbacks_)
        if (a == attribute) {
            v = value;
            return *this;
        }
    fallbacks_.emplace_back(attribute, value);
    return *this;
}

LayoutText& LayoutText::noFallback(const std::string& attribute) {
    std::erase_if(fallbacks_, [&](const auto& f) { return f.first == attribute; });
    return *this;
}

LayoutText& LayoutText::fallbackOrder(const std::vector<std::string>& attributes) {
    auto rank = [&](const std::pair<std::string, std::string>& f) {
        return size_t(std::find(attributes.begin(), attributes.end(), f.first) - attributes.begin());
    };
    std::stable_sort(fallbacks_.begin(), fallbacks_.end(), [&](const auto& a, const auto& b) { return rank(a) < rank(b); });
    return *this;
}

LayoutText& LayoutText::space(std::string lines) {
    space_ = std::move(lines);
    return *this;
}

LayoutText& LayoutText::clear(const std::string& line) {
    clear_ += line + "\n";
    return *this;
}

std::string LayoutText::text() const {
    std::string s = "name = \"" + name_ + "\"\ntitle = \"" + title_ + "\"\npipeline = \"" + pipeline_ + "\"\nsource = " +
                    source_ + "\n\n[depth]\n" + depth_;
    for (const std::string& t : targets_) s += "\n[[target]]\n" + t;
    if (!ids_.empty()) s += "\n[ids]\n" + ids_;
    if (targets_.empty()) return s;
    auto stored = [&](const std::string& attribute) {
        const std::string key = "attribute = \"" + attribute + "\"";
        return std::any_of(targets_.begin(), targets_.end(), [&](const std::string& t) { return t.find(key) != std::string::npos; });
    };
    s += "\n[fallback]\n";
    for (const auto& [attribute, value] : fallbacks_)
        if (!stored(attribute)) s += attribute + " = " + value + "\n";
    return s + "\n[space]\n" + space_ + "\n[clear]\n" + clear_;
}

}  // namespace gbl::test
