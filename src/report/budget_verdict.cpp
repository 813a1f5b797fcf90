#include "budget_verdict.h"

#include <algorithm>
#include <cstdio>

namespace gbl {
namespace {

bool counts(const RunReport& r, const std::string& reference) {
    return r.status == RunStatus::Ok && r.image && !r.isLightingComparison() && r.layout != reference;
}

// Per pixel, not per sample: the resolve shades once per pixel whatever the MSAA.
double vertexFetchBytesPerPixel(const RunReport& r) {
    for (const FrameTraffic& f : r.bandwidth)
        if (f.width > 0 && f.height > 0) return f.vertexFetchBytes / (double(f.width) * double(f.height));
    return kVisibilityVertexBytes;  // no frame recorded: the model's constant
}

std::string printed(const char* format, double v) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, format, v);
    return buffer;
}

std::string bytesText(const VerdictEntry& e) {
    if (!e.visibilityBuffer) return std::to_string(e.bytesPerPixel) + " B/px";
    return std::to_string(e.bytesPerPixel) + " B/px of ids and depth, " + printed("%g", e.countedBytes) +
           " counting its modelled vertex fetches";
}

std::string budgetText(const std::optional<int>& budget) {
    return budget ? "Up to " + std::to_string(*budget) + " B/px" : std::string("Unlimited");
}

// "; not run (interrupted by SIGINT): crysis3-thin (12 B/px), niagara (12 B/px)"
std::string notRunText(const BudgetLine& line, const std::string& interruptedBy) {
    if (line.notRun.empty()) return "";
    std::string s = "; not run (interrupted by " + interruptedBy + "): ";
    for (size_t i = 0; i < line.notRun.size(); ++i)
        s += (i ? ", " : "") + line.notRun[i].layout + " (" + printed("%g", line.notRun[i].countedBytes) + " B/px)";
    return s;
}

std::string sentenceOf(const BudgetLine& line, const std::string& over, const std::string& interruptedBy) {
    std::string s = budgetText(line.budget) + ": ";
    if (!line.best) {
        s += interruptedBy.empty() ? "no layout fits" : "no layout that ran fits";
        if (line.smallest)
            s += "; the smallest, " + line.smallest->layout + ", counts " + printed("%g", line.smallest->countedBytes) +
                 " B/px";
        return s + notRunText(line, interruptedBy) + ".";
    }
    s += line.best->layout + " (" + bytesText(*line.best) + ") has the lowest mean FLIP over " + over + ", " +
         printed("%.4f", line.best->flipMean);
    for (size_t i = 0; i < line.tiedWith.size(); ++i)
        s += (i == 0 ? ", tied with " : i + 1 == line.tiedWith.size() ? " and " : ", ") + line.tiedWith[i].layout +
             " (" + bytesText(line.tiedWith[i]) + ")";
    return s + notRunText(line, interruptedBy) + ".";
}

}  // namespace

double verdictCountedBytes(const RunReport& run) {
    double bytes = run.bytesPerPixel.total;
    if (run.isVisibilityBuffer()) bytes += vertexFetchBytesPerPixel(run) / 2.0;
    return bytes;
}

