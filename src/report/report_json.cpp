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
#include "report_bandwidth.h"
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
    for (ErrorAttribute a : kAllErrorAttributes) {  // a layer's absent in a scene without layers
        const AttributeErrors& e = table[a];
        if (e.empty()) continue;
        Json entry{{"unit", errorAttributeUnit(a)}};
        if (errorAttributeIsLayer(a)) entry["over"] = errorAttributeLayerClass(a);  // the pixels carrying the layer
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
    for (const auto& [name, member] : layerImageClasses()) put(name, e.*member);  // absent without layers
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
        if (!line.notRun.empty()) {  // an interrupted report: layouts that fit but never ran
            Json notRun = Json::array();
            for (const VerdictEntry& e : line.notRun)
                notRun.push_back(Json{{"layout", e.layout},
                                      {"bytes_per_pixel", e.bytesPerPixel},
                                      {"counted_bytes_per_pixel", number(e.countedBytes)}});
            b["not_run"] = std::move(notRun);
        }
        b["sentence"] = line.sentence;
        budgets.push_back(std::move(b));
    }
    Json j{{"ibl_mode", v.iblMode}, {"metric", "flip_mean"}};
    if (v.scenes > 0) j["scenes"] = v.scenes;  // across several scenes: the means are over them
    else j["views"] = v.views;
    j["basis"] = v.basis;
    j["budgets"] = std::move(budgets);
    return j;
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
    if (!r.notMeasured.empty()) j["not_measured"] = r.notMeasured;  // views left out, and why
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
    if (r.effective) j["effective_bandwidth"] = effectiveBandwidthJson(*r.effective);  // report_bandwidth.h
    return j;
}

}  // namespace

Json budgetVerdictToJson(const BudgetVerdict& verdict) { return verdictJson(verdict); }

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
                {"status", model.interruption ? "interrupted" : "complete"},
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
                             {"view_not_measured", run.viewNotMeasured},
                             {"notes", run.notes},
                             {"views", run.views},
                             {"exr_precision", run.exrPrecision}}},
                {"reference", Json{{"layout", model.reference.layout}, {"images", std::move(references)}}},
                {"runs", std::move(runs)}};
    if (model.interruption) {  // what the report lacks, for programs: the signal and the runs never run
        const ReportInterruption& i = *model.interruption;
        Json notRun = Json::array();
        for (const PlannedRun& p : i.notRun)
            notRun.push_back(Json{{"layout", p.layout},
                                  {"ibl_mode", p.iblMode},
                                  {"bytes_per_pixel", p.bytesPerPixel},
                                  {"counted_bytes_per_pixel", number(p.countedBytes)}});
        j["interruption"] = Json{{"signal", i.signal},
                                 {"runs_finished", i.runsFinished},
                                 {"runs_planned", i.runsPlanned},
                                 {"not_run", std::move(notRun)}};
    }
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
    if (!model.classSignificance.empty()) {  // per layer class: absent in a scene without layers
        Json byClass = Json::object();
        for (const auto& [name, sig] : model.classSignificance) byClass[name] = significanceJson(sig);
        j["significance_by_class"] = std::move(byClass);
    }
    if (const auto v = budgetVerdict(model)) j["verdict"] = verdictJson(*v);
    j["run"]["lighting"] = run.lighting;
    if (!effectiveRuns(model).empty()) j["bandwidth_as_paid"] = bandwidthAsPaidJson(model);  // report_bandwidth.h
    return j;
}

void to_json(Json& json, const ReportModel& model) { json = reportToJson(model); }

void writeReportJson(const std::filesystem::path& path, const ReportModel& model) {
    // Invalid UTF-8 (say, in a driver's error text) is replaced, not a reason to lose the report.
    writeFileAtomic(path, reportToJson(model).dump(2, ' ', false, Json::error_handler_t::replace) + "\n");
}

}  // namespace gbl
