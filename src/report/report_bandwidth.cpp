#include "report_bandwidth.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

#include "budget_verdict.h"
#include "json_number.h"
#include "report_html.h"

namespace gbl {
namespace {

using Json = nlohmann::ordered_json;

std::string bandwidthNumberText(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
    return std::string(buffer, result.ptr);
}

std::string fixedDigits(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.*f", digits, v);
    return buf;
}

const char* classTitle(const std::string& c) {
    if (c == "desktop-dcc") return "desktop (DCC-like)";
    if (c == "mali-afbc") return "Mali (AFBC)";
    if (c == "tile-subpass") return "tile, subpasses (Apple A11)";
    return "nominal";
}

// The bytes a run is held against a budget under a class: the nominal table's (with a visibility
// buffer's half fetches: budget_verdict.h), or the class's effective bytes (the same fetch share).
std::optional<double> classBytes(const RunReport& r, const std::string& gpuClass) {
    if (gpuClass == "nominal") return verdictCountedBytes(r);
    if (!r.effective) return std::nullopt;
    const ClassTraffic* c = r.effective->find(gpuClass);
    if (!c) return std::nullopt;
    return c->bytesPerPixel + (verdictCountedBytes(r) - double(r.bytesPerPixel.total));
}

}  // namespace

Json effectiveBandwidthJson(const EffectiveBandwidth& e) {
    Json targets = Json::array();
    for (const TargetEffective& t : e.targets)
        targets.push_back(Json{{"name", t.name},
                               {"format", t.format},
                               {"bytes_per_pixel", t.bytesPerPixel},
                               {"desktop_dcc_bytes_per_pixel", jsonNumber(t.dccBytesPerPixel)},
                               {"dcc_uncompressed_blocks", jsonNumber(t.dccUncompressedFraction)},
                               {"afbc", t.afbc},
                               {"mali_afbc_read_bytes_per_pixel", jsonNumber(t.afbcBytesPerPixel)},
                               {"mali_afbc_write_bytes_per_pixel", jsonNumber(t.afbcWriteBytesPerPixel)},
                               {"afbc_solid_superblocks", jsonNumber(t.afbcSolidFraction)},
                               {"afbc_uncompressed_subblocks", jsonNumber(t.afbcUncompressedFraction)}});
    Json classes = Json::array();
    for (const ClassTraffic& c : e.classes)
        classes.push_back(Json{{"class", c.gpuClass},
                               {"bytes_per_pixel", jsonNumber(c.bytesPerPixel)},
                               {"traffic_bytes_1080p", jsonNumber(c.trafficBytes)},
                               {"gb_per_s_1080p60", jsonNumber(c.gbPerSecond)},
                               {"assumes", c.assumes}});
    Json tile = Json::array();
    for (const TileFit& f : e.tile)
        tile.push_back(Json{{"family", f.family},
                            {"colour_bytes_per_pixel", f.colourBytesPerPixel},
                            {"colour_targets", f.colourTargets},
                            {"limit_bytes_per_pixel", f.limitBytesPerPixel},
                            {"fits", f.fits},
                            {"overflow", f.overflow}});
    return Json{{"frames", e.frames},
                {"width", e.width},
                {"height", e.height},
                {"lighting", e.lighting.text()},
                {"lighting_reads_per_pixel", jsonNumber(e.lighting.readsPerPixel)},
                {"nominal_bytes_per_pixel", jsonNumber(e.nominalBytesPerPixel)},
                {"nominal_traffic_bytes_1080p", jsonNumber(e.nominalTrafficBytes)},
                {"nominal_gb_per_s_1080p60", jsonNumber(e.nominalGbPerSecond)},
                {"targets", std::move(targets)},
                {"classes", std::move(classes)},
                {"tile_memory", std::move(tile)}};
}

std::vector<const RunReport*> effectiveRuns(const ReportModel& model) {
    std::vector<const RunReport*> runs;
    const std::string mode = model.run.iblModes.empty() ? std::string() : model.run.iblModes.front();
    for (const RunReport& r : model.runs)
        if (r.effective && (mode.empty() || r.iblMode == mode) && !r.isLightingComparison()) runs.push_back(&r);
    return runs;
}

std::vector<EffectiveVerdict> effectiveVerdicts(const ReportModel& model) {
    std::vector<EffectiveVerdict> out;
    std::vector<const RunReport*> runs;
    for (const RunReport* r : effectiveRuns(model))
        if (r->status == RunStatus::Ok && r->image && r->layout != model.reference.layout) runs.push_back(r);
    if (runs.empty()) return out;
    for (const char* gpuClass : {"nominal", "desktop-dcc", "mali-afbc", "tile-subpass"}) {
        EffectiveVerdict v;
        v.gpuClass = gpuClass;
        std::vector<std::optional<int>> budgets;
        for (int b : kVerdictBudgets) budgets.push_back(b);
        budgets.push_back(std::nullopt);
        for (const std::optional<int>& budget : budgets) {
            EffectiveBudgetLine line;
            line.budget = budget;
            const RunReport* best = nullptr;
            double bestBytes = 0;
            for (const RunReport* r : runs) {
                const std::optional<double> bytes = classBytes(*r, gpuClass);
                if (!bytes || (budget && *bytes > double(*budget) + 1e-9)) continue;
                if (!best || r->image->flipMean < best->image->flipMean) {
                    best = r;
                    bestBytes = *bytes;
                }
            }
            if (best) {
                line.best = best->layout;
                line.bytes = bestBytes;
                line.flipMean = best->image->flipMean;
            }
            v.lines.push_back(line);
        }
        out.push_back(std::move(v));
    }
    return out;
}

std::vector<std::string> verdictChanges(const std::vector<EffectiveVerdict>& verdicts) {
    std::vector<std::string> out;
    if (verdicts.empty()) return out;
    const EffectiveVerdict& nominal = verdicts.front();
    for (size_t c = 1; c < verdicts.size(); ++c)
        for (size_t i = 0; i < verdicts[c].lines.size() && i < nominal.lines.size(); ++i) {
            const EffectiveBudgetLine& a = nominal.lines[i];
            const EffectiveBudgetLine& b = verdicts[c].lines[i];
            if (a.best == b.best) continue;
            const std::string budget = b.budget ? std::to_string(*b.budget) + " B/px" : std::string("unlimited");
            out.push_back(std::string(classTitle(verdicts[c].gpuClass)) + ", " + budget + ": " +
                          (b.best.empty() ? std::string("nothing fits") : b.best + " (" + fixedDigits(b.bytes, 1) + " B/px effective)") +
                          " instead of " + (a.best.empty() ? std::string("nothing") : a.best + " (" + fixedDigits(a.bytes, 0) + " B/px nominal)"));
        }
    return out;
}

Json bandwidthAsPaidJson(const ReportModel& model) {
    Json classes = Json::array();
    classes.push_back(Json{{"class", "desktop-dcc"},
                           {"model", "AMD DCC's container (256-byte blocks in 32-byte sectors; radv) with the model "
                                     "coder (YCoCg-R, median prediction, Golomb-Rice with zero flags)"}});
    classes.push_back(Json{{"class", "mali-afbc"},
                           {"model", "AFBC's container (16x16 superblocks, 16-byte headers, 4x4 subblocks, solid and "
                                     "uncompressed cases; Mesa panfrost) with the model coder (YCoCg-R, median "
                                     "prediction, Golomb-Rice); 53.4 bytes read per superblock header (Mali-G57)"}});
    classes.push_back(Json{{"class", "tile-subpass"},
                           {"model", "Apple A11: 64 bytes of colour per pixel in tile memory; fits: only the lit "
                                     "output leaves the chip"}});
    Json families = Json::array();
    for (const TileFamily& f : tileFamilies())
        families.push_back(Json{{"family", f.id},
                                {"name", f.name},
                                {"limit_bytes_per_pixel", f.colourBytesPerPixel},
                                {"max_colour_targets", f.maxColourTargets},
                                {"hard_limit", f.hardLimit},
                                {"source", f.source}});
    Json verdicts = Json::array();
    const std::vector<EffectiveVerdict> v = effectiveVerdicts(model);
    for (const EffectiveVerdict& e : v) {
        Json lines = Json::array();
        for (const EffectiveBudgetLine& l : e.lines) {
            Json line{{"budget_bytes_per_pixel", l.budget ? Json(*l.budget) : Json("inf")}};
            if (!l.best.empty()) {
                line["best"] = l.best;
                line["bytes_per_pixel"] = jsonNumber(l.bytes);
                line["flip_mean"] = jsonNumber(l.flipMean);
            }
            lines.push_back(std::move(line));
        }
        verdicts.push_back(Json{{"class", e.gpuClass}, {"budgets", std::move(lines)}});
    }
    return Json{{"lighting", model.run.lighting},
                {"frames", "the words of view 0 under the first IBL mode (the G-buffer does not depend on the mode)"},
                {"uncertainty",
                 "container arithmetic exact; the payload coder is a model: docs/bandwidth.md gives its calibration "
                 "against published GPU measurements, row by row"},
                {"classes", std::move(classes)},
                {"tile_families", std::move(families)},
                {"verdicts", std::move(verdicts)},
                {"changes", verdictChanges(v)}};
}

std::vector<std::string> effectiveCsvHeader() {
    return {"effective_lighting",
            "nominal_gb_per_s_1080p60_with_lit",
            "desktop_dcc_bytes_per_pixel",
            "desktop_dcc_gb_per_s_1080p60",
            "mali_afbc_bytes_per_pixel",
            "mali_afbc_gb_per_s_1080p60",
            "tile_subpass_bytes_per_pixel",
            "tile_subpass_gb_per_s_1080p60",
            "tile_fits"};
}

std::vector<std::string> effectiveCsvFields(const RunReport& run) {
    std::vector<std::string> f(effectiveCsvHeader().size());
    if (!run.effective) return f;
    const EffectiveBandwidth& e = *run.effective;
    f[0] = e.lighting.text();
    f[1] = bandwidthNumberText(e.nominalGbPerSecond);
    size_t i = 2;
    for (const char* c : kGpuClasses) {
        if (const ClassTraffic* t = e.find(c)) {
            f[i] = bandwidthNumberText(t->bytesPerPixel);
            f[i + 1] = bandwidthNumberText(t->gbPerSecond);
        }
        i += 2;
    }
    std::string fits;
    for (const TileFit& t : e.tile)
        if (t.fits) fits += (fits.empty() ? "" : " ") + t.family;
    f[i] = fits;
    return f;
}

std::string atlasEffectiveBytesHtml(const ReportModel& model, const std::string& layout) {
    for (const RunReport* r : effectiveRuns(model)) {
        if (r->layout != layout) continue;
        const ClassTraffic* d = r->effective->find("desktop-dcc");
        const ClassTraffic* m = r->effective->find("mali-afbc");
        if (!d || !m) return "";
        return "<br><small title=\"effective bytes per pixel: desktop DCC-like / Mali AFBC (see Bandwidth as GPUs pay "
               "it)\">" + fixedDigits(d->bytesPerPixel, 1) + " / " + fixedDigits(m->bytesPerPixel, 1) + "</small>";
    }
    return "";
}

std::string bandwidthSectionHtml(const ReportModel& model) {
    const std::vector<const RunReport*> runs = effectiveRuns(model);
    if (runs.empty()) return "";
    std::string h = "<h2 id=\"bandwidth-as-paid\">Bandwidth as GPUs pay it</h2>\n";
    h += "<p>Bytes per pixel and render-target traffic of one 1920x1080 frame at 60 frames per second, lit output "
         "included, per GPU class; lighting: " + htmlEscape(model.run.lighting) +
         ". Effective bytes come from the words view 0 wrote: the compression containers' arithmetic is exact, "
         "their payload coder a calibrated model (docs/bandwidth.md); depth is counted uncompressed.</p>\n";
    h += "<table class=\"bandwidth\"><thead><tr><th>layout</th><th>nominal B/px</th><th>GB/s</th>";
    for (const char* c : kGpuClasses) h += std::string("<th>") + classTitle(c) + " B/px</th><th>GB/s</th>";
    h += "<th>fits tile memory of</th></tr></thead><tbody>\n";
    for (const RunReport* r : runs) {
        const EffectiveBandwidth& e = *r->effective;
        h += "<tr><td>" + htmlEscape(r->layout) + "</td><td>" + fixedDigits(e.nominalBytesPerPixel, 0) + "</td><td>" +
             fixedDigits(e.nominalGbPerSecond, 2) + "</td>";
        for (const char* c : kGpuClasses) {
            const ClassTraffic* t = e.find(c);
            h += t ? "<td>" + fixedDigits(t->bytesPerPixel, 1) + "</td><td>" + fixedDigits(t->gbPerSecond, 2) + "</td>"
                   : std::string("<td></td><td></td>");
        }
        std::string fits;
        for (const TileFit& f : e.tile)
            if (f.fits) fits += (fits.empty() ? "" : ", ") + f.family;
        h += "<td>" + htmlEscape(fits.empty() ? std::string("none") : fits) + "</td></tr>\n";
    }
    h += "</tbody></table>\n";
    // Per target: how each format compresses on this content.
    h += "<details><summary>Per target: nominal and effective bytes per pixel</summary>\n<table class=\"bandwidth\">"
         "<thead><tr><th>layout</th><th>target</th><th>format</th><th>B/px</th><th>DCC B/px</th>"
         "<th>DCC blocks uncompressed</th><th>AFBC read B/px</th><th>AFBC solid superblocks</th>"
         "<th>AFBC subblocks uncompressed</th></tr></thead><tbody>\n";
    for (const RunReport* r : runs)
        for (const TargetEffective& t : r->effective->targets)
            h += "<tr><td>" + htmlEscape(r->layout) + "</td><td>" + htmlEscape(t.name) + "</td><td>" + htmlEscape(t.format) +
                 "</td><td>" + std::to_string(t.bytesPerPixel) + "</td><td>" + fixedDigits(t.dccBytesPerPixel, 2) + "</td><td>" +
                 fixedDigits(100.0 * t.dccUncompressedFraction, 0) + " %</td><td>" + fixedDigits(t.afbcBytesPerPixel, 2) +
                 (t.afbc ? "" : " (not AFBC)") + "</td><td>" + fixedDigits(100.0 * t.afbcSolidFraction, 0) + " %</td><td>" +
                 fixedDigits(100.0 * t.afbcUncompressedFraction, 0) + " %</td></tr>\n";
    h += "</tbody></table></details>\n";
    // Tile memory per family.
    h += "<details><summary>Tile memory: colour bytes per pixel with the lit output (RGBA16F) against each family's "
         "limit</summary>\n<ul>\n";
    for (const TileFamily& f : tileFamilies())
        h += std::string("<li>") + htmlEscape(f.name) + ": " + std::to_string(f.colourBytesPerPixel) + " B/px" +
             (f.maxColourTargets ? ", " + std::to_string(f.maxColourTargets) + " targets" : std::string()) +
             (f.hardLimit ? "" : " (a recommendation: more works, more slowly)") + ". " + htmlEscape(f.source) + "</li>\n";
    h += "</ul></details>\n";
    // Verdicts by class.
    const std::vector<EffectiveVerdict> verdicts = effectiveVerdicts(model);
    if (!verdicts.empty()) {
        h += "<h3>Best layout by FLIP within each budget, bytes as each class pays them</h3>\n<table class=\"bandwidth\">"
             "<thead><tr><th>budget</th>";
        for (const EffectiveVerdict& v : verdicts) h += std::string("<th>") + classTitle(v.gpuClass) + "</th>";
        h += "</tr></thead><tbody>\n";
        for (size_t i = 0; i < verdicts.front().lines.size(); ++i) {
            const auto& budget = verdicts.front().lines[i].budget;
            h += "<tr><td>" + (budget ? std::to_string(*budget) + " B/px" : std::string("unlimited")) + "</td>";
            for (const EffectiveVerdict& v : verdicts) {
                const EffectiveBudgetLine& l = v.lines[i];
                h += "<td>" + (l.best.empty() ? std::string("none fits")
                                              : htmlEscape(l.best) + " (" + fixedDigits(l.bytes, 1) + ")") + "</td>";
            }
            h += "</tr>\n";
        }
        h += "</tbody></table>\n";
        const std::vector<std::string> changes = verdictChanges(verdicts);
        if (!changes.empty()) {
            h += "<ul>\n";
            for (const std::string& c : changes) h += "<li>" + htmlEscape(c) + "</li>\n";
            h += "</ul>\n";
        }
    }
    return h;
}

}  // namespace gbl
