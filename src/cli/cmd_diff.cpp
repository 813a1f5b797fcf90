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
#include "file_io.h"
#include "flip.h"
#include "image_io.h"
#include "json_number.h"
#include "memory_budget.h"

namespace gbl {

namespace fs = std::filesystem;

namespace {

float parseFloatFlag(const ParsedArgs& args, const std::string& flag) {
    const std::string text = args.get(flag);
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno != 0 || !std::isfinite(v))
        throwUserError("--" + flag + " " + quoteName(text) + ": not a number; give e.g. --" + flag + " -2.5");
    if (!std::isfinite(float(v)))
        throwUserError("--" + flag + " " + quoteName(text) + ": beyond the range of a float (about 3.4e38); give e.g. --" +
                       flag + " -2.5");
    return float(v);
}

double parsePixelsPerDegree(const ParsedArgs& args) {
    const std::string text = args.get("ppd");
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno != 0 || !(v > 0.0) ||
        !(v <= kMaxFlipPixelsPerDegree))
        throwUserError("--ppd " + quoteName(text) + ": give pixels per degree above 0 and at most " +
                       std::to_string(int(kMaxFlipPixelsPerDegree)) +
                       " (FLIP's filters widen with it); the default, 67.02, is 0.7 m from a 0.7 m wide 3840-pixel screen");
    return v;
}

std::string sizeText(const ImageFileInfo& i) { return std::to_string(i.width) + "x" + std::to_string(i.height); }

}  // namespace

