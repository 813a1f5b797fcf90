#include "report_json.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "error.h"
#include "file_io.h"
#include "budget_verdict.h"
#include "json_number.h"
#include "report_atlas.h"
#include "view_stats.h"
#include "visibility_verdict.h"

namespace gbl {
namespace {
using Json = nlohmann::ordered_json;

// ---- Writing ------------------------------------------------------------------------------------

Json number(double v) { return jsonNumber(v); }

Json statsJson(const ScalarStats& s) {
    return Json{{"count", s.count}, {"mean", number(s.mean)}, {"rms", number(s.rms)},
                {"p99", number(s.p99)}, {"max", number(s.max)}};
}

Json attributeStatsJson(const AttributeStats& a) {
    Json j = statsJson(a.error);
    if (a.rmse) j["rmse"] = number(*a.rmse);
    return j;
}

Json attributesJson(const AttributeErrorTable& table) {
    Json j = Json::object();
    for (ErrorAttribute a : kErrorAttributes) {
        const AttributeErrors& e = table[a];
        if (e.empty()) continue;
        Json entry{{"unit", errorAttributeUnit(a)}};
        if (e.all) entry["all"] = attributeStatsJson(*e.all);
        if (e.metal) entry["metal"] = attributeStatsJson(*e.metal);
        if (e.dielectric) entry["dielectric"] = attributeStatsJson(*e.dielectric);
        j[errorAttributeName(a)] = std::move(entry);
    }
    return j;
}

Json frameJson(const FrameTraffic& f) {
    return Json{{"width", f.width},
                {"height", f.height},
                {"samples", f.samples},
                {"geometry_write_bytes", number(f.geometryWriteBytes)},
                {"lighting_read_bytes", number(f.lightingReadBytes)},
                {"light_buffer_bytes", number(f.lightBufferBytes)},
                {"total_bytes", number(f.totalBytes)},
                {"gb_per_s_at_60fps", number(f.gigabytesPerSecond(60.0))},
                {"lit_output_bytes", number(f.litOutputBytes)},
                {"on_chip_external_bytes", number(f.onChipExternalBytes)},
                {"vertex_fetch_bytes", number(f.vertexFetchBytes)},
                {"texture_fetch_bytes", number(f.textureFetchBytes)}};
}

Json imageErrorsJson(const ImageErrors& e) {
    Json j{{"rmse_linear", number(e.rmseLinear)},
                {"psnr_linear_db", number(e.psnrLinear)},
                {"rmse_tonemapped", number(e.rmseToneMapped)},
                {"psnr_tonemapped_db", number(e.psnrToneMapped)},
                {"max_abs", number(e.maxAbs)},
                {"p99_abs", number(e.p99Abs)},
                {"flip_mean", number(e.flipMean)},
                {"flip_median", number(e.flipMedian)}};
    if (e.hdrFlipMean) {
        j["hdr_flip_mean"] = number(*e.hdrFlipMean);
        j["hdr_flip_exposures"] = e.hdrFlipExposures;
    }
    Json classes = Json::object();
    auto put = [&](const char* key, const std::optional<ImageClassErrors>& c) {
        if (!c) return;
        Json k{{"pixels", c->pixels},
               {"rel_luminance_mean", number(c->relLuminanceMean)},
               {"rmse_linear", number(c->rmseLinear)},
               {"flip_mean", number(c->flipMean)}};
        if (c->referenceNoise) k["reference_noise"] = number(*c->referenceNoise);
        classes[key] = std::move(k);
    };
    put("covered", e.covered);
    put("metal", e.metal);
    put("dielectric", e.dielectric);
    if (!classes.empty()) j["by_class"] = std::move(classes);
    return j;
}

Json groundTruthJson(const GroundTruthConvergence& g) {
    return Json{{"batches", g.batches},
                {"samples_per_pixel", g.samplesPerPixel},
                {"noise_target", number(g.noiseTarget)},
                {"mean_relative_noise", number(g.meanRelativeNoise)},
                {"target_met", g.targetMet},
                {"gpu_ms", number(g.gpuMs)}};
}

Json iblFigureJson(const IblFigure& f) {
    Json rows = Json::array();
    for (const IblFigureRow& r : f.rows) {
        Json row{{"ibl_mode", r.iblMode}, {"caption", r.caption}};
        if (r.metalError) row["metal_error"] = number(*r.metalError);
        if (r.dielectricError) row["dielectric_error"] = number(*r.dielectricError);
        if (r.metalNoise) row["metal_noise"] = number(*r.metalNoise);
        if (r.dielectricNoise) row["dielectric_noise"] = number(*r.dielectricNoise);
        rows.push_back(std::move(row));
    }
    return Json{{"png", f.png}, {"columns", f.columns}, {"rows", std::move(rows)}};
}

Json verdictEntryJson(const VerdictEntry& e) {
    return Json{{"layout", e.layout},
                {"bytes_per_pixel", e.bytesPerPixel},
                {"counted_bytes_per_pixel", number(e.countedBytes)},
                {"flip_mean", number(e.flipMean)}};
}

// The verdict per byte budget (budget_verdict.h); derived from the runs, not read back.
Json verdictJson(const BudgetVerdict& v) {
    Json budgets = Json::array();
    for (const BudgetLine& line : v.lines) {
        Json b{{"budget_bytes_per_pixel", line.budget ? Json(*line.budget) : number(INFINITY)}};
        if (line.best) b["best"] = verdictEntryJson(*line.best);
        Json tied = Json::array();
        for (const VerdictEntry& e : line.tiedWith) tied.push_back(verdictEntryJson(e));
        b["tied_with"] = std::move(tied);
        if (line.smallest) b["smallest"] = verdictEntryJson(*line.smallest);
        b["sentence"] = line.sentence;
        budgets.push_back(std::move(b));
    }
    return Json{{"ibl_mode", v.iblMode},
                {"metric", "flip_mean"},
                {"views", v.views},
                {"basis", v.basis},
                {"budgets", std::move(budgets)}};
}

// The atlas table (report_atlas.h), flat in its grouped order: one object per layout.
Json significanceJson(const SignificanceReport& s) {
    Json pairs = Json::array(), ranks = Json::array();
    for (const PairSignificance& p : s.pairs)
        pairs.push_back(Json{{"better", p.better},
                             {"worse", p.worse},
                             {"ibl_mode", p.iblMode},
                             {"mean_difference", number(p.meanDifference)},
                             {"units", p.units},
                             {"p_value", number(p.pValue)},
                             {"significant", p.significant}});
    for (const RankRange& r : s.ranks)
        ranks.push_back(Json{{"layout", r.layout},
                             {"ibl_mode", r.iblMode},
                             {"mean_error", number(r.meanError)},
                             {"rank", r.rank},
                             {"rank_low", r.low},
                             {"rank_high", r.high},
                             {"tied_rank", r.text()}});
    return Json{{"method", s.method}, {"pairs", std::move(pairs)}, {"ranks", std::move(ranks)}};
}

Json atlasJson(const ReportModel& model) {
    Json rows = Json::array();
    for (const AtlasRowGroup& g : atlasRows(model))
        for (const AtlasRow& r : g.rows) {
            const AtlasEntry& e = r.entry;
            Json attributes = Json::array();
            for (const AtlasAttribute& a : e.attributes)
                attributes.push_back(Json{{"name", a.name}, {"bits", a.bits}, {"encoding", a.encoding}});
            Json row{{"family", e.family},
                     {"layout", e.layout},
                     {"engine", e.engine},
                     {"title", e.title},
                     {"year", e.year},
                     {"bytes_per_pixel", e.bytesPerPixel},
                     {"bytes_kind", e.bytesKind},
                     {"light_buffer_bytes_per_pixel", e.lightBufferBytesPerPixel},
                     {"attributes", std::move(attributes)}};
            if (e.provenance.entries > 0) {
                const ProvenanceCounts& p = e.provenance;
                row["provenance"] = Json{{"entries", p.entries}, {"verified", p.verified}, {"talk", p.talk},
                                         {"lineage", p.lineage}, {"assumed", p.assumed},  {"own", p.own},
                                         {"missing", p.missing}, {"differs", p.differs}, {"text", p.text()}};
            }
            if (!r.iblMode.empty()) row["ibl_mode"] = r.iblMode;
            if (r.flipMean) row["flip_mean"] = number(*r.flipMean);
            if (r.psnrToneMapped) row["psnr_tonemapped_db"] = number(*r.psnrToneMapped);
            rows.push_back(std::move(row));
        }
    return rows;
}

Json imagesJson(const RunImages& images) {
    Json crops = Json::array();
    for (const ReportCrop& c : images.crops)
        crops.push_back(Json{{"x", c.x}, {"y", c.y}, {"w", c.w}, {"h", c.h},
                             {"reference", c.reference}, {"layout", c.layout}, {"heat", c.heat}});
    return Json{{"render", images.render},         {"render_exr", images.renderExr},
                {"hdr_preview", images.hdrPreview},         {"error_heatmap", images.errorHeatmap},
                {"flip", images.flip},             {"normal_error", images.normalError},
                {"difference", images.difference}, {"errors_exr", images.errorsExr},
                {"crops", std::move(crops)}};
}

// Every number under `views[0]` (attribute_errors, image_errors), as a spread over all views:
// {mean, min, max, std} at the same path. A leaf missing from some views is taken over the others.
void collectLeaves(const Json& j, const std::string& path, std::vector<std::string>& paths) {
    if (j.is_object()) {
        for (const auto& [k, v] : j.items()) collectLeaves(v, path + "/" + k, paths);
    } else if (j.is_number() || (j.is_string() && (j == "inf" || j == "-inf" || j == "nan"))) {
        paths.push_back(path);
    }
}

Json viewSpreadJson(const Json& views) {
    std::vector<std::string> paths;
    for (const Json& v : views) {
        std::vector<std::string> p;
        collectLeaves(v, "", p);
        for (const std::string& s : p)
            if (std::find(paths.begin(), paths.end(), s) == paths.end()) paths.push_back(s);
    }
    Json out = Json::object();
    for (const std::string& path : paths) {
        auto endsWith = [&](const std::string& tail) {
            return path.size() >= tail.size() && path.compare(path.size() - tail.size(), tail.size(), tail) == 0;
        };
        // Counts are not metrics (their sum over views is the run's).
        if (path == "/view" || endsWith("/count") || endsWith("/pixels") || endsWith("/hdr_flip_exposures")) continue;
        std::vector<double> values;
        const Json::json_pointer ptr(path);
        for (const Json& v : views) {
            if (!v.contains(ptr)) continue;
            const Json& x = v.at(ptr);
            if (double d; !x.is_null() && readJsonNumber(x, d)) values.push_back(d);
        }
        const ViewSpread s = spreadOf(values);
        out[ptr] = Json{{"mean", number(s.mean)}, {"min", number(s.min)}, {"max", number(s.max)},
                        {"std", number(s.stddev)}, {"views", s.n}};
    }
    return out;
}

Json runJson(const RunReport& r) {
    Json j{{"layout", r.layout},
           {"title", r.title},
           {"source", r.source},
           {"pipeline", r.pipeline},
           {"ibl_mode", r.iblMode},
           {"status", runStatusName(r.status)},
           {"error", r.error},
           {"bytes_per_pixel", Json{{"targets", r.bytesPerPixel.targets},
                                    {"depth", r.bytesPerPixel.depth},
                                    {"light_buffers", r.bytesPerPixel.lightBuffers},
                                    {"total", r.bytesPerPixel.total}}}};
    Json frames = Json::array();
    for (const FrameTraffic& f : r.bandwidth) frames.push_back(frameJson(f));
    j["bandwidth"] = std::move(frames);
    j["attribute_errors"] = attributesJson(r.attributes);
    if (r.image) j["image_errors"] = imageErrorsJson(*r.image);
    if (r.groundTruth) j["ground_truth"] = groundTruthJson(*r.groundTruth);
    if (r.times)
        j["pass_times_ms"] = Json{{"gbuffer", number(r.times->gbufferMs)},
                                  {"lighting", number(r.times->lightingMs)},
                                  {"device", r.times->device}};
    j["images"] = imagesJson(r.images);
    if (!r.views.empty()) {
        Json views = Json::array();
        for (size_t i = 0; i < r.views.size(); ++i) {
            Json v{{"view", int(i)}, {"attribute_errors", attributesJson(r.views[i].attributes)}};
            if (r.views[i].image) v["image_errors"] = imageErrorsJson(*r.views[i].image);
            views.push_back(std::move(v));
        }
        j["view_spread"] = viewSpreadJson(views);
        j["views"] = std::move(views);
    }
    if (r.singleFrame) {  // compare --temporal N: frame 0 alone, beside the resolve above
        Json single{{"attribute_errors", attributesJson(r.singleFrame->attributes)}};
        if (r.singleFrame->image) single["image_errors"] = imageErrorsJson(*r.singleFrame->image);
        j["single_frame"] = std::move(single);
    }
    return j;
}

// ---- Reading ------------------------------------------------------------------------------------

// A JSON value and where it is ("runs[2].image_errors"), for error messages.
struct Node {
    const Json& j;
    std::string where;

