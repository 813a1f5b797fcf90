// compare --temporal N in the report: run.temporal and runs[].single_frame written and read back,
// frame 0's numbers beside the resolve's in the CSV, the HTML table, plots and atlas, the atlas
// ranked by either; without them (--temporal 1) no trace of either.
#include <gtest/gtest.h>

#include <string>

#include "report_atlas.h"
#include "report_csv.h"
#include "report_html.h"
#include "report_json.h"
#include "report_sample.h"

namespace gbl {
namespace {

using Json = nlohmann::ordered_json;

// The sample with --temporal 4: frame 0's FLIP ranks the layouts the other way round.
ReportModel temporalSample() {
    ReportModel m = test::sampleReport();
    m.run.temporalFrames = 4;
    m.run.temporalResolve = "mean";
    m.run.temporalJitter = {{0.0, -1.0 / 6}, {-0.25, 1.0 / 6}, {0.25, -7.0 / 18}, {-0.375, -1.0 / 18}};
    for (RunReport& r : m.runs) {
        if (r.status != RunStatus::Ok) continue;
        SingleFrameMetrics s;
        s.attributes = r.attributes;
        s.attributes[ErrorAttribute::Normal].all->error.mean = 0.5 + r.bytesPerPixel.total / 100.0;
        s.image = *r.image;
        s.image->flipMean = 0.2 - r.image->flipMean;  // reversed order
        s.image->psnrToneMapped = 20.0 + r.bytesPerPixel.total;
        r.singleFrame = s;
    }
    m.atlas.push_back(AtlasEntry{});
    m.atlas.back().layout = "ue4";
    m.atlas.back().family = "Unreal Engine";
    m.atlas.push_back(AtlasEntry{});
    m.atlas.back().layout = "compact-octahedral";
    m.atlas.back().family = "gbufferlab";
    return m;
}

TEST(TemporalReport, JsonWritesAndReadsBack) {
    const ReportModel m = temporalSample();
    const Json j = reportToJson(m);
    EXPECT_EQ(j["run"]["temporal"]["frames"], 4);
    EXPECT_EQ(j["run"]["temporal"]["resolve"], "mean");
    EXPECT_EQ(j["run"]["temporal"]["jitter"].size(), 4u);
    EXPECT_DOUBLE_EQ(j["run"]["temporal"]["jitter"][1][0].get<double>(), -0.25);
    EXPECT_DOUBLE_EQ(j["runs"][0]["single_frame"]["image_errors"]["flip_mean"].get<double>(), 0.2 - 0.0213);
    EXPECT_FALSE(j["runs"].back().contains("single_frame"));  // the failed run
    const ReportModel back = reportFromJson(Json::parse(j.dump()));
    EXPECT_EQ(back.run.temporalFrames, 4);
    EXPECT_EQ(back.run.temporalJitter, m.run.temporalJitter);
    ASSERT_TRUE(back.runs[0].singleFrame);
    EXPECT_EQ(back.runs[0].singleFrame->image->flipMean, m.runs[0].singleFrame->image->flipMean);
    EXPECT_EQ(back.runs[0].singleFrame->attributes[ErrorAttribute::Normal].all->error.mean,
              m.runs[0].singleFrame->attributes[ErrorAttribute::Normal].all->error.mean);
    EXPECT_EQ(reportToJson(back), j);  // a fixed point

    const Json plain = reportToJson(test::sampleReport());
    EXPECT_FALSE(plain["run"].contains("temporal"));
    for (const Json& r : plain["runs"]) EXPECT_FALSE(r.contains("single_frame"));
}

TEST(TemporalReport, CsvHtmlAndAtlasShowBoth) {
    const ReportModel m = temporalSample();
    const std::string csv = reportCsv(m);
    EXPECT_NE(csv.find("single_frame_flip_mean"), std::string::npos);
    EXPECT_NE(csv.find(",0.1787"), std::string::npos) << "ue4's frame-0 FLIP (0.2 - 0.0213)";
    const std::string html = reportHtml(m);
    EXPECT_NE(html.find("Single frame (frame 0)"), std::string::npos);
    EXPECT_NE(html.find("Image error, resolved"), std::string::npos);
    EXPECT_NE(html.find("id=\"plot-flip-1f\""), std::string::npos);
    EXPECT_NE(html.find("id=\"plot-psnr-1f\""), std::string::npos);
    EXPECT_NE(html.find("Not modelled: motion and reprojection"), std::string::npos);
    // The atlas ranks by either FLIP: ue4 is better resolved (0.0213 < 0.0561), worse in frame 0.
    int ue4 = 0, ue4Single = 0, compact = 0, compactSingle = 0;
    for (const AtlasRowGroup& g : atlasRows(m))
        for (const AtlasRow& r : g.rows) {
            if (r.entry.layout == "ue4") ue4 = r.rank, ue4Single = r.rankSingleFrame;
            if (r.entry.layout == "compact-octahedral") compact = r.rank, compactSingle = r.rankSingleFrame;
        }
    EXPECT_EQ(ue4, 1);
    EXPECT_EQ(compact, 2);
    EXPECT_EQ(ue4Single, 2);
    EXPECT_EQ(compactSingle, 1);
    EXPECT_NE(html.find("FLIP mean (rank), single frame"), std::string::npos);

    const std::string plain = reportHtml(test::sampleReport());
    EXPECT_EQ(plain.find("Single frame"), std::string::npos);
    EXPECT_EQ(plain.find("plot-flip-1f"), std::string::npos);
}

}  // namespace
}  // namespace gbl
