#include "layout_catalog.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <system_error>

namespace gbl {
namespace fs = std::filesystem;

fs::path layoutDirectory() {
    if (const char* env = std::getenv("GBL_LAYOUT_DIR"); env && *env) {
        fs::path dir(env);
        std::error_code ec;
        if (!fs::is_directory(dir, ec))
            throwUserError("GBL_LAYOUT_DIR=" + dir.string() +
                           ": not a directory (point it at gbufferlab's layouts/ or unset it)");
        return dir;
    }
    fs::path dir(GBL_SOURCE_LAYOUT_DIR);
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throwUserError(dir.string() +
                       ": the layouts directory is missing; set GBL_LAYOUT_DIR to gbufferlab's "
                       "layouts/ directory");
    return dir;
}

std::vector<std::string> listLayoutNames(const fs::path& dir) {
    std::vector<std::string> names;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const fs::path& p = it->path();
        if (p.extension() == ".toml" && it->is_regular_file(ec)) names.push_back(p.stem().string());
    }
    if (ec) throwUserError(dir.string() + ": cannot list layouts (" + ec.message() + ")");
    std::sort(names.begin(), names.end());
    return names;
}

std::vector<std::string> listLayoutNames() { return listLayoutNames(layoutDirectory()); }

fs::path findLayoutFile(const std::string& nameOrPath) {
    const bool isPath = nameOrPath.find('/') != std::string::npos ||
                        (nameOrPath.size() > 5 && nameOrPath.compare(nameOrPath.size() - 5, 5, ".toml") == 0);
    std::error_code ec;
    if (isPath) {
        // Anything that exists is returned: reading it refuses directories and FIFOs by name.
        const bool exists = fs::exists(nameOrPath, ec);
        if (ec && ec.value() == ELOOP)
            throwUserError(escapeText(nameOrPath) + ": a symbolic link that loops (" + ec.message() +
                           "); point it at a layout file");
        if (ec) throwUserError(escapeText(nameOrPath) + ": cannot be read (" + ec.message() + "); check the path");
        if (!exists) throwUserError(escapeText(nameOrPath) + ": no such layout file");
        return nameOrPath;
    }
    const fs::path dir = layoutDirectory();
    const fs::path file = dir / (nameOrPath + ".toml");
    if (fs::is_regular_file(file, ec)) return file;
    std::string known;
    for (const std::string& n : listLayoutNames(dir)) known += (known.empty() ? "" : ", ") + n;
    throwUserError("unknown layout '" + nameOrPath + "' in " + dir.string() + " (known: " + known + ")");
}

Layout loadLayout(const std::string& nameOrPath) { return loadLayoutFile(findLayoutFile(nameOrPath)); }

Layout loadReferenceLayout(int sceneLayers) {
    Layout reference = loadLayout("reference");
    const auto dropped = [&](Attribute a) {
        const int bit = attributeLayerBit(a);
        return bit != 0 && (sceneLayers & bit) == 0;
    };
    for (Target& t : reference.targets)
        std::erase_if(t.fields, [&](const Field& f) { return dropped(f.attribute); });
    std::erase_if(reference.targets, [](const Target& t) { return t.fields.empty(); });
    std::erase_if(reference.clears, [&](const ClearValue& c) { return dropped(c.attribute); });
    return reference;
}

}  // namespace gbl
