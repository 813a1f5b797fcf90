// The report writer without a browser: report.json round trips every field, report.csv has its
// header and one row per run, report.html holds every run, the sortable table, the plots and
// formatted numbers, and is self-contained.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <unistd.h>

#include "error.h"
#include "file_io.h"
#include "report_csv.h"
#include "report_html.h"
#include "report_json.h"
#include "report_sample.h"
#include "view_stats.h"
#include "temp_dir.h"
#include "user_error.h"

namespace gbl {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

struct TempDir : test::TempDir {
    TempDir() : test::TempDir("gbl_report_test_") {}
};

size_t countOf(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

void expectSameStats(const ScalarStats& a, const ScalarStats& b) {
    EXPECT_EQ(a.count, b.count);
    EXPECT_EQ(a.mean, b.mean);
    EXPECT_EQ(a.rms, b.rms);
    EXPECT_EQ(a.p99, b.p99);
    EXPECT_EQ(a.max, b.max);
}

void expectSameRun(const RunReport& a, const RunReport& b) {
    SCOPED_TRACE(a.layout + " / " + a.iblMode);
    EXPECT_EQ(a.layout, b.layout);
    EXPECT_EQ(a.title, b.title);
    EXPECT_EQ(a.source, b.source);
    EXPECT_EQ(a.pipeline, b.pipeline);
    EXPECT_EQ(a.iblMode, b.iblMode);
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.error, b.error);
    EXPECT_EQ(a.bytesPerPixel.targets, b.bytesPerPixel.targets);
    EXPECT_EQ(a.bytesPerPixel.depth, b.bytesPerPixel.depth);
    EXPECT_EQ(a.bytesPerPixel.lightBuffers, b.bytesPerPixel.lightBuffers);
    EXPECT_EQ(a.bytesPerPixel.total, b.bytesPerPixel.total);
    ASSERT_EQ(a.bandwidth.size(), b.bandwidth.size());
    for (size_t i = 0; i < a.bandwidth.size(); ++i) {
        const FrameTraffic &x = a.bandwidth[i], &y = b.bandwidth[i];
        EXPECT_EQ(x.width, y.width);
        EXPECT_EQ(x.height, y.height);
        EXPECT_EQ(x.samples, y.samples);
        EXPECT_EQ(x.geometryWriteBytes, y.geometryWriteBytes);
        EXPECT_EQ(x.lightingReadBytes, y.lightingReadBytes);
        EXPECT_EQ(x.lightBufferBytes, y.lightBufferBytes);
        EXPECT_EQ(x.totalBytes, y.totalBytes);
        EXPECT_EQ(x.litOutputBytes, y.litOutputBytes);
        EXPECT_EQ(x.onChipExternalBytes, y.onChipExternalBytes);
    }
    for (ErrorAttribute attr : kErrorAttributes) {
        SCOPED_TRACE(errorAttributeName(attr));
        for (auto member : {&AttributeErrors::all, &AttributeErrors::metal, &AttributeErrors::dielectric}) {
            const auto &x = a.attributes[attr].*member, &y = b.attributes[attr].*member;
            ASSERT_EQ(x.has_value(), y.has_value());
            if (!x) continue;
            expectSameStats(x->error, y->error);
            ASSERT_EQ(x->rmse.has_value(), y->rmse.has_value());
            if (x->rmse) {
                EXPECT_EQ(*x->rmse, *y->rmse);
            }
        }
    }
    ASSERT_EQ(a.image.has_value(), b.image.has_value());
    if (a.image) {
        EXPECT_EQ(a.image->rmseLinear, b.image->rmseLinear);
        EXPECT_EQ(a.image->psnrLinear, b.image->psnrLinear);
        EXPECT_EQ(a.image->rmseToneMapped, b.image->rmseToneMapped);
        EXPECT_EQ(a.image->psnrToneMapped, b.image->psnrToneMapped);
        EXPECT_EQ(a.image->maxAbs, b.image->maxAbs);
        EXPECT_EQ(a.image->p99Abs, b.image->p99Abs);
        EXPECT_EQ(a.image->flipMean, b.image->flipMean);
        EXPECT_EQ(a.image->flipMedian, b.image->flipMedian);
    }
    ASSERT_EQ(a.times.has_value(), b.times.has_value());
    if (a.times) {
        EXPECT_EQ(a.times->gbufferMs, b.times->gbufferMs);
        EXPECT_EQ(a.times->lightingMs, b.times->lightingMs);
        EXPECT_EQ(a.times->device, b.times->device);
    }
    EXPECT_EQ(a.images.render, b.images.render);
    EXPECT_EQ(a.images.errorHeatmap, b.images.errorHeatmap);
    EXPECT_EQ(a.images.flip, b.images.flip);
    EXPECT_EQ(a.images.normalError, b.images.normalError);
    EXPECT_EQ(a.images.difference, b.images.difference);
    EXPECT_EQ(a.images.errorsExr, b.images.errorsExr);
    ASSERT_EQ(a.images.crops.size(), b.images.crops.size());
    for (size_t i = 0; i < a.images.crops.size(); ++i) {
        const ReportCrop &x = a.images.crops[i], &y = b.images.crops[i];
        EXPECT_EQ(std::tie(x.x, x.y, x.w, x.h, x.reference, x.layout, x.heat),
                  std::tie(y.x, y.y, y.w, y.h, y.reference, y.layout, y.heat));
    }
}

void expectSameModel(const ReportModel& a, const ReportModel& b) {
    EXPECT_EQ(a.run.scene, b.run.scene);
    EXPECT_EQ(a.run.environment, b.run.environment);
    EXPECT_EQ(a.run.width, b.run.width);
    EXPECT_EQ(a.run.height, b.run.height);
    EXPECT_EQ(a.run.device.name, b.run.device.name);
    EXPECT_EQ(a.run.device.driver, b.run.device.driver);
    EXPECT_EQ(a.run.device.type, b.run.device.type);
    EXPECT_EQ(a.run.date, b.run.date);
    EXPECT_EQ(a.run.commandLine, b.run.commandLine);
    EXPECT_EQ(a.run.iblModes, b.run.iblModes);
    EXPECT_EQ(a.run.notes, b.run.notes);
    EXPECT_EQ(a.reference.layout, b.reference.layout);
    ASSERT_EQ(a.reference.images.size(), b.reference.images.size());
    for (size_t i = 0; i < a.reference.images.size(); ++i) {
        EXPECT_EQ(a.reference.images[i].iblMode, b.reference.images[i].iblMode);
        EXPECT_EQ(a.reference.images[i].render, b.reference.images[i].render);
    }
    ASSERT_EQ(a.runs.size(), b.runs.size());
    for (size_t i = 0; i < a.runs.size(); ++i) expectSameRun(a.runs[i], b.runs[i]);
}

// ---- JSON ----------------------------------------------------------------------------------------

TEST(ReportJson, RoundTripsEveryField) {
    const ReportModel model = test::sampleReport();
    const std::string text = reportToJson(model).dump(2);
    const ReportModel back = reportFromJson(Json::parse(text));
    expectSameModel(model, back);
    EXPECT_EQ(reportToJson(back).dump(2), text);  // and writes back byte for byte
    // Via the ADL hooks too.
    const Json viaHook = model;
    EXPECT_EQ(viaHook.dump(), reportToJson(model).dump());
    const ReportModel viaGet = viaHook.get<ReportModel>();
    expectSameModel(model, viaGet);
}

TEST(ReportJson, FieldNamesUnitsAndSpecialValues) {
    const ReportModel model = test::sampleReport();
    const Json j = reportToJson(model);
    EXPECT_EQ(j["schema"], "gbufferlab-report");
    EXPECT_EQ(j["schema_version"], kReportSchemaVersion);
    EXPECT_EQ(j["run"]["device"]["type"], "cpu");
    EXPECT_EQ(j["run"]["ibl_modes"], Json::array({"split-sum", "none"}));
    EXPECT_EQ(j["reference"]["images"][1]["render"], "reference/none/render.png");
    const Json& ue4 = j["runs"][0];
    EXPECT_EQ(ue4["status"], "ok");
    EXPECT_EQ(ue4["bytes_per_pixel"]["total"], 20);
    EXPECT_EQ(ue4["attribute_errors"]["normal"]["unit"], "degrees");
    EXPECT_EQ(ue4["attribute_errors"]["base_color"]["unit"], "delta_e_2000");
    EXPECT_EQ(ue4["attribute_errors"]["depth"]["unit"], "relative");
    EXPECT_TRUE(ue4["attribute_errors"]["base_color"]["all"].contains("rmse"));
    EXPECT_FALSE(ue4["attribute_errors"]["roughness"]["all"].contains("rmse"));
    EXPECT_FALSE(ue4["attribute_errors"]["depth"].contains("metal"));  // absent class stays absent
    EXPECT_TRUE(ue4["attribute_errors"]["depth"].contains("dielectric"));
    EXPECT_EQ(ue4["image_errors"]["psnr_tonemapped_db"], 41.5);
    EXPECT_EQ(ue4["pass_times_ms"]["lighting"], 1.25);
    EXPECT_EQ(ue4["images"]["crops"][0]["w"], 16);
    const Json& frame = ue4["bandwidth"][1];
    EXPECT_EQ(frame["width"], 1920);
    EXPECT_DOUBLE_EQ(frame["gb_per_s_at_60fps"].get<double>(), frame["total_bytes"].get<double>() * 60 / 1e9);
    // Non-finite numbers are strings, one representation for each (docs/report-schema.md): +inf
    // (identical images) "inf", -inf "-inf", NaN "nan"; all read back, and so does the null that
    // reports written before "nan" held.
    EXPECT_EQ(j["runs"][2]["image_errors"]["psnr_tonemapped_db"], "inf");
    ReportModel withNan = model;
    withNan.runs[0].image->flipMedian = std::nan("");
    withNan.runs[0].image->psnrLinear = -INFINITY;
    Json k = reportToJson(withNan);
    EXPECT_EQ(k["runs"][0]["image_errors"]["flip_median"], "nan");
    EXPECT_EQ(k["runs"][0]["image_errors"]["psnr_linear_db"], "-inf");
    const ReportModel back = reportFromJson(Json::parse(k.dump()));
    EXPECT_TRUE(std::isnan(back.runs[0].image->flipMedian));
    EXPECT_EQ(back.runs[0].image->psnrLinear, -INFINITY);
    EXPECT_EQ(back.runs[2].image->psnrToneMapped, INFINITY);
    k["runs"][0]["image_errors"]["flip_median"] = nullptr;
    EXPECT_TRUE(std::isnan(reportFromJson(Json::parse(k.dump())).runs[0].image->flipMedian));
    // Every double of a run goes through one writer: no number of the runs is null (null means
    // "not measured", in the visibility verdict only).
    std::vector<std::string> nulls;
    std::function<void(const Json&, const std::string&)> walk = [&](const Json& v, const std::string& at) {
        if (v.is_null()) nulls.push_back(at);
        if (v.is_object())
            for (const auto& [key, value] : v.items()) walk(value, at + "/" + key);
        if (v.is_array())
            for (size_t i = 0; i < v.size(); ++i) walk(v[i], at + "/" + std::to_string(i));
    };
    walk(reportToJson(withNan)["runs"], "/runs");
    EXPECT_TRUE(nulls.empty()) << nulls.front();
    // A failed run: no image errors, no times, no attributes.
    const Json& failed = j["runs"][6];
    EXPECT_EQ(failed["status"], "failed");
    EXPECT_NE(failed["error"].get<std::string>().find("octEncode"), std::string::npos);
    EXPECT_FALSE(failed.contains("image_errors"));
    EXPECT_FALSE(failed.contains("pass_times_ms"));
    EXPECT_TRUE(failed["attribute_errors"].empty());
}

using test::userErrorOf;

TEST(ReportJson, SchemaErrorsNameTheField) {
    const Json good = reportToJson(test::sampleReport());
    Json j = good;
    j["runs"][3].erase("layout");
    EXPECT_EQ(userErrorOf([&] { reportFromJson(j); }), "report.json: runs[3]: missing field \"layout\"");
    j = good;
    j["runs"][1]["image_errors"]["flip_mean"] = "lots";
    EXPECT_NE(userErrorOf([&] { reportFromJson(j); }).find("runs[1].image_errors.flip_mean: expected a number"),
              std::string::npos);
    j = good;
    j["schema_version"] = 99;
    EXPECT_NE(userErrorOf([&] { reportFromJson(j); }).find("schema_version: version 99"), std::string::npos);
    j = good;
    j["runs"][0]["status"] = "meh";
    EXPECT_NE(userErrorOf([&] { reportFromJson(j); }).find("runs[0].status"), std::string::npos);
    j = good;
    j["runs"][0]["attribute_errors"]["sheen"] = Json::object();
    EXPECT_NE(userErrorOf([&] { reportFromJson(j); }).find("attribute_errors.sheen: unknown attribute"),
              std::string::npos);
}

TEST(ReportJson, WritesAndReadsFiles) {
    TempDir dir;
    const ReportModel model = test::sampleReport();
    writeReportJson(dir.path / "report.json", model);
    expectSameModel(model, readReportJson(dir.path / "report.json"));
    writeFileAtomic(dir.path / "bad.json", std::string("{\"schema\": \"gbufferlab-report\""));
    // "FILE:LINE:COL: not valid JSON: ..." (the place of the parse error; here the end of the text)
    const std::string badJson = userErrorOf([&] { readReportJson(dir.path / "bad.json"); });
    EXPECT_EQ(badJson.rfind((dir.path / "bad.json").string() + ":1:", 0), 0u) << badJson;
    EXPECT_NE(badJson.find(": not valid JSON: "), std::string::npos) << badJson;
    for (const auto& entry : fs::directory_iterator(dir.path))  // atomic writes leave no temporaries
        EXPECT_TRUE(entry.path().filename() == "report.json" || entry.path().filename() == "bad.json")
            << entry.path();
}

// ---- Several views (compare --views) --------------------------------------------------------------

// A run's metrics are the mean of its views'; view_spread gives min, max and the population
// standard deviation of each; the JSON reads back to the same document.
TEST(ReportViews, MeanOverViewsAndSpreadRoundTrip) {
    ReportModel model = test::sampleReport();
    auto it = std::find_if(model.runs.begin(), model.runs.end(), [](const RunReport& r) { return r.image.has_value(); });
    ASSERT_NE(it, model.runs.end());
    RunReport& r = *it;
    ViewMetrics a{r.attributes, r.image}, b = a;
    b.image->flipMean = a.image->flipMean + 0.02;
    b.image->rmseLinear = a.image->rmseLinear * 3.0;
    r.views = {a, b};
    averageViews(r);
    EXPECT_NEAR(r.image->flipMean, a.image->flipMean + 0.01, 1e-12);
    EXPECT_NEAR(r.image->rmseLinear, a.image->rmseLinear * 2.0, 1e-12);
    model.run.views = {"scene camera", "orbit"};
    const nlohmann::ordered_json j = reportToJson(model);
    const auto& run = j["runs"][size_t(it - model.runs.begin())];
    const auto& s = run["view_spread"]["image_errors"]["flip_mean"];
    EXPECT_NEAR(s["mean"].get<double>(), r.image->flipMean, 1e-12);
    EXPECT_NEAR(s["std"].get<double>(), 0.01, 1e-12);
    EXPECT_EQ(s["min"].get<double>(), a.image->flipMean);
    EXPECT_EQ(s["max"].get<double>(), b.image->flipMean);
    EXPECT_EQ(s["views"], 2);
    EXPECT_FALSE(run["view_spread"]["attribute_errors"]["normal"]["all"].contains("count"));
    EXPECT_EQ(spreadOf({1.0, 3.0}).stddev, 1.0);
    EXPECT_EQ(spreadOf({2.0, 2.0, 2.0}).stddev, 0.0);
    const ReportModel back = reportFromJson(j);
    EXPECT_EQ(back.run.views, model.run.views);
    EXPECT_EQ(reportToJson(back), j);
}

// ---- CSV -----------------------------------------------------------------------------------------

// RFC 4180 reader: rows of fields.
std::vector<std::vector<std::string>> parseCsv(const std::string& text) {
    std::vector<std::vector<std::string>> rows(1);
    std::string field;
    bool quoted = false, fieldStarted = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char ch = text[i];
        if (quoted) {
            if (ch == '"' && i + 1 < text.size() && text[i + 1] == '"') field += '"', ++i;
            else if (ch == '"') quoted = false;
            else field += ch;
        } else if (ch == '"' && !fieldStarted) {
            quoted = fieldStarted = true;
        } else if (ch == ',') {
            rows.back().push_back(field), field.clear(), fieldStarted = false;
        } else if (ch == '\n') {
            rows.back().push_back(field), field.clear(), fieldStarted = false;
            rows.emplace_back();
        } else {
            field += ch, fieldStarted = true;
        }
    }
    if (rows.back().empty()) rows.pop_back();
    return rows;
}

