#pragma once
// The search as a library call: what `gbufferlab search` runs once its flags are read.
//
//   app::SearchOptions options;
//   options.budget = 12;
//   options.width = 64, options.height = 36, options.viewCount = 1;
//   options.candidates = 16, options.confirm = false;
//   options.outDir = "out/search";
//   const app::SearchResult result = app::runSearch(options, {});
//   result.summary.front ...   // the Pareto front, by bytes
//
// It renders the float reference of each scene once on the device, explores layouts with the fast
// CPU evaluation (src/search), writes the front as layout files (front/found-<B>b.toml, with their
// HLSL and GLSL exports) and search-report.md / search.json, and, unless told not to, confirms the
// front and the published layouts with full renders: a comparison (compare_api.h) into <out>/compare.
// An output folder holding a search journal is resumed.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "compare_api.h"
#include "fast_eval.h"
#include "run_control.h"
#include "search_constraints.h"
#include "search_report.h"

namespace gbl::app {

struct SearchOptions {
    int budget = 16;  // bytes per pixel, render targets and depth-stencil included (4..64)
    search::EngineConstraints constraints;  // search --search-depth, --min-bits
    std::vector<std::string> sceneArgs;     // as compare's --scene (none: the built-in scene)
    std::string envPath;                    // empty: the built-in sky
    bool allowOutsideScene = false;
    uint32_t width = 480, height = 270;
    int viewCount = 3;
    search::Objective objective = search::Objective::Flip;
    uint64_t seed = 1;
    int candidates = 600;
    int threads = 0;      // candidates evaluated at once; 0: every core. Does not change the result
    bool confirm = true;  // full renders of the front and the published layouts (search --no-confirm: false)
    // search --budget-model: what the budget and the front's bytes count: "nominal" (the formats'
    // bytes), or a GPU class's effective bytes ("desktop-dcc", "mali-afbc": the targets as the
    // framebuffer-compression model stores the words the CPU codec writes for view 0 of each scene,
    // depth nominal; measure/effective_bandwidth.h). With a class, candidates up to twice the budget
    // in nominal bytes (at most 64) are explored, and those whose effective bytes fit are kept.
    std::string budgetModel = "nominal";
    std::filesystem::path outDir;  // new, empty, or holding a journal to resume
    std::string device;   // as compare's --device; empty: lavapipe
    // The command as the front files quote it, without what does not change the result (--out,
    // --threads, --device, --no-confirm), so that two runs with one seed write the same bytes.
    std::string commandLine = "gbufferlab search";
};

struct SearchResult {
    // 0, or 128 + the signal when interrupted (the journal keeps every round that finished: the
    // same options resume it).
    int exitStatus = 0;
    int interruptedBy = 0;  // RunControl::cancel's signal; 0: ran to its end
    // search-report.md's model: the whole front (by bytes, then the objective), the rows (found
    // layouts written as files, then the published ones), the run's facts.
    SearchSummary summary;
    std::filesystem::path outDir;
    std::string closingNote;  // the report's closing note
    std::optional<CompareResult> confirmation;  // the full renders (options.confirm)

    bool interrupted() const { return interruptedBy != 0; }
    int layoutsWritten() const;  // found layouts written to front/
};

// Throws the UserError search --budget gives when no layout inside `constraints` fits in `budget`
// bytes per pixel (the smallest the search packs).
void requirePackableBudget(int budget, const search::EngineConstraints& constraints);

// Runs the search `options` describe; bad input throws UserError before the device starts.
SearchResult runSearch(const SearchOptions& options, const RunControl& control = {});

}  // namespace gbl::app
