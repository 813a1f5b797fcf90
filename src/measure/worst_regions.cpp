#include "worst_regions.h"

#include <algorithm>
#include <cmath>

#include "error.h"
#include "image_io.h"

namespace gbl {

std::vector<Crop> findWorstRegions(const Image& errorMap, int cropSize, int count) {
    std::vector<Crop> out;
    const int w = errorMap.width, h = errorMap.height;
    if (count <= 0 || w <= 0 || h <= 0 || errorMap.channels < 1 || cropSize <= 0) return out;
    if (errorMap.pixels.size() != errorMap.pixelCount() * size_t(errorMap.channels))
        throwUserError("worst regions: inconsistent error map");
    const int s = std::min({cropSize, w, h});

    // Summed-area table, (w+1) x (h+1), zero first row and column.
    const size_t sw = size_t(w) + 1;
    std::vector<double> sat(sw * (size_t(h) + 1), 0.0);
    const size_t ch = size_t(errorMap.channels);
    for (int y = 0; y < h; ++y) {
        double row = 0.0;
        for (int x = 0; x < w; ++x) {
            const float v = errorMap.pixels[(size_t(y) * size_t(w) + size_t(x)) * ch];
            row += std::isfinite(v) ? double(v) : 0.0;
            sat[(size_t(y) + 1) * sw + size_t(x) + 1] = sat[size_t(y) * sw + size_t(x) + 1] + row;
        }
    }
    const int nx = w - s + 1, ny = h - s + 1;
    // Window sums, row-major over top-left corners.
    std::vector<double> sums(size_t(nx) * size_t(ny));
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
            const size_t y0 = size_t(y), y1 = size_t(y + s), x0 = size_t(x), x1 = size_t(x + s);
            sums[size_t(y) * size_t(nx) + size_t(x)] =
                sat[y1 * sw + x1] - sat[y0 * sw + x1] - sat[y1 * sw + x0] + sat[y0 * sw + x0];
        }
    const double area = double(s) * double(s);
    for (int k = 0; k < count; ++k) {
        double best = 0.0;
        long bx = -1, by = -1;
        for (int y = 0; y < ny; ++y) {
            // Skip the corner ranges that overlap a chosen window in this row: [cx - s + 1, cx + s - 1].
            for (int x = 0; x < nx; ++x) {
                bool overlaps = false;
                for (const Crop& c : out)
                    if (std::abs(x - c.x) < s && std::abs(y - c.y) < s) {
                        overlaps = true;
                        x = c.x + s - 1;  // jump past this window's overlap range
                        break;
                    }
                if (overlaps) continue;
                const double v = sums[size_t(y) * size_t(nx) + size_t(x)];
                if (v > best) {
                    best = v;
                    bx = x;
                    by = y;
                }
            }
        }
        if (bx < 0) break;  // nothing left with a positive error
        out.push_back({int(bx), int(by), s, best / area});
    }
    return out;
}

Image8 cropUpscaled(const Image8& image, const Crop& crop, int scale) {
    if (crop.x < 0 || crop.y < 0 || crop.size <= 0 || crop.x + crop.size > image.width ||
        crop.y + crop.size > image.height || image.channels < 1)
        throwUserError("crop " + std::to_string(crop.x) + "," + std::to_string(crop.y) + " size " +
                       std::to_string(crop.size) + " lies outside the " + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + " image");
    scale = std::max(scale, 1);
    const int n = crop.size * scale;
    const size_t ch = size_t(image.channels);
    Image8 out{n, n, image.channels, std::vector<unsigned char>(size_t(n) * size_t(n) * ch)};
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const size_t src = (size_t(crop.y + y / scale) * size_t(image.width) + size_t(crop.x + x / scale)) * ch;
            const size_t dst = (size_t(y) * size_t(n) + size_t(x)) * ch;
            for (size_t c = 0; c < ch; ++c) out.pixels[dst + c] = image.pixels[src + c];
        }
    return out;
}

CropFiles cropFileNames(const std::string& prefix, size_t i) {
    const std::string base = prefix + "crop" + std::to_string(i);
    return {base + "_reference.png", base + "_test.png", base + "_heat.png"};
}

std::vector<CropFiles> writeCrops(const std::filesystem::path& dir, const std::string& prefix,
                                  const std::vector<Crop>& crops, const Image8& reference, const Image8& test,
                                  const Image8& heat, int scale) {
    std::vector<CropFiles> out;
    std::error_code ec;
    for (size_t i = 0; i < crops.size(); ++i) {
        const CropFiles files = cropFileNames(prefix, i);
        const auto write = [&](const Image8& image, const std::string& rel) {
            const std::filesystem::path full = dir / rel;
            std::filesystem::create_directories(full.parent_path(), ec);
            writePng(full.string(), cropUpscaled(image, crops[i], scale));
        };
        write(reference, files.reference);
        write(test, files.test);
        write(heat, files.heat);
        out.push_back(files);
    }
    return out;
}

}  // namespace gbl