TEST(ReportCsv, HeaderAndOneRowPerRun) {
    const ReportModel model = test::sampleReport();
    const std::string csv = reportCsv(model);
    const auto rows = parseCsv(csv);
    ASSERT_EQ(rows.size(), model.runs.size() + 1);
    const std::vector<std::string>& header = rows[0];
    EXPECT_EQ(header, reportCsvHeader());
    const std::vector<std::string> leading = {"layout", "title", "pipeline", "ibl_mode", "status", "error",
                                              "bytes_per_pixel_targets", "bytes_per_pixel_depth",
                                              "bytes_per_pixel_light_buffers", "bytes_per_pixel_total",
                                              "gb_per_s_1080p60"};
    EXPECT_TRUE(std::equal(leading.begin(), leading.end(), header.begin()));
    // Every attribute x class x statistic, with its unit; RMSE for colours only.
    // Image errors per class (covered, metal, dielectric) x 4 statistics are counted apart.
    // Then each metric's spread over views (compare --views): _view_min, _view_max, _view_std.
    size_t attributeColumns = 0, imageClassColumns = 0, spreadColumns = 0;
    for (const std::string& name : header) {
        const auto endsWith = [&](const std::string& tail) {
            return name.size() > tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
        };
        if (endsWith("_view_min") || endsWith("_view_max") || endsWith("_view_std")) {
            spreadColumns += 1;
            continue;
        }
        if (name.rfind("image_", 0) == 0) {
            imageClassColumns += 1;
            continue;
        }
        attributeColumns += name.find("_all_") != std::string::npos || name.find("_metal_") != std::string::npos ||
                            name.find("_dielectric_") != std::string::npos;
    }
    EXPECT_EQ(attributeColumns, 8u * 3u * 3u + 3u * 3u);  // 8 attributes x 3 classes x 3 stats, 3 colour RMSEs
    EXPECT_EQ(imageClassColumns, 3u * 4u);
    // 8 image metrics + HDR-FLIP + the class and attribute columns, each with 3 spread columns.
    EXPECT_EQ(spreadColumns, 3u * (8u + 1u + 3u * 4u + 8u * 3u * 3u + 3u * 3u));
    const auto column = [&](const std::string& name) {
        const auto it = std::find(header.begin(), header.end(), name);
        EXPECT_NE(it, header.end()) << name;
        return size_t(it - header.begin());
    };
    for (const char* name : {"normal_all_mean_deg", "normal_all_p99_deg", "base_color_all_mean_de2000",
                             "specular_color_dielectric_rmse_linear", "roughness_metal_max_abs", "depth_all_mean_rel",
                             "psnr_tonemapped_db", "psnr_linear_db", "flip_mean", "flip_median", "gbuffer_ms",
                             "lighting_ms", "max_abs", "p99_abs", "rmse_linear", "rmse_tonemapped"})
        column(name);
    EXPECT_EQ(std::count(header.begin(), header.end(), "roughness_all_rmse_linear"), 0);
    for (size_t i = 1; i < rows.size(); ++i) {
        ASSERT_EQ(rows[i].size(), header.size()) << "row " << i;
        EXPECT_EQ(rows[i][column("layout")], model.runs[i - 1].layout);
        EXPECT_EQ(rows[i][column("title")], model.runs[i - 1].title);  // commas / quotes survive
    }
    // Values read back exactly; absent ones are empty; +inf is "inf".
    const RunReport& ue4 = model.runs[0];
    EXPECT_EQ(std::stod(rows[1][column("flip_mean")]), ue4.image->flipMean);
    EXPECT_EQ(std::stod(rows[1][column("normal_metal_p99_deg")]), ue4.attributes[ErrorAttribute::Normal].metal->error.p99);
    EXPECT_EQ(std::stod(rows[1][column("gb_per_s_1080p60")]), *ue4.gigabytesPerSecond1080p60());
    EXPECT_EQ(rows[1][column("depth_metal_mean_rel")], "");
    EXPECT_EQ(rows[1][column("status")], "ok");
    EXPECT_EQ(rows[3][column("psnr_tonemapped_db")], "inf");
    const auto& failed = rows[7];
    EXPECT_EQ(failed[column("status")], "failed");
    EXPECT_EQ(failed[column("error")], model.runs[6].error);
    EXPECT_EQ(failed[column("bytes_per_pixel_light_buffers")], "8");
    EXPECT_EQ(failed[column("flip_mean")], "");
    EXPECT_EQ(failed[column("normal_all_mean_deg")], "");
    // Quoting.
    EXPECT_EQ(csvField("plain"), "plain");
    EXPECT_EQ(csvField("a,b"), "\"a,b\"");
    EXPECT_EQ(csvField("say \"hi\""), "\"say \"\"hi\"\"\"");
    EXPECT_EQ(csvField("two\nlines"), "\"two\nlines\"");
}

