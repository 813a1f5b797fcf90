#include "cli.h"

#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "commands.h"
#include "error.h"
#include "shader_compiler.h"

namespace gbl {

namespace {

struct Command {
    std::string summary;
    std::function<int(const std::vector<std::string>&)> run;
};

const std::vector<std::pair<std::string, Command>>& commands() {
    static const std::vector<std::pair<std::string, Command>> list = {
        {"compare", {"render the reference and every layout, measure what each loses and costs, write a report",
                     runCompareCommand}},
        {"render", {"render a scene through the float reference G-buffer (EXR + PNG)", runRenderCommand}},
        {"layouts", {"check, list and show G-buffer layout files (layouts/*.toml)", runLayoutsCliCommand}},
        {"encodings", {"measure what each encoding loses on its own (mean / p99 / max error)", runEncodingsCommand}},
        {"ibl", {"pre-compute the image-based light of an environment (cube mips, BRDF LUT)", runIblCommand}},
        {"search", {"find layouts under a byte budget: the Pareto front of error against bytes per pixel",
                    runSearchCommand}},
        {"diff", {"compare two image files: RMSE, PSNR, max, LDR-/HDR-FLIP, an error map", runDiffCommand}},
        {"crossdiff", {"two renderers' frames compared where both cover geometry (scripts/crosscheck.sh)",
                       runCrossdiffCommand}},
        {"devices", {"list the Vulkan devices gbufferlab can use (--device)", runDevicesCommand}},
    };
    return list;
}

void printUsage(FILE* out) {
    std::fprintf(out,
                 "gbufferlab: what a deferred G-buffer layout costs and what it loses\n\n"
                 "usage: gbufferlab <command> [flags]   (gbufferlab <command> --help for its flags)\n\ncommands:\n");
    for (const auto& [name, cmd] : commands()) std::fprintf(out, "  %-10s %s\n", name.c_str(), cmd.summary.c_str());
}

}  // namespace

int runCli(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        printUsage(stdout);
        return args.empty() ? 2 : 0;
    }
    for (const auto& [name, cmd] : commands()) {
        if (name != args[0]) continue;
        try {
            return cmd.run(std::vector<std::string>(args.begin() + 1, args.end()));
        } catch (const UserError& e) {
            std::fprintf(stderr, "gbufferlab: error: %s\n", e.what());
            return 1;
        } catch (const ShaderCompileError& e) {
            std::fprintf(stderr, "gbufferlab: internal error (please report): %s\n", e.what());
            return 3;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "gbufferlab: internal error (please report): %s\n", e.what());
            return 3;
        }
    }
    std::string known;
    for (const auto& [name, cmd] : commands()) known += (known.empty() ? "" : ", ") + name;
    std::fprintf(stderr, "gbufferlab: error: unknown command %s (known: %s; see gbufferlab --help)\n",
                 quoteName(args[0]).c_str(), known.c_str());
    return 2;
}

}  // namespace gbl
