// `gbufferlab ibl`: pre-computes (or reads from the disk cache) the image-based light of an
// environment and writes it out: the pre-filtered cube mips and the BRDF LUT as EXR, the LUT also
// as CSV, and the SH9 irradiance as CSV.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_args.h"
#include "commands.h"
#include "error.h"
#include "file_io.h"
#include "ibl_cache.h"
#include "image_io.h"
#include "procedural_sky.h"
#include "vk_context.h"

namespace gbl {

namespace fs = std::filesystem;

namespace {

uint32_t parseCount(const ParsedArgs& parsed, const std::string& flag, uint32_t fallback, uint32_t maxValue) {
    if (!parsed.has(flag)) return fallback;
    const std::string text = parsed.get(flag);
    unsigned long v = 0;
    size_t used = 0;
    try {
        v = std::stoul(text, &used);
    } catch (...) {
        used = 0;
    }
    if (used != text.size() || v < 1 || v > maxValue)
        throwUserError("--" + flag + " " + text + ": expected a whole number from 1 to " + std::to_string(maxValue));
    return uint32_t(v);
}

// A cube mip as one image: the six faces stacked vertically (+X, -X, +Y, -Y, +Z, -Z), RGB.
Image cubeMipAsStrip(const CubeMip& mip) {
    Image img(int(mip.size), int(mip.size * 6), 3);
    for (size_t i = 0; i < img.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) img.pixels[i * 3 + c] = mip.rgba[i * 4 + c];
    return img;
}

}  // namespace

int runIblCommand(const std::vector<std::string>& args) {
    const std::vector<FlagSpec> specs = {
        {"env", "FILE", "equirectangular environment (.hdr/.exr); default: the built-in sky"},
        {"out", "DIR", "output directory, new or empty (default: out/ibl-<time>)"},
        {"force", "", "write into a non-empty --out directory, replacing files of the same name"},
        {"size", "N", "pre-filtered cube face size of mip 0 (default 128)"},
        {"mips", "N", "pre-filtered mips = roughness levels, roughness = mip / (mips - 1) (default 6)"},
        {"samples", "N", "samples per texel of the filtered pre-filter (default 64)"},
        {"brute-force", "", "the seed's brute-force pre-filter instead: 1024 samples of source mip 0"},
        {"lut-size", "N", "BRDF LUT size (default 128)"},
        {"no-cache", "", "compute even when the disk cache has the result (and do not write it)"},
        {"device", "NAME", "cpu (lavapipe, default), gpu, an index or a name from `gbufferlab devices`"},
        {"brdf-lut", "VARIANT", "converged (visible-normal sampling, 4096 samples; default) or seed (the seed's "
                                "IntegrateBRDF, 1024 samples)"},
        {"validation", "", "enable Vulkan validation layers"},
        {"help", "", "show this help"},
    };
    const ParsedArgs parsed = parseArgs("ibl", args, specs);
    if (parsed.has("help")) {
        std::printf("%s", formatHelp("gbufferlab ibl [--env F] [--out DIR]",
                                     "Pre-computes the image-based light of an environment on the GPU (cached in "
                                     "$GBL_CACHE_DIR,\n$XDG_CACHE_HOME/gbufferlab or ~/.cache/gbufferlab) and writes "
                                     "prefiltered_mipM.exr (6 faces\nstacked +X -X +Y -Y +Z -Z), brdf_lut.exr + "
                                     "brdf_lut.csv (A, B by NoV, roughness) and irradiance_sh9.csv.",
                                     specs)
                               .c_str());
        return 0;
    }
    if (!parsed.positional.empty())
        throwUserError("gbufferlab ibl: unexpected argument '" + parsed.positional[0] + "' (see --help)");
    IblSettings settings;
    settings.prefilteredFaceSize = parseCount(parsed, "size", settings.prefilteredFaceSize, 2048);
    settings.prefilteredMips = parseCount(parsed, "mips", settings.prefilteredMips, 16);
    settings.prefilterSamples = parseCount(parsed, "samples", settings.prefilterSamples, 65536);
    settings.lutSize = parseCount(parsed, "lut-size", settings.lutSize, 1024);
    settings.bruteForce = parsed.has("brute-force");
    if (parsed.has("brdf-lut")) applyBrdfLutVariant(parsed.get("brdf-lut"), settings);
    const fs::path outDir = parsed.has("out") ? fs::path(parsed.get("out")) : defaultOutputDirectory("ibl");
    checkOutputDirectory(outDir, parsed.has("force"), "--out");
    if (parsed.has("force")) refuseInputsInsideDirectory(outDir, {parsed.get("env")}, "--out");

    const EnvironmentMap env = parsed.has("env") ? loadEnvironmentMap(parsed.get("env")) : makeProceduralSky();
    VulkanContext ctx(DeviceOptions{parsed.get("device"), parsed.has("validation")});
    IblCacheStatus status;
    IblMaps maps;
    if (parsed.has("no-cache")) {
        maps = computeIblMaps(ctx, env, settings);
        status.note = "IBL cache not used (--no-cache)";
    } else {
        maps = loadOrComputeIbl(ctx, env, settings, &status);
    }

    prepareOutputDirectory(outDir, parsed.has("force"), "--out");
    const IblSettings& s = maps.settings;
    for (size_t m = 0; m < maps.prefiltered.size(); ++m)
        writeExr((outDir / ("prefiltered_mip" + std::to_string(m) + ".exr")).string(),
                 cubeMipAsStrip(maps.prefiltered[m]));
    writeExr((outDir / "brdf_lut.exr").string(), maps.brdfLut, {"A", "B"});
    std::ostringstream csv;
    csv << "nov,roughness,a,b\n";
    csv.precision(9);
    for (int y = 0; y < maps.brdfLut.height; ++y)
        for (int x = 0; x < maps.brdfLut.width; ++x)
            csv << (x + 0.5) / maps.brdfLut.width << ',' << (y + 0.5) / maps.brdfLut.height << ','
                << maps.brdfLut.at(x, y, 0) << ',' << maps.brdfLut.at(x, y, 1) << '\n';
    writeFileAtomic(outDir / "brdf_lut.csv", csv.str());
    std::ostringstream sh;
    sh << "coefficient,r,g,b\n";
    sh.precision(9);
    for (int k = 0; k < 9; ++k)
        sh << k << ',' << maps.irradianceSh[k].x << ',' << maps.irradianceSh[k].y << ',' << maps.irradianceSh[k].z
           << '\n';
    writeFileAtomic(outDir / "irradiance_sh9.csv", sh.str());

    std::printf("IBL of %s on %s\n  source cube %u px, pre-filtered %u px x %u mips (roughness = mip / %u), %s, "
                "LUT %u px (%s)\n  %s\n",
                env.source.c_str(), ctx.info.name.c_str(), s.sourceFaceSize, s.prefilteredFaceSize, s.prefilteredMips,
                std::max(s.prefilteredMips, 2u) - 1,
                s.bruteForce ? ("brute force " + std::to_string(s.bruteForceSamples) + " samples").c_str()
                             : ("filtered importance sampling " + std::to_string(s.prefilterSamples) + " samples").c_str(),
                s.lutSize, brdfLutVariantName(s).c_str(), status.note.c_str());
    if (!status.hit)
        std::printf("  GPU time: cube %.1f ms, pre-filter %.1f ms, LUT %.1f ms\n", maps.cubeMs, maps.prefilterMs,
                    maps.lutMs);
    std::printf("  wrote %s\n", outDir.string().c_str());
    return 0;
}

}  // namespace gbl
