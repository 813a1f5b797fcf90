#include "procedural_textures.h"

#include <algorithm>
#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "integer_hash.h"

namespace gbl {
namespace {

Texture blank(int size, bool srgb) {
    Texture t;
    t.width = t.height = size;
    t.srgb = srgb;
    t.rgba.assign(size_t(size) * size_t(size) * 4, 255);
    return t;
}

void put(Texture& t, int x, int y, std::array<uint8_t, 4> rgba) {
    uint8_t* p = &t.rgba[(size_t(y) * size_t(t.width) + size_t(x)) * 4];
    for (int c = 0; c < 4; ++c) p[c] = rgba[c];
}

// Fully saturated sRGB colours around the hue circle, and two darker ones.
constexpr std::array<std::array<uint8_t, 3>, 8> kHues = {{
    {230, 25, 25}, {240, 150, 0}, {235, 225, 20}, {30, 190, 40},
    {0, 180, 200}, {30, 60, 230}, {150, 30, 210}, {220, 20, 140},
}};

constexpr int kTile = 16;

// A tile's kind: 0..2 metals (gold, copper, silver), 3..7 painted dielectrics.
int tileKind(int tx, int ty) { return int(integerHash(uint32_t(tx), uint32_t(ty), 7) % 8u); }
float tileRoughness(int tx, int ty) { return 0.08f + 0.84f * float(integerHash(uint32_t(tx), uint32_t(ty), 11) % 256u) / 255.0f; }

}  // namespace

Texture makeMosaicAlbedo(int size) {
    Texture t = blank(size, true);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            if (x % 5 == 4 || y % 5 == 4) {
                put(t, x, y, {210, 205, 195, 255});  // grout
                continue;
            }
            const auto& h = kHues[integerHash(uint32_t(x / 5), uint32_t(y / 5), 3) % kHues.size()];
            put(t, x, y, {h[0], h[1], h[2], 255});
        }
    return t;
}

// A tile's occlusion by its distance in texels from the nearest groove (the tile's edge).
uint8_t tileOcclusion(int x, int y) {
    const int fromEdge = std::min({x % kTile, kTile - 1 - x % kTile, y % kTile, kTile - 1 - y % kTile});
    return fromEdge == 0 ? 89 : fromEdge == 1 ? 179 : 255;  // 0.35, 0.7, 1
}

Texture makeTileMetalRoughness(int size) {
    Texture t = blank(size, false);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const int tx = x / kTile, ty = y / kTile;
            const bool metal = tileKind(tx, ty) < 3;
            const uint8_t r = uint8_t(tileRoughness(tx, ty) * 255.0f + 0.5f);
            put(t, x, y, {tileOcclusion(x, y), r, uint8_t(metal ? 255 : 0), 255});
        }
    return t;
}

Texture makeTileBaseColor(int size) {
    // Metals: gold, copper, silver (their F0; sRGB-encoded approximations of the linear values
    // used elsewhere in the scene). Dielectrics: saturated paints.
    constexpr std::array<std::array<uint8_t, 3>, 8> kColours = {{
        {255, 226, 155}, {250, 208, 192}, {250, 246, 240},
        {200, 30, 30}, {30, 150, 60}, {30, 70, 200}, {230, 190, 20}, {120, 40, 170},
    }};
    Texture t = blank(size, true);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const auto& c = kColours[size_t(tileKind(x / kTile, y / kTile))];
            put(t, x, y, {c[0], c[1], c[2], 255});
        }
    return t;
}

Texture makeFenceAlbedo(int size) {
    Texture t = blank(size, true);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const bool wire = x % 16 < 2 || y % 16 < 2;
            put(t, x, y, {170, 172, 175, uint8_t(wire ? 255 : 0)});
        }
    return t;
}

Texture makeEmissiveStripes(int size) {
    Texture t = blank(size, true);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const int band = x / 8;
            if (band % 3 == 2) {
                put(t, x, y, {0, 0, 0, 255});
                continue;
            }
            const auto& h = kHues[size_t(band / 3) % kHues.size()];
            const int scale = (y / 32) % 2 ? 255 : 128;
            put(t, x, y, {uint8_t(h[0] * scale / 255), uint8_t(h[1] * scale / 255), uint8_t(h[2] * scale / 255), 255});
        }
    return t;
}

Texture makeGroundOcclusion(int size, float groundSize, const std::vector<OccludingSphere>& spheres) {
    Texture t = blank(size, false);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            // The texel's centre on the ground: uv (x + 0.5) / size, (y + 0.5) / size.
            const glm::vec3 p(((float(x) + 0.5f) / float(size) - 0.5f) * groundSize, 0.0f,
                              ((float(y) + 0.5f) / float(size) - 0.5f) * groundSize);
            double occlusion = 1.0;
            for (const OccludingSphere& s : spheres) {
                const double h = s.centre.y, d = glm::length(s.centre - p);
                if (h <= 0.0 || d <= 0.0) continue;
                occlusion *= 1.0 - std::min(1.0, h * double(s.radius) * double(s.radius) / (d * d * d));
            }
            put(t, x, y, {uint8_t(occlusion * 255.0 + 0.5), 255, 255, 255});
        }
    return t;
}

}  // namespace gbl
