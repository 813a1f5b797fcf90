// report.json read back (diff, re-rendering a report): every value checked, each error naming its
// place ("runs[2].image_errors.flip_mean").
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
        for (ErrorAttribute a : kAllErrorAttributes) {
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
        for (const auto& [name, member] : layerImageClasses()) get(name, e.*member);
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
    else if (status == "not-measured") r.status = RunStatus::NotMeasured;
    else n["status"].fail("expected \"ok\", \"failed\" or \"not-measured\", not \"" + status + "\"");
    r.error = n["error"].str();
    if (n.has("not_measured")) r.notMeasured = n["not_measured"].str();
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

// The run's description: scene, size, device, flags, views and the temporal resolve.
ReportRunInfo readRunInfo(const Node& run) {
    ReportRunInfo info;
    info.scene = run["scene"].str();
    info.environment = run["environment"].str();
    info.width = run["width"].i32();
    info.height = run["height"].i32();
    const Node device = run["device"];
    info.device = {device["name"].str(), device["driver"].str(), device["type"].str()};
    info.date = run["date"].str();
    info.commandLine = run["command_line"].str();
    info.iblModes = run["ibl_modes"].strings();
    info.notes = run["notes"].strings();
    if (run.has("exposure")) info.exposure = run["exposure"].num();
    if (run.has("exposure_method")) info.exposureMethod = run["exposure_method"].str();
    if (run.has("view_exposures"))
        for (size_t i = 0; i < run["view_exposures"].array().size(); ++i)
            info.viewExposures.push_back(run["view_exposures"].at(i).num());
    if (run.has("view_coverage"))
        for (size_t i = 0; i < run["view_coverage"].array().size(); ++i)
            info.viewCoverage.push_back(run["view_coverage"].at(i).num());
    if (run.has("view_not_measured")) info.viewNotMeasured = run["view_not_measured"].strings();
    if (run.has("views")) info.views = run["views"].strings();
    if (run.has("exr_precision")) info.exrPrecision = run["exr_precision"].str();
    if (run.has("temporal")) {
        const Node t = run["temporal"];
        info.temporalFrames = t["frames"].i32();
        info.temporalResolve = t["resolve"].str();
        const Node jitter = t["jitter"];
        for (size_t i = 0; i < jitter.array().size(); ++i)
            info.temporalJitter.push_back({jitter.at(i).at(0).num(), jitter.at(i).at(1).num()});
    }
    return info;
}

ReportReference readReference(const Node& reference) {
    ReportReference ref;
    ref.layout = reference["layout"].str();
    const Node images = reference["images"];
    for (size_t i = 0; i < images.array().size(); ++i)
        ref.images.push_back({images.at(i)["ibl_mode"].str(), images.at(i)["render"].str(),
                                          images.at(i).has("render_exr") ? images.at(i)["render_exr"].str() : "",
                                          images.at(i).has("hdr_preview") ? images.at(i)["hdr_preview"].str() : ""});
    return ref;
}

// An interrupted report says so (reports before `status`: complete).
std::optional<ReportInterruption> readInterruption(const Node& root) {
    if (root.has("status") && root["status"].str() != "complete" && root["status"].str() != "interrupted")
        root["status"].fail("expected \"complete\" or \"interrupted\", not \"" + root["status"].str() + "\"");
    if (root.has("interruption")) {
        const Node i = root["interruption"];
        ReportInterruption in;
        in.signal = i["signal"].str();
        in.runsFinished = i["runs_finished"].i32();
        in.runsPlanned = i["runs_planned"].i32();
        const Node notRun = i["not_run"];
        for (size_t k = 0; k < notRun.array().size(); ++k) {
            const Node p = notRun.at(k);
            in.notRun.push_back({p["layout"].str(), p["ibl_mode"].str(), p["bytes_per_pixel"].i32(),
                                 p["counted_bytes_per_pixel"].num()});
        }
        return in;
    } else if (root.has("status") && root["status"].str() == "interrupted") {
        root.fail("\"status\" is \"interrupted\" but there is no \"interruption\"");
    }
    return std::nullopt;
}

SignificanceReport readSignificance(const Node& sig) {
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
    return sr;
}

AtlasEntry readAtlasEntry(const Node& a) {
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
    return e;
}

IblFigure readIblFigure(const Node& f) {
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
    return fig;
}

}  // namespace

ReportModel reportFromJson(const Json& json) {
    const Node root{json, ""};
    if (root["schema"].str() != "gbufferlab-report") root["schema"].fail("expected \"gbufferlab-report\"");
    const int version = root["schema_version"].i32();
    if (version != kReportSchemaVersion)
        root["schema_version"].fail("version " + std::to_string(version) + "; this gbufferlab reads version " +
                                    std::to_string(kReportSchemaVersion));
    ReportModel model;
    model.run = readRunInfo(root["run"]);
    model.reference = readReference(root["reference"]);
    const Node runs = root["runs"];
    for (size_t i = 0; i < runs.array().size(); ++i) model.runs.push_back(readRun(runs.at(i)));
    model.interruption = readInterruption(root);
    if (root.has("significance_by_class")) {
        const Node byClass = root["significance_by_class"];
        byClass.object();
        for (auto it = byClass.j.begin(); it != byClass.j.end(); ++it)
            model.classSignificance.emplace_back(it.key(), readSignificance(Node{it.value(), byClass.child(it.key())}));
    }
    if (root.has("significance")) model.significance = readSignificance(root["significance"]);
    if (root.has("atlas")) {
        const Node atlas = root["atlas"];
        for (size_t i = 0; i < atlas.array().size(); ++i) model.atlas.push_back(readAtlasEntry(atlas.at(i)));
    }
    if (root.has("ibl_figure")) model.iblFigure = readIblFigure(root["ibl_figure"]);
    return model;
}

void from_json(const Json& json, ReportModel& model) { model = reportFromJson(json); }

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
