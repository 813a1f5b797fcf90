// Height field synthesis and conversion to a tangent-space normal map.
#include "scene_detail_normal_map.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "integer_hash.h"
#include "parallel_for.h"

namespace gbl {
namespace {

float hashUnit(uint32_t x, uint32_t y, uint32_t seed) { return float(integerHash(x, y, seed) >> 8) / float(1u << 24); }

float smooth(float t) { return t * t * (3.0f - 2.0f * t); }

// Value noise in [0, 1] with `cells` lattice cells across the texture, wrapping at its edges.
float tileableValueNoise(float x, float y, int size, int cells, uint32_t seed) {
    const float cell = float(size) / float(cells);
    const float fx = x / cell, fy = y / cell;
    const int ix = int(std::floor(fx)), iy = int(std::floor(fy));
    const float tx = smooth(fx - float(ix)), ty = smooth(fy - float(iy));
    auto at = [&](int cx, int cy) {
        return hashUnit(uint32_t((cx % cells + cells) % cells), uint32_t((cy % cells + cells) % cells), seed);
    };
    const float top = at(ix, iy) + (at(ix + 1, iy) - at(ix, iy)) * tx;
    const float bottom = at(ix, iy + 1) + (at(ix + 1, iy + 1) - at(ix, iy + 1)) * tx;
    return top + (bottom - top) * ty;
}

// Height in texels (so gradients come out in a sensible slope range).
float heightAt(int px, int py, int size) {
    const float x = float(px) + 0.5f, y = float(py) + 0.5f;
    float h = 0.0f;

    // Grooves: 8 x 8 tiles, a rounded 3-texel-wide channel, 2 texels deep.
    const float tile = float(size) / 8.0f;
    const float gx = std::fmod(x, tile), gy = std::fmod(y, tile);
    const float edge = std::min({gx, tile - gx, gy, tile - gy});
    if (edge < 3.0f) h -= 2.0f * (1.0f - (edge / 3.0f) * (edge / 3.0f));

    // Studs: a dome of radius 4 texels every 32 texels, offset from the grooves.
    const float stud = float(size) / 32.0f;
    const float sx = std::fmod(x, stud) - 0.5f * stud, sy = std::fmod(y, stud) - 0.5f * stud;
    const float r2 = (sx * sx + sy * sy) / 16.0f;
    if (r2 < 1.0f) h += 1.5f * std::sqrt(1.0f - r2);

    // Bumps at two scales, then per-texel grain: the finest detail any encoding must keep.
    h += 3.0f * tileableValueNoise(x, y, size, 16, 1u);
    h += 1.0f * tileableValueNoise(x, y, size, 128, 2u);
    h += 0.35f * hashUnit(uint32_t(px), uint32_t(py), 3u);
    return h;
}

}  // namespace

// Rows side by side in both loops (every texel on its own: the same bytes on any thread count);
// single-threaded the 1024^2 map was the largest part of loading the built-in scene (93 ms).
Texture makeDetailNormalMap(int size) {
    std::vector<float> height(size_t(size) * size_t(size));
    parallelFor(size, 0, [&](int64_t y0, int64_t y1) {
        for (int y = int(y0); y < int(y1); ++y)
            for (int x = 0; x < size; ++x) height[size_t(y) * size_t(size) + size_t(x)] = heightAt(x, y, size);
    });
    auto h = [&](int x, int y) {
        return height[size_t((y + size) % size) * size_t(size) + size_t((x + size) % size)];
    };

    Texture texture;
    texture.name = "built-in ground detail normal map";
    texture.width = texture.height = size;
    texture.srgb = false;  // vectors, not colours
    texture.rgba.resize(size_t(size) * size_t(size) * 4);
    parallelFor(size, 0, [&](int64_t y0, int64_t y1) {
        for (int y = int(y0); y < int(y1); ++y) {
            for (int x = 0; x < size; ++x) {
                const float dhdx = 0.5f * (h(x + 1, y) - h(x - 1, y));
                const float dhdRow = 0.5f * (h(x, y + 1) - h(x, y - 1));
                // Rows go down the image but tangent-space +Y goes up, hence +dhdRow.
                const glm::vec3 n = glm::normalize(glm::vec3(-dhdx, dhdRow, 1.0f));
                uint8_t* out = &texture.rgba[(size_t(y) * size_t(size) + size_t(x)) * 4];
                for (int c = 0; c < 3; ++c) out[c] = uint8_t(std::lround((n[c] * 0.5f + 0.5f) * 255.0f));
                out[3] = 255;
            }
        }
    });
    return texture;
}

}  // namespace gbl
