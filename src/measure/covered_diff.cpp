// Two renderers' images compared over the pixels both cover (covered_diff.h).
#include "covered_diff.h"

#include <algorithm>
#include <cmath>
#include <cctype>
#include <fstream>
#include <sstream>

#include "error.h"

namespace gbl {

namespace {
double luminance(const Image& im, int x, int y) {
    return 0.2126 * im.at(x, y, 0) + 0.7152 * im.at(x, y, 1) + 0.0722 * im.at(x, y, 2);
}

// The next header token of a PGM, skipping whitespace and # comments (netpbm's pgm(5)).
std::string pgmToken(std::istream& in) {
    std::string t;
    for (int c; (c = in.get()) != EOF;) {
        if (c == '#') {
            while ((c = in.get()) != EOF && c != '\n') {
            }
            continue;
        }
        if (std::isspace(c)) {
            if (!t.empty()) break;
            continue;
        }
        t.push_back(char(c));
    }
    return t;
}
}  // namespace

std::vector<uint8_t> readCoverageMask(const std::string& path, int width, int height) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throwUserError(path + ": cannot read the coverage mask; check the path");
    const std::string magic = pgmToken(in), w = pgmToken(in), h = pgmToken(in), maxval = pgmToken(in);
    if (magic != "P5" || maxval != "255")
        throwUserError(path + ": not a binary 8-bit PGM (P5, maxval 255); write the mask as tools/gltf-viewer/README.md says");
    if (w != std::to_string(width) || h != std::to_string(height))
        throwUserError(path + ": the mask is " + w + "x" + h + " but the images are " + std::to_string(width) + "x" +
                       std::to_string(height) + "; give the mask of the same render");
    std::vector<uint8_t> mask(size_t(width) * size_t(height));
    in.read(reinterpret_cast<char*>(mask.data()), std::streamsize(mask.size()));
    if (in.gcount() != std::streamsize(mask.size()))
        throwUserError(path + ": the mask ends after " + std::to_string(in.gcount()) + " of " +
                       std::to_string(mask.size()) + " pixels; the file is truncated");
    for (uint8_t& m : mask) m = m >= 128 ? 1 : 0;
    return mask;
}

double boxedRelativeRmse(const Image& reference, const Image& test, const std::vector<uint8_t>& referenceMask,
                         const std::vector<uint8_t>& testMask, int box, size_t* blocks) {
    const int w = reference.width, h = reference.height;
    double sumSq = 0.0, sumY = 0.0;
    size_t n = 0;
    for (int by = 0; by + box <= h; by += box)
        for (int bx = 0; bx + box <= w; bx += box) {
            bool whole = true;
            double r[3] = {0, 0, 0}, t[3] = {0, 0, 0};
            for (int y = by; y < by + box && whole; ++y)
                for (int x = bx; x < bx + box; ++x) {
                    const size_t i = size_t(y) * size_t(w) + size_t(x);
                    if (!referenceMask[i] || !testMask[i]) {
                        whole = false;
                        break;
                    }
                    for (int c = 0; c < 3; ++c) {
                        r[c] += reference.at(x, y, c);
                        t[c] += test.at(x, y, c);
                    }
                }
            if (!whole) continue;
            const double area = double(box) * double(box);
            for (int c = 0; c < 3; ++c) sumSq += (t[c] - r[c]) * (t[c] - r[c]) / (area * area);
            sumY += (0.2126 * r[0] + 0.7152 * r[1] + 0.0722 * r[2]) / area;
            ++n;
        }
    if (blocks) *blocks = n;
    if (n == 0 || sumY <= 0.0) return 0.0;
    return std::sqrt(sumSq / (3.0 * double(n))) / (sumY / double(n));
}

CoveredDiff coveredDiff(const Image& reference, const Image& test, const std::vector<uint8_t>& referenceMask,
                        const std::vector<uint8_t>& testMask, double tolerance) {
    const int w = reference.width, h = reference.height;
    CoveredDiff d;
    d.tolerance = tolerance;
    std::vector<uint8_t> both(size_t(w) * size_t(h), 0);
    double sumY = 0.0, sumTestY = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            both[i] = referenceMask[i] && testMask[i];
            d.onlyReference += referenceMask[i] && !testMask[i];
            d.onlyTest += testMask[i] && !referenceMask[i];
            if (both[i]) {
                ++d.covered;
                sumY += luminance(reference, x, y);
                sumTestY += luminance(test, x, y);
            }
        }
    if (d.covered == 0) return d;
    d.meanLuminance = sumY / double(d.covered);
    d.meanTestLuminance = sumTestY / double(d.covered);
    const double floor = 0.01 * d.meanLuminance;
    d.error = Image(w, h, 1);
    d.beyondMask.assign(both.size(), 0);
    Image maskedRef(w, h, 3), maskedTest(w, h, 3);
    double sumSq = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            if (!both[i]) continue;
            double worst = 0.0;
            for (int c = 0; c < 3; ++c) {
                maskedRef.at(x, y, c) = reference.at(x, y, c);
                maskedTest.at(x, y, c) = test.at(x, y, c);
                const double e = double(test.at(x, y, c)) - double(reference.at(x, y, c));
                sumSq += e * e;
                worst = std::max(worst, std::abs(e));
            }
            d.maxAbs = std::max(d.maxAbs, worst);
            const double rel = worst / std::max(luminance(reference, x, y), floor);
            d.error.at(x, y, 0) = float(rel);
            if (rel > d.maxRelative) {
                d.maxRelative = rel;
                d.worstX = x;
                d.worstY = y;
            }
            if (rel > tolerance) {
                ++d.beyond;
                d.beyondMask[i] = 1;
            }
        }
    d.rmse = std::sqrt(sumSq / (3.0 * double(d.covered)));
    d.relativeRmse = d.rmse / d.meanLuminance;
    d.flipMap = flipHdr(maskedRef, maskedTest).flip;
    for (size_t i = 0; i < both.size(); ++i)
        if (!both[i]) d.flipMap.pixels[i] = 0.0f;
    d.flip = flipStats(d.flipMap, &both);
    return d;
}

}  // namespace gbl
