// Image conversion to RGBA8 and the texture de-duplication table.
#include "scene_gltf_textures.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace gbl {
namespace {

// One channel of any bit depth tinygltf produces, as an 8-bit value.
uint8_t channelToByte(const uint8_t* p, int bits) {
    if (bits == 8) return *p;
    if (bits == 16) {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return static_cast<uint8_t>((uint32_t(v) * 255u + 32767u) / 65535u);  // round to nearest
    }
    float f;
    std::memcpy(&f, p, 4);
    if (!(f > 0.0f)) return 0;  // also NaN
    return static_cast<uint8_t>(std::lround(std::min(f, 1.0f) * 255.0f));
}

}  // namespace

Texture convertImageToRgba8(const GltfContext& ctx, size_t imageIndex, bool srgb) {
    const tinygltf::Image& image = ctx.model.images[imageIndex];
    const std::string name = !image.name.empty() ? image.name : !image.uri.empty() && image.uri.rfind("data:", 0) != 0
                                                                    ? image.uri
                                                                    : "image " + std::to_string(imageIndex);
    const std::string where = describeItem("image", imageIndex, name);
    if (image.width < 1 || image.height < 1 || image.image.empty())
        ctx.fail(where, "could not be loaded or decoded",
                 "check that the image file exists next to the glTF file and is a PNG or JPEG");
    if (image.component < 1 || image.component > 4 || (image.bits != 8 && image.bits != 16 && image.bits != 32))
        ctx.fail(where, "has " + std::to_string(image.component) + " channels of " + std::to_string(image.bits) +
                            " bits, which gbufferlab cannot convert", "save it as an 8-bit RGB or RGBA PNG");
    const size_t pixels = size_t(image.width) * size_t(image.height);
    const size_t bytesPerChannel = size_t(image.bits / 8);
    const size_t channels = size_t(image.component);
    if (image.image.size() != pixels * channels * bytesPerChannel)
        ctx.fail(where, "decoded to " + std::to_string(image.image.size()) + " bytes, not the expected " +
                            std::to_string(pixels * channels * bytesPerChannel),
                 "re-save the image as an 8-bit PNG");

    Texture texture;
    texture.name = name;
    texture.width = image.width;
    texture.height = image.height;
    texture.srgb = srgb;
    if (channels == 4 && image.bits == 8) {
        texture.rgba = image.image;  // already RGBA8: tinygltf asks stb for 4 channels
        return texture;
    }
    texture.rgba.resize(pixels * 4);
    const uint8_t* src = image.image.data();
    for (size_t i = 0; i < pixels; ++i) {
        const uint8_t* px = src + i * channels * bytesPerChannel;
        uint8_t c[4] = {0, 0, 0, 255};
        for (size_t ch = 0; ch < channels; ++ch) c[ch] = channelToByte(px + ch * bytesPerChannel, image.bits);
        if (channels <= 2) {  // grey (+ alpha): replicate grey, move alpha to A
            c[3] = channels == 2 ? c[1] : uint8_t(255);
            c[1] = c[2] = c[0];
        }
        std::memcpy(&texture.rgba[i * 4], c, 4);
    }
    return texture;
}

int TextureTable::get(int gltfTexture, bool srgb, const std::string& where) {
    if (gltfTexture < 0) return kNoTexture;
    const auto& model = ctx_.model;
    if (static_cast<size_t>(gltfTexture) >= model.textures.size())
        ctx_.fail(where, "refers to texture " + std::to_string(gltfTexture) + ", but the file has " +
                             std::to_string(model.textures.size()),
                  "the file is corrupt; re-export it");
    const int source = model.textures[static_cast<size_t>(gltfTexture)].source;
    if (source < 0) return kNoTexture;
    if (static_cast<size_t>(source) >= model.images.size())
        ctx_.fail(where, "texture " + std::to_string(gltfTexture) + " refers to image " + std::to_string(source) +
                             ", but the file has " + std::to_string(model.images.size()),
                  "the file is corrupt; re-export it");
    const auto key = std::make_pair(source, srgb);
    if (const auto it = byImageAndSrgb_.find(key); it != byImageAndSrgb_.end()) return it->second;
    textures_.push_back(convertImageToRgba8(ctx_, static_cast<size_t>(source), srgb));
    const int index = static_cast<int>(textures_.size()) - 1;
    byImageAndSrgb_.emplace(key, index);
    return index;
}

}  // namespace gbl