int runDiffCommand(const std::vector<std::string>& args) {
    const std::vector<FlagSpec> specs = {
        {"json", "", "print one JSON object instead of text"},
        {"out", "MAP", "write the FLIP error map: .png (colour-mapped, viridis 0..1) or .exr (float)"},
        {"force", "", "replace an existing --out file"},
        {"start-exposure", "C", "HDR-FLIP: first exposure, log2 scale (default: from the reference)"},
        {"stop-exposure", "C", "HDR-FLIP: last exposure, log2 scale (default: from the reference)"},
        {"num-exposures", "N", "HDR-FLIP: exposures (default max(2, ceil(stop - start)))"},
        {"ppd", "X", "FLIP's pixels per degree, at most 1000 (default 67.02: 0.7 m from a 0.7 m wide 3840-pixel screen)"},
        {"help", "", "show this help"},
    };
    const ParsedArgs parsed = parseArgs("diff", args, specs);
    if (parsed.has("help")) {
        std::printf("%s", formatHelp("gbufferlab diff REFERENCE TEST [--json] [--out MAP]",
                                     "Compares TEST with REFERENCE: RMSE, PSNR, max |difference| and FLIP.\n"
                                     "PNG/JPEG inputs (8 or 16 bits, read at full precision) are sRGB and get LDR-FLIP (PSNR peak 1); EXR/HDR/PFM inputs "
                                     "are linear and get\nHDR-FLIP (PSNR peak = the reference's largest value). Both "
                                     "files must have the same kind, size and\nchannels, and finite values (a NaN or "
                                     "infinity is refused, naming its pixel). A pair whose comparison\nwould not fit "
                                     "the memory budget (GBL_MEMORY_BUDGET, default 3/4 of the machine's memory) is "
                                     "refused\nbefore it is read.",
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
    if (parsed.has("ppd")) options.pixelsPerDegree = parsePixelsPerDegree(parsed);
    std::string outPath = parsed.get("out");
    std::string outExt;
    if (parsed.has("out")) {
        if (outPath.empty())
            throwUserError("--out '': an empty file name; give the error map's file name (.png or .exr), or leave "
                           "--out out");
        refuseNonRegularOutput(outPath, "--out");  // a device, FIFO or socket: never replaced, --force or not
        outExt = fs::path(outPath).extension().string();
        for (char& c : outExt) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (outExt != ".png" && outExt != ".exr")
            throwUserError("--out " + escapeText(outPath) + ": give a .png or .exr file name for the error map");
        refuseOutputOverInput(outPath, {refPath, testPath}, "--out");
        if (fs::exists(outPath) && !parsed.has("force"))
            throwUserError("--out " + escapeText(outPath) +
                           ": file exists; choose another name or add --force to replace it");
    }

    // From the headers alone: a pair that cannot be compared, or that would not fit in memory, is
    // refused before a pixel is decoded.
    for (const std::string& p : {refPath, testPath})
        if (!fs::exists(p)) throwUserError(escapeText(p) + ": no such file");
    const ImageFileInfo refInfo = probeImageFile(refPath), testInfo = probeImageFile(testPath);
    if (refInfo.width != testInfo.width || refInfo.height != testInfo.height)
        throwUserError(escapeText(testPath) + ": is " + sizeText(testInfo) + " but the reference " + escapeText(refPath) +
                       " is " + sizeText(refInfo) + "; give images of the same size");
    requireMemory(diffMemoryBytes(refInfo, testInfo),
                  "gbufferlab diff " + escapeText(refPath) + " " + escapeText(testPath) + " (" + sizeText(refInfo) +
                      (refInfo.hdr ? ", HDR-FLIP" : ", LDR-FLIP") + ")",
                  "compare crops of them (e.g. their four quarters), or raise GBL_MEMORY_BUDGET on a machine "
                  "with more memory");
    registerInput(refPath);
    registerInput(testPath);

    const DiffInput reference = readDiffInput(refPath);
    const DiffInput test = readDiffInput(testPath);
    const bool hdr = reference.kind == DiffKind::Hdr;
    if (!hdr && (options.startExposure || options.stopExposure || options.numExposures))
        throwUserError(escapeText(refPath) +
                       ": exposure flags are for HDR-FLIP, but the inputs are 8-bit (LDR-FLIP); drop them");
    const DiffResult r = diffImages(reference, test, escapeText(refPath), escapeText(testPath), options);
    const std::string precision = diffPrecision(reference, test);  // what the numbers were computed at

    if (parsed.has("out")) {
        if (outExt == ".png")
            writeColourMappedPng(outPath, applyColorMap(r.flipMap, 0.0f, 1.0f));
        else
            writeExr(outPath, r.flipMap, {"Y"});
    }

    if (parsed.has("json")) {
        nlohmann::ordered_json j;
        j["reference"] = refPath;
        j["test"] = testPath;
        j["kind"] = hdr ? "hdr" : "ldr";
        j["precision"] = precision;
        j["width"] = r.width;
        j["height"] = r.height;
        j["channels"] = r.channels;
        j["flip"] = hdr ? "hdr-flip" : "ldr-flip";
        j["flip_mean"] = jsonNumber(r.flip.mean);
        j["flip_weighted_median"] = jsonNumber(r.flip.weightedMedian);
        j["flip_weighted_q1"] = jsonNumber(r.flip.weightedQ1);
        j["flip_weighted_q3"] = jsonNumber(r.flip.weightedQ3);
        j["flip_max"] = jsonNumber(r.flip.max);
        j["psnr_db"] = jsonNumber(r.psnrDb);
        j["psnr_peak"] = jsonNumber(r.peak);
        j["rmse"] = jsonNumber(r.rmse);
        j["max_abs"] = jsonNumber(r.maxAbs);
        j["pixels_per_degree"] = options.pixelsPerDegree;
        if (hdr) {
            j["start_exposure"] = jsonNumber(r.exposures.start);
            j["stop_exposure"] = jsonNumber(r.exposures.stop);
            j["num_exposures"] = r.exposures.count;
        }
        if (parsed.has("out")) j["error_map"] = outPath;
        std::printf("%s\n", j.dump().c_str());
        return 0;
    }
    std::printf("%s vs %s: %dx%d, %d channel%s, %s\n", testPath.c_str(), refPath.c_str(), r.width, r.height,
                r.channels, r.channels == 1 ? "" : "s",
                hdr ? "HDR (linear)" : ("LDR (" + precision + " sRGB)").c_str());
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
