#include "search_metrics.h"

#include <cmath>
#include <cstdio>

namespace gbl::search {

const MetricInfo& metricInfo(int m) {
    static const MetricInfo v[kMetricCount] = {
        {"flip", "FLIP", false, 5},
        {"psnr_db", "PSNR", true, 2},
        {"normal_deg", "normal", false, 3},
        {"base_color_de", "base ΔE", false, 3},
        {"diffuse_color_de", "diffuse ΔE", false, 3},
        {"specular_color_de", "specular ΔE", false, 3},
        {"roughness", "roughness", false, 4},
        {"metallic", "metallic", false, 4},
        {"occlusion", "occlusion", false, 4},
    };
    return v[m];
}

double metricValue(const Evaluation& e, int m) {
    switch (Metric(m)) {
        case Metric::Flip: return e.flip;
        case Metric::Psnr: return e.psnr;
        case Metric::Normal: return e.normalDeg;
        case Metric::BaseColor: return e.baseColorDe;
        case Metric::DiffuseColor: return e.diffuseColorDe;
        case Metric::SpecularColor: return e.specularColorDe;
        case Metric::Roughness: return e.roughness;
        case Metric::Metallic: return e.metallic;
        default: return e.occlusion;
    }
}

double metricLoss(const Evaluation& e, int m) {
    const double v = metricValue(e, m);
    return metricInfo(m).higherIsBetter ? -v : v;
}

Evaluation meanEvaluation(const std::vector<Evaluation>& each) {
    Evaluation m;
    if (each.empty()) return m;
    const double n = double(each.size());
    m.flip = 0.0;
    for (const Evaluation& e : each) {
        m.error += e.error / n;
        m.psnr += e.psnr / n;
        m.attributes += e.attributes / n;
        m.flip = e.flip < 0 || m.flip < 0 ? -1.0 : m.flip + e.flip / n;
        m.normalDeg += e.normalDeg / n;
        m.baseColorDe += e.baseColorDe / n;
        m.diffuseColorDe += e.diffuseColorDe / n;
        m.specularColorDe += e.specularColorDe / n;
        m.roughness += e.roughness / n;
        m.metallic += e.metallic / n;
        m.occlusion += e.occlusion / n;
    }
    return m;
}

bool noWorseOnAll(const Evaluation& a, const Evaluation& b) {
    for (int m = 0; m < kMetricCount; ++m)
        if (metricLoss(a, m) > metricLoss(b, m)) return false;
    return true;
}

bool dominates(int bytesA, const Evaluation& a, int bytesB, const Evaluation& b) {
    if (bytesA > bytesB || !noWorseOnAll(a, b)) return false;
    if (bytesA < bytesB) return true;
    for (int m = 0; m < kMetricCount; ++m)
        if (metricLoss(a, m) < metricLoss(b, m)) return true;
    return false;
}

Verdict verdictOf(const Evaluation& found, const Evaluation& published) {
    bool better = false, worse = false;
    for (int m = 0; m < kMetricCount; ++m) {
        const double f = metricLoss(found, m), p = metricLoss(published, m);
        better = better || f < p;
        worse = worse || f > p;
    }
    if (better && worse) return Verdict::Trade;
    if (better) return Verdict::Beats;
    if (worse) return Verdict::Loses;
    return Verdict::Equal;
}

const char* verdictName(Verdict v) {
    switch (v) {
        case Verdict::Beats: return "beats";
        case Verdict::Equal: return "equal";
        case Verdict::Trade: return "trade";
        default: return "loses";
    }
}

std::string tradeText(const Evaluation& found, const Evaluation& published) {
    std::string out;
    char buf[96];
    for (int m = 0; m < kMetricCount; ++m) {
        const double f = metricValue(found, m), p = metricValue(published, m);
        if (f == p) continue;
        const MetricInfo& info = metricInfo(m);
        if (info.higherIsBetter) {
            std::snprintf(buf, sizeof buf, std::abs(f - p) >= 0.095 ? "%s %+.1f dB" : "%s %+.2f dB", info.label, f - p);
        } else if (p > 0.0 && f < 100.0 * p) {
            const double percent = 100.0 * (f - p) / p;
            std::snprintf(buf, sizeof buf, std::abs(percent) >= 9.95 ? "%s %+.0f %%" : "%s %+.1f %%", info.label, percent);
        } else {
            std::snprintf(buf, sizeof buf, "%s %+.*f", info.label, info.digits, f - p);
        }
        out += (out.empty() ? "" : ", ") + std::string(buf);
    }
    return out;
}

}  // namespace gbl::search
