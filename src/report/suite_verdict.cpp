// The headline of a comparison over several scenes (suite_verdict.h).
#include "suite_verdict.h"

#include <algorithm>
#include <cstdio>
#include <map>

namespace gbl {

namespace {

constexpr const char* kVisibilityPipeline = "visibility-buffer";

std::string twoDecimals(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.2f", v);
    return buffer;
}

// "a", "a and b", "a, b and c"
std::string joinedWithAnd(const std::vector<std::string>& items) {
    std::string out;
    for (size_t i = 0; i < items.size(); ++i)
        out += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
    return out;
}

std::string capitalised(std::string s) {
    if (!s.empty() && s[0] >= 'a' && s[0] <= 'z') s[0] = char(s[0] - 'a' + 'A');
    return s;
}

// The scene as a sentence names it.
std::string sceneWords(const SuiteScene& s) { return s.builtin ? "the built-in scene" : s.name; }

const RunReport* runOf(const SuiteScene& s, const std::string& layout, const std::string& mode) {
    if (!s.report) return nullptr;
    for (const RunReport& r : s.report->runs)
        if (r.layout == layout && r.iblMode == mode && !r.isLightingComparison()) return &r;
    return nullptr;
}

// The scenes whose comparison ran (their report holds runs).
std::vector<size_t> scenesThatRan(const SuiteModel& model) {
    std::vector<size_t> ran;
    for (size_t s = 0; s < model.scenes.size(); ++s)
        if (model.scenes[s].ok && model.scenes[s].report) ran.push_back(s);
    return ran;
}

// The IBL modes in the order the run asked for them, then any other a row holds.
std::vector<std::string> modesOf(const SuiteModel& model) {
    std::vector<std::string> modes = model.run.iblModes;
    for (const SuiteLayoutSummary& row : model.summary)
        if (std::find(modes.begin(), modes.end(), row.iblMode) == modes.end()) modes.push_back(row.iblMode);
    return modes;
}

}  // namespace

std::string ordinal(int n) {
    const int lastTwo = n % 100, last = n % 10;
    const char* suffix = (lastTwo >= 11 && lastTwo <= 13) ? "th"
                         : last == 1                       ? "st"
                         : last == 2                       ? "nd"
                         : last == 3                       ? "rd"
                                                           : "th";
    return std::to_string(n) + suffix;
}

std::string agreementMeaning(double tau) {
    if (tau >= 0.8) return "the ranking holds across them";
    if (tau >= 0.5) return "the rankings agree in broad lines but swap some layouts";
    return "rankings depend on content";
}

std::optional<BudgetVerdict> suiteBudgetVerdict(const SuiteModel& model) {
    const std::vector<size_t> ran = scenesThatRan(model);
    if (ran.size() < 2) return std::nullopt;
    for (const std::string& mode : modesOf(model)) {
        std::vector<VerdictEntry> entries;
        for (const SuiteLayoutSummary& row : model.summary) {
            if (row.iblMode != mode) continue;
            VerdictEntry e{row.layout, row.bytesPerPixel, 0.0, false, 0.0};
            bool everywhere = true;
            for (size_t s : ran) {
                const RunReport* r = runOf(model.scenes[s], row.layout, mode);
                if (!r || !row.errors[s]) {
                    everywhere = false;
                    break;
                }
                e.countedBytes = std::max(e.countedBytes, verdictCountedBytes(*r));
                e.visibilityBuffer = e.visibilityBuffer || r->pipeline == kVisibilityPipeline;
                e.flipMean += *row.errors[s];
            }
            if (!everywhere) continue;
            e.flipMean /= double(ran.size());
            entries.push_back(e);
        }
        if (entries.empty()) continue;
        const std::string scenes = std::to_string(ran.size()) + " scenes";
        BudgetVerdict v;
        v.iblMode = mode;
        v.scenes = int(ran.size());
        v.basis = "The best layout per byte budget across the " + scenes + ", under IBL " + mode +
                  ": the lowest FLIP (LDR) averaged over the scenes (each scene's mean over its views), among the "
                  "layouts measured on every scene whose bytes per pixel fit the budget. Bytes per pixel are the "
                  "table's; a visibility buffer also counts half of its resolve's modelled vertex fetches, the "
                  "largest over the scenes (each scene's report says why). The lines compare mean FLIP alone: "
                  "whether the best is significantly better than the next is the tied rank across the scenes (the "
                  "paired sign-flip test on every scene's FLIP tiles), and each scene's own verdict is in its report.";
        if (model.interruption)
            v.basis += " This report was interrupted by " + model.interruption->signal + " after " +
                       std::to_string(model.scenes.size()) + " of " + std::to_string(model.interruption->scenesPlanned) +
                       " scenes: the lines speak only of the scenes that finished.";
        v.lines = verdictLines(std::move(entries), {}, scenes, "");
        return v;
    }
    return std::nullopt;
}

std::optional<SuiteAgreementWords> suiteAgreementWords(const SuiteModel& model) {
    if (model.agreement.empty()) return std::nullopt;
    // The verdict's mode when it has pairs, else the first that has.
    std::string mode = model.agreement.front().iblMode;
    for (const std::string& m : modesOf(model))
        if (std::any_of(model.agreement.begin(), model.agreement.end(),
                        [&](const SceneAgreement& g) { return g.iblMode == m; })) {
            mode = m;
            break;
        }
    std::map<std::string, size_t> indexOf;
    for (size_t s = 0; s < model.scenes.size(); ++s) indexOf[model.scenes[s].name] = s;
    std::map<std::pair<size_t, size_t>, double> tau;  // (lower index, higher) -> tau
    std::vector<size_t> scenes;                       // those in a pair, in the suite's order
    double sum = 0.0;
    for (const SceneAgreement& g : model.agreement) {
        if (g.iblMode != mode) continue;
        const size_t a = indexOf.at(g.sceneA), b = indexOf.at(g.sceneB);
        tau[{std::min(a, b), std::max(a, b)}] = g.tau;
        sum += g.tau;
        for (size_t s : {a, b})
            if (std::find(scenes.begin(), scenes.end(), s) == scenes.end()) scenes.push_back(s);
    }
    std::sort(scenes.begin(), scenes.end());
    SuiteAgreementWords w;
    w.iblMode = mode;
    w.meanTau = sum / double(tau.size());
    const auto tauOf = [&](size_t a, size_t b) -> std::optional<double> {
        const auto it = tau.find({std::min(a, b), std::max(a, b)});
        return it == tau.end() ? std::nullopt : std::optional<double>(it->second);
    };
    // The mean tau of the pairs that hold `s` (holds = true) or not.
    const auto meanOver = [&](size_t s, bool holds) -> std::optional<double> {
        double total = 0.0;
        int n = 0;
        for (const auto& [pair, t] : tau)
            if ((pair.first == s || pair.second == s) == holds) total += t, ++n;
        return n ? std::optional<double>(total / n) : std::nullopt;
    };
    // "at tau 0.92" for one pair; "at tau 0.85-0.95 (mean 0.90)" for several.
    const auto atTau = [](const std::vector<double>& taus) {
        const auto [lo, hi] = std::minmax_element(taus.begin(), taus.end());
        if (taus.size() == 1 || twoDecimals(*lo) == twoDecimals(*hi)) return "at tau " + twoDecimals(*lo);
        double total = 0.0;
        for (double t : taus) total += t;
        return "at tau " + twoDecimals(*lo) + "-" + twoDecimals(*hi) + " (mean " + twoDecimals(total / double(taus.size())) + ")";
    };

    // The scene that stands apart: the lowest mean tau with the others, kApartTau below theirs.
    std::optional<size_t> apart;
    if (scenes.size() >= 3) {
        size_t lowest = scenes.front();
        for (size_t s : scenes)
            if (*meanOver(s, true) < *meanOver(lowest, true)) lowest = s;
        const std::optional<double> rest = meanOver(lowest, false);
        if (rest && *rest - *meanOver(lowest, true) >= kApartTau) apart = lowest;
    }
    if (scenes.size() == 2) {
        const double t = *tauOf(scenes[0], scenes[1]);
        w.sentence = capitalised(sceneWords(model.scenes[scenes[0]])) + " and " + sceneWords(model.scenes[scenes[1]]) +
                     " agree at tau " + twoDecimals(t) + ": " + agreementMeaning(t) + ".";
    } else if (apart) {
        std::vector<size_t> others;
        bool allAssets = true;
        for (size_t s : scenes)
            if (s != *apart) {
                others.push_back(s);
                allAssets = allAssets && !model.scenes[s].builtin;
            }
        const std::string group = allAssets && !model.scenes[*apart].builtin ? "the other assets"
                                  : allAssets                                ? "the assets"
                                                                             : "the other scenes";
        std::vector<std::string> each;
        std::vector<double> withOthers, amongOthers;
        for (size_t s : others)
            if (const auto t = tauOf(*apart, s)) {
                each.push_back(twoDecimals(*t) + " (" + model.scenes[s].name + ")");
                withOthers.push_back(*t);
            }
        for (size_t i = 0; i < others.size(); ++i)
            for (size_t k = i + 1; k < others.size(); ++k)
                if (const auto t = tauOf(others[i], others[k])) amongOthers.push_back(*t);
        const double meanWith = *meanOver(*apart, true), meanAmong = *meanOver(*apart, false);
        w.sentence = capitalised(sceneWords(model.scenes[*apart])) + " agrees with " + group + " at tau " +
                     joinedWithAnd(each) + ": " + agreementMeaning(meanWith) + ". " + capitalised(group) +
                     " agree with each other " + atTau(amongOthers) + ": " + agreementMeaning(meanAmong) + ".";
    } else {
        std::vector<double> all;
        for (const auto& [pair, t] : tau) all.push_back(t);
        w.sentence = "The " + std::to_string(scenes.size()) + " scenes agree " + atTau(all) + ": " +
                     agreementMeaning(w.meanTau) + ".";
    }
    if (w.meanTau < 0.8)
        w.sentence += " The verdict across the scenes is their mean: read the ranking of the scene nearest your "
                      "content beside it.";

    // The layouts whose plain rank moves most between the scenes.
    int ranked = 0;
    for (const SuiteLayoutSummary& row : model.summary) {
        if (row.iblMode != mode) continue;
        LayoutMove m{row.layout, row.ranks, 0};
        int best = 0, worst = 0, measured = 0;
        for (size_t s : scenes) {
            if (!row.ranks[s]) continue;
            best = measured ? std::min(best, *row.ranks[s]) : *row.ranks[s];
            worst = measured ? std::max(worst, *row.ranks[s]) : *row.ranks[s];
            ++measured;
        }
        if (measured) ++ranked;
        if (measured < 2 || worst == best) continue;
        m.spread = worst - best;
        w.moves.push_back(std::move(m));
    }
    std::stable_sort(w.moves.begin(), w.moves.end(), [](const LayoutMove& a, const LayoutMove& b) {
        return a.spread > b.spread;  // the summary's order (by mean rank) among equal spreads
    });
    if (w.moves.size() > size_t(kMovesListed)) w.moves.resize(size_t(kMovesListed));
    std::vector<std::string> parts;
    for (const LayoutMove& m : w.moves) {
        std::map<int, std::vector<std::string>> byRank;  // rank -> the scenes that give it
        for (size_t s : scenes)
            if (m.ranks[s]) byRank[*m.ranks[s]].push_back(sceneWords(model.scenes[s]));
        std::vector<std::string> places;
        for (const auto& [rank, names] : byRank) places.push_back(ordinal(rank) + " on " + joinedWithAnd(names));
        std::string part = m.layout + " ";
        for (size_t i = 0; i < places.size(); ++i) part += (i ? ", " : "") + places[i];
        parts.push_back(part);
    }
    if (!parts.empty()) {
        w.movesSentence = "Largest moves (rank by FLIP among " + std::to_string(ranked) + " layouts): ";
        for (size_t i = 0; i < parts.size(); ++i) w.movesSentence += (i ? "; " : "") + parts[i];
        w.movesSentence += ".";
    }
    return w;
}

}  // namespace gbl
