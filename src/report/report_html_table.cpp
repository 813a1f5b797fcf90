#include "report_html_table.h"

#include <charconv>
#include <cmath>
#include <functional>
#include <optional>

#include "report_html.h"
#include "view_stats.h"

namespace gbl {
namespace {

// Full precision for data-v (sorting) attributes; JavaScript's Number() reads "Infinity".
std::string dataNumber(double v) {
    if (std::isnan(v)) return "NaN";
    if (std::isinf(v)) return v > 0 ? "Infinity" : "-Infinity";
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
    return std::string(buffer, result.ptr);
}

std::optional<double> attributeMean(const RunReport& r, ErrorAttribute a) {
    const auto& all = r.attributes[a].all;
    return all ? std::optional<double>(all->error.mean) : std::nullopt;
}

struct TableColumn {
    const char* key;       // data-key, for sorting and #sort=
    const char* header;    // HTML (already escaped)
    const char* tooltip;
    const char* firstDir;  // the first click's direction: the better end first
    const char* group;     // the header above it (HTML)
    bool secondary;        // folded until "all columns" is ticked
    bool perView;          // measured per view: the spread over views goes under it
    std::function<std::optional<double>(const RunReport&)> value;
    std::function<std::string(double)> format;
};

std::vector<TableColumn> numericColumns(bool temporal) {
    const auto sig3 = [](double v) { return formatSignificant(v, 3); };
    const auto imageValue = [](double ImageErrors::*field) {
        return [field](const RunReport& r) { return r.image ? std::optional<double>(*r.image.*field) : std::nullopt; };
    };
    const char* cost = "Cost";
    const char* attribute = temporal ? "Attribute error of the temporal mean, mean" : "Attribute error, mean";
    const char* image = temporal ? "Image error, resolved" : "Image error";
    std::vector<TableColumn> columns = {
        {"bpp", "Bytes/px", "G-buffer bytes per pixel: targets + depth-stencil + light buffers", "ascending", cost,
         false, false, [](const RunReport& r) { return std::optional<double>(r.bytesPerPixel.total); },
         [](double v) { return formatFixed(v, 0); }},
        {"gbps", "GB/s 1080p60",
         "Render-target traffic at 1920x1080, 1 sample, 60 frames/s (model: src/measure/bandwidth.h; a visibility "
         "buffer's adds its resolve's vertex fetches, modelled with no cache reuse)",
         "ascending", cost, false, false, [](const RunReport& r) { return r.gigabytesPerSecond1080p60(); },
         [](double v) { return formatFixed(v, 2); }},
        {"normal_mean", "Normal&nbsp;&deg;", "Mean angle between stored and reference normals, degrees", "ascending",
         attribute, false, true, [](const RunReport& r) { return attributeMean(r, ErrorAttribute::Normal); }, sig3},
        {"normal_p99", "Normal p99&nbsp;&deg;", "99th percentile of the normal angle error, degrees", "ascending",
         attribute, true, true,
         [](const RunReport& r) {
             const auto& all = r.attributes[ErrorAttribute::Normal].all;
             return all ? std::optional<double>(all->error.p99) : std::nullopt;
         },
         sig3},
        {"albedo_de", "Albedo &Delta;E", "Base colour, mean CIEDE2000", "ascending", attribute, false, true,
         [](const RunReport& r) { return attributeMean(r, ErrorAttribute::BaseColor); }, sig3},
        {"specular_de", "Specular &Delta;E", "Specular colour (F0), mean CIEDE2000", "ascending", attribute, false, true,
         [](const RunReport& r) { return attributeMean(r, ErrorAttribute::SpecularColor); }, sig3},
        {"roughness", "Roughness", "Roughness, mean absolute error", "ascending", attribute, false, true,
         [](const RunReport& r) { return attributeMean(r, ErrorAttribute::Roughness); }, sig3},
        {"psnr", "PSNR dB", "PSNR of the tone-mapped sRGB image, peak 1 (&#8734; = identical to the reference)",
         "descending", image, false, true, imageValue(&ImageErrors::psnrToneMapped),
         [](double v) { return formatFixed(v, 2); }},
        {"flip", "FLIP mean", "Mean LDR-FLIP error, 0 (identical) to 1", "ascending", image, false, true,
         imageValue(&ImageErrors::flipMean), [](double v) { return formatFixed(v, 4); }},
    };
    if (!temporal) return columns;
    // compare --temporal N: the columns above are the resolve's; frame 0 alone beside them.
    const char* single = "Single frame (frame 0)";
    const auto singleImage = [](double ImageErrors::*field) {
        return [field](const RunReport& r) {
            return r.singleFrame && r.singleFrame->image ? std::optional<double>(*r.singleFrame->image.*field)
                                                         : std::nullopt;
        };
    };
    columns.push_back({"normal_mean_1f", "Normal&nbsp;&deg;", "Frame 0 alone: mean normal angle error, degrees",
                       "ascending", single, false, false,
                       [](const RunReport& r) -> std::optional<double> {
                           if (!r.singleFrame) return std::nullopt;
                           const auto& all = r.singleFrame->attributes[ErrorAttribute::Normal].all;
                           return all ? std::optional<double>(all->error.mean) : std::nullopt;
                       },
                       sig3});
    columns.push_back({"psnr_1f", "PSNR dB", "Frame 0 alone: PSNR of the tone-mapped image", "descending", single, false,
                       false, singleImage(&ImageErrors::psnrToneMapped), [](double v) { return formatFixed(v, 2); }});
    columns.push_back({"flip_1f", "FLIP mean", "Frame 0 alone: mean LDR-FLIP error", "ascending", single, false, false,
                       singleImage(&ImageErrors::flipMean), [](double v) { return formatFixed(v, 4); }});
    return columns;
}

// The group row: each run of columns under one group header, once with every column counted
// (shown with "all columns") and once without the secondary ones, since a header spanning a
// hidden cell would reach into the next group.
void writeGroupRow(std::string& out, const std::vector<TableColumn>& columns, bool rankColumn) {
    out += "<tr class=\"groups\"><th colspan=\"2\"></th>";
    for (size_t i = 0; i < columns.size();) {
        size_t end = i, all = 0, folded = 0;
        for (; end < columns.size() && std::string(columns[end].group) == columns[i].group; ++end) {
            ++all;
            folded += !columns[end].secondary;
        }
        const std::string group = columns[i].group;
        if (all == folded) {
            out += "<th colspan=\"" + std::to_string(all) + "\">" + group + "</th>";
        } else {
            out += "<th class=\"g-all\" colspan=\"" + std::to_string(all) + "\">" + group + "</th>";
            if (folded) out += "<th class=\"g-folded\" colspan=\"" + std::to_string(folded) + "\">" + group + "</th>";
        }
        i = end;
    }
    out += rankColumn ? "<th></th><th></th></tr>\n" : "<th></th></tr>\n";
}

}  // namespace

void writeLayoutsTable(std::string& out, const ReportModel& model, const std::vector<std::string>& ids) {
    const std::vector<TableColumn> columns = numericColumns(model.run.temporalFrames > 1);
    const bool spreads = model.run.views.size() > 1;
    out += std::string("<div class=\"fold\"><input type=\"checkbox\" id=\"all-columns\"><label for=\"all-columns\">"
                       "All columns (the normal angle's p99") +
           (spreads ? ", each value's spread over the views" : "") + ")</label>\n";
    out += "<table id=\"layouts\" class=\"data sortable\">\n<thead>";
    const bool ranks = model.significance && !model.significance->ranks.empty();
    writeGroupRow(out, columns, ranks);
    out += "<tr><th data-key=\"layout\" data-dir=\"ascending\" title=\"Layout name\">Layout</th>"
           "<th data-key=\"ibl\" data-dir=\"ascending\" title=\"Image-based lighting mode\">IBL</th>";
    for (const TableColumn& c : columns)
        out += std::string("<th class=\"num") + (c.secondary ? " secondary" : "") + "\" data-key=\"" + c.key +
               "\" data-dir=\"" + c.firstDir + "\" title=\"" + c.tooltip + "\">" + c.header + "</th>";
    if (ranks)
        out += "<th class=\"num\" data-key=\"rank\" data-dir=\"ascending\" title=\"Rank by mean FLIP; a range "
               "(4-6) where the differences to the neighbours are not significant: " +
               htmlEscape(model.significance->method) + "\">Rank</th>";
    out += "<th data-key=\"status\" data-dir=\"ascending\">Status</th></tr></thead>\n<tbody>\n";
    for (size_t i = 0; i < model.runs.size(); ++i) {
        const RunReport& r = model.runs[i];
        const bool failed = r.status == RunStatus::Failed;
        out += failed ? "<tr class=\"failed\">" : "<tr>";
        out += "<td><a href=\"#" + ids[i] + "\" title=\"" + htmlEscape(r.title) + "\">" + htmlEscape(r.layout) +
               "</a></td><td>" + htmlEscape(r.iblMode) + "</td>";
        for (const TableColumn& c : columns) {
            const std::string cell = c.secondary ? "<td class=\"num secondary\"" : "<td class=\"num\"";
            const std::optional<double> v = c.value(r);
            if (!v) {
                out += cell + "></td>";
                continue;
            }
            out += cell + " data-v=\"" + dataNumber(*v) + "\">" + c.format(*v);
            if (c.perView && r.views.size() > 1) {
                // compare --views: the mean over the views, and under it their range and deviation.
                const ViewSpread sp = viewSpread(r, c.value);
                out += "<small class=\"spread\" title=\"over " + std::to_string(sp.n) +
                       " views: min .. max, standard deviation\"><br><span>" + c.format(sp.min) + "&ndash;" +
                       c.format(sp.max) + "</span> <span>&sigma;" + formatSignificant(sp.stddev, 2) + "</span></small>";
            }
            out += "</td>";
        }
        if (ranks) {
            const RankRange* rank = model.significance->find(r.layout, r.iblMode);
            if (rank && !failed && !r.isLightingComparison())
                out += "<td class=\"num\" data-v=\"" + std::to_string(rank->low) + "\">" + rank->text() + "</td>";
            else
                out += "<td class=\"num\"></td>";
        }
        if (failed) out += "<td>failed<div class=\"errtext\">" + htmlEscape(r.error) + "</div></td>";
        else if (r.status == RunStatus::NotMeasured)
            out += "<td>not measured<div class=\"errtext\">" + htmlEscape(r.notMeasured) + "</div></td>";
        else out += "<td class=\"status-ok\">ok</td>";
        out += "</tr>\n";
    }
    out += "</tbody>\n</table>\n</div>\n";
}

}  // namespace gbl
