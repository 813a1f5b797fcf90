// Pairwise significance and tied ranks (rank_significance.h).
#include "rank_significance.h"

#include <algorithm>
#include <cstdio>
#include <map>

#include "parallel_for.h"
#include "significance.h"

namespace gbl {

const RankRange* SignificanceReport::find(const std::string& layout, const std::string& iblMode) const {
    for (const RankRange& r : ranks)
        if (r.layout == layout && r.iblMode == iblMode) return &r;
    return nullptr;
}

std::vector<double> runUnits(const RunReport& run) {
    std::vector<double> units;
    if (run.status != RunStatus::Ok || !run.image) return units;
    auto add = [&](const ImageErrors& e) {
        if (e.flipTiles.empty()) units.push_back(e.flipMean);
        else units.insert(units.end(), e.flipTiles.begin(), e.flipTiles.end());
    };
    if (run.views.empty()) {
        add(*run.image);
    } else {
        for (const ViewMetrics& v : run.views)
            if (v.image) add(*v.image);
    }
    return units;
}

SignificanceReport rankWithSignificance(const std::vector<LayoutUnits>& layouts) {
    SignificanceReport report;
    char method[400];
    std::snprintf(method, sizeof method,
                  "paired sign-flip permutation test (two-sided) of the difference in LDR-FLIP per unit: tiles of a "
                  "%d x %d grid over every view%s; exact up to %d units, else %d random sign assignments (seeded); "
                  "significant at p < %g; ranks low-high: 1 + layouts significantly better .. layouts - those "
                  "significantly worse",
                  kSignificanceTileColumns, kSignificanceTileRows,
                  layouts.empty() || layouts.front().unitsPerScene.size() < 2 ? "" : " of every scene both ran on",
                  kExactSignFlipUnits, kSignFlipResamples, kSignificanceAlpha);
    report.method = method;
    std::map<std::string, std::vector<size_t>> byMode;
    for (size_t i = 0; i < layouts.size(); ++i) {
        bool any = false;
        for (const auto& u : layouts[i].unitsPerScene) any = any || !u.empty();
        if (any) byMode[layouts[i].iblMode].push_back(i);
    }
    for (auto& modeMembers : byMode) {
        // Named, not a structured binding: clang 14 (the sanitizer build) captures no binding.
        const std::string& mode = modeMembers.first;
        std::vector<size_t>& members = modeMembers.second;
        std::stable_sort(members.begin(), members.end(),
                         [&](size_t a, size_t b) { return layouts[a].meanError < layouts[b].meanError; });
        const size_t n = members.size();
        std::vector<std::vector<char>> significant(n, std::vector<char>(n, 0));
        // Every pair (i < k), tested on the cores (the tests are independent; the order of the
        // report's pairs is the loop's).
        std::vector<std::pair<size_t, size_t>> order;
        for (size_t i = 0; i < n; ++i)
            for (size_t k = i + 1; k < n; ++k) order.emplace_back(i, k);
        std::vector<PairSignificance> pairs(order.size());
        parallelFor(int64_t(order.size()), 0, [&](int64_t begin, int64_t end) {
            for (int64_t q = begin; q < end; ++q) {
                const LayoutUnits& a = layouts[members[order[size_t(q)].first]];  // the lower (or equal) mean error
                const LayoutUnits& b = layouts[members[order[size_t(q)].second]];
                std::vector<double> d;
                for (size_t s = 0; s < a.unitsPerScene.size() && s < b.unitsPerScene.size(); ++s) {
                    const auto& ua = a.unitsPerScene[s];
                    const auto& ub = b.unitsPerScene[s];
                    if (ua.empty() || ua.size() != ub.size()) continue;
                    for (size_t u = 0; u < ua.size(); ++u) d.push_back(ub[u] - ua[u]);
                }
                PairSignificance& p = pairs[size_t(q)];
                p.better = a.layout;
                p.worse = b.layout;
                p.iblMode = mode;
                p.meanDifference = b.meanError - a.meanError;
                p.units = int(d.size());
                p.pValue = pairedSignFlipPValue(d);
                p.significant = !d.empty() && p.pValue < kSignificanceAlpha && p.meanDifference > 0.0;
            }
        });
        for (size_t q = 0; q < order.size(); ++q) {
            const auto [i, k] = order[q];
            significant[i][k] = significant[k][i] = pairs[q].significant;
            report.pairs.push_back(std::move(pairs[q]));
        }
        for (size_t i = 0; i < n; ++i) {
            RankRange r;
            r.layout = layouts[members[i]].layout;
            r.iblMode = mode;
            r.meanError = layouts[members[i]].meanError;
            r.rank = 1;
            for (size_t k = 0; k < n; ++k)
                if (layouts[members[k]].meanError < r.meanError) ++r.rank;
            int better = 0, worse = 0;
            for (size_t k = 0; k < n; ++k) {
                if (!significant[i][k]) continue;
                if (layouts[members[k]].meanError < r.meanError) ++better;
                else ++worse;
            }
            r.low = 1 + better;
            r.high = int(n) - worse;
            report.ranks.push_back(std::move(r));
        }
    }
    return report;
}

namespace {
// runUnits over one class's pixels.
std::vector<double> classUnits(const RunReport& run, ImageClassMember member) {
    std::vector<double> units;
    auto add = [&](const ImageErrors& e) {
        const std::optional<ImageClassErrors>& c = e.*member;
        if (!c) return;
        if (c->flipTiles.empty()) units.push_back(c->flipMean);
        else units.insert(units.end(), c->flipTiles.begin(), c->flipTiles.end());
    };
    if (run.views.empty()) add(*run.image);
    else
        for (const ViewMetrics& v : run.views)
            if (v.image) add(*v.image);
    return units;
}
}  // namespace

std::vector<std::pair<std::string, SignificanceReport>> rankLayerClassesWithSignificance(const ReportModel& model) {
    std::vector<std::pair<std::string, SignificanceReport>> out;
    for (const auto& [name, member] : layerImageClasses()) {
        std::vector<LayoutUnits> layouts;
        for (const RunReport& r : model.runs) {
            if (r.isLightingComparison() || r.status != RunStatus::Ok || !r.image || !((*r.image).*member)) continue;
            layouts.push_back({r.layout, r.iblMode, ((*r.image).*member)->flipMean, {classUnits(r, member)}});
        }
        if (layouts.empty()) continue;
        SignificanceReport sr = rankWithSignificance(layouts);
        sr.method += std::string("; LDR-FLIP over the ") + name + " class's pixels only (a tile without any counts 0)";
        out.emplace_back(name, std::move(sr));
    }
    return out;
}

SignificanceReport rankWithSignificance(const ReportModel& model) {
    std::vector<LayoutUnits> layouts;
    for (const RunReport& r : model.runs) {
        if (r.isLightingComparison() || r.status != RunStatus::Ok || !r.image) continue;
        layouts.push_back({r.layout, r.iblMode, r.image->flipMean, {runUnits(r)}});
    }
    return rankWithSignificance(layouts);
}

}  // namespace gbl
