#include "cli_args.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "error.h"

namespace gbl {

std::string ParsedArgs::get(const std::string& flag, const std::string& fallback) const {
    auto it = values.find(flag);
    return it == values.end() ? fallback : it->second;
}

std::vector<std::string> ParsedArgs::all(const std::string& flag) const {
    auto it = repeated.find(flag);
    return it == repeated.end() ? std::vector<std::string>{} : it->second;
}

ParsedArgs parseArgs(const std::string& command, const std::vector<std::string>& args,
                     const std::vector<FlagSpec>& specs) {
    ParsedArgs parsed;
    auto findSpec = [&](const std::string& name) -> const FlagSpec* {
        for (const FlagSpec& s : specs)
            if (s.name == name) return &s;
        return nullptr;
    };
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a.rfind("--", 0) != 0 || a == "--") {
            parsed.positional.push_back(a);
            continue;
        }
        std::string name = a.substr(2), value;
        const auto eq = name.find('=');
        const bool inlineValue = eq != std::string::npos;
        if (inlineValue) {
            value = name.substr(eq + 1);
            name = name.substr(0, eq);
        }
        const FlagSpec* spec = findSpec(name);
        if (!spec) {
            std::string known;
            for (const FlagSpec& s : specs) known += (known.empty() ? "--" : ", --") + s.name;
            throwUserError("gbufferlab " + command + ": unknown flag --" + escapeText(name) + " (known: " + known +
                           "; see gbufferlab " + command + " --help)");
        }
        if (spec->valueName.empty()) {
            if (inlineValue) throwUserError("gbufferlab " + command + ": --" + name + " takes no value");
            parsed.values[name] = "1";
            continue;
        }
        if (!inlineValue) {
            if (i + 1 >= args.size())
                throwUserError("gbufferlab " + command + ": --" + name + " needs a value (" + spec->valueName + ")");
            // "--out --force" is a forgotten value, not a directory named "--force"; a value that
            // really starts with "--" can be given as --out=--force.
            if (args[i + 1].rfind("--", 0) == 0 && args[i + 1].size() > 2)
                throwUserError("gbufferlab " + command + ": --" + name + " needs a value (" + spec->valueName +
                               ") but is followed by the flag " + escapeText(args[i + 1]) + "; give the value (or --" +
                               name + "=VALUE)");
            value = args[++i];
        }
        if (spec->repeatable) {
            parsed.repeated[name].push_back(value);
            parsed.values[name] = value;
            continue;
        }
        if (parsed.values.count(name))
            throwUserError("gbufferlab " + command + ": --" + name + " is given twice (" +
                           quoteName(parsed.values[name]) + " and " + quoteName(value) + "); give it once");
        parsed.values[name] = value;
    }
    return parsed;
}

std::string formatHelp(const std::string& usage, const std::string& summary, const std::vector<FlagSpec>& specs) {
    std::string out = "usage: " + usage + "\n\n" + summary + "\n";
    if (!specs.empty()) out += "\nflags:\n";
    for (const FlagSpec& s : specs) {
        std::string left = "  --" + s.name + (s.valueName.empty() ? "" : " " + s.valueName);
        if (left.size() < 26) left.resize(26, ' ');
        else left += "  ";
        out += left + s.help + "\n";
    }
    return out;
}

int parseIntFlag(const ParsedArgs& args, const std::string& flag, int fallback, int lo, int hi) {
    if (!args.has(flag)) return fallback;
    const std::string text = args.get(flag);
    int v = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || v < lo || v > hi)
        throwUserError("--" + flag + " " + text + ": expected a whole number from " + std::to_string(lo) + " to " +
                       std::to_string(hi));
    return v;
}

float parsePositiveFloatFlag(const ParsedArgs& args, const std::string& flag, float fallback) {
    if (!args.has(flag)) return fallback;
    const std::string text = args.get(flag);
    // Read as a double, so that a positive value a float cannot hold (1e-300, 1e39) is told apart
    // from one that is not positive: strtof turns both into 0 or infinity.
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || std::isnan(v) || !(v > 0.0))
        throwUserError("--" + flag + " " + quoteName(text) + ": expected a positive number, e.g. 1.5");
    if (const std::string problem = positiveFloatProblem(v); !problem.empty())
        throwUserError("--" + flag + " " + quoteName(text) + ": " + problem);
    return float(v);
}

std::pair<uint32_t, uint32_t> parseSize(const std::string& text, const std::string& flag) {
    const auto x = text.find('x');
    auto parse = [&](const std::string& part, uint32_t& v) {
        const auto r = std::from_chars(part.data(), part.data() + part.size(), v);
        return r.ec == std::errc() && r.ptr == part.data() + part.size() && !part.empty();
    };
    uint32_t w = 0, h = 0;
    if (x == std::string::npos || !parse(text.substr(0, x), w) || !parse(text.substr(x + 1), h))
        throwUserError(flag + " " + text + ": expected WIDTHxHEIGHT, e.g. 1920x1080");
    if (w == 0 || h == 0) throwUserError(flag + " " + text + ": width and height must be at least 1, e.g. 1920x1080");
    if (w > 16384 || h > 16384)
        throwUserError(flag + " " + text + ": at most 16384 pixels per side (and the device may allow fewer)");
    return {w, h};
}

}  // namespace gbl
