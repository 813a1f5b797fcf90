#pragma once
// A small argument parser for subcommands: "--flag value", "--flag=value" and boolean
// "--flag". Unknown flags are a UserError naming the flag and listing the known ones; so are a
// value flag followed by another flag instead of its value, and a value flag given twice (unless
// its FlagSpec says it is repeatable).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "option_values.h"  // positiveFloatProblem, splitFlagList

namespace gbl {

struct FlagSpec {
    std::string name;  // without dashes
    std::string valueName;  // empty for boolean flags
    std::string help;
    bool repeatable = false;  // a value flag that may be given several times (ParsedArgs::all)
};

struct ParsedArgs {
    std::map<std::string, std::string> values;
    std::vector<std::string> positional;
    // Every value of a repeatable flag, in the order given (values[] holds the last).
    std::map<std::string, std::vector<std::string>> repeated;
    std::vector<std::string> all(const std::string& flag) const;
    bool has(const std::string& flag) const { return values.count(flag) != 0; }
    std::string get(const std::string& flag, const std::string& fallback = "") const;
};

ParsedArgs parseArgs(const std::string& command, const std::vector<std::string>& args,
                     const std::vector<FlagSpec>& specs);
std::string formatHelp(const std::string& usage, const std::string& summary, const std::vector<FlagSpec>& specs);

// The flag's value as a whole number in [lo, hi] (all of it: "12abc" is refused), or `fallback`
// when absent; anything else is a UserError naming the flag and the range.
int parseIntFlag(const ParsedArgs& args, const std::string& flag, int fallback, int lo, int hi);
// The flag's value as a finite number > 0, or `fallback` when absent.
float parsePositiveFloatFlag(const ParsedArgs& args, const std::string& flag, float fallback);
// "1920x1080" -> (1920, 1080); anything else is a UserError naming the flag.
std::pair<uint32_t, uint32_t> parseSize(const std::string& text, const std::string& flag);

}  // namespace gbl
