#include "scene_gltf_images.h"

#include "error.h"
#include "image_io.h"
#include "memory_budget.h"

namespace gbl {

namespace {

// Per decoded RGBA8 byte (16-bit images: two): stb's buffer, tinygltf's copy of it, the texture's
// RGBA8 copy (scene_gltf_textures.h) and its upload with a mip chain (a third more).
constexpr double kCopiesPerDecodedByte = 4.5;

}  // namespace

void GltfImageBudget::install(tinygltf::TinyGLTF& parser) { parser.SetImageLoader(&GltfImageBudget::load, this); }

bool GltfImageBudget::load(tinygltf::Image* image, int imageIndex, std::string* err, std::string* warn, int reqWidth,
                           int reqHeight, const unsigned char* bytes, int size, void* self) {
    auto* budget = static_cast<GltfImageBudget*>(self);
    const std::string name = image && !image->uri.empty() && image->uri.rfind("data:", 0) != 0
                                 ? image->uri
                                 : "image " + std::to_string(imageIndex);
    const std::string where =
        formatPlace(escapeText(budget->scenePath_)) + ": images[" + std::to_string(imageIndex) + "] " + quoteName(name);
    auto refuse = [&](const std::string& message) {
        if (budget->refusal_.empty()) budget->refusal_ = message;
        if (err) *err = message;
        return false;
    };
    std::string whyNot;
    const auto info = probeImageMemory(bytes, size_t(size > 0 ? size : 0), &whyNot);
    // stb_image decodes what tinygltf decodes: a header it cannot read is no image for either.
    if (!info)
        return refuse(where + ": not an image stb_image can decode (" + escapeText(whyNot) +
                      "); re-save it as an 8-bit PNG or JPEG");
    const double decoded = double(info->width) * double(info->height) * 4.0 * (info->sixteenBit ? 2.0 : 1.0);
    const double total = budget->bytesSoFar_ + decoded * kCopiesPerDecodedByte;
    try {
        requireMemory(total,
                      where + " (" + std::to_string(info->width) + "x" + std::to_string(info->height) +
                          ", with the scene's images before it)",
                      "give the scene smaller textures, or raise GBL_MEMORY_BUDGET");
    } catch (const UserError& e) {
        return refuse(e.what());
    }
    budget->bytesSoFar_ = total;
    return tinygltf::LoadImageData(image, imageIndex, err, warn, reqWidth, reqHeight, bytes, size, nullptr);
}

}  // namespace gbl
