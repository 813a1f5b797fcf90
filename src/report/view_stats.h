#pragma once
// Several views (compare --views N): a run's metrics are measured from N cameras; the report gives
// each metric's mean over the views and its spread, so that no verdict hinges on one camera.
#include <functional>
#include <optional>
#include <vector>

#include "report_model.h"

namespace gbl {

// The spread of one metric over the views that have it. stddev: population standard deviation
// (divides by n). Non-finite values (an identical image's PSNR of +inf) make mean, min or max
// infinite and stddev NaN unless all are equal.
struct ViewSpread {
    int n = 0;
    double mean = 0.0, min = 0.0, max = 0.0, stddev = 0.0;
};
ViewSpread spreadOf(const std::vector<double>& values);

// The run as seen from view i alone: a copy with that view's attributes and image.
RunReport viewOf(const RunReport& run, size_t i);

// Spread over run.views of one metric (absent in a view: skipped). No views: the run's own value.
ViewSpread viewSpread(const RunReport& run, const std::function<std::optional<double>(const RunReport&)>& metric);

// Sets run.attributes and run.image to the mean of run.views, number by number: every double is
// the mean over the views that have it (PSNR in dB is averaged as dB), sample and pixel counts are
// summed. No views: leaves the run as it is.
void averageViews(RunReport& run);

}  // namespace gbl
