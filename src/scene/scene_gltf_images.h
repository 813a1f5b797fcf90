#pragma once
// tinygltf's image decoding, with the memory budget (memory_budget.h) checked from each image's
// header first: a 100 KB PNG whose header claims 60000x60000 pixels would otherwise be decoded
// into 14 GB (and copied to RGBA8, and uploaded with its mips). The images of one scene are
// counted together. A refusal names the scene, the image and the fix; tinygltf then fails the
// load and the loader reports the refusal instead of tinygltf's own message.
#include <string>

#include <tiny_gltf.h>

namespace gbl {

class GltfImageBudget {
public:
    explicit GltfImageBudget(std::string scenePath) : scenePath_(std::move(scenePath)) {}
    // Installs the checking loader on `parser` (this object must outlive the load).
    void install(tinygltf::TinyGLTF& parser);
    const std::string& refusal() const { return refusal_; }

private:
    static bool load(tinygltf::Image* image, int imageIndex, std::string* err, std::string* warn, int reqWidth,
                     int reqHeight, const unsigned char* bytes, int size, void* self);

    std::string scenePath_;
    double bytesSoFar_ = 0.0;
    std::string refusal_;
};

}  // namespace gbl
