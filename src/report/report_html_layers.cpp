#include "report_html_layers.h"

#include "report_html.h"

namespace gbl {

void writeLayerSection(std::string& out, const ReportModel& model) {
    if (!model.hasLayerMetrics()) return;
    out += "<section id=\"layers\">\n<h2>Material layers</h2>\n<p class=\"small\">Attribute errors (means) over the "
           "covered pixels whose reference carries the layer: coat, coat roughness, sheen roughness and anisotropy "
           "strength as |test &minus; reference|; the coat normal (the base normal where none is stored) and the "
           "anisotropy direction (as lines, 0&ndash;90&deg;) in degrees; the sheen colour in CIEDE2000. Then the "
           "lit image's LDR-FLIP over each material class&rsquo;s pixels (coated, sheen, anisotropic; plain: none "
           "of them; a pixel may be in several) with its tied rank within the class "
           "(<a href=\"report.json\">significance_by_class</a>). &ldquo;&ndash;&rdquo;: no pixel carries it.</p>\n"
           "<table class=\"small\"><thead><tr><th>Layout</th><th>IBL</th>";
    for (ErrorAttribute a : kLayerErrorAttributes)
        out += std::string("<th class=\"num\">") + errorAttributeName(a) + " <span class=\"muted\">(" +
               errorAttributeUnit(a) + ")</span></th>";
    for (const auto& [name, member] : layerImageClasses())
        out += std::string("<th class=\"num\">FLIP ") + name + " <span class=\"muted\">(rank)</span></th>";
    out += "</tr></thead><tbody>\n";
    for (const RunReport& r : model.runs) {
        if (r.status != RunStatus::Ok) continue;
        out += "<tr><td>" + htmlEscape(r.layout) + "</td><td class=\"muted\">" + htmlEscape(r.iblMode) + "</td>";
        for (ErrorAttribute a : kLayerErrorAttributes) {
            const auto& s = r.attributes[a].all;
            out += "<td class=\"num\">" + (s ? formatSignificant(s->error.mean, 3) : std::string("&ndash;")) + "</td>";
        }
        for (const auto& [name, member] : layerImageClasses()) {
            const std::optional<ImageClassErrors> c = r.image ? (*r.image).*member : std::nullopt;
            std::string cell = "&ndash;";
            if (c) {
                cell = formatFixed(c->flipMean, 4);
                for (const auto& [n, sig] : model.classSignificance)
                    if (n == name)
                        if (const RankRange* rank = sig.find(r.layout, r.iblMode)) cell += " (" + rank->text() + ")";
            }
            out += "<td class=\"num\">" + cell + "</td>";
        }
        out += "</tr>\n";
    }
    out += "</tbody></table>\n<p class=\"small muted\">Pixels per class:";
    for (const RunReport& r : model.runs) {
        if (r.status != RunStatus::Ok || !r.image) continue;
        for (const auto& [name, member] : layerImageClasses())
            if (const auto& c = (*r.image).*member) out += std::string(" ") + name + " " + std::to_string(c->pixels);
        break;  // the reference's classes, the same for every run
    }
    out += ".</p>\n</section>\n";
}

}  // namespace gbl
