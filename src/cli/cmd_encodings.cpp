#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "cli_args.h"
#include "cmd_layouts.h"
#include "commands.h"
#include "encoding_registry.h"
#include "encoding_stats.h"
#include "error.h"

namespace gbl {


int runEncodingsCommand(const std::vector<std::string>& args) {
    const std::vector<FlagSpec> specs = {
        {"encoding", "NAME", "measure one encoding (default: all, each at its default bits)"},
        {"bits", "N", "bits per code for --encoding (default: the encoding's default)"},
        {"samples", "N", "uniformly distributed samples (default 1048576)"},
        {"seed", "N", "random seed (default 1)"},
        {"json", "", "print JSON instead of a table"},
        {"list", "", "list the encodings with their bit ranges and sources"},
        {"help", "", "show this help"},
    };
    const ParsedArgs parsed = parseArgs("encodings", args, specs);
    if (parsed.has("help")) {
        std::printf("%s", formatHelp("gbufferlab encodings [--encoding NAME [--bits N]] [--samples N] [--json]",
                                     "Measures what an encoding loses on its own (Cigolle et al. 2014 style): mean, "
                                     "99th percentile and max\nerror over uniformly distributed samples; degrees for "
                                     "normals, absolute and CIEDE2000 for colours.",
                                     specs)
                               .c_str());
        return 0;
    }
    if (parsed.has("list")) {
        for (const EncodingInfo& e : listEncodings())
            std::printf("%-28s bits %2d..%-2d (default %2d)  %s\n", e.name.c_str(), e.minBits, e.maxBits, e.defaultBits,
                        e.description.c_str());
        return 0;
    }
    const int samples = parseIntFlag(parsed, "samples", 1 << 20, 1, 1 << 26);
    const int seed = parseIntFlag(parsed, "seed", 1, 0, 1 << 30);
    std::vector<EncodingStats> stats;
    if (parsed.has("encoding")) {
        const std::string name = parsed.get("encoding");
        const EncodingInfo* info = findEncoding(name);
        if (!info) throwUserError("--encoding " + name + ": unknown encoding (known: " + knownEncodingNames() + ")");
        const int bits = parseIntFlag(parsed, "bits", info->defaultBits, 1, 32);
        stats.push_back(measureEncoding(name, bits, samples, uint64_t(seed)));
    } else {
        if (parsed.has("bits")) throwUserError("--bits needs --encoding NAME (bits differ per encoding)");
        stats = measureAllEncodings(samples, uint64_t(seed));
    }
    if (parsed.has("json")) std::printf("%s\n", encodingStatsToJson(stats).dump(2).c_str());
    else std::printf("%s", formatEncodingStatsTable(stats).c_str());
    return 0;
}

int runLayoutsCliCommand(const std::vector<std::string>& args) {
    return runLayoutsCommand(args, std::cout, std::cerr);
}

}  // namespace gbl
