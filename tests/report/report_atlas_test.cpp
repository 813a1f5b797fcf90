// The atlas view (report_atlas.h): report.json's "atlas" holds one row per layout in the grouped
// order, each row's errors are its layout's run (the first IBL mode) in the same report.json, a
// row whose bytes are ids (a pipeline without attribute targets) is carried as such, the atlas
// reads back, and report.html shows the same table.
#include <gtest/gtest.h>

#include <cmath>

#include "report_atlas.h"
#include "report_html.h"
#include "report_json.h"
#include "report_sample.h"

namespace gbl {
namespace {
using Json = nlohmann::ordered_json;

AtlasEntry entry(const std::string& layout, const std::string& family, int year, int bytes,
                 std::vector<AtlasAttribute> attributes, const std::string& kind = "attributes") {
    AtlasEntry e;
    e.layout = layout;
    e.family = family;
    e.engine = family + " engine";
    e.title = "Title of " + layout;
    e.year = year;
    e.bytesPerPixel = bytes;
    e.bytesKind = kind;
    e.attributes = std::move(attributes);
    return e;
}

ReportModel atlasModel() {
    ReportModel m = test::sampleReport();  // runs of ue4, compact-octahedral, fat-naive, ryse
    m.atlas = {
        entry("ue4", "Unreal Engine", 2017, 25, {{"normal", 30, "normal_xyz"}, {"specular_color", 0, "derived: ue4"}}),
        entry("ryse", "CryENGINE", 2014, 16, {{"normal", 24, "normal_xyz"}}),
        entry("compact-octahedral", "gbufferlab", 2023, 16, {{"normal", 24, "normal_octahedral"}}),
        entry("fat-naive", "early deferred", 2005, 24, {{"position", 48, "float16"}}),
        // A pipeline whose targets hold ids (a visibility buffer): no attributes, no run.
        entry("visbuffer", "gbufferlab", 2024, 8, {}, "ids"),
    };
    // Provenance counts (layout.h, provenanceCounts): ue4's as its file has them; ryse's talk-based
    // mix; visbuffer's none (a layout written before provenance, or a user's without [sources]).
    ProvenanceCounts& ue4 = m.atlas[0].provenance;
    ue4.entries = 27;
    ue4.verified = 25;
    ue4.assumed = 2;
    ue4.differs = 3;
    ProvenanceCounts& ryse = m.atlas[1].provenance;
    ryse.entries = 19;
    ryse.verified = 0;
    ryse.talk = 3;
    ryse.lineage = 6;
    ryse.assumed = 7;
    ryse.own = 3;
    ryse.differs = 6;
    return m;
}

const Json* runOf(const Json& report, const std::string& layout, const std::string& mode) {
    for (const Json& r : report["runs"])
        if (r["layout"] == layout && r["ibl_mode"] == mode) return &r;
    return nullptr;
}

TEST(ReportAtlas, JsonRowsAreGroupedAndCarryTheirRunsErrors) {
    const Json j = reportToJson(atlasModel());
    ASSERT_TRUE(j.contains("atlas"));
    const Json& atlas = j["atlas"];
    ASSERT_EQ(atlas.size(), 5u);
    // Families by their earliest year: early deferred 2005, CryENGINE 2014, Unreal Engine 2017,
    // gbufferlab 2023 (compact-octahedral 2023, then visbuffer 2024).
    std::vector<std::string> order;
    for (const Json& row : atlas) order.push_back(row["layout"].get<std::string>());
    EXPECT_EQ(order, (std::vector<std::string>{"fat-naive", "ryse", "ue4", "compact-octahedral", "visbuffer"}));
    for (const Json& row : atlas) {
        const std::string layout = row["layout"];
        SCOPED_TRACE(layout);
        const Json* run = runOf(j, layout, "split-sum");  // the report's first IBL mode
        if (!run) {
            EXPECT_FALSE(row.contains("flip_mean"));
            EXPECT_FALSE(row.contains("ibl_mode"));
            continue;
        }
        EXPECT_EQ(row["ibl_mode"], "split-sum");
        EXPECT_EQ(row["flip_mean"], (*run)["image_errors"]["flip_mean"]);
        EXPECT_EQ(row["psnr_tonemapped_db"], (*run)["image_errors"]["psnr_tonemapped_db"]);
    }
    EXPECT_EQ(atlas[0]["psnr_tonemapped_db"], "inf");  // fat-naive is identical to the reference
    EXPECT_EQ(atlas[2]["bytes_per_pixel"], 25);
    EXPECT_EQ(atlas[2]["family"], "Unreal Engine");
    EXPECT_EQ(atlas[2]["attributes"][0], (Json{{"name", "normal"}, {"bits", 30}, {"encoding", "normal_xyz"}}));
    EXPECT_EQ(atlas[2]["attributes"][1]["encoding"], "derived: ue4");
    EXPECT_EQ(atlas[4]["bytes_kind"], "ids");
    EXPECT_TRUE(atlas[4]["attributes"].empty());
}

TEST(ReportAtlas, ReadsBackAndWritesTheSameJson) {
    const ReportModel model = atlasModel();
    const std::string text = reportToJson(model).dump(2);
    const ReportModel back = reportFromJson(Json::parse(text));
    ASSERT_EQ(back.atlas.size(), model.atlas.size());
    EXPECT_EQ(reportToJson(back).dump(2), text);
    // A report without an atlas (written before it existed) has none.
    Json old = Json::parse(text);
    old.erase("atlas");
    EXPECT_TRUE(reportFromJson(old).atlas.empty());
    // A malformed atlas is refused with the field's path.
    Json bad = Json::parse(text);
    bad["atlas"][1].erase("bytes_per_pixel");
    try {
        (void)reportFromJson(bad);
        ADD_FAILURE() << "accepted an atlas row without bytes_per_pixel";
    } catch (const UserError& e) {
        EXPECT_NE(std::string(e.what()).find("atlas[1]: missing field \"bytes_per_pixel\""), std::string::npos) << e.what();
    }
}

// Each row carries how much of its layout is verified; a row without provenance carries none; the
// counts read back and must add up.
TEST(ReportAtlas, RowsCarryProvenanceCounts) {
    const ReportModel model = atlasModel();
    const Json j = reportToJson(model);
    const Json* ue4 = nullptr;
    const Json* visbuffer = nullptr;
    for (const Json& row : j["atlas"]) {
        if (row["layout"] == "ue4") ue4 = &row;
        if (row["layout"] == "visbuffer") visbuffer = &row;
    }
    ASSERT_TRUE(ue4 && visbuffer);
    EXPECT_EQ((*ue4)["provenance"], (Json{{"entries", 27}, {"verified", 25}, {"talk", 0}, {"lineage", 0}, {"assumed", 2},
                                          {"own", 0}, {"missing", 0}, {"differs", 3},
                                          {"text", "verified 25/27, assumed 2, differs 3"}}));
    EXPECT_FALSE(visbuffer->contains("provenance"));
    // Back from JSON: the same counts.
    const ReportModel back = reportFromJson(Json::parse(j.dump()));
    for (const AtlasEntry& e : back.atlas) {
        if (e.layout != "ryse") continue;
        EXPECT_EQ(e.provenance.text(), "verified 0/19, talk 3, lineage 6, assumed 7, own 3, differs 6");
    }
    // Counts that do not add up to the entries are refused, with the path.
    Json bad = j;
    for (Json& row : bad["atlas"])
        if (row["layout"] == "ue4") row["provenance"]["verified"] = 24;
    try {
        (void)reportFromJson(bad);
        ADD_FAILURE() << "accepted provenance counts that do not add up";
    } catch (const UserError& e) {
        EXPECT_NE(std::string(e.what()).find(".provenance: verified + talk + lineage + assumed + own + missing must "
                                             "equal entries"),
                  std::string::npos)
            << e.what();
    }
    // report.html: the provenance column of each row, "-" without.
    const std::string html = reportHtml(model);
    const size_t at = html.find("<section id=\"atlas\">");
    ASSERT_NE(at, std::string::npos);
    EXPECT_NE(html.find("<th>Provenance</th>", at), std::string::npos);
    const size_t ue4Row = html.find(">ue4</td>", at);
    ASSERT_NE(ue4Row, std::string::npos);
    const std::string row = html.substr(ue4Row, html.find("</tr>", ue4Row) - ue4Row);
    EXPECT_NE(row.find("<td class=\"provenance\">verified 25/27, assumed 2, differs 3</td>"), std::string::npos) << row;
    const size_t visRow = html.find(">visbuffer</td>", at);
    const std::string vis = html.substr(visRow, html.find("</tr>", visRow) - visRow);
    EXPECT_NE(vis.find("<td class=\"provenance\">&ndash;</td>"), std::string::npos) << vis;
}

TEST(ReportAtlas, HtmlTableShowsTheSameRows) {
    const ReportModel model = atlasModel();
    const std::string html = reportHtml(model);
    const size_t at = html.find("<section id=\"atlas\">");
    ASSERT_NE(at, std::string::npos);
    const std::string section = html.substr(at, html.find("</section>", at) - at);
    for (const char* family : {"early deferred", "CryENGINE", "Unreal Engine", "gbufferlab"})
        EXPECT_NE(section.find(std::string("<tr class=\"family\"><th colspan=\"8\">") + family + "</th>"), std::string::npos)
            << family;
    // Rows in the JSON's order, each with its FLIP and PSNR as report.json has them.
    size_t last = 0;
    const Json report = reportToJson(model);  // a named value: a temporary's ["atlas"] would dangle in the loop
    for (const Json& row : report["atlas"]) {
        const std::string layout = row["layout"];
        const size_t p = section.find(">" + layout + "</td>");
        ASSERT_NE(p, std::string::npos) << layout;
        EXPECT_GT(p, last) << layout;
        last = p;
        const std::string tail = section.substr(p, section.find("</tr>", p) - p);
        if (row.contains("flip_mean")) {
            char flip[32];
            std::snprintf(flip, sizeof flip, "%.4f", row["flip_mean"].get<double>());
            EXPECT_NE(tail.find(flip), std::string::npos) << layout << ": " << tail;
        }
    }
    EXPECT_NE(section.find("&infin;"), std::string::npos);      // fat-naive's PSNR
    EXPECT_NE(section.find("8 ids"), std::string::npos);        // the visibility buffer's bytes
    EXPECT_NE(section.find("normal <b>30</b> normal_xyz"), std::string::npos);
    EXPECT_NE(section.find("specular_color <b>&ndash;</b> derived: ue4"), std::string::npos);
    // No atlas, no section.
    EXPECT_EQ(reportHtml(test::sampleReport()).find("id=\"atlas\""), std::string::npos);
}

}  // namespace
}  // namespace gbl