    [[noreturn]] void fail(const std::string& what) const {
        throwUserError("report.json: " + (where.empty() ? std::string("the document") : where) + ": " + what);
    }
    std::string child(const std::string& key) const { return where.empty() ? key : where + "." + key; }
    bool has(const char* key) const { return j.is_object() && j.contains(key); }
    Node operator[](const char* key) const {
        if (!j.is_object()) fail("expected an object");
        const auto it = j.find(key);
        if (it == j.end()) fail("missing field \"" + std::string(key) + "\"");
        return {*it, child(key)};
    }
    Node at(size_t i) const { return {j[i], where + "[" + std::to_string(i) + "]"}; }
    const Json& array() const {
        if (!j.is_array()) fail("expected an array");
        return j;
    }
    void object() const {
        if (!j.is_object()) fail("expected an object");
    }
    std::string str() const {
        if (!j.is_string()) fail("expected a string");
        return j.get<std::string>();
    }
    double num() const {
        if (double v; readJsonNumber(j, v)) return v;
        fail("expected a number (or \"inf\", \"-inf\", \"nan\"; null from older reports)");
    }
    long long integer(long long lo, long long hi) const {
        if (!j.is_number_integer()) fail("expected an integer");
        const long long v = j.get<long long>();
        if (v < lo || v > hi) fail("value " + std::to_string(v) + " out of range");
        return v;
    }
    int i32() const { return int(integer(INT32_MIN, INT32_MAX)); }
    std::vector<std::string> strings() const {
        std::vector<std::string> out;
        for (size_t i = 0; i < array().size(); ++i) out.push_back(at(i).str());
        return out;
    }
};

ScalarStats readStats(const Node& n) {
    ScalarStats s;
    s.count = size_t(n["count"].integer(0, INT64_MAX));
    s.mean = n["mean"].num();
    s.rms = n["rms"].num();
    s.p99 = n["p99"].num();
    s.max = n["max"].num();
    return s;
}

AttributeStats readAttributeStats(const Node& n) {
    AttributeStats a;
    a.error = readStats(n);
    if (n.has("rmse")) a.rmse = n["rmse"].num();
    return a;
}

AttributeErrorTable readAttributes(const Node& n) {
    n.object();
    AttributeErrorTable table;
    for (auto it = n.j.begin(); it != n.j.end(); ++it) {
        const Node entry{it.value(), n.child(it.key())};
        bool known = false;
        for (ErrorAttribute a : kErrorAttributes) {
            if (it.key() != errorAttributeName(a)) continue;
            known = true;
            if (entry["unit"].str() != errorAttributeUnit(a))
                entry["unit"].fail("expected \"" + std::string(errorAttributeUnit(a)) + "\"");
            AttributeErrors& e = table[a];
            if (entry.has("all")) e.all = readAttributeStats(entry["all"]);
            if (entry.has("metal")) e.metal = readAttributeStats(entry["metal"]);
            if (entry.has("dielectric")) e.dielectric = readAttributeStats(entry["dielectric"]);
        }
        if (!known) entry.fail("unknown attribute");
    }
    return table;
}

FrameTraffic readFrame(const Node& n) {
    FrameTraffic f;
    f.width = uint32_t(n["width"].integer(0, UINT32_MAX));
    f.height = uint32_t(n["height"].integer(0, UINT32_MAX));
    f.samples = n["samples"].i32();
    f.geometryWriteBytes = n["geometry_write_bytes"].num();
    f.lightingReadBytes = n["lighting_read_bytes"].num();
    f.lightBufferBytes = n["light_buffer_bytes"].num();
    f.totalBytes = n["total_bytes"].num();
    f.litOutputBytes = n["lit_output_bytes"].num();
    f.onChipExternalBytes = n["on_chip_external_bytes"].num();
    if (n.has("vertex_fetch_bytes")) f.vertexFetchBytes = n["vertex_fetch_bytes"].num();  // absent before the visibility buffer
    if (n.has("texture_fetch_bytes")) f.textureFetchBytes = n["texture_fetch_bytes"].num();
    return f;  // gb_per_s_at_60fps is derived from total_bytes
}

ImageErrors readImageErrors(const Node& n) {
    ImageErrors e;
    e.rmseLinear = n["rmse_linear"].num();
    e.psnrLinear = n["psnr_linear_db"].num();
    e.rmseToneMapped = n["rmse_tonemapped"].num();
    e.psnrToneMapped = n["psnr_tonemapped_db"].num();
    e.maxAbs = n["max_abs"].num();
    e.p99Abs = n["p99_abs"].num();
    e.flipMean = n["flip_mean"].num();
    e.flipMedian = n["flip_median"].num();
    if (n.has("hdr_flip_mean")) {
        e.hdrFlipMean = n["hdr_flip_mean"].num();
        e.hdrFlipExposures = int(n["hdr_flip_exposures"].num());
    }
    if (n.has("by_class")) {
        const Node classes = n["by_class"];
        auto get = [&](const char* key, std::optional<ImageClassErrors>& out) {
            if (!classes.has(key)) return;
            const Node c = classes[key];
            ImageClassErrors k;
            k.pixels = int64_t(c["pixels"].num());
            k.relLuminanceMean = c["rel_luminance_mean"].num();
            k.rmseLinear = c["rmse_linear"].num();
            k.flipMean = c["flip_mean"].num();
            if (c.has("reference_noise")) k.referenceNoise = c["reference_noise"].num();
            out = k;
        };
        get("covered", e.covered);
        get("metal", e.metal);
        get("dielectric", e.dielectric);
    }
    return e;
}

RunImages readImages(const Node& n) {
    RunImages images;
    images.render = n["render"].str();
    if (n.has("render_exr")) images.renderExr = n["render_exr"].str();
    if (n.has("hdr_preview")) images.hdrPreview = n["hdr_preview"].str();
    images.errorHeatmap = n["error_heatmap"].str();
    images.flip = n["flip"].str();
    images.normalError = n["normal_error"].str();
    images.difference = n["difference"].str();
    images.errorsExr = n["errors_exr"].str();
    const Node crops = n["crops"];
    for (size_t i = 0; i < crops.array().size(); ++i) {
        const Node c = crops.at(i);
        images.crops.push_back({c["x"].i32(), c["y"].i32(), c["w"].i32(), c["h"].i32(), c["reference"].str(),
                                c["layout"].str(), c["heat"].str()});
    }
    return images;
}

RunReport readRun(const Node& n) {
    RunReport r;
    r.layout = n["layout"].str();
    r.title = n["title"].str();
    r.source = n["source"].str();
    r.pipeline = n["pipeline"].str();
    r.iblMode = n["ibl_mode"].str();
    const std::string status = n["status"].str();
    if (status == "ok") r.status = RunStatus::Ok;
    else if (status == "failed") r.status = RunStatus::Failed;
    else n["status"].fail("expected \"ok\" or \"failed\", not \"" + status + "\"");
    r.error = n["error"].str();
    const Node bpp = n["bytes_per_pixel"];
    r.bytesPerPixel = {bpp["targets"].i32(), bpp["depth"].i32(), bpp["light_buffers"].i32(), bpp["total"].i32()};
    const Node frames = n["bandwidth"];
    for (size_t i = 0; i < frames.array().size(); ++i) r.bandwidth.push_back(readFrame(frames.at(i)));
    r.attributes = readAttributes(n["attribute_errors"]);
    if (n.has("image_errors")) r.image = readImageErrors(n["image_errors"]);
    if (n.has("ground_truth")) {
        const Node g = n["ground_truth"];
        GroundTruthConvergence c;
        c.batches = g["batches"].i32();
        c.samplesPerPixel = g["samples_per_pixel"].i32();
        c.noiseTarget = g["noise_target"].num();
        c.meanRelativeNoise = g["mean_relative_noise"].num();
        if (!g["target_met"].j.is_boolean()) g["target_met"].fail("expected true or false");
        c.targetMet = g["target_met"].j.get<bool>();
        c.gpuMs = g["gpu_ms"].num();
        r.groundTruth = c;
    }
    if (n.has("pass_times_ms")) {
        const Node t = n["pass_times_ms"];
        r.times = PassTimes{t["gbuffer"].num(), t["lighting"].num(), t["device"].str()};
    }
    r.images = readImages(n["images"]);
    if (n.has("views")) {
        const Node views = n["views"];
        for (size_t i = 0; i < views.array().size(); ++i) {
            const Node v = views.at(i);
            ViewMetrics m;
            m.attributes = readAttributes(v["attribute_errors"]);
            if (v.has("image_errors")) m.image = readImageErrors(v["image_errors"]);
            r.views.push_back(std::move(m));
        }
    }
    if (n.has("single_frame")) {
        const Node single = n["single_frame"];
        SingleFrameMetrics m;
        m.attributes = readAttributes(single["attribute_errors"]);
        if (single.has("image_errors")) m.image = readImageErrors(single["image_errors"]);
        r.singleFrame = std::move(m);
    }
    return r;
}

}  // namespace

Json reportToJson(const ReportModel& model) {
    const ReportRunInfo& run = model.run;
    Json references = Json::array();
    for (const ReferenceImage& image : model.reference.images)
        references.push_back(
            Json{{"ibl_mode", image.iblMode}, {"render", image.render}, {"render_exr", image.renderExr},
                 {"hdr_preview", image.hdrPreview}});
    Json runs = Json::array();
    for (const RunReport& r : model.runs) runs.push_back(runJson(r));
    Json j{{"schema", "gbufferlab-report"},
                {"schema_version", kReportSchemaVersion},
                {"run", Json{{"scene", run.scene},
                             {"environment", run.environment},
                             {"width", run.width},
                             {"height", run.height},
                             {"device", Json{{"name", run.device.name},
                                             {"driver", run.device.driver},
                                             {"type", run.device.type}}},
                             {"date", run.date},
                             {"command_line", run.commandLine},
                             {"ibl_modes", run.iblModes},
                             {"exposure", run.exposure},
                             {"exposure_method", run.exposureMethod},
                             {"view_exposures", run.viewExposures},
                             {"view_coverage", run.viewCoverage},
                             {"notes", run.notes},
                             {"views", run.views},
                             {"exr_precision", run.exrPrecision}}},
                {"reference", Json{{"layout", model.reference.layout}, {"images", std::move(references)}}},
                {"runs", std::move(runs)}};
    if (run.temporalFrames > 1) {  // compare --temporal N
        Json jitter = Json::array();
        for (const auto& [x, y] : run.temporalJitter) jitter.push_back(Json::array({number(x), number(y)}));
        j["run"]["temporal"] = Json{{"frames", run.temporalFrames}, {"resolve", run.temporalResolve}, {"jitter", jitter}};
    }
    if (model.iblFigure) j["ibl_figure"] = iblFigureJson(*model.iblFigure);
    if (const auto v = gbufferOrVisibility(model)) {  // derived from the runs: not read back
        auto opt = [](const std::optional<double>& x) { return x ? Json(number(*x)) : Json(nullptr); };
        j["gbuffer_or_visibility"] = Json{
            {"ibl_mode", v->iblMode},
            {"gbuffer", Json{{"layout", v->gbufferLayout},
                             {"flip_mean", number(v->gbufferFlip)},
                             {"psnr_tonemapped_db", number(v->gbufferPsnr)},
                             {"normal_degrees_mean", opt(v->gbufferNormalDegrees)},
                             {"base_color_delta_e_mean", opt(v->gbufferBaseColorDeltaE)},
                             {"bytes_per_pixel_1080p", number(v->gbufferBytesPerPixel)}}},
            {"visibility", Json{{"layout", v->visibilityLayout},
                                {"flip_mean", number(v->visibilityFlip)},
                                {"psnr_tonemapped_db", number(v->visibilityPsnr)},
                                {"normal_degrees_mean", opt(v->visibilityNormalDegrees)},
                                {"base_color_delta_e_mean", opt(v->visibilityBaseColorDeltaE)},
                                {"bytes_per_pixel_1080p", number(v->visibilityIdBytesPerPixel)},
                                {"vertex_fetch_bytes_per_pixel_modelled", number(v->visibilityVertexBytesPerPixel)}}},
            {"answer", v->answer}};
    }
    if (!model.atlas.empty()) j["atlas"] = atlasJson(model);
    if (model.significance) j["significance"] = significanceJson(*model.significance);
    if (const auto v = budgetVerdict(model)) j["verdict"] = verdictJson(*v);
    return j;
}

ReportModel reportFromJson(const Json& json) {
    const Node root{json, ""};
    if (root["schema"].str() != "gbufferlab-report") root["schema"].fail("expected \"gbufferlab-report\"");
    const int version = root["schema_version"].i32();
    if (version != kReportSchemaVersion)
        root["schema_version"].fail("version " + std::to_string(version) + "; this gbufferlab reads version " +
                                    std::to_string(kReportSchemaVersion));
    ReportModel model;
    const Node run = root["run"];
    model.run.scene = run["scene"].str();
    model.run.environment = run["environment"].str();
    model.run.width = run["width"].i32();
    model.run.height = run["height"].i32();
    const Node device = run["device"];
    model.run.device = {device["name"].str(), device["driver"].str(), device["type"].str()};
    model.run.date = run["date"].str();
    model.run.commandLine = run["command_line"].str();
    model.run.iblModes = run["ibl_modes"].strings();
    model.run.notes = run["notes"].strings();
    if (run.has("exposure")) model.run.exposure = run["exposure"].num();
    if (run.has("exposure_method")) model.run.exposureMethod = run["exposure_method"].str();
    if (run.has("view_exposures"))
        for (size_t i = 0; i < run["view_exposures"].array().size(); ++i)
            model.run.viewExposures.push_back(run["view_exposures"].at(i).num());
    if (run.has("view_coverage"))
        for (size_t i = 0; i < run["view_coverage"].array().size(); ++i)
            model.run.viewCoverage.push_back(run["view_coverage"].at(i).num());
    if (run.has("views")) model.run.views = run["views"].strings();
    if (run.has("exr_precision")) model.run.exrPrecision = run["exr_precision"].str();
    if (run.has("temporal")) {
        const Node t = run["temporal"];
        model.run.temporalFrames = t["frames"].i32();
        model.run.temporalResolve = t["resolve"].str();
        const Node jitter = t["jitter"];
        for (size_t i = 0; i < jitter.array().size(); ++i)
            model.run.temporalJitter.push_back({jitter.at(i).at(0).num(), jitter.at(i).at(1).num()});
    }
    const Node reference = root["reference"];
    model.reference.layout = reference["layout"].str();
    const Node images = reference["images"];
    for (size_t i = 0; i < images.array().size(); ++i)
        model.reference.images.push_back({images.at(i)["ibl_mode"].str(), images.at(i)["render"].str(),
                                          images.at(i).has("render_exr") ? images.at(i)["render_exr"].str() : "",
                                          images.at(i).has("hdr_preview") ? images.at(i)["hdr_preview"].str() : ""});
    const Node runs = root["runs"];
    for (size_t i = 0; i < runs.array().size(); ++i) model.runs.push_back(readRun(runs.at(i)));
    if (root.has("significance")) {
        const Node sig = root["significance"];
        SignificanceReport sr;
        sr.method = sig["method"].str();
        for (size_t i = 0; i < sig["pairs"].array().size(); ++i) {
            const Node p = sig["pairs"].at(i);
            if (!p["significant"].j.is_boolean()) p["significant"].fail("expected true or false");
            sr.pairs.push_back({p["better"].str(), p["worse"].str(), p["ibl_mode"].str(), p["mean_difference"].num(),
                                p["units"].i32(), p["p_value"].num(), p["significant"].j.get<bool>()});
        }
        for (size_t i = 0; i < sig["ranks"].array().size(); ++i) {
            const Node r = sig["ranks"].at(i);
            sr.ranks.push_back({r["layout"].str(), r["ibl_mode"].str(), r["mean_error"].num(), r["rank"].i32(),
                                r["rank_low"].i32(), r["rank_high"].i32()});
        }
        model.significance = std::move(sr);
    }
    if (root.has("atlas")) {
        const Node atlas = root["atlas"];
        for (size_t i = 0; i < atlas.array().size(); ++i) {
            const Node a = atlas.at(i);
            AtlasEntry e;
            e.family = a["family"].str();
            e.layout = a["layout"].str();
            e.engine = a["engine"].str();
            e.title = a["title"].str();
            e.year = a["year"].i32();
            e.bytesPerPixel = a["bytes_per_pixel"].i32();
            e.bytesKind = a["bytes_kind"].str();
            e.lightBufferBytesPerPixel = a["light_buffer_bytes_per_pixel"].i32();
            const Node attributes = a["attributes"];
            for (size_t k = 0; k < attributes.array().size(); ++k) {
                const Node at = attributes.at(k);
                e.attributes.push_back({at["name"].str(), at["bits"].i32(), at["encoding"].str()});
            }
            if (a.has("provenance")) {  // absent in reports written before provenance existed
                const Node p = a["provenance"];
                ProvenanceCounts& c = e.provenance;
                c.entries = p["entries"].i32();
                c.verified = p["verified"].i32();
                c.talk = p["talk"].i32();
                c.lineage = p["lineage"].i32();
                c.assumed = p["assumed"].i32();
                c.own = p["own"].i32();
                c.missing = p["missing"].i32();
                c.differs = p["differs"].i32();
                if (c.verified + c.talk + c.lineage + c.assumed + c.own + c.missing != c.entries)
                    p.fail("verified + talk + lineage + assumed + own + missing must equal entries");
            }
            model.atlas.push_back(std::move(e));
        }
    }
    if (root.has("ibl_figure")) {
        const Node f = root["ibl_figure"];
        IblFigure fig;
        fig.png = f["png"].str();
        fig.columns = f["columns"].strings();
        const Node rows = f["rows"];
        for (size_t i = 0; i < rows.array().size(); ++i) {
            const Node r = rows.at(i);
            IblFigureRow row;
            row.iblMode = r["ibl_mode"].str();
            row.caption = r["caption"].str();
            if (r.has("metal_error")) row.metalError = r["metal_error"].num();
            if (r.has("dielectric_error")) row.dielectricError = r["dielectric_error"].num();
            if (r.has("metal_noise")) row.metalNoise = r["metal_noise"].num();
            if (r.has("dielectric_noise")) row.dielectricNoise = r["dielectric_noise"].num();
            fig.rows.push_back(std::move(row));
        }
        model.iblFigure = std::move(fig);
    }
    return model;
}

void to_json(Json& json, const ReportModel& model) { json = reportToJson(model); }
void from_json(const Json& json, ReportModel& model) { model = reportFromJson(json); }

void writeReportJson(const std::filesystem::path& path, const ReportModel& model) {
    // Invalid UTF-8 (say, in a driver's error text) is replaced, not a reason to lose the report.
    writeFileAtomic(path, reportToJson(model).dump(2, ' ', false, Json::error_handler_t::replace) + "\n");
}

ReportModel readReportJson(const std::filesystem::path& path) {
    const std::string text = readTextFile(path);
    Json json;
    try {
        json = Json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        throwUserError(jsonParseErrorMessage(path.string(), text, e.byte, e.what()));
    } catch (const nlohmann::json::exception& e) {
        throwUserError(escapeText(path.string()) + ": not valid JSON: " + escapeText(e.what()));
    }
    try {
        return reportFromJson(json);
    } catch (const UserError& e) {
        std::string message = e.what();
        const std::string prefix = "report.json: ";
        if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
        throwUserError(path.string() + ": " + message);
    }
}

}  // namespace gbl