// ---- HTML ----------------------------------------------------------------------------------------

TEST(ReportFormat, Numbers) {
    EXPECT_EQ(formatSignificant(0.0123456, 3), "0.0123");
    EXPECT_EQ(formatSignificant(38.1234, 3), "38.1");
    EXPECT_EQ(formatSignificant(9.996, 3), "10.0");
    EXPECT_EQ(formatSignificant(1250, 3), "1250");
    EXPECT_EQ(formatSignificant(0.0, 3), "0");
    EXPECT_EQ(formatSignificant(-0.5, 2), "-0.50");
    EXPECT_EQ(formatSignificant(1.234e-7, 2), "1.2e-07");
    EXPECT_EQ(formatSignificant(3.5e8, 3), "3.50e+08");
    EXPECT_EQ(formatSignificant(INFINITY, 3), "\xE2\x88\x9E");
    EXPECT_EQ(formatFixed(41.499, 2), "41.50");
    EXPECT_EQ(formatFixed(-0.0001, 2), "0.00");
    EXPECT_EQ(formatFixed(INFINITY, 2), "\xE2\x88\x9E");
    EXPECT_EQ(formatFixed(-INFINITY, 2), "-\xE2\x88\x9E");
    EXPECT_EQ(formatFixed(std::nan(""), 2), "NaN");
    EXPECT_EQ(htmlEscape("<a href=\"x\">Tom & Jerry's</a>"),
              "&lt;a href=&quot;x&quot;&gt;Tom &amp; Jerry&#39;s&lt;/a&gt;");
    EXPECT_EQ(urlPathEscape("runs/my layout#1/render.png"), "runs/my%20layout%231/render.png");
    EXPECT_EQ(urlPathEscape("a/\xC3\xA9.png"), "a/%C3%A9.png");
}

