// The material layers in the report (issue 40): report.json writes the layer attributes (with the
// class they are over), the layer classes' image errors and significance_by_class, and reads them
// back byte for byte; report.csv adds their columns only to a report that has them (a report
// without them has exactly the columns it always had); report.html gets its #layers section; a
// view mean averages them as the others.
#include <gtest/gtest.h>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "rank_significance.h"
#include "report_csv.h"
#include "report_html.h"
#include "report_json.h"
#include "report_sample.h"
#include "view_stats.h"

namespace gbl {
namespace {

using Json = nlohmann::ordered_json;

AttributeStats stats(double mean, size_t count) {
    AttributeStats a;
    a.error.count = count;
    a.error.mean = mean;
    a.error.rms = mean * 1.1;
    a.error.p99 = mean * 2.0;
    a.error.max = mean * 3.0;
    return a;
}

ImageClassErrors cls(int64_t pixels, double flip) {
    ImageClassErrors c;
    c.pixels = pixels;
    c.relLuminanceMean = flip * 2.0;
    c.rmseLinear = flip * 0.5;
    c.flipMean = flip;
    return c;
}

// The sample report with layers on every ok run: layout i's coat error i + 1 tenths.
ReportModel layeredReport() {
    ReportModel m = test::sampleReport();
    double k = 1.0;
    for (RunReport& r : m.runs) {
        if (r.status != RunStatus::Ok || !r.image) continue;
        r.attributes[ErrorAttribute::Coat].all = stats(0.1 * k, 500);
        r.attributes[ErrorAttribute::Coat].dielectric = stats(0.1 * k, 500);
        r.attributes[ErrorAttribute::SheenColor].all = stats(2.0 * k, 300);
        r.attributes[ErrorAttribute::SheenColor].all->rmse = 0.05 * k;
        r.attributes[ErrorAttribute::AnisotropyDirection].all = stats(5.0 * k, 40);
        r.image->coated = cls(500, 0.01 * k);
        r.image->sheen = cls(300, 0.02 * k);
        r.image->plain = cls(1000, 0.001 * k);
        k += 1.0;
    }
    m.classSignificance = rankLayerClassesWithSignificance(m);
    return m;
}

TEST(ReportLayers, JsonWritesAndReadsThemBack) {
    const ReportModel model = layeredReport();
    ASSERT_TRUE(model.hasLayerMetrics());
    const Json j = reportToJson(model);
    const Json& run = j["runs"][0];
    ASSERT_TRUE(run["attribute_errors"].contains("coat"));
    EXPECT_EQ(run["attribute_errors"]["coat"]["over"], "coated");
    EXPECT_EQ(run["attribute_errors"]["coat"]["unit"], "absolute");
    EXPECT_EQ(run["attribute_errors"]["sheen_color"]["unit"], "delta_e_2000");
    EXPECT_EQ(run["attribute_errors"]["sheen_color"]["all"]["rmse"], 0.05);
    EXPECT_EQ(run["attribute_errors"]["anisotropy_direction"]["over"], "anisotropic");
    EXPECT_FALSE(run["attribute_errors"].contains("coat_roughness"));  // not measured: absent
    EXPECT_EQ(run["image_errors"]["by_class"]["coated"]["pixels"], 500);
    EXPECT_FALSE(run["image_errors"]["by_class"].contains("anisotropic"));
    // Ranked per class: the classes some run measured, in kLayerClasses order.
    ASSERT_TRUE(j.contains("significance_by_class"));
    std::vector<std::string> keys;
    for (const auto& [key, value] : j["significance_by_class"].items()) keys.push_back(key);
    EXPECT_EQ(keys, (std::vector<std::string>{"coated", "sheen", "plain"}));
    EXPECT_NE(j["significance_by_class"]["coated"]["method"].get<std::string>().find("coated"), std::string::npos);
    // Read back, written again byte for byte.
    const std::string text = j.dump(2);
    const ReportModel back = reportFromJson(Json::parse(text));
    EXPECT_EQ(reportToJson(back).dump(2), text);
    EXPECT_TRUE(back.runs[0].image->coated.has_value());
    EXPECT_EQ(back.classSignificance.size(), 3u);
}

TEST(ReportLayers, CsvColumnsOnlyWithLayers) {
    const ReportModel plain = test::sampleReport();
    ASSERT_FALSE(plain.hasLayerMetrics());
    const std::string plainCsv = reportCsv(plain);
    std::string header = plainCsv.substr(0, plainCsv.find('\n'));
    std::string expected;
    for (const std::string& c : reportCsvHeader()) expected += (expected.empty() ? "" : ",") + c;
    EXPECT_EQ(header, expected);  // the columns of every report before the layers
    EXPECT_EQ(header.find("coat"), std::string::npos);

    const ReportModel layered = layeredReport();
    const std::string csv = reportCsv(layered);
    header = csv.substr(0, csv.find('\n'));
    std::string withLayers;
    for (const std::string& c : reportCsvHeader(true)) withLayers += (withLayers.empty() ? "" : ",") + c;
    EXPECT_EQ(header, withLayers);
    for (const char* column : {",coat_all_mean_abs,", ",coat_normal_all_p99_deg,", ",sheen_color_all_rmse_linear,",
                               ",anisotropy_direction_all_max_deg,", ",image_coated_flip_mean,", ",image_plain_rmse_linear,",
                               ",coat_all_mean_abs_view_std,"})
        EXPECT_NE(header.find(column), std::string::npos) << column;
    // The layer columns come after the base attributes', before `views`; the base ones keep their order.
    EXPECT_LT(header.find(",depth_dielectric_max_rel,"), header.find(",coat_all_mean_abs,"));
    EXPECT_LT(header.find(",image_plain_reference_noise,"), header.find(",views,"));
    // The first run's coat mean, 0.1, in its column.
    const std::vector<std::string> names = reportCsvHeader(true);
    const size_t col = size_t(std::find(names.begin(), names.end(), "coat_all_mean_abs") - names.begin());
    // The second line's fields (RFC 4180: a quoted field may hold commas and doubled quotes).
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (size_t i = csv.find('\n') + 1; i < csv.size(); ++i) {
        const char ch = csv[i];
        if (quoted) {
            if (ch == '"' && i + 1 < csv.size() && csv[i + 1] == '"') fields.back() += '"', ++i;
            else if (ch == '"') quoted = false;
            else fields.back() += ch;
        } else if (ch == '"') {
            quoted = true;
        } else if (ch == ',') {
            fields.emplace_back();
        } else if (ch == '\n') {
            break;
        } else {
            fields.back() += ch;
        }
    }
    ASSERT_GE(fields.size(), names.size());  // then the bandwidth and status columns
    ASSERT_LT(col, names.size());
    EXPECT_EQ(fields[col], "0.1");
}

TEST(ReportLayers, HtmlSectionOnlyWithLayers) {
    EXPECT_EQ(reportHtml(test::sampleReport()).find("id=\"layers\""), std::string::npos);
    const std::string html = reportHtml(layeredReport());
    EXPECT_NE(html.find("id=\"layers\""), std::string::npos);
    EXPECT_NE(html.find("FLIP coated"), std::string::npos);
}

TEST(ReportLayers, ViewMeansAverageThem) {
    RunReport run;
    run.status = RunStatus::Ok;
    for (double coat : {0.2, 0.4}) {
        ViewMetrics v;
        v.attributes[ErrorAttribute::Coat].all = stats(coat, 10);
        ImageErrors e;
        e.coated = cls(10, coat / 10.0);
        v.image = e;
        run.views.push_back(v);
    }
    averageViews(run);
    ASSERT_TRUE(run.attributes[ErrorAttribute::Coat].all.has_value());
    EXPECT_NEAR(run.attributes[ErrorAttribute::Coat].all->error.mean, 0.3, 1e-15);
    EXPECT_EQ(run.attributes[ErrorAttribute::Coat].all->error.count, 20u);
    ASSERT_TRUE(run.image->coated.has_value());
    EXPECT_NEAR(run.image->coated->flipMean, 0.03, 1e-15);
    EXPECT_FALSE(run.image->sheen.has_value());
}

}  // namespace
}  // namespace gbl
