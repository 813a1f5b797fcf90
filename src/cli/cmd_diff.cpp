// `gbufferlab diff REFERENCE TEST [--json] [--out MAP]`: PSNR, RMSE, max and FLIP of two image
// files (src/image_diff.h says exactly what each number is).
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "cli_args.h"
#include "color_map.h"
#include "commands.h"
#include "error.h"
#include "image_diff.h"
#include "image_io.h"

namespace gbl {

namespace fs = std::filesystem;

namespace {

float parseFloatFlag(const ParsedArgs& args, const std::string& flag) {
    const std::string text = args.get(flag);
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno != 0 || !std::isfinite(v))
        throwUserError("--" + flag + " " + text + ": not a number; give e.g. --" + flag + " -2.5");
    return float(v);
}

// JSON has no infinity: "inf" as report.json writes it (docs/report-schema.md).
nlohmann::ordered_json number(double v) {
    if (std::isnan(v)) return nullptr;
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return v;
}

}  // namespace

int runDiffCommand(const std::vector<std::string>& args) {
    const std::vector<FlagSpec> specs = {
        {"json", "", "print one JSON object instead of text"},
        {"out", "MAP", "write the FLIP error map: .png (colour-mapped, viridis 0..1) or .exr (float)"},
        {"force", "", "replace an existing --out file"},
        {"start-exposure", "C", "HDR-FLIP: first exposure, log2 scale (default: from the reference)"},
        {"stop-exposure", "C", "HDR-FLIP: last exposure, log2 scale (default: from the reference)"},
        {"num-exposures", "N", "HDR-FLIP: exposures (default max(2, ceil(stop - start)))"},
        {"ppd", "X", "FLIP's pixels per degree (default 67.02: 0.7 m from a 0.7 m wide 3840-pixel screen)"},
        {"help", "", "show this help"},
    };
    const ParsedArgs parsed = parseArgs("diff", args, specs);
    if (parsed.has("help")) {
        std::printf("%s", formatHelp("gbufferlab diff REFERENCE TEST [--json] [--out MAP]",
                                     "Compares TEST with REFERENCE: RMSE, PSNR, max |difference| and FLIP.\n"
                                     "8-bit PNG/JPEG inputs are sRGB and get LDR-FLIP (PSNR peak 1); EXR/HDR inputs are "
                                     "linear and get\nHDR-FLIP (PSNR peak = the reference's largest value). Both files "
                                     "must have the same kind, size and channels.",
                                     specs)
                               .c_str());
        return 0;
    }
    if (parsed.positional.size() != 2)
        throwUserError("gbufferlab diff: give two images, REFERENCE and TEST (got " +
                       std::to_string(parsed.positional.size()) + "); see --help");
    const std::string refPath = parsed.positional[0], testPath = parsed.positional[1];
    DiffOptions options;
    if (parsed.has("start-exposure")) options.startExposure = parseFloatFlag(parsed, "start-exposure");
    if (parsed.has("stop-exposure")) options.stopExposure = parseFloatFlag(parsed, "stop-exposure");
    if (parsed.has("num-exposures")) options.numExposures = parseIntFlag(parsed, "num-exposures", 2, 2, 1000);
    if (parsed.has("ppd")) options.pixelsPerDegree = parsePositiveFloatFlag(parsed, "ppd", 67.0f);
    std::string outPath = parsed.get("out");
    if (parsed.has("out")) {
        std::string ext = fs::path(outPath).extension().string();
        for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (ext != ".png" && ext != ".exr")
            throwUserError("--out " + outPath + ": give a .png or .exr file name for the error map");
        if (fs::exists(outPath) && !parsed.has("force"))
            throwUserError("--out " + outPath + ": file exists; choose another name or add --force to replace it");
    }

    const DiffInput reference = readDiffInput(refPath);
    const DiffInput test = readDiffInput(testPath);
    const bool hdr = reference.kind == DiffKind::Hdr;
    if (!hdr && (options.startExposure || options.stopExposure || options.numExposures))
        throwUserError(refPath + ": exposure flags are for HDR-FLIP, but the inputs are 8-bit (LDR-FLIP); drop them");
    const DiffResult r = diffImages(reference, test, refPath, testPath, options);

    if (parsed.has("out")) {
        if (fs::path(outPath).extension() == ".png" || fs::path(outPath).extension() == ".PNG")
            writePng(outPath, applyColorMap(r.flipMap, 0.0f, 1.0f));
        else
            writeExr(outPath, r.flipMap, {"Y"});
    }

    if (parsed.has("json")) {
        nlohmann::ordered_json j;
        j["reference"] = refPath;
        j["test"] = testPath;
        j["kind"] = hdr ? "hdr" : "ldr";
        j["width"] = r.width;
        j["height"] = r.height;
        j["channels"] = r.channels;
        j["flip"] = hdr ? "hdr-flip" : "ldr-flip";
        j["flip_mean"] = number(r.flip.mean);
        j["flip_weighted_median"] = number(r.flip.weightedMedian);
        j["flip_weighted_q1"] = number(r.flip.weightedQ1);
        j["flip_weighted_q3"] = number(r.flip.weightedQ3);
        j["flip_max"] = number(r.flip.max);
        j["psnr_db"] = number(r.psnrDb);
        j["psnr_peak"] = number(r.peak);
        j["rmse"] = number(r.rmse);
        j["max_abs"] = number(r.maxAbs);
        j["pixels_per_degree"] = options.pixelsPerDegree;
        if (hdr) {
            j["start_exposure"] = number(r.exposures.start);
            j["stop_exposure"] = number(r.exposures.stop);
            j["num_exposures"] = r.exposures.count;
        }
        if (parsed.has("out")) j["error_map"] = outPath;
        std::printf("%s\n", j.dump().c_str());
        return 0;
    }
    std::printf("%s vs %s: %dx%d, %d channel%s, %s\n", testPath.c_str(), refPath.c_str(), r.width, r.height,
                r.channels, r.channels == 1 ? "" : "s", hdr ? "HDR (linear)" : "LDR (8-bit sRGB)");
    std::printf("  RMSE       %.6g\n  PSNR       %s dB (peak %.6g)\n  max |diff| %.6g\n", r.rmse,
                std::isinf(r.psnrDb) ? "inf" : std::to_string(r.psnrDb).c_str(), r.peak, r.maxAbs);
    std::printf("  %s mean %.6f, weighted median %.6f, max %.6f\n", hdr ? "HDR-FLIP" : "LDR-FLIP", r.flip.mean,
                r.flip.weightedMedian, r.flip.max);
    if (hdr)
        std::printf("  exposures  %.4f .. %.4f, %d\n", r.exposures.start, r.exposures.stop, r.exposures.count);
    if (parsed.has("out")) std::printf("  error map  %s\n", outPath.c_str());
    return 0;
}

}  // namespace gbl