TEST(ReportPareto, Front) {
    // (bytes, error): (12, .05) (16, .07: dominated) (20, .02) (44, 0) (20, .03: same bytes, worse)
    const std::vector<std::pair<double, double>> points = {{20, 0.02}, {12, 0.05}, {16, 0.07}, {44, 0.0}, {20, 0.03}};
    EXPECT_EQ(paretoFront(points, false), (std::vector<size_t>{1, 0, 3}));
    // Higher is better (PSNR), +inf the best of all.
    const std::vector<std::pair<double, double>> psnr = {{20, 41.5}, {12, 33.0}, {16, 30.0}, {44, INFINITY}, {50, 60}};
    EXPECT_EQ(paretoFront(psnr, true), (std::vector<size_t>{1, 0, 3}));
    EXPECT_EQ(paretoFront({{1, 1}, {1, 1}}, false), (std::vector<size_t>{0}));  // equal points: the first
    EXPECT_EQ(paretoFront({{1, std::nan("")}, {2, 1}}, false), (std::vector<size_t>{1}));
    EXPECT_TRUE(paretoFront({}, false).empty());
}

TEST(ReportHtml, HoldsEveryRunTheTableAndThePlots) {
    const ReportModel model = test::sampleReport();
    const std::string html = reportHtml(model);
    EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_NE(html.find("<meta charset=\"utf-8\">"), std::string::npos);
    // Header: the run info.
    for (const char* text : {"DamagedHelmet.gltf", "studio_small_03_1k.hdr", "64&times;36", "llvmpipe Mesa 22.3.6",
                             "2024-05-01T12:00:00Z", "split-sum, none", "reference-float",
                             "--out &quot;my report&quot;", "3 ringing texels clamped"})
        EXPECT_NE(html.find(text), std::string::npos) << text;
    // The table: one row per run, every column header, sortable.
    const size_t tableAt = html.find("<table id=\"layouts\" class=\"data sortable\">");
    ASSERT_NE(tableAt, std::string::npos);
    const std::string table = html.substr(tableAt, html.find("</table>", tableAt) - tableAt);
    EXPECT_EQ(countOf(table, "<tr"), model.runs.size() + 2);  // the group row, the header row, one per run
    for (const char* key : {"layout", "ibl", "bpp", "gbps", "normal_mean", "normal_p99", "albedo_de", "specular_de",
                            "roughness", "psnr", "flip", "status"})
        EXPECT_NE(table.find(std::string("data-key=\"") + key + "\""), std::string::npos) << key;
    EXPECT_NE(table.find("data-key=\"psnr\" data-dir=\"descending\""), std::string::npos);  // better first
    // Every run (layout names escaped) has a row linking to its section.
    for (const RunReport& r : model.runs) EXPECT_NE(table.find(">" + htmlEscape(r.layout) + "</a>"), std::string::npos);
    for (const char* id : {"run-ue4-split-sum", "run-compact-octahedral-split-sum", "run-fat-naive-split-sum",
                           "run-ryse-split-sum", "run-ue4-none", "run-compact-octahedral-none",
                           "run-broken-layout-split-sum"}) {
        EXPECT_NE(table.find(std::string("href=\"#") + id + "\""), std::string::npos) << id;
        EXPECT_NE(html.find(std::string("<section class=\"layout\" id=\"") + id + "\""), std::string::npos) << id;
    }
    // Numbers: formatted in the cell, full precision for sorting; ∞ for identical images.
    EXPECT_NE(table.find("data-v=\"0.0213\">0.0213</td>"), std::string::npos);  // FLIP mean, 4 decimals
    EXPECT_NE(table.find("data-v=\"41.5\">41.50</td>"), std::string::npos);     // PSNR, 2 decimals
    EXPECT_NE(table.find("data-v=\"Infinity\">\xE2\x88\x9E</td>"), std::string::npos);
    EXPECT_NE(table.find(">20</td>"), std::string::npos);                       // bytes per pixel
    const double gbps = *model.runs[0].gigabytesPerSecond1080p60();
    EXPECT_NE(table.find(">" + formatFixed(gbps, 2) + "</td>"), std::string::npos);
    // The failed run: in red (class), with its error escaped, and no script injected.
    EXPECT_NE(table.find("<tr class=\"failed\">"), std::string::npos);
    EXPECT_NE(html.find("no matching overloaded function &lt;script&gt;x&lt;/script&gt;"), std::string::npos);
    EXPECT_EQ(html.find("<script>x</script>"), std::string::npos);
    EXPECT_NE(html.find("<div class=\"errorbox\">"), std::string::npos);
    // Images beside the reference, with the crops.
    EXPECT_NE(html.find("src=\"reference/split-sum/render.png\""), std::string::npos);
    EXPECT_NE(html.find("src=\"reference/none/render.png\""), std::string::npos);
    for (const char* file : {"render.png", "error_heatmap.png", "flip.png", "normal_error.png", "difference.png",
                             "crop0_reference.png", "crop0_layout.png", "crop0_heat.png"})
        EXPECT_NE(html.find(std::string("src=\"runs/ue4-split-sum/") + file + "\""), std::string::npos) << file;
    EXPECT_NE(html.find("href=\"runs/ue4-split-sum/errors.exr\""), std::string::npos);
    // Three plots (FLIP on a log axis shown; FLIP on a linear axis and PSNR hidden) with Pareto
    // fronts, labelled points and a legend.
    EXPECT_NE(html.find("<figure class=\"plot\" id=\"plot-flip\">"), std::string::npos);
    EXPECT_NE(html.find("<figure class=\"plot\" id=\"plot-flip-linear\" hidden>"), std::string::npos);
    EXPECT_NE(html.find("<figure class=\"plot\" id=\"plot-psnr\" hidden>"), std::string::npos);
    EXPECT_EQ(countOf(html, "<svg xmlns"), 3u);
    EXPECT_EQ(countOf(html, "class=\"pareto\""), 6u);  // per plot, per IBL mode (no visibility buffer here)
    EXPECT_EQ(countOf(html, "</title></circle>"), 3u * 6u);  // points; the failed run is not plotted
    EXPECT_NE(html.find(">compact-octahedral</text>"), std::string::npos);
    EXPECT_NE(html.find("Pareto front"), std::string::npos);
    EXPECT_NE(html.find("layouts, IBL split-sum"), std::string::npos);
    // Self-contained: no external resources.
    for (const char* external : {"src=\"http", "href=\"http", "<link", "@import", "url(http", "//cdn"})
        EXPECT_EQ(html.find(external), std::string::npos) << external;
}

