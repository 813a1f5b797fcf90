#include "compare_console.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "budget_verdict.h"
#include "report_bandwidth.h"
#include "suite_verdict.h"
#include "view_stats.h"
#include "visibility_verdict.h"

namespace gbl::compare {

namespace {

// Material layers (a scene with them): each layer attribute's mean error over the pixels whose
// reference carries the layer, then LDR-FLIP per layer class with its tied rank in that class.
void printLayerTable(const ReportModel& model, int w) {
    if (!model.hasLayerMetrics()) return;
    std::printf("\nMaterial layers: mean attribute error over the covered pixels whose reference carries the layer "
                "(coat, roughnesses, strength: |d|; normals, direction: degrees; sheen colour: CIEDE2000); "
                "LDR-FLIP per material class (a pixel may be in several; rank as above, within the class):\n");
    std::printf("%-*s %-16s %6s %6s %7s %7s %6s %6s %7s", w, "layout", "ibl", "coat", "coatR", "coatN°", "sheenΔE",
                "sheenR", "aniso", "aniso°");
    for (const auto& [name, member] : layerImageClasses()) std::printf(" %17s", name);
    std::printf("\n");
    auto findSig = [&](const char* name) -> const SignificanceReport* {
        for (const auto& [n, sig] : model.classSignificance)
            if (n == name) return &sig;
        return nullptr;
    };
    for (const RunReport& r : model.runs) {
        if (r.status != RunStatus::Ok) continue;
        std::printf("%-*s %-16s", w, r.layout.c_str(), r.iblMode.c_str());
        const int widths[] = {6, 6, 7, 7, 6, 6, 7};
        for (size_t k = 0; k < kLayerErrorAttributeCount; ++k) {
            const auto& a = r.attributes[kLayerErrorAttributes[k]].all;
            if (a) std::printf(" %*.3f", widths[k], a->error.mean);
            else std::printf(" %*s", widths[k], "-");
        }
        for (const auto& [name, member] : layerImageClasses()) {
            const std::optional<ImageClassErrors>& c = r.image ? (*r.image).*member : std::nullopt;
            char cell[40] = "-";
            if (c) {
                const SignificanceReport* sig = findSig(name);
                const RankRange* rank = sig ? sig->find(r.layout, r.iblMode) : nullptr;
                std::snprintf(cell, sizeof cell, "%.4f (%s)", c->flipMean, rank ? rank->text().c_str() : "");
            }
            std::printf(" %17s", cell);
        }
        std::printf("\n");
    }
    std::printf("pixels per class:");
    for (const RunReport& r : model.runs) {
        if (r.status != RunStatus::Ok || !r.image) continue;
        for (const auto& [name, member] : layerImageClasses())
            if (const auto& c = (*r.image).*member) std::printf(" %s %lld", name, (long long)c->pixels);
        break;  // the reference's classes: the same for every layout (of the pixels covered in both)
    }
    std::printf("\n");
}

}  // namespace

void printTable(const ReportModel& model) {
    // The layout column is as wide as its longest name ("reference (split-sum-shader vs ground-truth)").
    int w = 20;
    for (const RunReport& r : model.runs) w = std::max(w, int(r.layout.size()));
    const size_t views = model.run.views.size();
    size_t measured = 0;  // a view with nothing to measure is in no mean
    for (size_t i = 0; i < views; ++i)
        measured += i >= model.run.viewNotMeasured.size() || model.run.viewNotMeasured[i].empty();
    if (views > 1)
        std::printf("\nEvery metric is the mean over %d %s; the row under each run gives its spread over them:\n"
                    "± standard deviation, PSNR as min..max dB.",
                    int(measured), measured == views ? "views" : ("of the " + std::to_string(views) + " views").c_str());
    // compare --temporal N: the resolved errors, then the first frame's alone (1f) beside them.
    const bool temporal = model.run.temporalFrames > 1;
    if (temporal)
        std::printf("\n--temporal %d: normal°, albedoΔE, PSNR and FLIP are the resolved images' (%s of %d jittered "
                    "frames; attributes: their temporal mean); \"1f\" columns: frame 0 alone.",
                    model.run.temporalFrames, model.run.temporalResolve.c_str(), model.run.temporalFrames);
    std::printf("\n%-*s %-16s %6s %9s %9s %9s %10s %8s %6s", w, "layout", "ibl", "B/px", "GB/s@1080", "normal°",
                "albedoΔE", "PSNR(tm)", "FLIP", "rank");
    if (temporal) std::printf(" %9s %10s %8s", "normal°1f", "PSNR 1f", "FLIP 1f");
    std::printf("\n");
    for (const RunReport& r : model.runs) {
        if (r.status == RunStatus::Failed) {
            std::printf("%-*s %-16s FAILED: %s\n", w, r.layout.c_str(), r.iblMode.c_str(), r.error.c_str());
            continue;
        }
        if (r.status == RunStatus::NotMeasured) {  // no view had anything to measure: no numbers
            std::printf("%-*s %-16s %6d NOT MEASURED (no view had anything to measure)\n", w, r.layout.c_str(),
                        r.iblMode.c_str(), r.bytesPerPixel.total);
            continue;
        }
        const auto& n = r.attributes[ErrorAttribute::Normal].all;
        const auto& a = r.attributes[ErrorAttribute::DiffuseColor].all;
        const RankRange* rank = model.significance ? model.significance->find(r.layout, r.iblMode) : nullptr;
        std::printf("%-*s %-16s %6d %9.2f %9.3f %9.3f %10s %8.4f %6s", w, r.layout.c_str(), r.iblMode.c_str(),
                    r.bytesPerPixel.total, r.gigabytesPerSecond1080p60().value_or(0.0), n ? n->error.mean : 0.0,
                    a ? a->error.mean : 0.0, formatPsnr(r.image ? r.image->psnrToneMapped : 0.0).c_str(),
                    r.image ? r.image->flipMean : 0.0, rank ? rank->text().c_str() : "");
        if (temporal && r.singleFrame) {
            const auto& n1 = r.singleFrame->attributes[ErrorAttribute::Normal].all;
            const auto& i1 = r.singleFrame->image;
            std::printf(" %9.3f %10s %8.4f", n1 ? n1->error.mean : 0.0,
                        formatPsnr(i1 ? i1->psnrToneMapped : 0.0).c_str(), i1 ? i1->flipMean : 0.0);
        }
        std::printf("\n");
        if (views > 1 && r.views.size() > 1) {
            auto attr = [](ErrorAttribute which) {
                return [which](const RunReport& v) -> std::optional<double> {
                    const auto& s = v.attributes[which].all;
                    if (!s) return std::nullopt;
                    return s->error.mean;
                };
            };
            const ViewSpread ns = viewSpread(r, attr(ErrorAttribute::Normal));
            const ViewSpread as = viewSpread(r, attr(ErrorAttribute::DiffuseColor));
            const ViewSpread p = viewSpread(r, [](const RunReport& v) -> std::optional<double> {
                if (!v.image) return std::nullopt;
                return v.image->psnrToneMapped;
            });
            const ViewSpread f = viewSpread(r, [](const RunReport& v) -> std::optional<double> {
                if (!v.image) return std::nullopt;
                return v.image->flipMean;
            });
            char psnr[32];
            std::snprintf(psnr, sizeof(psnr), "%.1f..%.1f", p.min, p.max);
            std::printf("%-*s %-16s %6s %9s   ±%6.3f   ±%6.3f %10s  ±%6.4f\n", w, "", "  spread", "", "", ns.stddev,
                        as.stddev, psnr, f.stddev);
        }
    }
    for (size_t v = 0; v < model.run.viewNotMeasured.size(); ++v)
        if (!model.run.viewNotMeasured[v].empty())
            std::printf("view %d not measured: %s; it is left out of every mean, rank and verdict\n", int(v),
                        model.run.viewNotMeasured[v].c_str());
    if (model.significance && !model.significance->ranks.empty())
        std::printf("rank: by mean FLIP; a range (4-6) where the differences are not significant (%s)\n",
                    model.significance->method.c_str());
    printLayerTable(model, w);
    if (const auto v = gbufferOrVisibility(model)) std::printf("\nG-buffer or visibility buffer? %s\n", v->answer.c_str());
    printVerdict(model);
    printBandwidthAsPaid(model);
}

// Bandwidth as GPUs pay it (report_bandwidth.h): per layout, nominal and effective bytes per pixel
// and 1080p60 traffic per GPU class, the tile families it fits, and the budget lines that change.
void printBandwidthAsPaid(const ReportModel& model) {
    const std::vector<const RunReport*> runs = effectiveRuns(model);
    if (runs.empty()) return;
    int w = 6;
    for (const RunReport* r : runs) w = std::max(w, int(r->layout.size()));
    std::printf("\nBandwidth as GPUs pay it (1080p60, lit output included; lighting %s; docs/bandwidth.md):\n",
                model.run.lighting.c_str());
    std::printf("%-*s %13s %17s %17s %17s  %s\n", w, "layout", "nominal", "desktop-dcc", "mali-afbc", "tile-subpass",
                "fits tile memory of");
    for (const RunReport* r : runs) {
        const EffectiveBandwidth& e = *r->effective;
        char cells[3][40];
        int i = 0;
        for (const char* c : kGpuClasses) {
            const ClassTraffic* t = e.find(c);
            std::snprintf(cells[i++], sizeof(cells[0]), "%5.1f B %5.2f GB/s", t ? t->bytesPerPixel : 0.0,
                          t ? t->gbPerSecond : 0.0);
        }
        std::string fits;
        for (const TileFit& f : e.tile)
            if (f.fits) fits += (fits.empty() ? "" : " ") + f.family;
        std::printf("%-*s %3.0f B %5.2f GB/s %s %s %s  %s\n", w, r->layout.c_str(), e.nominalBytesPerPixel,
                    e.nominalGbPerSecond, cells[0], cells[1], cells[2], fits.empty() ? "none" : fits.c_str());
    }
    const std::vector<std::string> changes = verdictChanges(effectiveVerdicts(model));
    if (changes.empty()) std::printf("the best layout at each budget is the same with every class's effective bytes\n");
    for (const std::string& c : changes) std::printf("  %s\n", c.c_str());
}

namespace {

void printVerdictLines(const BudgetVerdict& v, const char* title) {
    std::printf("\n%s %s\n", title, v.basis.c_str());
    for (const BudgetLine& line : v.lines) std::printf("  %s\n", line.sentence.c_str());
}

}  // namespace

void printVerdict(const ReportModel& model) {
    if (const auto v = budgetVerdict(model)) printVerdictLines(*v, "Verdict.");
}

void printTimings(const CompareTimings& t) {
    std::printf("\ntime by stage (wall):");
    for (size_t s = 0; s < kStageCount; ++s)
        std::printf("%s %s %.2f s", s ? "," : "", stageName(Stage(s)), t.stages.ms[s] / 1000.0);
    std::printf("\nshaders: %d compiled by glslang, %d from the SPIR-V cache%s; pipelines: %d created, %d found in "
                "the pipeline cache (driver's report), %d reused across views and modes",
                t.glslangCompiles, t.spirvCacheHits,
                t.spirvCacheInvalid ? (", " + std::to_string(t.spirvCacheInvalid) + " invalid cache files ignored").c_str()
                                    : "",
                t.pipelines, t.pipelineCacheHits, t.pipelinesReused);
    for (const auto& [kind, w] : t.warmUps)
        std::printf("\nwarm-ups %s: %d, %.2f s (slowest %.2f s: %s)", kind.c_str(), w.count, w.ms / 1000.0,
                    w.slowestMs / 1000.0, w.slowest.c_str());
    std::printf("\ntotal %.2f s = %.2fx the GPU passes' own %.2f s (timestamps%s)\n", t.stages.totalMs / 1000.0,
                t.gpuPassMs > 0.0 ? t.stages.totalMs / t.gpuPassMs : 0.0, t.gpuPassMs / 1000.0,
                t.cpuDevice ? "; on this CPU device the passes share the cores with the file encoders, which can "
                              "lengthen them"
                            : "");
}

void printSuiteTable(const SuiteModel& model) {
    int w = 20;
    for (const SuiteLayoutSummary& row : model.summary) w = std::max(w, int(row.layout.size()));
    std::printf("\nAcross %d scenes (error: mean LDR-FLIP over each scene's views; rank 1 = lowest in that scene):\n",
                int(model.scenes.size()));
    std::printf("%-*s %-12s %5s %9s %6s %6s %6s", w, "layout", "ibl", "B/px", "mean FLIP", "tied#", "mean#",
                "worst#");
    for (const SuiteScene& s : model.scenes) std::printf(" %16.16s", s.name.c_str());
    std::printf("\n");
    for (const SuiteLayoutSummary& row : model.summary) {
        std::printf("%-*s %-12s %5d", w, row.layout.c_str(), row.iblMode.c_str(), row.bytesPerPixel);
        if (row.scenesMeasured)
            std::printf(" %9.5f %6s %6.2f %6d", row.meanError, row.tiedRankAcross.c_str(), row.meanRank, row.worstRank);
        else
            std::printf(" %9s %6s %6s %6s", "FAILED", "", "", "");
        for (size_t s = 0; s < model.scenes.size(); ++s) {
            char buf[40] = "-";
            if (row.errors[s]) std::snprintf(buf, sizeof(buf), "%.5f (%s)", *row.errors[s], row.tiedRanks[s].c_str());
            std::printf(" %16s", buf);
        }
        std::printf("\n");
    }
    std::printf("tied#: by mean FLIP over the scenes, a range where differences are not significant (%s); per scene: "
                "its FLIP (its own tied rank); mean#, worst#: plain ranks\n", model.acrossScenes.method.c_str());
    for (const SceneAgreement& g : model.agreement)
        std::printf("rank agreement %s / %s (%s): Kendall's tau-b %.2f, %d of %d layout pairs swap\n", g.sceneA.c_str(),
                    g.sceneB.c_str(), g.iblMode.c_str(), g.tau, int(g.swaps.size()), g.pairs);
    for (const SuiteScene& s : model.scenes)
        if (!s.ok) std::printf("scene %s FAILED: %s\n", s.name.c_str(), s.error.c_str());
    // The headline: how far the scenes agree, then the verdict across them (suite_verdict.h).
    if (const auto words = suiteAgreementWords(model)) {
        std::printf("\nAgreement. %s\n", words->sentence.c_str());
        if (!words->movesSentence.empty()) std::printf("%s\n", words->movesSentence.c_str());
    }
    if (const auto v = suiteBudgetVerdict(model)) printVerdictLines(*v, "Verdict across the scenes.");
}

void printReport(const app::CompareResult& result) {
    if (result.suite) printSuiteTable(*result.suite);
    else if (result.report) printTable(*result.report);
    if (result.timings) printTimings(*result.timings);
    std::printf("report: %s\n", (result.outDir / "report.html").string().c_str());
    // A file that could not be written, runs or scenes that failed: one line each, never lost.
    for (const std::string& e : result.errors) std::fprintf(stderr, "gbufferlab: error: %s\n", e.c_str());
}

}  // namespace gbl::compare
