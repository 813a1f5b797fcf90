#include "scene_gltf_files.h"

#include <filesystem>

#include "error.h"
#include "file_io.h"

namespace gbl {
namespace fs = std::filesystem;

GltfFileAccess::GltfFileAccess(const std::string& scenePath, bool allowOutsideScene)
    : scenePath_(scenePath), allowOutside_(allowOutsideScene) {
    const fs::path parent = fs::path(scenePath).parent_path();
    baseDir_ = parent.empty() ? "." : parent.string();
    std::error_code ec;
    folder_ = fs::weakly_canonical(fs::absolute(baseDir_, ec), ec).string();
}

tinygltf::FsCallbacks GltfFileAccess::callbacks() {
    return tinygltf::FsCallbacks{&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, this};
}

void GltfFileAccess::refuse(const std::string& message) {
    if (refusal_.empty()) refusal_ = message;
}

bool GltfFileAccess::fileExists(const std::string& path, void*) {
    // Any kind of file "exists": readWholeFile then refuses what is not regular, with a reason.
    std::error_code ec;
    return fs::exists(fs::symlink_status(path, ec)) && fs::exists(path, ec);
}

// tinygltf joins the base folder and the URI with '/', so an absolute URI arrives as
// "<base>//abs/path" (or ".//abs/path" on its second try): give it back its absolute form, so
// that the confinement check sees where it really points.
std::string GltfFileAccess::expandFilePath(const std::string& path, void* self) {
    const auto* access = static_cast<GltfFileAccess*>(self);
    for (const std::string& base : {access->baseDir_, std::string(".")}) {
        const std::string prefix = base + "//";
        if (path.size() > prefix.size() && path.compare(0, prefix.size(), prefix) == 0)
            return path.substr(base.size() + 1);
    }
    return path;
}

bool GltfFileAccess::readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                                   void* self) {
    auto* access = static_cast<GltfFileAccess*>(self);
    std::error_code ec;
    const std::string resolved = fs::weakly_canonical(fs::absolute(path, ec), ec).string();
    const std::string& folder = access->folder_;
    const bool inside = !ec && resolved.size() > folder.size() && resolved.compare(0, folder.size(), folder) == 0 &&
                        (folder.back() == '/' || resolved[folder.size()] == '/');
    if (!inside && !access->allowOutside_) {
        access->refuse(formatPlace(escapeText(access->scenePath_)) + ": the URI " + quoteName(path) +
                       " resolves to " + quoteName(resolved) +
                       ", outside the scene's folder; move the file beside the scene, or pass "
                       "--allow-outside-scene if you trust this scene");
        if (err) *err = "outside the scene's folder";
        return false;
    }
    try {
        *out = readBinaryFile(path);
        registerInput(path);  // no output may replace it (file_io.h)
    } catch (const UserError& e) {
        access->refuse(formatPlace(escapeText(access->scenePath_)) + ": a URI of the scene: " + e.what());
        if (err) *err = e.what();
        return false;
    }
    return true;
}

bool GltfFileAccess::writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err = "gbufferlab never writes glTF files";
    return false;
}

}  // namespace gbl
