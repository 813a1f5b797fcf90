#include "report_html.h"
#include "report_html_layers.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "error.h"
#include "file_io.h"
#include "report_atlas.h"
#include "report_csv.h"
#include "budget_verdict.h"
#include "report_bandwidth.h"
#include "report_html_plot.h"
#include "report_html_table.h"
#include "report_html_template.h"
#include "visibility_verdict.h"
#include "report_json.h"
#include "tone_map.h"

namespace gbl {

std::string htmlEscape(const std::string& text) {
    std::string out;
    out.reserve(text.size() + 8);
    for (char ch : text) {
        switch (ch) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += ch;
        }
    }
    return out;
}

std::string urlPathEscape(const std::string& path) {
    static const char* kHex = "0123456789ABCDEF";
    std::string out;
    for (unsigned char ch : path) {
        const bool plain = (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') ||
                           ch == '-' || ch == '.' || ch == '_' || ch == '~' || ch == '/';
        if (plain) {
            out += char(ch);
        } else {
            out += '%';
            out += kHex[ch >> 4];
            out += kHex[ch & 15];
        }
    }
    return out;
}

namespace {

std::string nonFinite(double v) {
    if (std::isnan(v)) return "NaN";
    return v > 0 ? kInfinity : std::string("-") + kInfinity;
}

std::string printf1(const char* format, int precision, double v) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, format, precision, v);
    return buffer;
}
}  // namespace

std::string formatSignificant(double v, int digits) {
    if (!std::isfinite(v)) return nonFinite(v);
    if (v == 0.0) return "0";
    digits = std::max(digits, 1);
    // The exponent after rounding to `digits` (9.996 -> 1.00e+01), so "10.0", not "9.996" or "10.00".
    const std::string scientific = printf1("%.*e", digits - 1, v);
    const int exponent = std::atoi(scientific.c_str() + scientific.find('e') + 1);
    if (exponent < -4 || exponent >= 6) return scientific.substr(0, scientific.find('e')) + "e" +
                                               (exponent < 0 ? "-" : "+") + (std::abs(exponent) < 10 ? "0" : "") +
                                               std::to_string(std::abs(exponent));
    return printf1("%.*f", std::max(0, digits - 1 - exponent), v);
}

std::string formatFixed(double v, int decimals) {
    if (!std::isfinite(v)) return nonFinite(v);
    std::string text = printf1("%.*f", std::max(decimals, 0), v);
    if (text.find_first_not_of("-0.") == std::string::npos && text[0] == '-') text.erase(0, 1);  // no "-0.00"
    return text;
}

std::vector<size_t> paretoFront(const std::vector<std::pair<double, double>>& points, bool higherIsBetter) {
    std::vector<size_t> order;
    for (size_t i = 0; i < points.size(); ++i)
        if (!std::isnan(points[i].first) && !std::isnan(points[i].second)) order.push_back(i);
    const auto better = [&](double a, double b) { return higherIsBetter ? a > b : a < b; };
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        if (points[a].first != points[b].first) return points[a].first < points[b].first;
        return better(points[a].second, points[b].second);
    });
    std::vector<size_t> front;
    for (size_t i : order)
        if (front.empty() || better(points[i].second, points[front.back()].second)) front.push_back(i);
    return front;
}

