#pragma once
// The layout search: a seeded evolutionary search over Genomes (search_space.h) under a byte
// budget, keeping a Pareto archive over bytes per pixel and every error (search_metrics.h).
//
// Each round proposes a batch of candidates from the current archive (a fresh random genome, shrunk
// to a random size between the smallest packable and the budget, with probability 0.15 and for
// the first rounds, else a mutation of a parent drawn from the pool: the
// archive's 3 best at each byte count by the objective), brings it inside the engine constraints
// (search_constraints.h), packs each into a layout (layout_packer.h), drops those
// over the budget or already seen (same canonical text), parses and validates the rest with the
// real parser, evaluates the batch in parallel, and only then updates the archive in candidate
// order. Nothing depends on the thread count or timing, so a seed gives the same candidates,
// scores and front on any machine; the journal (search_journal.h) makes it resumable.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "fast_eval.h"
#include "search_constraints.h"
#include "search_space.h"

namespace gbl::search {

struct Candidate {
    int index = 0;
    Genome genome;
    std::string body;  // layout text after the name line (layout_packer.h)
    uint64_t hash = 0;
    int bytes = 0;
    Evaluation eval;
    std::string how;   // "random", "mutation of #12"
    bool fromJournal = false;
};

struct SearchProgress {
    int evaluated = 0, total = 0;
    int resumed = 0;          // of evaluated, read from the journal
    double seconds = 0.0;     // wall time of this process's evaluations (a resumed search counts anew)
    double perMinute = 0.0;   // this process's rate (0 until something was evaluated)
    double etaSeconds = 0.0;
    const Candidate* bestAtBudget = nullptr;  // lowest error of the front
};

using EvaluateFn = std::function<Evaluation(const std::string& layoutText)>;

struct SearchOptions {
    int budgetBytes = 16;
    uint64_t seed = 1;
    int candidates = 600;   // evaluations to run (journal entries included)
    int batch = 8;          // candidates proposed and evaluated per round (fixed: part of the result)
    int threads = 0;        // evaluations at once (0: hardwareThreads()); does not change the result
    std::string journalPath;  // empty: no journal
    std::string journalKey;
    EngineConstraints constraints;  // on by default (search_constraints.h)
    // The scenes carry material layers (clear coat, sheen, anisotropy): the genomes choose whether
    // and in how many bits to store each, and whether under a shading-model selector
    // (search_space.h). Off: the search space, and its random draws, are those of before.
    bool layers = false;
    std::function<void(const SearchProgress&)> progress;  // after every round
    // Before every round: true ends the search there (what was evaluated is the result; the
    // journal holds it, so the same options resume). Unset: it runs to `candidates`.
    std::function<bool()> stop;
};

struct SearchResult {
    std::vector<Candidate> evaluated;  // in index order
    std::vector<int> front;            // indices into evaluated, by bytes ascending
    int overBudget = 0, duplicates = 0, unpackable = 0;
    int rejectedByValidation = 0;  // always expected 0: the packer only writes valid layouts
    std::vector<std::string> validationMessages;
    int rejectedByConstraints = 0;  // always expected 0: genomes are constrained before packing
    std::vector<std::string> constraintMessages;
    int resumed = 0;
    double seconds = 0.0;     // this process's evaluation wall time
    double cpuSeconds = 0.0;  // ... and the process's CPU time over it (all threads): on a loaded
                              // machine, what the evaluations cost regardless of the other work
};

// `evaluate` receives the whole layout text (name "candidate"); it is called concurrently.
SearchResult runSearch(const EvaluateFn& evaluate, const SearchOptions& options);

// The Pareto front of `cands` over bytes and every metric (search_metrics.h): the candidates no
// other is at most as costly and no worse on any metric than, and better on one; of candidates
// equal on all, the earliest. Indices by bytes ascending, then in the objective's order (error).
std::vector<int> paretoFront(const std::vector<Candidate>& cands);

// Spearman's rank correlation of two equally long series (average ranks for ties).
double spearman(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace gbl::search
