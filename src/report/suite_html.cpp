// report.html of a comparison over several scenes: the run, the summary across scenes, and a
// section per scene (its ranking, a link to its own full report under scenes/<name>/).
#include <algorithm>
#include <cmath>

#include "report_html.h"
#include "report_html_template.h"
#include "suite_report.h"
#include "suite_verdict.h"

namespace gbl {

namespace {

std::string cell(const std::string& text, bool number = false) {
    return std::string(number ? "<td class=\"num\">" : "<td>") + text + "</td>";
}

std::string errorText(const std::optional<double>& v) { return v ? formatSignificant(*v, 3) : "&ndash;"; }

}  // namespace

std::string suiteHtml(const SuiteModel& model) {
    const ReportRunInfo& r = model.run;
    std::string out = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>gbufferlab compare: " +
                      std::to_string(model.scenes.size()) + " scenes</title>\n<style>";
    out += report_template::kCss;
    out += "</style></head><body><main>\n<header class=\"run\"><h1>G-buffer layouts on " +
           std::to_string(model.scenes.size()) + " scenes</h1>\n<dl class=\"info\"><dt>size</dt><dd>" +
           std::to_string(r.width) + "&times;" + std::to_string(r.height) + "</dd><dt>device</dt><dd>" +
           htmlEscape(r.device.name) + "</dd><dt>date</dt><dd>" + htmlEscape(r.date) + "</dd><dt>IBL</dt><dd>";
    for (size_t i = 0; i < r.iblModes.size(); ++i) out += (i ? ", " : "") + htmlEscape(r.iblModes[i]);
    out += "</dd></dl><pre class=\"cmd\">" + htmlEscape(r.commandLine) + "</pre>";
    if (!r.notes.empty()) {
        out += "<ul class=\"notes\">";
        for (const std::string& n : r.notes) out += "<li>" + htmlEscape(n) + "</li>";
        out += "</ul>";
    }
    if (model.interruption) {  // what this report lacks comes first
        std::string names;
        for (const std::string& n : model.interruption->notFinished) names += (names.empty() ? "" : ", ") + htmlEscape(n);
        out += "<div class=\"errorbox\" id=\"interrupted\"><strong>Incomplete:</strong> interrupted by " +
               htmlEscape(model.interruption->signal) + " after " + std::to_string(model.scenes.size()) + " of " +
               std::to_string(model.interruption->scenesPlanned) +
               " scenes; this report covers only the scenes that finished. Not finished: " + names + ".</div>\n";
    }
    out += "</header>\n";

    // The headline: the verdict across the scenes, and how far they agree (suite_verdict.h).
    const auto verdict = suiteBudgetVerdict(model);
    const auto words = suiteAgreementWords(model);
    if (verdict || words) {
        out += "<section id=\"verdict\">\n<h2>Verdict across the scenes</h2>\n";
        if (words) {
            out += "<p class=\"agreement\">" + htmlEscape(words->sentence) + "</p>\n";
            if (!words->movesSentence.empty()) out += "<p class=\"moves\">" + htmlEscape(words->movesSentence) + "</p>\n";
        }
        if (verdict) {
            out += "<ul class=\"verdict-lines\">\n";
            for (const BudgetLine& line : verdict->lines)
                out += "<li data-budget=\"" + (line.budget ? std::to_string(*line.budget) : std::string("unlimited")) +
                       "\"" + (line.best ? "" : " class=\"none-fits\"") + ">" + htmlEscape(line.sentence) + "</li>\n";
            out += "</ul>\n<p class=\"hint\">" + htmlEscape(verdict->basis) + "</p>\n";
        }
        out += "<p class=\"hint\">Each scene's own ranking and verdict: its section below and its full report.</p>\n"
               "</section>\n";
    }

    // The summary: one row per layout and mode, one error (rank) column per scene.
    out += "<h2 id=\"summary\">Across the scenes</h2>\n<p class=\"muted\">Error: mean LDR-FLIP over each scene's "
           "views. Rank 1 = the lowest error of that scene's layouts under the same IBL mode. Mean and worst over the "
           "scenes where the layout ran.</p>\n<table class=\"data\"><thead><tr><th>layout</th><th>IBL</th>"
           "<th>B/px</th><th>mean FLIP</th><th>tied rank</th><th>mean rank</th><th>worst rank</th>";
    for (const SuiteScene& s : model.scenes) out += "<th>" + htmlEscape(s.name) + "</th>";
    out += "</tr></thead><tbody>\n";
    for (const SuiteLayoutSummary& row : model.summary) {
        out += "<tr>" + cell(htmlEscape(row.layout)) + cell(htmlEscape(row.iblMode)) +
               cell(std::to_string(row.bytesPerPixel), true);
        if (row.scenesMeasured) {
            out += cell(formatSignificant(row.meanError, 3), true) + cell(htmlEscape(row.tiedRankAcross), true) +
                   cell(formatFixed(row.meanRank, 2), true) +
                   cell(std::to_string(row.worstRank), true);
        } else {
            out += cell("failed") + cell("") + cell("") + cell("");
        }
        for (size_t s = 0; s < model.scenes.size(); ++s)
            out += cell(errorText(row.errors[s]) + (row.errors[s] ? " (" + htmlEscape(row.tiedRanks[s]) + ")" : ""), true);
        out += "</tr>\n";
    }
    out += "</tbody></table>\n<p class=\"muted\">Tied rank: by mean FLIP over the scenes; a range where the "
           "differences are not significant (" + htmlEscape(model.acrossScenes.method) +
           "). In the scene columns: the error (the scene's own tied rank).</p>\n";

    // Rank agreement: a scene x scene matrix of Kendall's tau per IBL mode.
    std::vector<std::string> modes;
    for (const SceneAgreement& g : model.agreement)
        if (std::find(modes.begin(), modes.end(), g.iblMode) == modes.end()) modes.push_back(g.iblMode);
    if (!modes.empty()) out += "<h2 id=\"agreement\">Rank agreement</h2>\n";
    for (const std::string& mode : modes) {
        out += "<p class=\"muted\">Kendall's tau-b between two scenes' rankings of the layouts (" + htmlEscape(mode) +
               "); 1 = the same order. Under the diagonal: the layout pairs that swap.</p>\n<table class=\"data\" "
               "style=\"width:auto\"><thead><tr><th></th>";
        for (const SuiteScene& s : model.scenes) out += "<th>" + htmlEscape(s.name) + "</th>";
        out += "</tr></thead><tbody>\n";
        for (const SuiteScene& a : model.scenes) {
            out += "<tr><th>" + htmlEscape(a.name) + "</th>";
            for (const SuiteScene& b : model.scenes) {
                const SceneAgreement* g = nullptr;
                for (const SceneAgreement& x : model.agreement)
                    if (x.iblMode == mode && ((x.sceneA == a.name && x.sceneB == b.name) ||
                                              (x.sceneA == b.name && x.sceneB == a.name)))
                        g = &x;
                if (&a == &b) out += cell("1", true);
                else if (!g) out += cell("&ndash;", true);
                else if (&a < &b) out += cell(formatFixed(g->tau, 2), true);
                else out += cell(std::to_string(g->swaps.size()) + " of " + std::to_string(g->pairs), true);
            }
            out += "</tr>\n";
        }
        out += "</tbody></table>\n";
    }

    // A section per scene.
    for (const SuiteScene& s : model.scenes) {
        out += "<h2 id=\"scene-" + htmlEscape(s.name) + "\">Scene " + htmlEscape(s.name) + "</h2>\n<p>" +
               htmlEscape(s.scene) + " under " + htmlEscape(s.environment) + ". ";
        if (!s.ok) {
            out += "<strong>FAILED</strong>: " + htmlEscape(s.error) + "</p>\n";
            continue;
        }
        const std::string link = urlPathEscape(s.folder() + "/report.html");
        out += "Full report with images: <a href=\"" + link + "\">" + htmlEscape(s.folder()) + "/report.html</a>";
        if (s.report) out += "; exposure " + formatSignificant(s.report->run.exposure, 4);
        out += ".</p>\n<table class=\"data\"><thead><tr><th>tied rank</th><th>layout</th><th>IBL</th><th>B/px</th>"
               "<th>FLIP</th><th>PSNR (tone-mapped)</th></tr></thead><tbody>\n";
        size_t index = size_t(&s - model.scenes.data());
        std::vector<const SuiteLayoutSummary*> rows;
        for (const SuiteLayoutSummary& row : model.summary) rows.push_back(&row);
        std::stable_sort(rows.begin(), rows.end(), [&](const SuiteLayoutSummary* a, const SuiteLayoutSummary* b) {
            if (a->iblMode != b->iblMode) return a->iblMode < b->iblMode;
            const int ra = a->ranks[index].value_or(1 << 20), rb = b->ranks[index].value_or(1 << 20);
            return ra < rb;
        });
        for (const SuiteLayoutSummary* row : rows) {
            const RunReport* run = nullptr;
            for (const RunReport& candidate : s.report->runs)
                if (candidate.layout == row->layout && candidate.iblMode == row->iblMode) run = &candidate;
            if (!run) continue;
            out += "<tr>" + cell(row->ranks[index] ? htmlEscape(row->tiedRanks[index]) : "&ndash;", true) +
                   cell(htmlEscape(row->layout)) + cell(htmlEscape(row->iblMode)) +
                   cell(std::to_string(row->bytesPerPixel), true);
            if (run->status == RunStatus::Ok && run->image)
                out += cell(formatSignificant(run->image->flipMean, 3), true) +
                       cell(formatFixed(run->image->psnrToneMapped, 1) + " dB", true);
            else
                out += "<td colspan=\"2\">FAILED: " + htmlEscape(run->error) + "</td>";
            out += "</tr>\n";
        }
        out += "</tbody></table>\n";
    }
    out += "</main></body></html>\n";
    return out;
}

}  // namespace gbl