namespace {

struct Ids {
    std::map<std::string, int> used;
    std::string make(const std::string& text) {
        std::string id = "run-";
        for (unsigned char ch : text) {
            if (std::isalnum(ch)) id += char(std::tolower(ch));
            else if (id.back() != '-') id += '-';
        }
        while (id.size() > 4 && id.back() == '-') id.pop_back();
        const int n = ++used[id];
        return n == 1 ? id : id + "-" + std::to_string(n);
    }
};

// ---- Per-run sections ----------------------------------------------------------------------------

void writeImage(std::string& out, const std::string& path, const std::string& caption, const char* figureClass = "") {
    if (path.empty()) return;
    const std::string src = urlPathEscape(path);
    out += std::string("<figure") + (*figureClass ? std::string(" class=\"") + figureClass + "\"" : "") + "><a href=\"" +
           src + "\"><img src=\"" + src + "\" alt=\"" + htmlEscape(caption) +
           "\" onerror=\"this.classList.add('missing')\"></a><figcaption>" + htmlEscape(caption) +
           "</figcaption></figure>\n";
}

// The A/B viewer (the script's setupViewer): the reference and this run's render stacked, one
// shown at a time. Without the script it is the reference image alone.
void writeViewer(std::string& out, const ReportModel& model, const ReferenceImage& reference, const RunReport& r,
                 const std::string& id) {
    const bool hdr = !reference.hdrPreview.empty() && !r.images.hdrPreview.empty();
    char range[96];
    std::snprintf(range, sizeof(range), " data-log2-min=\"%g\" data-log2-max=\"%g\" data-exposure=\"%.9g\"",
                  double(kPreviewLog2Min), double(kPreviewLog2Max), model.run.exposure);
    const auto img = [&](const std::string& png, const std::string& log, const std::string& name, bool hidden) {
        return "<img src=\"" + urlPathEscape(png) + "\" data-png=\"" + urlPathEscape(png) + "\" data-log=\"" +
               (hdr ? urlPathEscape(log) : std::string()) + "\" data-name=\"" + htmlEscape(name) + "\" alt=\"" +
               htmlEscape(name) + "\"" + (hidden ? " hidden" : "") + " onerror=\"this.classList.add('missing')\">";
    };
    out += "<div class=\"ab\" tabindex=\"0\" id=\"ab-" + id + "\"" + range +
           " aria-label=\"A/B viewer: click, Space or F flips; wheel or + - zooms; drag or arrows pan\">\n"
           "<div class=\"ab-bar\"><button type=\"button\" class=\"ab-flip\" aria-pressed=\"false\">Showing: <b "
           "class=\"ab-which\">reference</b></button><span class=\"muted\">click / Space / F flips, wheel / + / - "
           "zooms, drag / arrows pan, 0 fits, 1 = 1:1</span><label>Exposure <input type=\"range\" class=\"ab-ev\" "
           "min=\"-8\" max=\"8\" step=\"0.5\" value=\"0\"" + (hdr ? "" : " disabled") +
           "></label><output class=\"ab-ev-out\">+0 EV</output><button type=\"button\" class=\"ab-reset\">Fit"
           "</button><output class=\"ab-zoom-out\"></output><output class=\"ab-pixel\"></output></div>\n"
           "<div class=\"ab-view\"><div class=\"ab-stage\">" +
           img(reference.render, reference.hdrPreview, "reference (" + model.reference.layout + ")", false) +
           img(r.images.render, r.images.hdrPreview, r.layout, true) +
           "</div></div>\n<svg width=\"0\" height=\"0\" aria-hidden=\"true\" style=\"position:absolute\"><filter "
           "id=\"abf-" + id + "\" color-interpolation-filters=\"sRGB\"><feComponentTransfer><feFuncR type=\"table\" "
           "tableValues=\"0 1\"/><feFuncG type=\"table\" tableValues=\"0 1\"/><feFuncB type=\"table\" "
           "tableValues=\"0 1\"/></feComponentTransfer></filter></svg>\n</div>\n";
}

void statRow(std::string& out, const char* name, const std::string& value, const char* unit = "") {
    out += std::string("<tr><th>") + name + "</th><td class=\"num\">" + value + "</td><td class=\"muted\">" + unit +
           "</td></tr>\n";
}
void textRow(std::string& out, const char* name, const std::string& valueHtml) {
    out += std::string("<tr><th>") + name + "</th><td class=\"text\" colspan=\"2\">" + valueHtml + "</td></tr>\n";
}

void writeAttributeTable(std::string& out, const AttributeErrorTable& table) {
    bool any = false;
    for (ErrorAttribute a : kAllErrorAttributes) any = any || !table[a].empty();
    if (!any) return;
    out += "<table class=\"small\"><thead><tr><th>Attribute</th><th>Unit</th><th>Class</th>"
           "<th class=\"num\">Mean</th><th class=\"num\">p99</th><th class=\"num\">Max</th>"
           "<th class=\"num\">RMSE</th></tr></thead><tbody>\n";
    const std::pair<const char*, std::optional<AttributeStats> AttributeErrors::*> classes[] = {
        {"all", &AttributeErrors::all}, {"metal", &AttributeErrors::metal}, {"dielectric", &AttributeErrors::dielectric}};
    for (ErrorAttribute a : kAllErrorAttributes)  // the layers' over the pixels carrying the layer only
        for (const auto& [className, member] : classes) {
            const auto& s = table[a].*member;
            if (!s) continue;
            const std::string cls = !errorAttributeIsLayer(a) ? std::string(className)
                                    : member == &AttributeErrors::all
                                        ? std::string(errorAttributeLayerClass(a))
                                        : std::string(errorAttributeLayerClass(a)) + ", " + className;
            out += std::string("<tr><td>") + errorAttributeName(a) + "</td><td class=\"muted\">" +
                   errorAttributeUnit(a) + "</td><td class=\"muted\">" + cls + "</td><td class=\"num\">" +
                   formatSignificant(s->error.mean, 3) + "</td><td class=\"num\">" + formatSignificant(s->error.p99, 3) +
                   "</td><td class=\"num\">" + formatSignificant(s->error.max, 3) + "</td><td class=\"num\">" +
                   (s->rmse ? formatSignificant(*s->rmse, 3) : std::string()) + "</td></tr>\n";
        }
    out += "</tbody></table>\n";
}

void writeRunSection(std::string& out, const ReportModel& model, const RunReport& r, const std::string& id) {
    out += "<section class=\"layout\" id=\"" + id + "\">\n<h2>" + htmlEscape(r.layout) +
           (r.title.empty() ? "" : " &mdash; " + htmlEscape(r.title)) + " <span class=\"muted\">(IBL " +
           htmlEscape(r.iblMode) + ")</span></h2>\n";
    if (!r.source.empty()) out += "<p class=\"cite\">" + htmlEscape(r.source) + "</p>\n";
    if (r.status == RunStatus::Failed)
        out += "<div class=\"errorbox\"><strong>Failed:</strong> " + htmlEscape(r.error) + "</div>\n";
    if (!r.notMeasured.empty())
        out += "<div class=\"errorbox\"><strong>" +
               std::string(r.status == RunStatus::NotMeasured ? "Not measured" : "Views left out") + ":</strong> " +
               htmlEscape(r.notMeasured) + "</div>\n";
    out += "<div class=\"cols\">\n<table class=\"small\"><tbody>\n";
    textRow(out, "Pipeline", htmlEscape(r.pipeline));
    statRow(out, "Targets", formatFixed(r.bytesPerPixel.targets, 0), "B/px");
    statRow(out, "Depth-stencil", formatFixed(r.bytesPerPixel.depth, 0), "B/px");
    if (r.bytesPerPixel.lightBuffers) statRow(out, "Light buffers", formatFixed(r.bytesPerPixel.lightBuffers, 0), "B/px");
    statRow(out, "Total", formatFixed(r.bytesPerPixel.total, 0), "B/px");
    if (const auto gbps = r.gigabytesPerSecond1080p60()) statRow(out, "1080p60 traffic", formatFixed(*gbps, 2), "GB/s");
    for (const FrameTraffic& f : r.bandwidth)  // a visibility buffer's resolve (src/measure/bandwidth.h)
        if (f.width == 1920 && f.height == 1080 && f.samples == 1 && f.vertexFetchBytes > 0) {
            const double pixels = 1920.0 * 1080.0;
            statRow(out, "Vertex fetches (modelled, in the traffic)", formatFixed(f.vertexFetchBytes / pixels, 0), "B/px");
            statRow(out, "Texel fetches (modelled, not in it)", formatFixed(f.textureFetchBytes / pixels, 0), "B/px");
        }
    if (r.times) {
        statRow(out, "G-buffer pass", formatSignificant(r.times->gbufferMs, 3), "ms");
        statRow(out, "Lighting pass", formatSignificant(r.times->lightingMs, 3), "ms");
        textRow(out, "Timed on", htmlEscape(r.times->device));
    }
    out += "</tbody></table>\n";
    if (r.image) {
        const ImageErrors& e = *r.image;
        out += "<table class=\"small\"><tbody>\n";
        statRow(out, "PSNR tone-mapped", formatFixed(e.psnrToneMapped, 2), "dB");
        statRow(out, "RMSE tone-mapped", formatSignificant(e.rmseToneMapped, 3));
        statRow(out, "PSNR linear HDR", formatFixed(e.psnrLinear, 2), "dB");
        statRow(out, "RMSE linear HDR", formatSignificant(e.rmseLinear, 3));
        statRow(out, "Max |error|", formatSignificant(e.maxAbs, 3), "linear");
        statRow(out, "p99 |error|", formatSignificant(e.p99Abs, 3), "linear");
        statRow(out, "FLIP mean", formatFixed(e.flipMean, 4));
        statRow(out, "FLIP median", formatFixed(e.flipMedian, 4));
        if (e.hdrFlipMean)
            statRow(out, "HDR-FLIP mean", formatFixed(*e.hdrFlipMean, 4),
                    (std::to_string(e.hdrFlipExposures) + " exposures").c_str());
        for (const auto& [name, c] : {std::pair{"metal", &e.metal}, std::pair{"dielectric", &e.dielectric},
                                      std::pair{"coated", &e.coated}, std::pair{"sheen", &e.sheen},
                                      std::pair{"anisotropic", &e.anisotropic}, std::pair{"plain", &e.plain}}) {
            if (!*c) continue;
            const std::string label = std::string("Rel. luminance error, ") + name;
            statRow(out, label.c_str(), formatSignificant((*c)->relLuminanceMean, 3),
                    ("mean; FLIP " + formatFixed((*c)->flipMean, 4)).c_str());
            if ((*c)->referenceNoise)
                statRow(out, (std::string("Ground-truth noise, ") + name).c_str(),
                        formatSignificant(*(*c)->referenceNoise, 3), "mean relative");
        }
        out += "</tbody></table>\n";
    }
    if (r.groundTruth) {
        const GroundTruthConvergence& g = *r.groundTruth;
        out += "<p class=\"small\">Ground truth: " + std::to_string(g.batches) + " batches, " +
               std::to_string(g.samplesPerPixel) + " samples per pixel, mean relative noise " +
               formatSignificant(g.meanRelativeNoise, 3) + " (target " + formatSignificant(g.noiseTarget, 3) +
               (g.targetMet ? ", met" : ", NOT met") + "), " + formatSignificant(g.gpuMs, 3) + " ms GPU</p>\n";
    }
    writeAttributeTable(out, r.attributes);
    out += "</div>\n";
    const RunImages& im = r.images;
    const ReferenceImage* reference = model.reference.find(r.iblMode);
    if (!reference && model.reference.images.size() == 1) reference = &model.reference.images[0];
    if (reference && !im.render.empty()) writeViewer(out, model, *reference, r, id);
    std::string gallery;
    if (reference && !im.render.empty())
        writeImage(gallery, reference->render, "Reference (" + model.reference.layout + ")");
    writeImage(gallery, im.render, "Render: " + r.layout);
    writeImage(gallery, im.errorHeatmap, "Error heat map");
    writeImage(gallery, im.flip, "FLIP");
    writeImage(gallery, im.normalError, "Normal error");
    writeImage(gallery, im.difference, "Difference (amplified)");
    if (!gallery.empty()) out += "<div class=\"gallery\">\n" + gallery + "</div>\n";
    if (!im.errorsExr.empty())
        out += "<p class=\"hint\">Per-pixel errors (float): <a href=\"" + urlPathEscape(im.errorsExr) + "\"><code>" +
               htmlEscape(im.errorsExr) + "</code></a></p>\n";
    if (!im.crops.empty()) {
        out += "<h3>Crops</h3>\n<div class=\"crops\">\n";
        for (const ReportCrop& c : im.crops) {
            out += "<div class=\"crop\"><div class=\"where\">x " + std::to_string(c.x) + ", y " + std::to_string(c.y) +
                   ", " + std::to_string(c.w) + "&times;" + std::to_string(c.h) + "</div>\n";
            writeImage(out, c.reference, "Reference");
            writeImage(out, c.layout, r.layout);
            writeImage(out, c.heat, "Error");
            out += "</div>\n";
        }
        out += "</div>\n";
    }
    out += "</section>\n";
}

void infoRow(std::string& out, const char* name, const std::string& valueHtml) {
    out += std::string("<dt>") + name + "</dt><dd>" + valueHtml + "</dd>";
}

// "G-buffer or visibility buffer?" (visibility_verdict.h), when the runs include both.
void writeVisibilityVerdict(std::string& out, const ReportModel& model) {
    const auto v = gbufferOrVisibility(model);
    if (!v) return;
    auto opt = [](const std::optional<double>& x, int decimals) { return x ? formatFixed(*x, decimals) : "&ndash;"; };
    auto row = [&](const std::string& name, const std::string& g, const std::string& s) {
        out += "<tr><th>" + name + "</th><td>" + g + "</td><td>" + s + "</td></tr>";
    };
    out += "<section id=\"gbuffer-or-visibility\">\n<h2>G-buffer or visibility buffer?</h2>\n<p>" +
           htmlEscape(v->answer) + "</p>\n<table class=\"verdict\"><thead><tr><th></th><th>" +
           htmlEscape(v->gbufferLayout) + " (best G-buffer)</th><th>" + htmlEscape(v->visibilityLayout) +
           "</th></tr></thead><tbody>";
    row("FLIP mean", formatFixed(v->gbufferFlip, 4), formatFixed(v->visibilityFlip, 4));
    row("PSNR dB (tone-mapped)", formatFixed(v->gbufferPsnr, 2), formatFixed(v->visibilityPsnr, 2));
    row("Normal angle, mean (&deg;)", opt(v->gbufferNormalDegrees, 3), opt(v->visibilityNormalDegrees, 3));
    row("Base colour &Delta;E2000, mean", opt(v->gbufferBaseColorDeltaE, 3), opt(v->visibilityBaseColorDeltaE, 3));
    row("Targets + depth, written and read (B/pixel, 1080p)", formatFixed(v->gbufferBytesPerPixel, 0),
        formatFixed(v->visibilityIdBytesPerPixel, 0));
    row("Resolve's vertex fetches (B/pixel, modelled, no cache reuse)", "0",
        formatFixed(v->visibilityVertexBytesPerPixel, 0));
    out += "</tbody></table>\n<p class=\"hint\">IBL mode " + htmlEscape(v->iblMode) +
           ". Traffic from the bandwidth model (src/measure/bandwidth.h): both pipelines fetch the same material "
           "texels, so they are in neither figure.</p>\n</section>\n";
}

// The verdict per byte budget (budget_verdict.h): what the run concluded, before any detail.
void writeBudgetVerdict(std::string& out, const ReportModel& model) {
    const auto v = budgetVerdict(model);
    if (!v) return;
    out += "<section id=\"verdict\">\n<h2>Verdict</h2>\n<ul class=\"verdict-lines\">\n";
    for (const BudgetLine& line : v->lines)
        out += "<li data-budget=\"" + (line.budget ? std::to_string(*line.budget) : std::string("unlimited")) + "\"" +
               (line.best ? "" : " class=\"none-fits\"") + ">" + htmlEscape(line.sentence) + "</li>\n";
    out += "</ul>\n<p class=\"hint\">" + htmlEscape(v->basis) + "</p>\n</section>\n";
}

}  // namespace

