// `gbufferlab search`: its flags read into app::SearchOptions, the search run (app/search_api.h),
// its closing lines printed.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "cli_args.h"
#include "commands.h"
#include "console_run.h"
#include "error.h"
#include "file_io.h"
#include "parallel_for.h"
#include "search_api.h"

namespace gbl {

namespace fs = std::filesystem;

namespace {

std::vector<FlagSpec> searchFlags() {
    const std::string smallest = std::to_string(search::smallestPackedBytes(search::EngineConstraints{}));
    return {
        {"budget", "B", "bytes per pixel, render targets and depth-stencil included (required; " + smallest +
                            "..64: the smallest layout the search packs under the default constraints takes " +
                            smallest + ")"},
        {"scene", "FILE", "glTF 2.0 scene (.gltf/.glb), builtin (the default) or a scene suite .toml; give it "
                          "several times to minimise the mean error over the scenes (as compare --scene)", true},
        {"env", "FILE", "equirectangular environment (.hdr/.exr); default: the built-in sky"},
        {"allow-outside-scene", "", "let the scene's buffer and image URIs point outside its folder"},
        {"size", "WxH", "image size of the evaluation and the confirmation (default 480x270)"},
        {"views", "N", "cameras, as compare --views (default 3)"},
        {"objective", "NAME", "flip (default), psnr or attributes: what the front minimises"},
        {"budget-model", "MODEL", "what the budget counts: nominal (default: the formats' bytes), desktop-dcc or "
                                  "mali-afbc (the targets' effective bytes under that class's compression model, "
                                  "on view 0's words; docs/bandwidth.md)"},
        {"seed", "S", "seed of the search (default 1); a seed gives the same front every time"},
        {"candidates", "N", "layouts to evaluate (default 600)"},
        {"threads", "N", "candidates evaluated at once (default: every core); does not change the result"},
        {"out", "DIR", "output directory (default out/search-<time>); a directory holding a search journal "
                       "is resumed"},
        {"search-depth", "", "let the search choose the depth format too (D16 included); by default depth keeps a "
                             "layout family's format (D24S8 or D32): it serves shadows, SSAO, SSR, fog and decals, "
                             "which gbufferlab does not model"},
        {"min-bits", "LIST", "minimum bits of each stored attribute, e.g. occlusion=4,roughness=6 (defaults: normal 8, "
                             "roughness 7, base/diffuse/specular colour, metallic and specular 8, occlusion 4; the "
                             "layers, searched when a scene carries them: coat and coat_roughness 4, coat_normal, "
                             "sheen_color, sheen_roughness, anisotropy_strength and anisotropy_direction 8; 0: none)"},
        {"no-confirm", "", "skip the full GPU renders of the front and the published layouts"},
        {"device", "NAME", "cpu (lavapipe, default), gpu, an index or a name from `gbufferlab devices`"},
        {"help", "", "show this help"},
    };
}

void printSearchHelp(const std::vector<FlagSpec>& specs) {
    std::printf("%s", formatHelp("gbufferlab search --budget B [--scene F] [--env F] [--size WxH] [--views N] "
                                 "[--objective flip|psnr|attributes] [--seed S] [--out DIR] [--min-bits LIST] "
                                 "[--search-depth]",
                                 "Searches G-buffer layouts within B bytes per pixel (encodings, bits, fallbacks, "
                                 "packing into real\nformats), writes the Pareto front of error against bytes as "
                                 "layout files and a report beside\nthe published layouts. The front is over bytes and every metric, under engine constraints\n(depth family, minimum bits, free stencil). Resumable: rerun with "
                                 "the same arguments and --out.",
                                 specs)
                          .c_str());
}

// The command as the front files quote it: without what does not change the result (--out,
// --threads, --device, --no-confirm), so two runs with one seed write the same bytes.
std::string quotedCommand(const std::vector<std::string>& args) {
    std::string commandLine = "gbufferlab search";
    for (size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--out" || args[i] == "--threads" || args[i] == "--device") {
            ++i;
            continue;
        }
        if (args[i] != "--no-confirm") commandLine += " " + args[i];
    }
    return commandLine;
}

// The options of `gbufferlab search ARGS`, checked in the order the flags are listed; unset when
// --help was asked (the help is printed).
std::optional<app::SearchOptions> parseSearchOptions(const std::vector<std::string>& args) {
    const std::vector<FlagSpec> specs = searchFlags();
    const ParsedArgs parsed = parseArgs("search", args, specs);
    if (parsed.has("help")) {
        printSearchHelp(specs);
        return std::nullopt;
    }
    if (!parsed.positional.empty())
        throwUserError("gbufferlab search: unexpected argument '" + parsed.positional[0] + "' (see --help)");
    if (!parsed.has("budget")) throwUserError("gbufferlab search: --budget B is required (bytes per pixel, e.g. 16)");
    app::SearchOptions o;
    o.budget = parseIntFlag(parsed, "budget", 16, 4, 64);
    o.constraints.searchDepth = parsed.has("search-depth");
    if (parsed.has("min-bits")) search::parseMinBits(parsed.get("min-bits"), o.constraints);
    o.budgetModel = parsed.get("budget-model", "nominal");
    if (o.budgetModel != "nominal" && o.budgetModel != "desktop-dcc" && o.budgetModel != "mali-afbc")
        throwUserError("gbufferlab search: --budget-model " + o.budgetModel + ": give nominal, desktop-dcc or mali-afbc");
    // With a class's effective bytes, nominal layouts up to twice the budget are explored.
    app::requirePackableBudget(o.budgetModel == "nominal" ? o.budget : std::min(64, 2 * o.budget), o.constraints);
    const auto [width, height] = parseSize(parsed.get("size", "480x270"), "--size");
    o.width = width;
    o.height = height;
    o.viewCount = parseIntFlag(parsed, "views", 3, 1, 16);
    o.objective = search::parseObjective(parsed.get("objective", "flip"));
    o.seed = uint64_t(parseIntFlag(parsed, "seed", 1, 0, 2147483647));
    o.candidates = parseIntFlag(parsed, "candidates", 600, 1, 1000000);
    o.threads = parseIntFlag(parsed, "threads", hardwareThreads(), 1, 256);
    o.confirm = !parsed.has("no-confirm");
    o.outDir = parsed.has("out") ? fs::path(parsed.get("out")) : defaultOutputDirectory("search");
    o.sceneArgs = parsed.all("scene");
    o.envPath = parsed.get("env");
    o.allowOutsideScene = parsed.has("allow-outside-scene");
    o.device = parsed.get("device");
    o.commandLine = quotedCommand(args);
    return o;
}

}  // namespace

int runSearchCommand(const std::vector<std::string>& args) {
    const std::optional<app::SearchOptions> options = parseSearchOptions(args);
    if (!options) return 0;  // --help
    const app::SearchResult result = app::runSearch(*options, consoleRunControl());
    if (result.interrupted()) return consoleExitStatus(result.exitStatus, result.interruptedBy);
    std::printf("search: %zu layouts on the front (bytes and every metric); %d written to %s\n%s",
                result.summary.front.size(), result.layoutsWritten(), (result.outDir / "front").string().c_str(),
                result.closingNote.c_str());
    std::printf("search: report %s\n", (result.outDir / "search-report.md").string().c_str());
    return result.exitStatus;
}

}  // namespace gbl