TEST(ReportHtml, ParetoFrontOfTheFlipPlot) {
    const ReportModel model = test::sampleReport();
    const std::string html = reportHtml(model);
    const size_t flip = html.find("id=\"plot-flip\"");
    const std::string plot = html.substr(flip, html.find("</figure>", flip) - flip);
    // split-sum: compact-octahedral (12 B) -> ue4 (20 B) -> fat-naive (44 B, exact); ryse (16 B) is dominated.
    const size_t line = plot.find("class=\"pareto\"");
    ASSERT_NE(line, std::string::npos);
    const std::string points = plot.substr(plot.find("points=\"", line) + 8);
    EXPECT_EQ(std::count(points.begin(), points.begin() + long(points.find('"')), ','), 3);
}

TEST(ReportHtml, EmptyAndAllFailedModels) {
    ReportModel empty;
    const std::string html = reportHtml(empty);
    EXPECT_NE(html.find("No measured runs to plot."), std::string::npos);
    EXPECT_NE(html.find("</html>"), std::string::npos);
    ReportModel failed = test::sampleReport();
    for (RunReport& r : failed.runs) r.status = RunStatus::Failed, r.error = "device lost", r.image.reset();
    EXPECT_EQ(countOf(reportHtml(failed), "<tr class=\"failed\">"), failed.runs.size());
}