std::string reportHtml(const ReportModel& model) {
    const ReportRunInfo& run = model.run;
    std::string out;
    out.reserve(64 * 1024 + model.runs.size() * 8 * 1024);
    out += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
           "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
           "<title>gbufferlab report";
    if (!run.scene.empty()) out += " &mdash; " + htmlEscape(run.scene);
    out += "</title>\n<style>";
    out += report_template::kCss;
    out += "</style>\n</head>\n<body>\n<main>\n<header class=\"run\">\n<h1>G-buffer layout comparison</h1>\n";
    size_t failed = 0;
    for (const RunReport& r : model.runs) failed += r.status == RunStatus::Failed;
    out += "<dl class=\"info\">";
    infoRow(out, "Scene", htmlEscape(run.scene));
    infoRow(out, "Environment", htmlEscape(run.environment));
    infoRow(out, "Resolution", std::to_string(run.width) + "&times;" + std::to_string(run.height));
    infoRow(out, "Reference", htmlEscape(model.reference.layout));
    infoRow(out, "Device", htmlEscape(run.device.name) +
                               (run.device.type.empty() ? "" : " <span class=\"muted\">(" +
                                                                   htmlEscape(run.device.type) + ")</span>"));
    infoRow(out, "Driver", htmlEscape(run.device.driver));
    infoRow(out, "Date", htmlEscape(run.date));
    std::string modes;
    for (const std::string& m : run.iblModes) modes += (modes.empty() ? "" : ", ") + htmlEscape(m);
    infoRow(out, "IBL modes", modes);
    infoRow(out, "Runs", std::to_string(model.runs.size()) + (failed ? ", <span style=\"color:var(--bad)\">" +
                                                                           std::to_string(failed) + " failed</span>"
                                                                     : std::string()));
    out += "</dl>\n";
    // What this report lacks comes first: an interruption, views with nothing to measure.
    if (model.interruption) {
        const ReportInterruption& i = *model.interruption;
        std::string notRun;
        for (const PlannedRun& p : i.notRun)
            notRun += (notRun.empty() ? "" : ", ") + htmlEscape(p.layout) + " (" + htmlEscape(p.iblMode) + ")";
        out += "<div class=\"errorbox\" id=\"interrupted\"><strong>Incomplete:</strong> interrupted by " +
               htmlEscape(i.signal) + " after " + std::to_string(i.runsFinished) + " of " +
               std::to_string(i.runsPlanned) + " runs; this report lists only the runs that finished." +
               (notRun.empty() ? std::string() : " Not run: " + notRun + ".") + "</div>\n";
    }
    for (size_t v = 0; v < run.viewNotMeasured.size(); ++v)
        if (!run.viewNotMeasured[v].empty())
            out += "<div class=\"errorbox\"><strong>View " + std::to_string(v) +
                   " not measured:</strong> " + htmlEscape(run.viewNotMeasured[v]) +
                   "; it is left out of every mean, rank and verdict.</div>\n";
    if (!run.commandLine.empty()) out += "<pre class=\"cmd\"><code>" + htmlEscape(run.commandLine) + "</code></pre>\n";
    if (!run.notes.empty()) {
        out += "<ul class=\"notes\">";
        for (const std::string& n : run.notes) out += "<li>" + htmlEscape(n) + "</li>";
        out += "</ul>\n";
    }
    out += "</header>\n";

    Ids idMaker;
    std::vector<std::string> ids;
    for (const RunReport& r : model.runs) ids.push_back(idMaker.make(r.layout + "-" + r.iblMode));

    writeBudgetVerdict(out, model);

    if (model.iblFigure) {
        const IblFigure& f = *model.iblFigure;
        out += "<section id=\"ibl-figure\">\n<h2>IBL modes against ground truth</h2>\n<figure><img src=\"" +
               urlPathEscape(f.png) + "\" alt=\"IBL comparison figure\" style=\"max-width:100%;image-rendering:pixelated\">"
               "<figcaption>Rows: IBL modes (the seed's figure); columns: metal, then dielectric balls, roughness rising "
               "left to right. Under each row: mean relative luminance error against ground truth over each class's "
               "pixels, and for ground truth its own estimated noise.<ul>";
        for (const IblFigureRow& r : f.rows) out += "<li>" + htmlEscape(r.caption) + "</li>";
        out += "</ul></figcaption></figure>\n</section>\n";
    }

    out += "<section id=\"summary\">\n<h2>Layouts</h2>\n";
    if (model.run.views.size() > 1) {
        // Over the views measured: a view with nothing to measure is in no mean (run.viewNotMeasured).
        size_t measured = 0;
        for (size_t i = 0; i < model.run.views.size(); ++i)
            measured += i >= model.run.viewNotMeasured.size() || model.run.viewNotMeasured[i].empty();
        out += "<p class=\"views\">Every metric is the mean over " + std::to_string(measured) +
               (measured == model.run.views.size() ? std::string(" views")
                                                   : " of the " + std::to_string(model.run.views.size()) +
                                                         " views (the others had nothing to measure)") +
               "; under each, its range (min&ndash;max) and standard deviation &sigma; over them. Views: ";
        for (size_t i = 0; i < model.run.views.size(); ++i)
            out += (i ? "; " : "") + std::to_string(i) + ": " + htmlEscape(model.run.views[i]) +
                   (i < model.run.viewNotMeasured.size() && !model.run.viewNotMeasured[i].empty() ? " (not measured)"
                                                                                                   : "");
        out += ". Images and crops are the first view's.</p>\n";
    }
    writeLayoutsTable(out, model, ids);
    out += "<p class=\"hint\">Click a column header to sort (again to reverse). Errors are against the float "
           "reference; means are over covered pixels. Also in <a href=\"report.csv\">report.csv</a> and "
           "<a href=\"report.json\">report.json</a>.</p>\n</section>\n";

    writeLayerSection(out, model);  // report_html_layers.h: nothing without layers
    writeVisibilityVerdict(out, model);
    writeAtlasHtml(out, model);

    out += "<section id=\"plots\">\n<h2>Error against bytes per pixel</h2>\n<div class=\"toggle\" role=\"group\">"
           "<button type=\"button\" data-plot=\"flip\" aria-pressed=\"true\">FLIP mean, log axis</button>"
           "<button type=\"button\" data-plot=\"flip-linear\" aria-pressed=\"false\">FLIP mean, linear axis</button>"
           "<button type=\"button\" data-plot=\"psnr\" aria-pressed=\"false\">PSNR</button>";
    // compare --temporal N: the plots above rank the resolves; these the first frame alone.
    const bool temporal = model.run.temporalFrames > 1;
    if (temporal)
        out += "<button type=\"button\" data-plot=\"flip-1f\" aria-pressed=\"false\">FLIP mean, single frame</button>"
               "<button type=\"button\" data-plot=\"psnr-1f\" aria-pressed=\"false\">PSNR, single frame</button>";
    // Against the bytes each GPU class pays (report_bandwidth.h), when the runs have them.
    const bool effective = !effectiveRuns(model).empty();
    if (effective)
        out += "<button type=\"button\" data-plot=\"flip-dcc\" aria-pressed=\"false\">FLIP, desktop DCC bytes</button>"
               "<button type=\"button\" data-plot=\"flip-afbc\" aria-pressed=\"false\">FLIP, Mali AFBC bytes</button>";
    out += "</div>\n";
    if (temporal)
        out += "<p class=\"hint\">--temporal " + std::to_string(model.run.temporalFrames) +
               ": FLIP and PSNR are the resolved images' (" + htmlEscape(model.run.temporalResolve) +
               " of the jittered frames, as temporal anti-aliasing converges with a still camera); \"single frame\": "
               "frame 0 alone. Not modelled: motion and reprojection, history rejection, upscalers.</p>\n";
    const auto flip4 = [](double v) { return formatFixed(v, 4); };
    writePlot(out, model, ids, {"flip", "FLIP mean", false, true, true, &ImageErrors::flipMean, flip4}, false);
    writePlot(out, model, ids, {"flip-linear", "FLIP mean", false, true, false, &ImageErrors::flipMean, flip4}, true);
    writePlot(out, model, ids, {"psnr", "PSNR dB (tone-mapped)", true, false, false, &ImageErrors::psnrToneMapped,
                                [](double v) { return formatFixed(v, 2); }},
              true);
    if (temporal) {
        PlotSpec flip1{"flip-1f", "FLIP mean, single frame", false, true, true, &ImageErrors::flipMean, flip4};
        flip1.singleFrame = true;
        writePlot(out, model, ids, flip1, true);
        PlotSpec psnr1{"psnr-1f", "PSNR dB (tone-mapped), single frame", true, false, false,
                       &ImageErrors::psnrToneMapped, [](double v) { return formatFixed(v, 2); }};
        psnr1.singleFrame = true;
        writePlot(out, model, ids, psnr1, true);
    }
    if (effective) {
        PlotSpec dcc{"flip-dcc", "FLIP mean", false, true, true, &ImageErrors::flipMean, flip4};
        dcc.xClass = "desktop-dcc";
        writePlot(out, model, ids, dcc, true);
        PlotSpec afbc{"flip-afbc", "FLIP mean", false, true, true, &ImageErrors::flipMean, flip4};
        afbc.xClass = "mali-afbc";
        writePlot(out, model, ids, afbc, true);
        out += "<p class=\"hint\">FLIP against effective bytes: each layout's bytes per pixel as the class stores "
               "them, from the compression model on view 0's words (section <a href=\"#bandwidth-as-paid\">Bandwidth "
               "as GPUs pay it</a>).</p>\n";
    }
    out += "</section>\n";
    out += bandwidthSectionHtml(model);  // report_bandwidth.h

    for (size_t i = 0; i < model.runs.size(); ++i) writeRunSection(out, model, model.runs[i], ids[i]);
    out += "<footer>Written by gbufferlab. Images are files beside this page; numbers are also in report.csv and "
           "report.json (schema: docs/report-schema.md).</footer>\n</main>\n<script>";
    out += report_template::kScript;
    out += "</script>\n</body>\n</html>\n";
    return out;
}

void writeReportHtml(const std::filesystem::path& path, const ReportModel& model) {
    writeFileAtomic(path, reportHtml(model));
}

void writeReport(const std::filesystem::path& dir, const ReportModel& model) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throwUserError(dir.string() + ": cannot create the report directory: " + ec.message());
    writeReportJson(dir / "report.json", model);
    writeReportCsv(dir / "report.csv", model);
    writeReportHtml(dir / "report.html", model);
}

}  // namespace gbl
