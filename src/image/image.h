#pragma once
// A CPU image of 32-bit floats, rows top to bottom, channels interleaved.
// Linear values unless a function says otherwise.
#include <cstddef>
#include <vector>

namespace gbl {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels;

    Image() = default;
    Image(int w, int h, int c, float fill = 0.0f);

    float& at(int x, int y, int c) { return pixels[(size_t(y) * width + x) * channels + c]; }
    float at(int x, int y, int c) const { return pixels[(size_t(y) * width + x) * channels + c]; }
    size_t pixelCount() const { return size_t(width) * size_t(height); }
    bool empty() const { return pixels.empty(); }
};

// An 8-bit image (for PNG output), rows top to bottom.
struct Image8 {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<unsigned char> pixels;
};

}  // namespace gbl
