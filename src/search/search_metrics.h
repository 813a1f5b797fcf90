#pragma once
// The errors a layout is judged on, in one order: the search's Pareto front is over bytes and all
// of them, a found layout "beats" a published one only when it is no worse on any, and otherwise
// the report states the trade ("FLIP -30 %, PSNR -13.0 dB").
#include <string>
#include <vector>

#include "fast_eval.h"

namespace gbl::search {

enum class Metric { Flip, Psnr, Normal, BaseColor, DiffuseColor, SpecularColor, Roughness, Metallic, Occlusion };
inline constexpr int kMetricCount = 9;

struct MetricInfo {
    const char* key;    // JSON key: "flip", "psnr_db", "normal_deg", ...
    const char* label;  // in tables and trades: "FLIP", "PSNR", "normal", "base ΔE", ...
    bool higherIsBetter;
    int digits;  // decimals in tables
};
const MetricInfo& metricInfo(int m);

// The metric as reported (PSNR in dB).
double metricValue(const Evaluation& e, int m);
// Lower is better (minus the PSNR).
double metricLoss(const Evaluation& e, int m);

// The mean of several evaluations (of one layout over several scenes), member by member.
Evaluation meanEvaluation(const std::vector<Evaluation>& each);

// a no worse than b on every metric.
bool noWorseOnAll(const Evaluation& a, const Evaluation& b);
// a no worse than b on every metric and on bytes, and better on one of them.
bool dominates(int bytesA, const Evaluation& a, int bytesB, const Evaluation& b);

// How `found` compares with `published`, on the metrics only (the bytes are the caller's to say).
enum class Verdict {
    Beats,     // no worse on any metric, better on one
    Equal,     // equal on every metric
    Trade,     // better on some, worse on others
    Loses,     // no better on any metric, worse on one
};
Verdict verdictOf(const Evaluation& found, const Evaluation& published);
const char* verdictName(Verdict v);  // "beats", "equal", "trade", "loses"

// The metrics on which they differ, in metric order, as found's change from published: relative
// for errors ("FLIP -30 %"; the absolute change where published's is 0 or found's is 100 times
// it, as a rounding-level error against a real one: "metallic +0.0140"), in dB for PSNR
// ("PSNR -13.0 dB", two decimals under 0.1 dB). "" when equal on all.
std::string tradeText(const Evaluation& found, const Evaluation& published);

}  // namespace gbl::search
