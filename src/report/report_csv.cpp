#include "report_csv.h"

#include <charconv>
#include <cmath>
#include <functional>
#include <optional>

#include "file_io.h"

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

struct Column {
    std::string name;
    std::function<std::string(const RunReport&)> value;
};

const char* unitSuffix(ErrorAttribute a) {
    switch (a) {
        case ErrorAttribute::Normal: return "deg";
        case ErrorAttribute::BaseColor:
        case ErrorAttribute::DiffuseColor:
        case ErrorAttribute::SpecularColor: return "de2000";
        case ErrorAttribute::Depth: return "rel";
        default: return "abs";
    }
}

std::vector<Column> columns() {
    std::vector<Column> c;
    const auto text = [&](std::string name, std::string RunReport::*field) {
        c.push_back({std::move(name), [field](const RunReport& r) { return r.*field; }});
    };
    const auto image = [&](std::string name, double ImageErrors::*field) {
        c.push_back({std::move(name), [field](const RunReport& r) {
                         return r.image ? numberText(*r.image.*field) : std::string();
                     }});
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
    c.push_back({"hdr_flip_mean", [](const RunReport& r) {
                     return r.image && r.image->hdrFlipMean ? numberText(*r.image->hdrFlipMean) : std::string();
                 }});
    using ImageClassMember = std::optional<ImageClassErrors> ImageErrors::*;
    const std::pair<const char*, ImageClassMember> imageClasses[] = {{"covered", &ImageErrors::covered},
                                                                     {"metal", &ImageErrors::metal},
                                                                     {"dielectric", &ImageErrors::dielectric}};
    for (const auto& [className, member] : imageClasses) {
        const std::string prefix = std::string("image_") + className + "_";
        const std::pair<const char*, double ImageClassErrors::*> fields[] = {
            {"rel_luminance_mean", &ImageClassErrors::relLuminanceMean},
            {"rmse_linear", &ImageClassErrors::rmseLinear},
            {"flip_mean", &ImageClassErrors::flipMean}};
        for (const auto& [fieldName, field] : fields)
            c.push_back({prefix + fieldName, [member, field](const RunReport& r) {
                             if (!r.image || !(*r.image.*member)) return std::string();
                             return numberText(*(*r.image.*member).*field);
                         }});
        c.push_back({prefix + "reference_noise", [member](const RunReport& r) {
                         if (!r.image || !(*r.image.*member) || !(*r.image.*member)->referenceNoise) return std::string();
                         return numberText(*(*r.image.*member)->referenceNoise);
                     }});
    }
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
                c.push_back({prefix + statName + "_" + unitSuffix(a), [a, member, stat](const RunReport& r) {
                                 const auto& s = r.attributes[a].*member;
                                 return s ? numberText(s->error.*stat) : std::string();
                             }});
            if (errorAttributeIsColor(a))
                c.push_back({prefix + "rmse_linear", [a, member](const RunReport& r) {
                                 const auto& s = r.attributes[a].*member;
                                 return s && s->rmse ? numberText(*s->rmse) : std::string();
                             }});
        }
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

std::vector<std::string> reportCsvHeader() {
    std::vector<std::string> names;
    for (const Column& c : columns()) names.push_back(c.name);
    return names;
}

std::string reportCsv(const ReportModel& model) {
    const std::vector<Column> cols = columns();
    std::string out;
    for (size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + cols[i].name;
    out += "\n";
    for (const RunReport& run : model.runs) {
        for (size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + csvField(cols[i].value(run));
        out += "\n";
    }
    return out;
}

void writeReportCsv(const std::filesystem::path& path, const ReportModel& model) {
    writeFileAtomic(path, reportCsv(model));
}

}  // namespace gbl
