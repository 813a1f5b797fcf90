#include "report_csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <optional>

#include "file_io.h"
#include "report_bandwidth.h"
#include "view_stats.h"

namespace gbl {
namespace {

std::string numberText(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);  // shortest round trip
    return std::string(buffer, result.ptr);
}
std::string numberText(std::optional<double> v) { return v ? numberText(*v) : std::string(); }

using Metric = std::function<std::optional<double>(const RunReport&)>;
struct Column {
    std::string name;
    std::function<std::string(const RunReport&)> value;
    Metric metric;  // set for metrics: they also get _view_min, _view_max, _view_std columns
};

// A metric column: its text is the number's.
Column metricColumn(std::string name, Metric metric) {
    return {std::move(name), [metric](const RunReport& r) { return numberText(metric(r)); }, metric};
}

const char* unitSuffix(ErrorAttribute a) {
    switch (a) {
        case ErrorAttribute::Normal:
        case ErrorAttribute::CoatNormal:
        case ErrorAttribute::AnisotropyDirection: return "deg";
        case ErrorAttribute::BaseColor:
        case ErrorAttribute::DiffuseColor:
        case ErrorAttribute::SpecularColor:
        case ErrorAttribute::SheenColor: return "de2000";
        case ErrorAttribute::Depth: return "rel";
        default: return "abs";
    }
}

// `layers`: a report some run of which measured the material layers (ReportModel::hasLayerMetrics):
// their columns follow the attributes'; a report without them has the columns it always had.
std::vector<Column> columns(bool layers) {
    std::vector<Column> c;
    const auto text = [&](std::string name, std::string RunReport::*field) {
        c.push_back({std::move(name), [field](const RunReport& r) { return r.*field; }});
    };
    const auto image = [&](std::string name, double ImageErrors::*field) {
        c.push_back(metricColumn(std::move(name), [field](const RunReport& r) -> std::optional<double> {
            if (!r.image) return std::nullopt;
            return *r.image.*field;
        }));
    };
    const auto bytes = [&](std::string name, int BytesPerPixel::*field) {
        c.push_back({std::move(name), [field](const RunReport& r) { return std::to_string(r.bytesPerPixel.*field); }});
    };
    text("layout", &RunReport::layout);
    text("title", &RunReport::title);
    text("pipeline", &RunReport::pipeline);
    text("ibl_mode", &RunReport::iblMode);
    c.push_back({"status", [](const RunReport& r) { return std::string(runStatusName(r.status)); }});
    text("error", &RunReport::error);
    bytes("bytes_per_pixel_targets", &BytesPerPixel::targets);
    bytes("bytes_per_pixel_depth", &BytesPerPixel::depth);
    bytes("bytes_per_pixel_light_buffers", &BytesPerPixel::lightBuffers);
    bytes("bytes_per_pixel_total", &BytesPerPixel::total);
    c.push_back({"gb_per_s_1080p60", [](const RunReport& r) { return numberText(r.gigabytesPerSecond1080p60()); }});
    image("rmse_linear", &ImageErrors::rmseLinear);
    image("psnr_linear_db", &ImageErrors::psnrLinear);
    image("rmse_tonemapped", &ImageErrors::rmseToneMapped);
    image("psnr_tonemapped_db", &ImageErrors::psnrToneMapped);
    image("max_abs", &ImageErrors::maxAbs);
    image("p99_abs", &ImageErrors::p99Abs);
    image("flip_mean", &ImageErrors::flipMean);
    image("flip_median", &ImageErrors::flipMedian);
    c.push_back(metricColumn("hdr_flip_mean", [](const RunReport& r) -> std::optional<double> {
        if (!r.image) return std::nullopt;
        return r.image->hdrFlipMean;
    }));
    const std::pair<const char*, ImageClassMember> imageClasses[] = {{"covered", &ImageErrors::covered},
                                                                     {"metal", &ImageErrors::metal},
                                                                     {"dielectric", &ImageErrors::dielectric}};
    const auto imageClass = [&](const char* className, ImageClassMember member) {
        const std::string prefix = std::string("image_") + className + "_";
        const std::pair<const char*, double ImageClassErrors::*> fields[] = {
            {"rel_luminance_mean", &ImageClassErrors::relLuminanceMean},
            {"rmse_linear", &ImageClassErrors::rmseLinear},
            {"flip_mean", &ImageClassErrors::flipMean}};
        for (const auto& [fieldName, field] : fields)
            c.push_back(metricColumn(prefix + fieldName, [member = member, field = field](const RunReport& r) -> std::optional<double> {
                if (!r.image || !(*r.image.*member)) return std::nullopt;
                return *(*r.image.*member).*field;
            }));
        c.push_back(metricColumn(prefix + "reference_noise", [member = member](const RunReport& r) -> std::optional<double> {
            if (!r.image || !(*r.image.*member)) return std::nullopt;
            return (*r.image.*member)->referenceNoise;
        }));
    };
    for (const auto& [className, member] : imageClasses) imageClass(className, member);
    c.push_back({"ground_truth_batches", [](const RunReport& r) {
                     return r.groundTruth ? std::to_string(r.groundTruth->batches) : std::string();
                 }});
    c.push_back({"ground_truth_samples_per_pixel", [](const RunReport& r) {
                     return r.groundTruth ? std::to_string(r.groundTruth->samplesPerPixel) : std::string();
                 }});
    c.push_back({"ground_truth_mean_relative_noise", [](const RunReport& r) {
                     return r.groundTruth ? numberText(r.groundTruth->meanRelativeNoise) : std::string();
                 }});
    c.push_back({"ground_truth_gpu_ms", [](const RunReport& r) {
                     return r.groundTruth ? numberText(r.groundTruth->gpuMs) : std::string();
                 }});
    c.push_back({"gbuffer_ms", [](const RunReport& r) {
                     return r.times ? numberText(r.times->gbufferMs) : std::string();
                 }});
    c.push_back({"lighting_ms", [](const RunReport& r) {
                     return r.times ? numberText(r.times->lightingMs) : std::string();
                 }});
    using ClassMember = std::optional<AttributeStats> AttributeErrors::*;
    const std::pair<const char*, ClassMember> classes[] = {
        {"all", &AttributeErrors::all}, {"metal", &AttributeErrors::metal}, {"dielectric", &AttributeErrors::dielectric}};
    const std::pair<const char*, double ScalarStats::*> stats[] = {
        {"mean", &ScalarStats::mean}, {"p99", &ScalarStats::p99}, {"max", &ScalarStats::max}};
    for (ErrorAttribute a : kErrorAttributes)
        for (const auto& [className, member] : classes) {
            const std::string prefix = std::string(errorAttributeName(a)) + "_" + className + "_";
            for (const auto& [statName, stat] : stats)
                c.push_back(metricColumn(prefix + statName + "_" + unitSuffix(a),
                                         [a, member = member, stat = stat](const RunReport& r) -> std::optional<double> {
                                             const auto& s = r.attributes[a].*member;
                                             if (!s) return std::nullopt;
                                             return s->error.*stat;
                                         }));
            if (errorAttributeIsColor(a))
                c.push_back(metricColumn(prefix + "rmse_linear", [a, member = member](const RunReport& r) -> std::optional<double> {
                    const auto& s = r.attributes[a].*member;
                    if (!s) return std::nullopt;
                    return s->rmse;
                }));
        }
    if (layers) {
        // The layers' attributes over the pixels carrying them (`all`), then the image per layer class.
        for (ErrorAttribute a : kLayerErrorAttributes) {
            const std::string prefix = std::string(errorAttributeName(a)) + "_all_";
            for (const auto& [statName, stat] : stats)
                c.push_back(metricColumn(prefix + statName + "_" + unitSuffix(a),
                                         [a, stat = stat](const RunReport& r) -> std::optional<double> {
                                             const auto& s = r.attributes[a].all;
                                             if (!s) return std::nullopt;
                                             return s->error.*stat;
                                         }));
            if (errorAttributeIsColor(a))
                c.push_back(metricColumn(prefix + "rmse_linear", [a](const RunReport& r) -> std::optional<double> {
                    const auto& s = r.attributes[a].all;
                    if (!s) return std::nullopt;
                    return s->rmse;
                }));
        }
        for (const auto& [className, member] : layerImageClasses()) imageClass(className, member);
    }
    // Several views (compare --views): the metrics above are means over the views; each one's
    // spread follows, at the end so that the columns above keep their places.
    c.push_back({"views", [](const RunReport& r) { return std::to_string(std::max<size_t>(1, r.views.size())); }, {}});
    const size_t metrics = c.size();
    for (size_t i = 0; i < metrics; ++i) {
        if (!c[i].metric) continue;
        const Metric m = c[i].metric;
        const std::string name = c[i].name;
        auto spread = [m](const RunReport& r, double ViewSpread::*f) -> std::string {
            const ViewSpread s = viewSpread(r, m);
            return s.n ? numberText(s.*f) : std::string();
        };
        c.push_back({name + "_view_min", [spread](const RunReport& r) { return spread(r, &ViewSpread::min); }, {}});
        c.push_back({name + "_view_max", [spread](const RunReport& r) { return spread(r, &ViewSpread::max); }, {}});
        c.push_back({name + "_view_std", [spread](const RunReport& r) { return spread(r, &ViewSpread::stddev); }, {}});
    }
    // compare --temporal N: frame 0 alone (the columns above are the resolve's); empty otherwise.
    auto single = [](const RunReport& r) { return r.singleFrame && r.singleFrame->image ? &*r.singleFrame->image : nullptr; };
    c.push_back({"single_frame_psnr_tonemapped_db", [single](const RunReport& r) {
                     return single(r) ? numberText(single(r)->psnrToneMapped) : std::string();
                 }, {}});
    c.push_back({"single_frame_flip_mean", [single](const RunReport& r) {
                     return single(r) ? numberText(single(r)->flipMean) : std::string();
                 }, {}});
    c.push_back({"single_frame_normal_mean_deg", [](const RunReport& r) {
                     if (!r.singleFrame) return std::string();
                     const auto& n = r.singleFrame->attributes[ErrorAttribute::Normal].all;
                     return n ? numberText(n->error.mean) : std::string();
                 }, {}});
    // The views left out of the metrics (nothing to measure), and why; empty when every view counted.
    text("not_measured", &RunReport::notMeasured);
    return c;
}

}  // namespace

