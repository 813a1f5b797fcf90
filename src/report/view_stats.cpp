#include "view_stats.h"

#include <algorithm>
#include <cmath>

namespace gbl {

ViewSpread spreadOf(const std::vector<double>& values) {
    ViewSpread s;
    s.n = int(values.size());
    if (values.empty()) return s;
    s.min = *std::min_element(values.begin(), values.end());
    s.max = *std::max_element(values.begin(), values.end());
    double sum = 0.0;
    for (double v : values) sum += v;
    s.mean = sum / double(values.size());
    if (s.min == s.max) {
        s.mean = s.min;
        s.stddev = 0.0;
        return s;
    }
    double sq = 0.0;
    for (double v : values) sq += (v - s.mean) * (v - s.mean);
    s.stddev = std::sqrt(sq / double(values.size()));
    return s;
}

RunReport viewOf(const RunReport& run, size_t i) {
    RunReport v = run;
    v.views.clear();
    v.attributes = run.views.at(i).attributes;
    v.image = run.views.at(i).image;
    return v;
}

ViewSpread viewSpread(const RunReport& run, const std::function<std::optional<double>(const RunReport&)>& metric) {
    std::vector<double> values;
    if (run.views.empty()) {
        if (auto v = metric(run)) values.push_back(*v);
    } else {
        for (size_t i = 0; i < run.views.size(); ++i)
            if (auto v = metric(viewOf(run, i))) values.push_back(*v);
    }
    return spreadOf(values);
}

namespace {

// Mean of the values present; nullopt when none is.
template <class T, class Get>
std::optional<double> meanOf(const std::vector<T>& items, Get get) {
    std::vector<double> v;
    for (const T& item : items)
        if (auto x = get(item)) v.push_back(*x);
    if (v.empty()) return std::nullopt;
    return spreadOf(v).mean;
}

ScalarStats meanStats(const std::vector<const ScalarStats*>& s) {
    ScalarStats m;
    for (const ScalarStats* p : s) m.count += p->count;
    auto field = [&](double ScalarStats::*f) {
        return *meanOf(s, [f](const ScalarStats* p) { return std::optional<double>(p->*f); });
    };
    m.mean = field(&ScalarStats::mean);
    m.rms = field(&ScalarStats::rms);
    m.p99 = field(&ScalarStats::p99);
    m.max = field(&ScalarStats::max);
    return m;
}

std::optional<AttributeStats> meanAttribute(const std::vector<const std::optional<AttributeStats>*>& in) {
    std::vector<const AttributeStats*> present;
    for (const auto* p : in)
        if (*p) present.push_back(&**p);
    if (present.empty()) return std::nullopt;
    AttributeStats a;
    std::vector<const ScalarStats*> stats;
    for (const AttributeStats* p : present) stats.push_back(&p->error);
    a.error = meanStats(stats);
    a.rmse = meanOf(present, [](const AttributeStats* p) { return p->rmse; });
    return a;
}

std::optional<ImageClassErrors> meanClass(const std::vector<const std::optional<ImageClassErrors>*>& in) {
    std::vector<const ImageClassErrors*> present;
    for (const auto* p : in)
        if (*p) present.push_back(&**p);
    if (present.empty()) return std::nullopt;
    ImageClassErrors c;
    for (const ImageClassErrors* p : present) c.pixels += p->pixels;
    auto field = [&](double ImageClassErrors::*f) {
        return *meanOf(present, [f](const ImageClassErrors* p) { return std::optional<double>(p->*f); });
    };
    c.relLuminanceMean = field(&ImageClassErrors::relLuminanceMean);
    c.rmseLinear = field(&ImageClassErrors::rmseLinear);
    c.flipMean = field(&ImageClassErrors::flipMean);
    c.referenceNoise = meanOf(present, [](const ImageClassErrors* p) { return p->referenceNoise; });
    return c;
}

}  // namespace

void averageViews(RunReport& run) {
    if (run.views.empty()) return;
    for (ErrorAttribute a : kAllErrorAttributes) {
        using Member = std::optional<AttributeStats> AttributeErrors::*;
        for (Member m : {&AttributeErrors::all, &AttributeErrors::metal, &AttributeErrors::dielectric}) {
            std::vector<const std::optional<AttributeStats>*> in;
            for (const ViewMetrics& v : run.views) in.push_back(&(v.attributes[a].*m));
            run.attributes[a].*m = meanAttribute(in);
        }
    }
    std::vector<const ImageErrors*> images;
    for (const ViewMetrics& v : run.views)
        if (v.image) images.push_back(&*v.image);
    if (images.empty()) {
        run.image.reset();
        return;
    }
    ImageErrors e;
    auto field = [&](double ImageErrors::*f) {
        return *meanOf(images, [f](const ImageErrors* p) { return std::optional<double>(p->*f); });
    };
    e.rmseLinear = field(&ImageErrors::rmseLinear);
    e.psnrLinear = field(&ImageErrors::psnrLinear);
    e.rmseToneMapped = field(&ImageErrors::rmseToneMapped);
    e.psnrToneMapped = field(&ImageErrors::psnrToneMapped);
    e.maxAbs = field(&ImageErrors::maxAbs);
    e.p99Abs = field(&ImageErrors::p99Abs);
    e.flipMean = field(&ImageErrors::flipMean);
    e.flipMedian = field(&ImageErrors::flipMedian);
    e.hdrFlipMean = meanOf(images, [](const ImageErrors* p) { return p->hdrFlipMean; });
    e.hdrFlipExposures = images.front()->hdrFlipExposures;
    using ClassMember = std::optional<ImageClassErrors> ImageErrors::*;
    for (ClassMember m : {&ImageErrors::covered, &ImageErrors::metal, &ImageErrors::dielectric, &ImageErrors::coated,
                          &ImageErrors::sheen, &ImageErrors::anisotropic, &ImageErrors::plain}) {
        std::vector<const std::optional<ImageClassErrors>*> in;
        for (const ImageErrors* p : images) in.push_back(&(p->*m));
        e.*m = meanClass(in);
    }
    run.image = e;
}

}  // namespace gbl
