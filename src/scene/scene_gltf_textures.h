#pragma once
// glTF textures -> Scene::textures, decoded to RGBA8, one entry per (image, colour space) pair.
#include <map>
#include <string>
#include <utility>

#include "scene.h"
#include "scene_gltf_context.h"

namespace gbl {

class TextureTable {
public:
    TextureTable(const GltfContext& ctx, std::vector<Texture>& textures) : ctx_(ctx), textures_(textures) {}

    // The Scene::textures index for glTF texture `gltfTexture` read as sRGB or linear data, or
    // kNoTexture for -1 (absent) and for textures with no core image source (e.g. one that only
    // names a KHR_texture_basisu image). An image used as both sRGB and linear gets two entries,
    // one per flag; one used twice the same way is shared. `where` names the material slot.
    int get(int gltfTexture, bool srgb, const std::string& where);

private:
    const GltfContext& ctx_;
    std::vector<Texture>& textures_;
    std::map<std::pair<int, bool>, int> byImageAndSrgb_;
};

// Expands a decoded tinygltf image (1-4 channels, 8/16/32-bit) to RGBA8: grey to RGB, opaque
// alpha when missing, 16-bit rounded to nearest. Throws when the image was not decoded.
Texture convertImageToRgba8(const GltfContext& ctx, size_t imageIndex, bool srgb);

}  // namespace gbl
