// Bandwidth as GPUs pay it in the report: report.json's effective_bandwidth and bandwidth_as_paid,
// report.csv's columns, report.html's section, the plot against effective bytes, the atlas's cell,
// and the budget lines under each class's bytes.
#include <gtest/gtest.h>

#include <string>

#include "layout_catalog.h"
#include "report_bandwidth.h"
#include "report_csv.h"
#include "report_html.h"
#include "report_json.h"

namespace gbl {
namespace {

FrameCompression uniform(const Layout& layout, double dcc, double afbc) {
    FrameCompression f;
    f.width = 480;
    f.height = 270;
    for (const Target& t : layout.targets) {
        TargetCompression c;
        c.name = t.name;
        c.format = t.format;
        c.bytesPerPixel = t.bytes();
        c.pixels = 480 * 270;
        c.dcc.bytes = dcc * double(c.pixels);
        c.dcc.blocks = 10;
        c.afbc.compressed = t.bytes() <= 4;
        c.afbc.readBytes = afbc * double(c.pixels);
        c.afbc.bodyBytes = afbc * double(c.pixels);
        c.afbc.superblocks = 4;
        c.afbc.solidSuperblocks = 1;
        f.targets.push_back(c);
    }
    return f;
}

RunReport run(const std::string& name, double flip, double dcc, double afbc) {
    const Layout layout = loadLayout(name);
    RunReport r;
    r.layout = name;
    r.pipeline = pipelineName(layout.pipeline);
    r.iblMode = "split-sum";
    r.bytesPerPixel = bytesPerPixelOf(computeBandwidth(layout, 480, 270));
    r.bandwidth = computeBandwidth(layout, 480, 270).frames;
    ImageErrors e;
    e.flipMean = flip;
    r.image = e;
    r.effective = computeEffectiveBandwidth(layout, uniform(layout, dcc, afbc), 1, LightingModel{});
    return r;
}

ReportModel model() {
    ReportModel m;
    m.run.iblModes = {"split-sum"};
    m.run.lighting = "tiled";
    m.reference.layout = "reference";
    // ue4 (25 B nominal) is better than crysis3-thin (12 B); with its targets at 1 B/px under
    // DCC (5 + 5 depth = 10 B) it fits 12 B/px, where nominally crysis3-thin is the best.
    m.runs.push_back(run("ue4", 0.01, 1.0, 1.0));
    m.runs.push_back(run("crysis3-thin", 0.04, 3.0, 3.0));
    return m;
}

TEST(ReportBandwidth, JsonFields) {
    const nlohmann::ordered_json j = reportToJson(model());
    const auto& e = j["runs"][0]["effective_bandwidth"];
    for (const char* key : {"frames", "width", "height", "lighting", "lighting_reads_per_pixel", "nominal_bytes_per_pixel",
                            "nominal_traffic_bytes_1080p", "nominal_gb_per_s_1080p60", "targets", "classes", "tile_memory"})
        EXPECT_TRUE(e.contains(key)) << key;
    ASSERT_EQ(e["classes"].size(), 3u);
    EXPECT_EQ(e["classes"][0]["class"], "desktop-dcc");
    EXPECT_DOUBLE_EQ(e["classes"][0]["bytes_per_pixel"].get<double>(), 5 * 1.0 + 5);
    EXPECT_EQ(e["targets"].size(), 5u);
    EXPECT_TRUE(e["targets"][0].contains("mali_afbc_read_bytes_per_pixel"));
    EXPECT_EQ(e["tile_memory"].size(), 4u);
    EXPECT_EQ(j["run"]["lighting"], "tiled");
    const auto& section = j["bandwidth_as_paid"];
    EXPECT_EQ(section["tile_families"].size(), 4u);
    EXPECT_EQ(section["verdicts"].size(), 4u);
    EXPECT_FALSE(section["changes"].empty());
}

TEST(ReportBandwidth, VerdictChangesUnderEffectiveBytes) {
    const std::vector<EffectiveVerdict> v = effectiveVerdicts(model());
    ASSERT_EQ(v.size(), 4u);
    EXPECT_EQ(v[0].gpuClass, "nominal");
    // 12 B/px: nominally crysis3-thin (12 B), under desktop-dcc ue4 (10 B).
    EXPECT_EQ(v[0].lines[1].best, "crysis3-thin");
    EXPECT_EQ(v[1].gpuClass, "desktop-dcc");
    EXPECT_EQ(v[1].lines[1].best, "ue4");
    EXPECT_DOUBLE_EQ(v[1].lines[1].bytes, 10.0);
    bool found = false;
    for (const std::string& c : verdictChanges(v))
        found = found || c.find("12 B/px: ue4") != std::string::npos;
    EXPECT_TRUE(found);
}

TEST(ReportBandwidth, CsvHtmlAndPlot) {
    const ReportModel m = model();
    const std::string csv = reportCsv(m);
    for (const std::string& column : effectiveCsvHeader()) EXPECT_NE(csv.find(column), std::string::npos) << column;
    EXPECT_LT(csv.find("tile_fits"), csv.find("report_status"));  // report_status stays last
    const std::string html = reportHtml(m);
    EXPECT_NE(html.find("id=\"bandwidth-as-paid\""), std::string::npos);
    EXPECT_NE(html.find("id=\"plot-flip-dcc\""), std::string::npos);
    EXPECT_NE(html.find("id=\"plot-flip-afbc\""), std::string::npos);
    EXPECT_NE(html.find("Effective bytes per pixel (desktop-dcc)"), std::string::npos);
    // A run without effective numbers adds empty CSV fields and no section.
    ReportModel plain = m;
    for (RunReport& r : plain.runs) r.effective.reset();
    EXPECT_EQ(bandwidthSectionHtml(plain), "");
    EXPECT_EQ(effectiveCsvFields(plain.runs[0]), std::vector<std::string>(effectiveCsvHeader().size()));
}

}  // namespace
}  // namespace gbl
