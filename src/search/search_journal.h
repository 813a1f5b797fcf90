#pragma once
// The search's journal: one line per evaluated candidate, appended and fsync'd as soon as it is
// known, so an interrupted search loses at most the batch in flight. A rerun with the same
// arguments replays the journal instead of re-evaluating: the generator is deterministic, so it
// proposes the same candidates in the same order, and each one's recorded score (checked against
// its layout text's hash) stands in for its evaluation. The run therefore ends exactly where an
// uninterrupted one would. Scores are written as C99 hexadecimal floats: exact round trips.
//
//   gbufferlab-search-journal 2 <TAB> <key: every argument the result depends on>
//   <index> <TAB> <hash of the layout text, 16 hex digits> <TAB> <bytes> <TAB> <error> <TAB> <flip> <TAB> <psnr>
//     <TAB> <attributes> <TAB> <normal> <TAB> <base ΔE> <TAB> <diffuse ΔE> <TAB> <specular ΔE> <TAB> <roughness>
//     <TAB> <metallic> <TAB> <occlusion>     (one line; Evaluation's members in order)
// Version 1 journals (one error per candidate) are refused with that reason.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "fast_eval.h"

namespace gbl::search {

struct JournalEntry {
    int index = 0;
    uint64_t hash = 0;
    int bytes = 0;
    Evaluation eval;
};

class Journal {
public:
    // Opens `path` (created if missing). An existing journal whose key differs is a UserError
    // naming the file and the fix (another --out, or the same arguments); a torn last line (an
    // interruption mid-write) is dropped.
    Journal(const std::filesystem::path& path, const std::string& key);
    ~Journal();
    Journal(const Journal&) = delete;
    Journal& operator=(const Journal&) = delete;

    const std::vector<JournalEntry>& entries() const { return entries_; }
    void append(const JournalEntry& e);  // written and fsync'd before it returns

private:
    std::filesystem::path path_;
    std::vector<JournalEntry> entries_;
    int fd_ = -1;
};

// FNV-1a, 64 bits (Fnv64::bytes), of the layout text (the journal's check that a replayed candidate
// is the same).
uint64_t textHash(const std::string& text);

}  // namespace gbl::search