std::optional<BudgetVerdict> budgetVerdict(const ReportModel& model) {
    std::vector<std::string> modes = model.run.iblModes;
    for (const RunReport& r : model.runs)
        if (std::find(modes.begin(), modes.end(), r.iblMode) == modes.end()) modes.push_back(r.iblMode);
    for (const std::string& mode : modes) {
        std::vector<VerdictEntry> entries;
        int views = 1;
        for (const RunReport& r : model.runs) {
            if (r.iblMode != mode || !counts(r, model.reference.layout)) continue;
            entries.push_back({r.layout, r.bytesPerPixel.total, verdictCountedBytes(r), r.isVisibilityBuffer(),
                               r.image->flipMean});
            // The views measured (a view with nothing to measure has no image errors: not in the mean).
            const int measured = r.views.empty() ? 1
                                                 : int(std::count_if(r.views.begin(), r.views.end(),
                                                                     [](const ViewMetrics& v) { return bool(v.image); }));
            views = std::max(views, measured);
        }
        if (entries.empty()) continue;
        // What an interruption left unrun under this mode.
        std::vector<VerdictEntry> notRun;
        if (model.interruption)
            for (const PlannedRun& p : model.interruption->notRun)
                if (p.iblMode == mode) notRun.push_back({p.layout, p.bytesPerPixel, p.countedBytes, false, 0.0});
        BudgetVerdict v;
        v.iblMode = mode;
        v.views = views;
        v.interruptedBy = model.interruption ? model.interruption->signal : "";
        v.basis = "The best layout per byte budget, under IBL " + mode +
                  ": the lowest mean FLIP (LDR) over " + std::to_string(views) + (views == 1 ? " view" : " views") +
                  " among the measured layouts whose bytes per pixel fit the budget. Bytes per pixel are the "
                  "table's (targets + depth + light buffers); a visibility buffer also counts half of its "
                  "resolve's modelled vertex fetches (no cache reuse), since the bandwidth model moves a stored "
                  "byte twice (written, then read) and a fetched byte once. The lines compare mean FLIP alone: "
                  "\"tied with\" names layouts of exactly equal mean, and a line does not say whether its layout "
                  "is significantly better than the next; the Rank column does (the paired sign-flip test on "
                  "FLIP tiles: layouts that share a rank range are not significantly different).";
        if (model.interruption)
            v.basis += " This report was interrupted by " + model.interruption->signal + " after " +
                       std::to_string(model.interruption->runsFinished) + " of " +
                       std::to_string(model.interruption->runsPlanned) +
                       " runs: the lines speak only of the layouts that ran and name those that fit but did not.";
        v.lines = verdictLines(std::move(entries), std::move(notRun),
                               std::to_string(views) + (views == 1 ? " view" : " views"), v.interruptedBy);
        return v;
    }
    return std::nullopt;
}

std::vector<BudgetLine> verdictLines(std::vector<VerdictEntry> entries, std::vector<VerdictEntry> notRun,
                                     const std::string& over, const std::string& interruptedBy) {
    std::vector<BudgetLine> lines;
    if (entries.empty()) return lines;
    // Best first; among equal means the fewer counted bytes, then the name, so ties read the same
    // way in every run.
    std::stable_sort(entries.begin(), entries.end(), [](const VerdictEntry& a, const VerdictEntry& b) {
        if (a.flipMean != b.flipMean) return a.flipMean < b.flipMean;
        if (a.countedBytes != b.countedBytes) return a.countedBytes < b.countedBytes;
        return a.layout < b.layout;
    });
    const VerdictEntry smallest = *std::min_element(
        entries.begin(), entries.end(),
        [](const VerdictEntry& a, const VerdictEntry& b) { return a.countedBytes < b.countedBytes; });
    // The unrun, by counted bytes then name.
    std::stable_sort(notRun.begin(), notRun.end(), [](const VerdictEntry& a, const VerdictEntry& b) {
        return a.countedBytes != b.countedBytes ? a.countedBytes < b.countedBytes : a.layout < b.layout;
    });
    std::vector<std::optional<int>> budgets(std::begin(kVerdictBudgets), std::end(kVerdictBudgets));
    budgets.push_back(std::nullopt);
    for (const std::optional<int>& budget : budgets) {
        BudgetLine line;
        line.budget = budget;
        for (const VerdictEntry& e : entries) {
            if (budget && e.countedBytes > *budget) continue;
            if (!line.best) line.best = e;
            else if (e.flipMean == line.best->flipMean) line.tiedWith.push_back(e);
            else break;
        }
        if (!line.best) line.smallest = smallest;
        for (const VerdictEntry& e : notRun)
            if (!budget || e.countedBytes <= *budget) line.notRun.push_back(e);
        line.sentence = sentenceOf(line, over, interruptedBy);
        lines.push_back(std::move(line));
    }
    return lines;
}

}  // namespace gbl
