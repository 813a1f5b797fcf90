#pragma once
// The files a glTF scene reads besides itself (buffer and image URIs), for tinygltf's file
// callbacks: only regular files (a FIFO or device is refused, never read), and only inside the
// scene's folder unless the user allows more (--allow-outside-scene): a URI like
// "../../etc/passwd" or "/etc/passwd" must not turn a private file into geometry.
#include <string>

#include <tiny_gltf.h>

namespace gbl {

class GltfFileAccess {
public:
    GltfFileAccess(const std::string& scenePath, bool allowOutsideScene);
    // Callbacks bound to this object (which must outlive the load).
    tinygltf::FsCallbacks callbacks();
    // The folder tinygltf resolves relative URIs against.
    const std::string& baseDir() const { return baseDir_; }
    // The first refusal, as a one-line message naming the scene and the URI; "" when none. A
    // failed load reports this instead of tinygltf's generic "File read error".
    const std::string& refusal() const { return refusal_; }

private:
    static bool fileExists(const std::string& path, void* self);
    static std::string expandFilePath(const std::string& path, void* self);
    static bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* self);
    static bool writeWholeFile(std::string* err, const std::string& path, const std::vector<unsigned char>& bytes,
                               void* self);
    void refuse(const std::string& message);

    std::string scenePath_;
    std::string baseDir_;
    std::string folder_;  // canonical scene folder, for the confinement check
    bool allowOutside_;
    std::string refusal_;
};

}  // namespace gbl