TEST(Report, WritesAllThreeFilesAtomically) {
    TempDir dir;
    ReportModel model = test::sampleReport();
    // A big comparison: 40 layouts x 2 IBL modes.
    const ReportModel base = model;
    for (int i = 0; i < 40; ++i)
        for (const std::string ibl : {"split-sum", "none"})
            model.runs.push_back(test::sampleRun("layout-" + std::to_string(i), ibl, 8 + i, 0.002 * (40 - i) + 0.001,
                                                 30 + i * 0.4));
    const auto start = std::chrono::steady_clock::now();
    writeReport(dir.path / "out", model);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const auto htmlStart = std::chrono::steady_clock::now();
    writeReportHtml(dir.path / "out" / "report.html", model);
    const double htmlMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - htmlStart).count();
    std::printf("[ info ] %zu runs: report.html+json+csv written in %.1f ms (html alone %.1f ms, %zu KiB)\n",
                model.runs.size(), ms, htmlMs, size_t(fs::file_size(dir.path / "out" / "report.html") / 1024));
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir.path / "out")) names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"report.csv", "report.html", "report.json"}));  // no temporaries
    EXPECT_EQ(readTextFile(dir.path / "out" / "report.html"), reportHtml(model));
    EXPECT_EQ(readTextFile(dir.path / "out" / "report.csv"), reportCsv(model));
    expectSameModel(model, readReportJson(dir.path / "out" / "report.json"));
    // A directory that cannot be made is a UserError naming it.
    writeFileAtomic(dir.path / "file", std::string("x"));
    EXPECT_NE(userErrorOf([&] { writeReport(dir.path / "file" / "sub", base); }).find((dir.path / "file").string()),
              std::string::npos);
}