std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char ch : text) {
        if (ch == '"') quoted += '"';
        quoted += ch;
    }
    return quoted + "\"";
}

// The last column, of the report rather than of its run: "complete", or "interrupted by SIGINT"
// (the rows are then only the runs that finished).
constexpr const char* kReportStatusColumn = "report_status";

std::vector<std::string> reportCsvHeader(bool layers) {
    std::vector<std::string> names;
    for (const Column& c : columns(layers)) names.push_back(c.name);
    for (const std::string& c : effectiveCsvHeader()) names.push_back(c);  // report_bandwidth.h
    names.push_back(kReportStatusColumn);
    return names;
}

std::string reportCsv(const ReportModel& model) {
    const std::vector<Column> cols = columns(model.hasLayerMetrics());
    const std::string status =
        model.interruption ? "interrupted by " + model.interruption->signal : std::string("complete");
    std::string out;
    for (size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + cols[i].name;
    for (const std::string& c : effectiveCsvHeader()) out += "," + c;  // report_bandwidth.h
    out += std::string(",") + kReportStatusColumn + "\n";
    for (const RunReport& run : model.runs) {
        for (size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + csvField(cols[i].value(run));
        for (const std::string& f : effectiveCsvFields(run)) out += "," + csvField(f);
        out += "," + csvField(status) + "\n";
    }
    return out;
}

void writeReportCsv(const std::filesystem::path& path, const ReportModel& model) {
    writeFileAtomic(path, reportCsv(model));
}

}  // namespace gbl
