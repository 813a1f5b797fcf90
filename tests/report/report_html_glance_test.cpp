// What report.html shows at a glance, read from the page's text (the browser test measures the
// same in Chromium): the verdict first, FLIP on a log axis, one Pareto front per pipeline kind,
// a visibility buffer's second marker at its counted bytes, points linked to their runs, labels
// whose boxes do not intersect, and the table's folded columns.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <regex>

#include "budget_verdict.h"
#include "crowded_report_sample.h"
#include "plot_labels.h"
#include "report_html.h"
#include "report_sample.h"

namespace gbl {
namespace {

std::string figure(const std::string& html, const std::string& id) {
    const size_t at = html.find("<figure class=\"plot\" id=\"plot-" + id + "\"");
    return at == std::string::npos ? "" : html.substr(at, html.find("</figure>", at) - at);
}

size_t countOf(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

// Each G-buffer point's centre, by the run section it links to.
std::map<std::string, std::pair<double, double>> circles(const std::string& plot) {
    std::map<std::string, std::pair<double, double>> out;
    const std::regex re("<a class=\"pt\" href=\"#([^\"]+)\"[^>]*><circle cx=\"([-0-9.]+)\" cy=\"([-0-9.]+)\"");
    for (auto it = std::sregex_iterator(plot.begin(), plot.end(), re); it != std::sregex_iterator(); ++it)
        out[(*it)[1]] = {std::stod((*it)[2]), std::stod((*it)[3])};
    return out;
}

// The points of each front polyline, by kind.
std::vector<std::pair<std::string, int>> fronts(const std::string& plot) {
    std::vector<std::pair<std::string, int>> out;
    const std::regex re("<polyline class=\"pareto\" data-kind=\"([a-z]+)\"[^>]* points=\"([^\"]+)\"");
    for (auto it = std::sregex_iterator(plot.begin(), plot.end(), re); it != std::sregex_iterator(); ++it) {
        const std::string points = (*it)[2];
        out.push_back({(*it)[1], int(std::count(points.begin(), points.end(), ',')) });
    }
    return out;
}

TEST(ReportGlance, TheVerdictComesFirstWithReportJsonsSentences) {
    const ReportModel model = test::crowdedReport();
    const std::string html = reportHtml(model);
    const size_t verdict = html.find("<section id=\"verdict\">");
    ASSERT_NE(verdict, std::string::npos);
    EXPECT_LT(verdict, html.find("<section id=\"summary\">"));
    EXPECT_LT(verdict, html.find("<section id=\"plots\">"));
    const auto v = budgetVerdict(model);
    ASSERT_TRUE(v.has_value());
    size_t at = verdict;
    for (const BudgetLine& line : v->lines) {  // in order, each escaped once
        at = html.find(">" + htmlEscape(line.sentence) + "</li>", at);
        EXPECT_NE(at, std::string::npos) << line.sentence;
    }
    EXPECT_NE(html.find(htmlEscape(v->basis)), std::string::npos);
    // The visibility buffers' 8 and 12 B/px of ids win no budget: counted, they are 86 and 90.
    EXPECT_EQ(v->lines[1].best->layout, "crysis3-thin");
    EXPECT_EQ(v->lines[2].best->layout, "compact-octahedral");
    EXPECT_EQ(v->lines[3].best->layout, "hdrp-lit");
    EXPECT_EQ(v->lines[5].best->layout, "visibility-32");
    ReportModel failed = test::sampleReport();
    for (RunReport& r : failed.runs) r.status = RunStatus::Failed;
    EXPECT_EQ(reportHtml(failed).find("<section id=\"verdict\">"), std::string::npos);
}

TEST(ReportGlance, FlipOnALogAxisByDefaultLinearAsAnOption) {
    const std::string html = reportHtml(test::crowdedReport());
    const std::string log = figure(html, "flip"), linear = figure(html, "flip-linear");
    ASSERT_FALSE(log.empty());
    ASSERT_FALSE(linear.empty());
    EXPECT_EQ(log.rfind("<figure class=\"plot\" id=\"plot-flip\">", 0), 0u);  // shown: no hidden attribute
    EXPECT_NE(linear.find("id=\"plot-flip-linear\" hidden>"), std::string::npos);
    EXPECT_NE(log.find("FLIP mean (log scale) against bytes per pixel"), std::string::npos);
    EXPECT_EQ(linear.find("log scale"), std::string::npos);
    // Equal ratios, equal distances: 0.0027 -> 0.0082 -> 0.1165 (ue5-16bit, hdrp-lit, niagara).
    const auto c = circles(log);
    const double a = c.at("run-ue5-16bit-split-sum").second, b = c.at("run-hdrp-lit-split-sum").second,
                 n = c.at("run-niagara-split-sum").second;
    const double perDecadeLow = (a - b) / std::log10(0.0082 / 0.0027);
    const double perDecadeHigh = (b - n) / std::log10(0.1165 / 0.0082);
    EXPECT_GT(perDecadeLow, 100.0);  // three decades over the plot's 440 units
    EXPECT_NEAR(perDecadeLow, perDecadeHigh, 0.2);
    // On the linear axis the crowd is squeezed: niagara is far above, the rest within a sliver.
    const auto l = circles(linear);
    EXPECT_LT(l.at("run-ue5-16bit-split-sum").second - l.at("run-hdrp-lit-split-sum").second, 25.0);
    // A FLIP of 0 (identical) has no logarithm: it sits in a "0" lane under the axis.
    const std::string sample = figure(reportHtml(test::sampleReport()), "flip");
    EXPECT_NE(sample.find("0 (under the log axis): identical to the reference"), std::string::npos);
}

TEST(ReportGlance, OneFrontPerPipelineKind) {
    ReportModel model = test::crowdedReport();
    // G-buffer layouts: crysis3-thin (12 B) -> compact-octahedral (16) -> urp-deferred-accurate (17)
    // -> hdrp-lit (21) -> ue5-16bit (57), deferred shading and lighting together. Were the visibility
    // buffers on it, visibility-32 (8 B of ids, FLIP 0.0002) would be the whole front.
    EXPECT_EQ(fronts(figure(reportHtml(model), "flip")), (std::vector<std::pair<std::string, int>>{{"gbuffer", 5}}));
    // Both visibility buffers on their own front once neither dominates the other.
    for (RunReport& r : model.runs)
        if (r.layout == "visibility-64") r.image->flipMean = 0.0001;
    for (RunReport& r : model.runs)
        if (r.layout == "visibility-32") r.image->flipMean = 0.0003;
    const std::string plot = figure(reportHtml(model), "flip");
    EXPECT_EQ(fronts(plot), (std::vector<std::pair<std::string, int>>{{"gbuffer", 5}, {"visibility", 2}}));
    EXPECT_NE(plot.find("data-kind=\"visibility\" fill=\"none\" stroke=\"#1f5fa8\" stroke-width=\"2\" "
                        "stroke-opacity=\"0.75\" stroke-dasharray"),
              std::string::npos);
}

TEST(ReportGlance, AVisibilityBufferShowsItsCountedBytesAsASecondMarker) {
    const std::string whole = figure(reportHtml(test::crowdedReport()), "flip");
    const std::string plot = whole.substr(0, whole.find("</svg>"));  // not the legend's samples
    EXPECT_EQ(countOf(plot, "<polygon"), 2u * 2u);  // two visibility buffers, two markers each
    EXPECT_EQ(countOf(plot, "<line class=\"fetches\""), 2u);
    EXPECT_NE(plot.find("visibility-32 (IBL split-sum) counted with half its modelled vertex fetches (no cache "
                        "reuse): 86.0 B/px"),
              std::string::npos);
    EXPECT_NE(plot.find(">visibility-32 + fetches</text>"), std::string::npos);
    // The second marker lies right of the first, at 86 on an axis whose 0 and 100 the ticks give.
    const std::regex re("<polygon points=\"([-0-9.]+),");
    std::vector<double> tops;  // each diamond's top vertex x, i.e. its centre x
    for (auto it = std::sregex_iterator(plot.begin(), plot.end(), re); it != std::sregex_iterator(); ++it)
        tops.push_back(std::stod((*it)[1]));
    ASSERT_EQ(tops.size(), 4u);
    const std::regex tick("<text x=\"([-0-9.]+)\" y=\"[-0-9.]+\" text-anchor=\"middle\">(0|100)</text>");
    std::map<std::string, double> ticks;
    for (auto it = std::sregex_iterator(plot.begin(), plot.end(), tick); it != std::sregex_iterator(); ++it)
        ticks[(*it)[2]] = std::stod((*it)[1]);
    ASSERT_EQ(ticks.size(), 2u);
    const auto bytesAt = [&](double x) { return (x - ticks["0"]) / (ticks["100"] - ticks["0"]) * 100.0; };
    EXPECT_NEAR(bytesAt(tops[0]), 8.0, 0.1);   // visibility-32's ids and depth
    EXPECT_NEAR(bytesAt(tops[1]), 86.0, 0.1);  // ... counted with its fetches
}

TEST(ReportGlance, EveryPointLinksToItsRunAndNoLabelsIntersect) {
    const ReportModel model = test::crowdedReport();
    const std::string html = reportHtml(model);
    for (const char* id : {"flip", "flip-linear", "psnr"}) {
        SCOPED_TRACE(id);
        const std::string plot = figure(html, id);
        const std::regex link("<a class=\"pt\" href=\"#([^\"]+)\"");
        size_t points = 0;
        for (auto it = std::sregex_iterator(plot.begin(), plot.end(), link); it != std::sregex_iterator(); ++it) {
            ++points;
            EXPECT_NE(html.find("<section class=\"layout\" id=\"" + std::string((*it)[1]) + "\""), std::string::npos);
        }
        EXPECT_EQ(points, model.runs.size() + 2);  // and a second marker per visibility buffer
        // Each label's box as placed: x, baseline and pinned width; none intersects another.
        const std::regex label("<text class=\"label\" data-pt=\"[0-9]+\" x=\"([-0-9.]+)\" y=\"([-0-9.]+)\" "
                               "textLength=\"([-0-9.]+)\">");
        std::vector<PlotBox> boxes;
        for (auto it = std::sregex_iterator(plot.begin(), plot.end(), label); it != std::sregex_iterator(); ++it) {
            const double x = std::stod((*it)[1]), y = std::stod((*it)[2]), w = std::stod((*it)[3]);
            boxes.push_back({x, y - 11 * kLabelAscent, x + w, y + 11 * kLabelDescent});
        }
        ASSERT_EQ(boxes.size(), points);
        for (size_t i = 0; i < boxes.size(); ++i)
            for (size_t j = i + 1; j < boxes.size(); ++j) EXPECT_FALSE(boxes[i].intersects(boxes[j])) << i << " " << j;
    }
}

TEST(ReportGlance, TheTableGroupsItsColumnsAndFoldsTheSecondaryOnes) {
    const ReportModel model = test::crowdedReport();
    const std::string html = reportHtml(model);
    const size_t at = html.find("<table id=\"layouts\"");
    const std::string table = html.substr(at, html.find("</table>", at) - at);
    // The checkbox that unfolds them comes before the table (CSS reaches it with ~).
    EXPECT_LT(html.find("<input type=\"checkbox\" id=\"all-columns\">"), at);
    // Groups: their spans add up to the columns, all shown or the secondary ones folded.
    const std::regex span("<th( class=\"(g-all|g-folded)\")? colspan=\"([0-9]+)\"");
    const std::string groups = table.substr(0, table.find("</tr>"));
    int all = 0, folded = 0;
    for (auto it = std::sregex_iterator(groups.begin(), groups.end(), span); it != std::sregex_iterator(); ++it) {
        const int n = std::stoi((*it)[3]);
        if ((*it)[2] != "g-folded") all += n;
        if ((*it)[2] != "g-all") folded += n;
    }
    EXPECT_EQ(all + 1, 12);     // + the status column
    EXPECT_EQ(folded + 1, 11);  // the normal p99 folded
    for (const char* group : {">Cost<", ">Attribute error, mean<", ">Image error<"})
        EXPECT_NE(groups.find(group), std::string::npos) << group;
    EXPECT_NE(table.find("<th class=\"num secondary\" data-key=\"normal_p99\""), std::string::npos);
    EXPECT_EQ(countOf(table, "<td class=\"num secondary\""), model.runs.size());
    // With several views each measured value has its spread (folded too); a single view has none.
    EXPECT_EQ(countOf(table, "<small class=\"spread\""), model.runs.size() * 7);
    EXPECT_EQ(reportHtml(test::sampleReport()).find("class=\"spread\""), std::string::npos);
}

}  // namespace
}  // namespace gbl
