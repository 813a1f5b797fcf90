#include "report_atlas.h"

#include <cmath>
#include <cstdio>

#include "report_bandwidth.h"
#include "report_html.h"

namespace gbl {

namespace {

const RunReport* atlasRun(const ReportModel& model, const std::string& layout) {
    const std::string firstMode = model.run.iblModes.empty() ? std::string() : model.run.iblModes.front();
    const RunReport* any = nullptr;
    for (const RunReport& r : model.runs) {
        if (r.layout != layout) continue;
        if (r.iblMode == firstMode) return &r;
        if (!any) any = &r;
    }
    return any;
}

std::string fixed(double v, int decimals) {
    if (std::isinf(v)) return v > 0 ? "&infin;" : "-&infin;";
    if (std::isnan(v)) return "&ndash;";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

}  // namespace

std::vector<AtlasRowGroup> atlasRows(const ReportModel& model) {
    std::vector<AtlasRowGroup> out;
    for (AtlasGroup& g : groupAtlas(model.atlas)) {
        AtlasRowGroup group{g.family, {}};
        for (AtlasEntry& e : g.entries) {
            AtlasRow row;
            if (const RunReport* r = atlasRun(model, e.layout)) {
                row.iblMode = r->iblMode;
                if (r->status == RunStatus::Ok && r->image) {
                    row.flipMean = r->image->flipMean;
                    row.psnrToneMapped = r->image->psnrToneMapped;
                    if (r->singleFrame && r->singleFrame->image) row.flipMeanSingleFrame = r->singleFrame->image->flipMean;
                }
            }
            row.entry = std::move(e);
            group.rows.push_back(std::move(row));
        }
        out.push_back(std::move(group));
    }
    // Ranks by either FLIP (the resolve's, frame 0's): the atlas read in either order.
    for (auto [value, rank] : {std::pair{&AtlasRow::flipMean, &AtlasRow::rank},
                               std::pair{&AtlasRow::flipMeanSingleFrame, &AtlasRow::rankSingleFrame}})
        for (AtlasRowGroup& g : out)
            for (AtlasRow& row : g.rows) {
                if (!(row.*value)) continue;
                int better = 0;
                for (const AtlasRowGroup& h : out)
                    for (const AtlasRow& other : h.rows)
                        if ((other.*value) && *(other.*value) < *(row.*value)) ++better;
                row.*rank = 1 + better;
            }
    return out;
}

void writeAtlasHtml(std::string& out, const ReportModel& model) {
    if (model.atlas.empty()) return;
    const std::vector<AtlasRowGroup> groups = atlasRows(model);
    const bool temporal = model.run.temporalFrames > 1;
    std::string mode;
    for (const AtlasRowGroup& g : groups)
        for (const AtlasRow& r : g.rows)
            if (mode.empty()) mode = r.iblMode;
    out += "<section id=\"atlas\">\n<h2>Atlas of G-buffers</h2>\n"
           "<p class=\"hint\">Every layout compared, grouped by engine family, oldest first. Bytes per pixel: the "
           "G-buffer's targets and depth-stencil (light buffers after +); a layout whose targets hold ids, not "
           "attributes, says so. Bits: what each stored attribute occupies, with its encoding; attributes not "
           "stored say how they are obtained. Provenance: the layout's entries (depth, targets, fields, fallbacks, "
           "clear values, ...) by where the file says each comes from: verified in the engine's source, from a talk, "
           "assumed, or gbufferlab's own; \"differs\" counts the entries that state a known difference from the "
           "engine. Errors: the run under " +
           htmlEscape(mode.empty() ? std::string("-") : mode) + " against the float reference.</p>\n";
    out += "<table class=\"atlas\">\n<thead><tr><th>Layout</th><th>Engine</th><th>Year</th><th>Bytes/px</th>"
           "<th>Attributes: bits, encoding</th><th>Provenance</th><th>FLIP mean" +
           std::string(temporal ? " (rank), resolved" : "") + "</th><th>PSNR dB</th>" +
           (temporal ? "<th>FLIP mean (rank), single frame</th>" : "") + "</tr></thead>\n<tbody>\n";
    for (const AtlasRowGroup& g : groups) {
        out += "<tr class=\"family\"><th colspan=\"" + std::string(temporal ? "9" : "8") + "\">" +
               htmlEscape(g.family) + "</th></tr>\n";
        for (const AtlasRow& r : g.rows) {
            const AtlasEntry& e = r.entry;
            std::string bytes = std::to_string(e.bytesPerPixel);
            if (e.bytesKind != "attributes") bytes += " " + htmlEscape(e.bytesKind);
            if (e.lightBufferBytesPerPixel > 0) bytes += " +" + std::to_string(e.lightBufferBytesPerPixel);
            bytes += atlasEffectiveBytesHtml(model, e.layout);  // report_bandwidth.h
            std::string attrs;
            for (const AtlasAttribute& a : e.attributes) {
                attrs += "<span class=\"attr" + std::string(a.bits ? "" : " derived") + "\">" + htmlEscape(a.name) +
                         " <b>" + (a.bits ? std::to_string(a.bits) : std::string("&ndash;")) + "</b> " +
                         htmlEscape(a.encoding) + "</span> ";
            }
            out += "<tr><td title=\"" + htmlEscape(e.title) + "\">" + htmlEscape(e.layout) + "</td><td>" +
                   htmlEscape(e.engine) + "</td><td class=\"num\">" + std::to_string(e.year) +
                   "</td><td class=\"num\">" + bytes + "</td><td class=\"attrs\">" + attrs +
                   "</td><td class=\"provenance\">" +
                   (e.provenance.entries > 0 ? htmlEscape(e.provenance.text()) : std::string("&ndash;")) +
                   "</td><td class=\"num\">" + (r.flipMean ? fixed(*r.flipMean, 4) : "&ndash;") +
                   (temporal && r.rank ? " (" + std::to_string(r.rank) + ")" : std::string()) +
                   "</td><td class=\"num\">" + (r.psnrToneMapped ? fixed(*r.psnrToneMapped, 2) : "&ndash;") +
                   (temporal ? "</td><td class=\"num\">" +
                                   (r.flipMeanSingleFrame ? fixed(*r.flipMeanSingleFrame, 4) + " (" +
                                                                std::to_string(r.rankSingleFrame) + ")"
                                                          : std::string("&ndash;"))
                             : std::string()) +
                   "</td></tr>\n";
        }
    }
    out += "</tbody>\n</table>\n</section>\n";
}

}  // namespace gbl
