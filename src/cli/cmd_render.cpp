#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "cli_args.h"
#include "commands.h"
#include "error.h"
#include "forward_mask.h"
#include "file_io.h"
#include "gbuffer_wiring.h"
#include "image_io.h"
#include "procedural_sky.h"
#include "renderer.h"
#include "scene_inputs.h"
#include "tone_map.h"
#include "viewer_job.h"
#include "vk_context.h"

namespace gbl {

namespace fs = std::filesystem;

int runDevicesCommand(const std::vector<std::string>& args) {
    const std::vector<FlagSpec> specs = {{"help", "", "show this help"}};
    const ParsedArgs parsed = parseArgs("devices", args, specs);
    if (parsed.has("help")) {
        std::printf("%s", formatHelp("gbufferlab devices", "Lists Vulkan devices; pass an index or name to --device.", specs).c_str());
        return 0;
    }
    const auto devices = listPhysicalDevices();
    for (size_t i = 0; i < devices.size(); ++i)
        std::printf("%zu: %s (%s) driver %s\n", i, devices[i].name.c_str(), devices[i].typeName.c_str(),
                    devices[i].driver.c_str());
    return 0;
}

int runRenderCommand(const std::vector<std::string>& args) {
    const std::vector<FlagSpec> specs = {
        {"scene", "FILE", "glTF 2.0 scene (.gltf/.glb); default: the built-in scene (the sphere grid and its surroundings)"},
        {"env", "FILE", "equirectangular environment (.hdr/.exr); default: the built-in sky"},
        {"allow-outside-scene", "", "let the scene's buffer and image URIs point outside its folder"},
        {"size", "WxH", "image size (default 1280x720)"},
        {"out", "DIR", "output directory, new or empty (default: out/render-<time>)"},
        {"force", "", "write into a non-empty --out directory, replacing files of the same name"},
        {"device", "NAME", "cpu (lavapipe, default), gpu, an index or a name from `gbufferlab devices`"},
        {"exposure", "X", "exposure multiplier for the PNG tone map (default 1)"},
        {"ibl", "MODE", "specular IBL: ground-truth, split-sum-shader, split-sum (default), envbrdf-approx, bo2"},
        {"ibl-samples", "N", "samples per pixel of split-sum-shader (default 1024), and steps per batch of ground-truth (default 64)"},
        {"brdf", "NAME", "the direct lights' BRDF: ue4 (default: Smith-Schlick with UE4's k, Karis' Fresnel) or gltf (the glTF 2.0 specification's, Appendix B, as the Khronos glTF Sample Viewer computes it)"},
        {"no-ibl", "", "punctual lights only: no image-based light (the environment's radiance scaled by 0, background black)"},
        {"viewer-job", "FILE", "also write the Khronos glTF Sample Viewer job (tools/gltf-viewer/README.md) of this render to FILE, and the coverage mask reference.mask.pgm (needs --scene)"},
        {"texture-base-level", "", "sample every material texture at its base level only (bilinear, no mips), as a glTF sampler with minFilter LINEAR: a cross-check without filtering differences"},
        {"texture-nearest", "", "sample every material texture at its base level, nearest texel (glTF's NEAREST filters): a cross-check without bilinear weights"},
        {"band-rows", "N", "render N rows of the frame at a time (less memory at large sizes; the same image, bit for bit); default: all"},
        {"validation", "", "enable Vulkan validation layers"},
        {"help", "", "show this help"},
    };
    const ParsedArgs parsed = parseArgs("render", args, specs);
    if (parsed.has("help")) {
        std::printf("%s", formatHelp("gbufferlab render [--scene F] [--env F] [--size WxH] [--out DIR]",
                                     "Renders the scene through the float reference G-buffer with the UE4 shading "
                                     "model and writes\nreference.exr (linear HDR) and reference.png (tone-mapped: "
                                     "exposure, ACES fit of Narkowicz 2016, sRGB).",
                                     specs)
                               .c_str());
        return 0;
    }
    if (!parsed.positional.empty())
        throwUserError("gbufferlab render: unexpected argument '" + parsed.positional[0] + "' (see --help)");
    const auto [width, height] = parseSize(parsed.get("size", "1280x720"), "--size");
    const float exposure = parsePositiveFloatFlag(parsed, "exposure", 1.0f);
    const IblMode iblMode = parseIblMode(parsed.get("ibl", "split-sum"));
    const int iblSamples = parseIntFlag(parsed, "ibl-samples", 1024, 1, 65536);
    const uint32_t bandRows = uint32_t(parseIntFlag(parsed, "band-rows", 0, 1, 65536));
    const std::string brdfName = parsed.get("brdf", "ue4");
    if (brdfName != "ue4" && brdfName != "gltf")
        throwUserError("--brdf " + brdfName + ": unknown BRDF (known: ue4, gltf)");
    if (parsed.has("viewer-job") && !parsed.has("scene"))
        throwUserError("--viewer-job " + parsed.get("viewer-job") +
                       ": the viewer renders a glTF file; give it with --scene (the built-in scene is not one)");
    if (bandRows && iblMode == IblMode::GroundTruth)
        throwUserError("--band-rows " + std::to_string(bandRows) +
                       ": the ground truth converges over the whole frame; leave --band-rows out with --ibl ground-truth");
    const fs::path outDir = parsed.has("out") ? fs::path(parsed.get("out")) : defaultOutputDirectory("render");
    // Refuse a non-empty output directory before any work, but create it only once all succeeded.
    checkOutputDirectory(outDir, parsed.has("force"), "--out");
    if (parsed.has("force")) refuseInputsInsideDirectory(outDir, {parsed.get("scene"), parsed.get("env")}, "--out");
    // The frame (and, in bands, the band) against the memory budget before anything is loaded or
    // allocated: in bands only the HDR image and its PNG are frame-sized.
    requireRenderMemory(width, height, bandRows >= height ? 0u : bandRows, "--size");

    SceneInputs inputs = loadSceneInputs(parsed.get("scene"), parsed.get("env"), float(width) / float(height),
                                                GltfLoadOptions{parsed.has("allow-outside-scene")});
    inputs.scene.textureBaseLevelOnly = parsed.has("texture-base-level") || parsed.has("texture-nearest");
    inputs.scene.textureNearest = parsed.has("texture-nearest");
    VulkanContext ctx(DeviceOptions{parsed.get("device"), parsed.has("validation")});
    Renderer renderer(ctx, inputs.scene, inputs.environment);
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.specularIbl = iblMode;
    settings.brdf = brdfName == "gltf" ? 1 : 0;  // brdf.glsl BRDF_GLTF / BRDF_UE4
    if (parsed.has("no-ibl")) settings.environmentIntensity = 0.0f;
    if (parsed.has("ibl-samples")) settings.groundTruthSamples = iblSamples;  // per batch (default 64)
    settings.splitSumShaderSamples = iblSamples;
    settings.readTargetWords = false;  // only the HDR image is written
    RenderOutput out;
    if (bandRows == 0 || bandRows >= height) {
        out = renderer.render(makeReferenceWiring(renderer.sceneLayers()), settings);
    } else {
        // Band by band (renderer.h RenderSettings::bandRows): only the HDR image is whole.
        const GBufferWiring reference = makeReferenceWiring(renderer.sceneLayers());
        out.hdr = Image(int(width), int(height), 4);
        for (uint32_t first = 0; first < height; first += bandRows) {
            settings.bandFirstRow = first;
            settings.bandRows = std::min(bandRows, height - first);
            const RenderOutput band = renderer.render(reference, settings);
            std::copy(band.hdr.pixels.begin(), band.hdr.pixels.end(),
                      out.hdr.pixels.begin() + std::ptrdiff_t(size_t(first) * width * 4));
            out.timings.gbufferMs += band.timings.gbufferMs;
            out.timings.lightingMs += band.timings.lightingMs;
        }
    }

    prepareOutputDirectory(outDir, parsed.has("force"), "--out");
    writeExr((outDir / "reference.exr").string(), out.hdr);
    writePng((outDir / "reference.png").string(), toneMapToSrgb8(out.hdr, exposure));
    if (parsed.has("viewer-job")) {
        ViewerJob job;
        job.gltf = fs::absolute(parsed.get("scene")).lexically_normal().string();
        job.width = width;
        job.height = height;
        job.camera = inputs.scene.camera;
        job.exposure = exposure;
        job.ibl = !parsed.has("no-ibl");
        if (job.ibl && parsed.has("env")) job.environment = fs::absolute(parsed.get("env")).lexically_normal().string();
        job.ibl = job.ibl && !job.environment.empty();  // the built-in sky is no file the viewer can load
        job.output = "viewer.pfm";
        writeFileAtomic(parsed.get("viewer-job"), viewerJobJson(job, inputs.scene));
        // Pixels a deferred renderer draws forward (transmission, volume: forward_mask.h) or that the
        // viewer blends (alphaMode BLEND) are not like for like: left out of the mask.
        Scene notLikeForLike = inputs.scene;
        for (Material& m : notLikeForLike.materials)
            if (m.alphaBlend && m.forward.empty()) m.forward = "alphaMode BLEND";
        RenderSettings maskSettings = settings;
        maskSettings.bandFirstRow = maskSettings.bandRows = 0;
        const std::vector<uint8_t> excluded = renderForwardMask(renderer, notLikeForLike, maskSettings);
        writeCoverageMask((outDir / "reference.mask.pgm").string(), out.hdr, excluded);
    }
    std::printf("rendered %s under %s on %s at %ux%u\n  G-buffer pass %.1f ms, lighting pass %.1f ms\n  wrote %s\n",
                inputs.scene.source.c_str(), inputs.environment.source.c_str(), ctx.info.name.c_str(), width, height,
                out.timings.gbufferMs, out.timings.lightingMs, outDir.string().c_str());
    if (iblMode == IblMode::GroundTruth)
        std::printf("  ground truth: %d batches, %d samples per pixel, mean relative noise %.5f (target %.5f%s)\n",
                    out.groundTruth.batches, out.groundTruth.samplesPerPixel, out.groundTruth.meanRelativeNoise,
                    out.groundTruth.targetRelativeNoise, out.groundTruth.targetMet ? ", met" : ", NOT met");
    return 0;
}

}  // namespace gbl