// A view with nothing to measure gave "PSNR inf, FLIP 0.0000" and ties; such a view is marked
// not measured with its reason in report.json, report.csv and report.html, and a run with no view
// measured has no numbers and its own status. An interrupted report's CSV says so on every row.
TEST(ReportNotMeasured, EveryFileSaysWhichViewsWereLeftOutAndWhy) {
    ReportModel m = test::sampleReport();
    const std::string why = "the reference tone-maps to all black at exposure 1e-30, where no layout's error can show";
    m.run.viewNotMeasured = {why};
    for (RunReport& r : m.runs) {
        if (r.status != RunStatus::Ok) continue;
        r.status = RunStatus::NotMeasured;
        r.notMeasured = "view 0: " + why;
        r.attributes = {};
        r.image.reset();
    }
    const Json j = reportToJson(m);
    EXPECT_EQ(j["run"]["view_not_measured"][0], why);
    EXPECT_EQ(j["runs"][0]["status"], "not-measured");
    EXPECT_EQ(j["runs"][0]["not_measured"], "view 0: " + why);
    EXPECT_FALSE(j["runs"][0].contains("image_errors"));
    EXPECT_FALSE(j.contains("verdict")) << "a verdict of nothing measured";
    const ReportModel back = reportFromJson(j);
    EXPECT_EQ(back.runs[0].status, RunStatus::NotMeasured);
    EXPECT_EQ(back.runs[0].notMeasured, m.runs[0].notMeasured);
    EXPECT_EQ(back.run.viewNotMeasured, m.run.viewNotMeasured);
    const auto rows = parseCsv(reportCsv(m));
    const auto& header = rows[0];
    const auto column = [&](const std::string& name) {
        return size_t(std::find(header.begin(), header.end(), name) - header.begin());
    };
    ASSERT_LT(column("not_measured"), header.size());
    EXPECT_EQ(rows[1][column("status")], "not-measured");
    EXPECT_EQ(rows[1][column("not_measured")], "view 0: " + why);
    EXPECT_EQ(rows[1][column("flip_mean")], "");
    EXPECT_EQ(rows[1][column("report_status")], "complete");
    const std::string html = reportHtml(m);
    EXPECT_NE(html.find("View 0 not measured:</strong> " + htmlEscape(why)), std::string::npos);
    EXPECT_NE(html.find("<td>not measured<div"), std::string::npos);
    // Interrupted: every row of the CSV says so.
    m.interruption = ReportInterruption{"SIGTERM", 2, 5, {}};
    const auto interrupted = parseCsv(reportCsv(m));
    EXPECT_EQ(interrupted[1][column("report_status")], "interrupted by SIGTERM");
    EXPECT_NE(reportHtml(m).find("interrupted by SIGTERM after 2 of 5 runs"), std::string::npos);
}

}  // namespace
}  // namespace gbl
