// "G-buffer or visibility buffer?": which runs the report sets against each other, the traffic it
// quotes, and the answer it writes, against figures worked out here from the sample runs.
#include <gtest/gtest.h>

#include "report_html.h"
#include "report_json.h"
#include "report_sample.h"
#include "visibility_verdict.h"

namespace gbl {
namespace {

constexpr double kPixels = 1920.0 * 1080.0;

// A visibility run: `idBytes` of ids + depth per pixel written and read, `vertexBytes` of
// modelled vertex fetches per pixel, at 1080p.
RunReport visibilityRun(const std::string& name, double idBytes, double vertexBytes, double flip) {
    RunReport r = test::sampleRun(name, "split-sum", int(idBytes), flip, 40.0);
    r.pipeline = "visibility-buffer";
    for (FrameTraffic& f : r.bandwidth) {
        const double pixels = double(f.width) * f.height;
        f.geometryWriteBytes = f.lightingReadBytes = pixels * f.samples * idBytes;
        f.lightBufferBytes = 0;
        f.vertexFetchBytes = pixels * vertexBytes;
        f.totalBytes = f.geometryWriteBytes + f.lightingReadBytes + f.vertexFetchBytes;
    }
    return r;
}

ReportModel withVisibility(double flip, double idBytes, double vertexBytes) {
    ReportModel m = test::sampleReport();
    m.runs.erase(m.runs.begin() + 2);  // fat-naive, identical to the reference: leave ue4 the best G-buffer
    m.runs.push_back(visibilityRun("visibility-64", idBytes + 4, vertexBytes, flip));
    m.runs.push_back(visibilityRun("visibility-32", idBytes, vertexBytes, flip));
    return m;
}

TEST(VisibilityVerdict, NeedsBothKindsOfRun) {
    EXPECT_FALSE(gbufferOrVisibility(test::sampleReport()).has_value());  // no visibility run
    ReportModel m = withVisibility(0.01, 8, 156);
    m.runs.erase(m.runs.begin(), m.runs.begin() + 4);  // only "none" runs, a failure and the visibility runs
    for (RunReport& r : m.runs)
        if (r.pipeline != "visibility-buffer") r.iblMode = "none";
    EXPECT_FALSE(gbufferOrVisibility(m).has_value());  // no G-buffer run under the first mode
}

TEST(VisibilityVerdict, BestGBufferAgainstTheCheapestVisibilityBuffer) {
    const auto v = gbufferOrVisibility(withVisibility(0.0100, 8, 156));
    ASSERT_TRUE(v.has_value());
    EXPECT_EQ(v->iblMode, "split-sum");  // the first mode
    EXPECT_EQ(v->gbufferLayout, "ue4");  // FLIP 0.0213 < compact-octahedral 0.0561 < ryse 0.0710
    EXPECT_EQ(v->visibilityLayout, "visibility-32");  // 8 B/pixel beats 12
    EXPECT_DOUBLE_EQ(v->gbufferFlip, 0.0213);
    EXPECT_DOUBLE_EQ(v->visibilityFlip, 0.0100);
    // The sample's 1080p frame: 20 B/pixel written and read, plus 12345.5 B of light buffers.
    EXPECT_NEAR(v->gbufferBytesPerPixel, 40.0 + 12345.5 / kPixels, 1e-9);
    EXPECT_NEAR(v->visibilityIdBytesPerPixel, 16.0, 1e-9);
    EXPECT_NEAR(v->visibilityVertexBytesPerPixel, 156.0, 1e-9);
    // Less error; 16 < 40 B/pixel, but 16 + 156 > 40: ahead while caches serve more than
    // 1 - (40.006 - 16) / 156 = 84.6 % of the vertex fetches.
    EXPECT_NE(v->answer.find("visibility-32 loses less than ue4"), std::string::npos) << v->answer;
    EXPECT_NE(v->answer.find("more than 85% of them"), std::string::npos) << v->answer;
    EXPECT_NE(v->answer.find("Answer: the visibility buffer."), std::string::npos) << v->answer;
}

TEST(VisibilityVerdict, TheAnswerFollowsErrorAndTraffic) {
    // Cheaper even with every vertex fetch missing the cache.
    auto v = gbufferOrVisibility(withVisibility(0.0100, 8, 20));
    ASSERT_TRUE(v.has_value());
    EXPECT_NE(v->answer.find("even with every vertex fetch"), std::string::npos) << v->answer;
    // More error, more traffic: the G-buffer.
    v = gbufferOrVisibility(withVisibility(0.0300, 24, 156));
    ASSERT_TRUE(v.has_value());
    EXPECT_NE(v->answer.find("loses more than ue4"), std::string::npos) << v->answer;
    EXPECT_NE(v->answer.find("Answer: the G-buffer (ue4)."), std::string::npos) << v->answer;
    // More error, fewer bytes: a trade.
    v = gbufferOrVisibility(withVisibility(0.0300, 8, 156));
    ASSERT_TRUE(v.has_value());
    EXPECT_NE(v->answer.find("the G-buffer (ue4) for quality, the visibility buffer for bandwidth"), std::string::npos)
        << v->answer;
}

TEST(VisibilityVerdict, WrittenIntoJsonAndHtml) {
    const ReportModel m = withVisibility(0.0100, 8, 156);
    const auto v = gbufferOrVisibility(m);
    ASSERT_TRUE(v.has_value());
    const nlohmann::ordered_json j = reportToJson(m);
    ASSERT_TRUE(j.contains("gbuffer_or_visibility"));
    EXPECT_EQ(j["gbuffer_or_visibility"]["answer"], v->answer);
    EXPECT_EQ(j["gbuffer_or_visibility"]["visibility"]["layout"], "visibility-32");
    EXPECT_DOUBLE_EQ(j["gbuffer_or_visibility"]["visibility"]["vertex_fetch_bytes_per_pixel_modelled"].get<double>(), 156.0);
    const std::string html = reportHtml(m);
    EXPECT_NE(html.find("<section id=\"gbuffer-or-visibility\">"), std::string::npos);
    // Each visibility run's section states its modelled vertex fetches.
    EXPECT_NE(html.find("Vertex fetches (modelled, in the traffic)</th><td class=\"num\">156<"), std::string::npos);
    EXPECT_FALSE(reportToJson(test::sampleReport()).contains("gbuffer_or_visibility"));
    EXPECT_EQ(reportHtml(test::sampleReport()).find("gbuffer-or-visibility"), std::string::npos);
}

}  // namespace
}  // namespace gbl
