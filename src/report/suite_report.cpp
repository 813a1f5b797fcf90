// The summary of a comparison over several scenes, and its report.json (suite_report.h).
#include "suite_report.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "file_io.h"
#include "json_number.h"
#include "rank_agreement.h"
#include "rank_significance.h"
#include "report_json.h"
#include "suite_verdict.h"

namespace gbl {

namespace {
using Json = nlohmann::ordered_json;

// The runs a scene ranks: ok layout runs (not the lighting comparisons) of one IBL mode.
bool ranked(const RunReport& r) { return r.status == RunStatus::Ok && r.image && !r.isLightingComparison(); }

Json optionalNumber(const std::optional<double>& v) { return v ? jsonNumber(*v) : Json(nullptr); }

}  // namespace

static void finishSuiteSummary(SuiteModel& model);

void summariseSuite(SuiteModel& model) {
    model.summary.clear();
    std::map<std::pair<std::string, std::string>, size_t> index;  // (layout, mode) -> summary row
    const size_t sceneCount = model.scenes.size();
    auto rowOf = [&](const RunReport& r) -> SuiteLayoutSummary& {
        auto [it, fresh] = index.emplace(std::make_pair(r.layout, r.iblMode), model.summary.size());
        if (fresh) {
            SuiteLayoutSummary s;
            s.layout = r.layout;
            s.iblMode = r.iblMode;
            s.bytesPerPixel = r.bytesPerPixel.total;
            s.errors.resize(sceneCount);
            s.ranks.resize(sceneCount);
            model.summary.push_back(std::move(s));
        }
        return model.summary[it->second];
    };
    for (size_t s = 0; s < sceneCount; ++s) {
        if (!model.scenes[s].report) continue;
        const std::vector<RunReport>& runs = model.scenes[s].report->runs;
        for (const RunReport& r : runs) {
            if (r.isLightingComparison()) continue;
            SuiteLayoutSummary& row = rowOf(r);
            if (!ranked(r)) continue;
            row.errors[s] = r.image->flipMean;
            // Competition rank among the same mode's runs: 1 + how many have a strictly lower error.
            int rank = 1;
            for (const RunReport& other : runs)
                if (ranked(other) && other.iblMode == r.iblMode && other.image->flipMean < r.image->flipMean) ++rank;
            row.ranks[s] = rank;
        }
    }
    finishSuiteSummary(model);
    // Tied ranks: each scene's from its own test, across the scenes from the pooled one.
    std::vector<LayoutUnits> pooled;
    for (SuiteLayoutSummary& row : model.summary) {
        row.tiedRanks.assign(sceneCount, "");
        LayoutUnits units{row.layout, row.iblMode, 0.0, std::vector<std::vector<double>>(sceneCount)};
        int measured = 0;
        for (size_t s = 0; s < sceneCount; ++s) {
            const std::optional<ReportModel>& report = model.scenes[s].report;
            if (!report || !row.errors[s]) continue;
            if (report->significance)
                if (const RankRange* r = report->significance->find(row.layout, row.iblMode)) row.tiedRanks[s] = r->text();
            for (const RunReport& r : report->runs)
                if (r.layout == row.layout && r.iblMode == row.iblMode) units.unitsPerScene[s] = runUnits(r);
            units.meanError += *row.errors[s];
            ++measured;
        }
        if (measured) units.meanError /= measured;
        pooled.push_back(std::move(units));
    }
    model.acrossScenes = rankWithSignificance(pooled);
    for (SuiteLayoutSummary& row : model.summary)
        if (const RankRange* r = model.acrossScenes.find(row.layout, row.iblMode)) row.tiedRankAcross = r->text();

    // Rank agreement of every pair of scenes, per mode, over the layouts both ranked.
    model.agreement.clear();
    std::vector<std::string> modes;
    for (const SuiteLayoutSummary& row : model.summary)
        if (std::find(modes.begin(), modes.end(), row.iblMode) == modes.end()) modes.push_back(row.iblMode);
    for (const std::string& mode : modes)
        for (size_t a = 0; a < sceneCount; ++a)
            for (size_t b = a + 1; b < sceneCount; ++b) {
                std::vector<const SuiteLayoutSummary*> rows;
                std::vector<double> ea, eb;
                for (const SuiteLayoutSummary& row : model.summary)
                    if (row.iblMode == mode && row.errors[a] && row.errors[b]) {
                        rows.push_back(&row);
                        ea.push_back(*row.errors[a]);
                        eb.push_back(*row.errors[b]);
                    }
                if (rows.size() < 2) continue;
                const KendallTau k = kendallTau(ea, eb);
                SceneAgreement g{model.scenes[a].name, model.scenes[b].name, mode, int(rows.size()), k.tau, k.pairs, {}};
                for (const auto& [i, j] : k.swaps) {
                    const bool iBetterInA = ea[size_t(i)] < ea[size_t(j)];
                    g.swaps.emplace_back(iBetterInA ? rows[size_t(i)]->layout : rows[size_t(j)]->layout,
                                         iBetterInA ? rows[size_t(j)]->layout : rows[size_t(i)]->layout);
                }
                model.agreement.push_back(std::move(g));
            }
}

static void finishSuiteSummary(SuiteModel& model) {
    const size_t sceneCount = model.scenes.size();
    for (SuiteLayoutSummary& row : model.summary) {
        double errorSum = 0.0, rankSum = 0.0;
        for (size_t s = 0; s < sceneCount; ++s) {
            if (!row.errors[s]) continue;
            ++row.scenesMeasured;
            errorSum += *row.errors[s];
            rankSum += *row.ranks[s];
            row.worstRank = std::max(row.worstRank, *row.ranks[s]);
        }
        if (row.scenesMeasured > 0) {
            row.meanError = errorSum / row.scenesMeasured;
            row.meanRank = rankSum / row.scenesMeasured;
        }
    }
    std::stable_sort(model.summary.begin(), model.summary.end(), [](const SuiteLayoutSummary& a, const SuiteLayoutSummary& b) {
        if (a.iblMode != b.iblMode) return a.iblMode < b.iblMode;
        if ((a.scenesMeasured > 0) != (b.scenesMeasured > 0)) return a.scenesMeasured > 0;
        if (a.meanRank != b.meanRank) return a.meanRank < b.meanRank;
        return a.meanError < b.meanError;
    });
}

nlohmann::ordered_json suiteToJson(const SuiteModel& model) {
    const ReportRunInfo& r = model.run;
    Json run{{"width", r.width},
             {"height", r.height},
             {"device", Json{{"name", r.device.name}, {"driver", r.device.driver}, {"type", r.device.type}}},
             {"date", r.date},
             {"command_line", r.commandLine},
             {"ibl_modes", r.iblModes},
             {"notes", r.notes}};
    Json scenes = Json::array();
    for (const SuiteScene& s : model.scenes) {
        Json j{{"name", s.name},
               {"scene", s.scene},
               {"environment", s.environment},
               {"status", s.ok ? "ok" : "failed"},
               {"error", s.error},
               {"exit_status", s.exitStatus},
               {"folder", s.ok ? s.folder() : ""}};
        j["report"] = s.report ? reportToJson(*s.report) : Json(nullptr);
        scenes.push_back(std::move(j));
    }
    Json layouts = Json::array();
    for (const SuiteLayoutSummary& row : model.summary) {
        Json perScene = Json::array();
        for (size_t s = 0; s < model.scenes.size(); ++s)
            perScene.push_back(Json{{"scene", model.scenes[s].name},
                                    {"error", optionalNumber(row.errors[s])},
                                    {"rank", row.ranks[s] ? Json(*row.ranks[s]) : Json(nullptr)},
                                    {"tied_rank", row.tiedRanks.size() > s ? row.tiedRanks[s] : ""}});
        layouts.push_back(Json{{"layout", row.layout},
                               {"ibl_mode", row.iblMode},
                               {"bytes_per_pixel", row.bytesPerPixel},
                               {"scenes_measured", row.scenesMeasured},
                               {"mean_error", row.scenesMeasured ? jsonNumber(row.meanError) : Json(nullptr)},
                               {"mean_rank", row.scenesMeasured ? jsonNumber(row.meanRank) : Json(nullptr)},
                               {"worst_rank", row.scenesMeasured ? Json(row.worstRank) : Json(nullptr)},
                               {"tied_rank_across_scenes", row.tiedRankAcross},
                               {"per_scene", std::move(perScene)}});
    }
    Json pairs = Json::array();
    for (const PairSignificance& p : model.acrossScenes.pairs)
        pairs.push_back(Json{{"better", p.better},
                             {"worse", p.worse},
                             {"ibl_mode", p.iblMode},
                             {"mean_difference", jsonNumber(p.meanDifference)},
                             {"units", p.units},
                             {"p_value", jsonNumber(p.pValue)},
                             {"significant", p.significant}});
    Json inWords;  // how far the scenes agree, in words (suite_verdict.h)
    if (const auto w = suiteAgreementWords(model)) {
        Json moves = Json::array();
        for (const LayoutMove& m : w->moves) {
            Json ranks = Json::object();
            for (size_t i = 0; i < model.scenes.size(); ++i)
                if (model.scenes[i].ok) ranks[model.scenes[i].name] = m.ranks[i] ? Json(*m.ranks[i]) : Json(nullptr);
            moves.push_back(Json{{"layout", m.layout}, {"rank_per_scene", std::move(ranks)}, {"spread", m.spread}});
        }
        inWords = Json{{"ibl_mode", w->iblMode},
                       {"mean_kendall_tau", jsonNumber(w->meanTau)},
                       {"sentence", w->sentence},
                       {"largest_moves", std::move(moves)},
                       {"moves_sentence", w->movesSentence}};
    }
    Json agreement = Json::array();
    for (const SceneAgreement& g : model.agreement) {
        Json swaps = Json::array();
        for (const auto& [x, y] : g.swaps) swaps.push_back(Json::array({x, y}));
        agreement.push_back(Json{{"scene_a", g.sceneA},
                                 {"scene_b", g.sceneB},
                                 {"ibl_mode", g.iblMode},
                                 {"layouts", g.layouts},
                                 {"layout_pairs", g.pairs},
                                 {"kendall_tau", jsonNumber(g.tau)},
                                 {"swapped_pairs", std::move(swaps)}});
    }
    Json interruption;
    if (model.interruption)
        interruption = Json{{"signal", model.interruption->signal},
                            {"scenes_finished", int(model.scenes.size())},
                            {"scenes_planned", model.interruption->scenesPlanned},
                            {"not_finished", model.interruption->notFinished}};
    Json j{{"schema", "gbufferlab-scene-suite"},
                {"schema_version", kReportSchemaVersion},
                {"status", model.interruption ? "interrupted" : "complete"}};
    if (model.interruption) j["interruption"] = std::move(interruption);
    j["run"] = std::move(run);
    if (const auto v = suiteBudgetVerdict(model)) j["verdict"] = budgetVerdictToJson(*v);
    Json rest{
                {"scenes", std::move(scenes)},
                {"summary", Json{{"error", "image_errors.flip_mean"},
                                 {"rank", "1 = lowest error of the scene's layouts under the same IBL mode; equal errors "
                                          "share the better rank"},
                                 {"tied_rank", "each scene's: its report's significance.ranks; across the scenes: "
                                               "significance_across_scenes, ranked by mean_error"},
                                 {"layouts", std::move(layouts)}}},
                {"significance_across_scenes", Json{{"method", model.acrossScenes.method}, {"pairs", std::move(pairs)}}},
                {"rank_agreement", Json{{"method", "Kendall's tau-b between two scenes' orders of the layouts both "
                                                   "ranked (by mean LDR-FLIP); swapped_pairs: [better in scene_a, "
                                                   "better in scene_b]"},
                                        {"in_words", std::move(inWords)},
                                        {"pairs", std::move(agreement)}}}};
    for (auto& [key, value] : rest.items()) j[key] = std::move(value);
    return j;
}

void writeSuiteReport(const std::filesystem::path& dir, const SuiteModel& model) {
    writeFileAtomic(dir / "report.json",
                    suiteToJson(model).dump(2, ' ', false, Json::error_handler_t::replace) + "\n");
    writeFileAtomic(dir / "report.html", suiteHtml(model));
}

}  // namespace gbl
