// `gbufferlab crossdiff`: one frame of two renderers compared over the pixels both cover
// (measure/covered_diff.h) -- the metric step of scripts/crosscheck.sh (docs/crosscheck.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "cli_args.h"
#include "color_map.h"
#include "commands.h"
#include "covered_diff.h"
#include "error.h"
#include "file_io.h"
#include "image_diff.h"
#include "image_io.h"

namespace gbl {

namespace fs = std::filesystem;

int runCrossdiffCommand(const std::vector<std::string>& args) {
    const std::vector<FlagSpec> specs = {
        {"tolerance", "X", "a covered pixel is beyond tolerance where max_c |test - ref| > X max(Y_ref, 0.01 mean Y) (default 1e-3)"},
        {"box", "N", "also the relative RMSE of N x N block means over wholly covered blocks (default 8): detail finer than N averaged away"},
        {"out", "DIR", "write error.exr (that relative error) and error.png (log scale, tolerance/10 to 1), flip.exr / flip.png (HDR-FLIP, 0 where uncovered) and beyond.pgm there"},
        {"json", "", "print one JSON object instead of text"},
        {"help", "", "show this help"},
    };
    const ParsedArgs parsed = parseArgs("crossdiff", args, specs);
    if (parsed.has("help")) {
        std::printf("%s", formatHelp("gbufferlab crossdiff REFERENCE REFERENCE_MASK TEST TEST_MASK [--tolerance X] [--out DIR] [--json]",
                                     "Compares two renders of one frame (linear HDR: .exr, .hdr, .pfm) where both coverage "
                                     "masks\n(binary PGM, 255 = geometry) hold geometry: relative RMSE (RMSE / mean reference "
                                     "luminance),\nmax, the pixels beyond a tolerance, HDR-FLIP. docs/crosscheck.md.",
                                     specs)
                               .c_str());
        return 0;
    }
    if (parsed.positional.size() != 4)
        throwUserError("gbufferlab crossdiff: give REFERENCE REFERENCE_MASK TEST TEST_MASK (got " +
                       std::to_string(parsed.positional.size()) + " arguments); see --help");
    const double tolerance = parsePositiveFloatFlag(parsed, "tolerance", 1e-3f);
    const std::string refPath = parsed.positional[0], testPath = parsed.positional[2];
    const DiffInput ref = readDiffInput(refPath), test = readDiffInput(testPath);
    if (ref.kind != DiffKind::Hdr || test.kind != DiffKind::Hdr)
        throwUserError((ref.kind != DiffKind::Hdr ? refPath : testPath) +
                       ": not a linear HDR image; give the renders' .exr / .pfm, not their PNGs");
    if (ref.image.width != test.image.width || ref.image.height != test.image.height || ref.image.channels != 3 ||
        test.image.channels != 3)
        throwUserError(testPath + ": is " + std::to_string(test.image.width) + "x" + std::to_string(test.image.height) +
                       " with " + std::to_string(test.image.channels) + " channels, the reference " +
                       std::to_string(ref.image.width) + "x" + std::to_string(ref.image.height) + " with " +
                       std::to_string(ref.image.channels) + "; render both at the same size in RGB");
    requireFinite(ref.image, refPath);
    requireFinite(test.image, testPath);
    const int w = ref.image.width, h = ref.image.height;
    const auto refMask = readCoverageMask(parsed.positional[1], w, h);
    const auto testMask = readCoverageMask(parsed.positional[3], w, h);
    const CoveredDiff d = coveredDiff(ref.image, test.image, refMask, testMask, tolerance);
    const int box = parseIntFlag(parsed, "box", 8, 2, 256);
    size_t blocks = 0;
    const double boxed = boxedRelativeRmse(ref.image, test.image, refMask, testMask, box, &blocks);
    if (d.covered == 0) throwUserError(parsed.positional[1] + ": no pixel is covered in both masks; nothing to compare");
    if (parsed.has("out")) {
        const fs::path dir = parsed.get("out");
        fs::create_directories(dir);
        writeExr((dir / "error.exr").string(), d.error, {"Y"});
        writeExr((dir / "flip.exr").string(), d.flipMap, {"Y"});
        // The relative error on a log scale, viridis from the tolerance / 10 (dark) to 1 (bright).
        Image logError(w, h, 1);
        for (size_t i = 0; i < logError.pixels.size(); ++i)
            logError.pixels[i] = float(std::log10(std::max(double(d.error.pixels[i]), 1e-12)));
        writeColourMappedPng((dir / "error.png").string(),
                             applyColorMap(logError, float(std::log10(tolerance / 10.0)), 0.0f));
        writeColourMappedPng((dir / "flip.png").string(), applyColorMap(d.flipMap, 0.0f, 1.0f));
        std::string pgm = "P5\n" + std::to_string(w) + " " + std::to_string(h) + "\n255\n";
        for (uint8_t b : d.beyondMask) pgm.push_back(b ? char(255) : char(0));
        writeFileAtomic(dir / "beyond.pgm", pgm);
    }
    if (parsed.has("json")) {
        const nlohmann::json j = {{"covered_pixels", d.covered},
                                  {"only_reference_pixels", d.onlyReference},
                                  {"only_test_pixels", d.onlyTest},
                                  {"mean_reference_luminance", d.meanLuminance},
                                  {"mean_test_luminance", d.meanTestLuminance},
                                  {"rmse", d.rmse},
                                  {"relative_rmse", d.relativeRmse},
                                  {"max_abs", d.maxAbs},
                                  {"box", box},
                                  {"box_blocks", blocks},
                                  {"box_relative_rmse", boxed},
                                  {"max_relative", d.maxRelative},
                                  {"worst_pixel", {d.worstX, d.worstY}},
                                  {"tolerance", d.tolerance},
                                  {"beyond_tolerance_pixels", d.beyond},
                                  {"hdr_flip_mean", d.flip.mean},
                                  {"hdr_flip_max", d.flip.max}};
        std::printf("%s\n", j.dump(2).c_str());
        return 0;
    }
    std::printf("%zu pixels covered in both (%zu only in the reference, %zu only in the test)\n", d.covered,
                d.onlyReference, d.onlyTest);
    std::printf("  relative RMSE %.3e (RMSE %.3e / mean luminance %.4g; the test's %.4g), max |diff| %.3e\n",
                d.relativeRmse, d.rmse, d.meanLuminance, d.meanTestLuminance, d.maxAbs);
    std::printf("  relative RMSE of %dx%d block means %.3e (%zu wholly covered blocks)\n", box, box, boxed, blocks);
    std::printf("  max relative %.3e at (%d, %d); %zu pixels (%.3f %%) beyond %.1e\n", d.maxRelative, d.worstX, d.worstY,
                d.beyond, 100.0 * double(d.beyond) / double(d.covered), d.tolerance);
    std::printf("  HDR-FLIP mean %.6f, max %.6f over the covered pixels\n", d.flip.mean, d.flip.max);
    return 0;
}

}  // namespace gbl
