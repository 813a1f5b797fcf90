#pragma once
// The report page's error-against-bytes plot (an inline SVG per image metric, with the Pareto
// front), written by report_html_plot.cpp for report_html.cpp. Internal to the report library.
#include <functional>
#include <string>

#include "report_model.h"

namespace gbl {

struct PlotSpec {
    const char* id;          // figure id: plot-<id>
    const char* yLabel;
    bool higherIsBetter;
    bool yFromZero;
    double ImageErrors::*field;
    std::function<std::string(double)> format;
};

// Appends the plot of `spec.field` against bytes per pixel, one series per IBL mode.
void writePlot(std::string& out, const ReportModel& model, const PlotSpec& spec, bool hidden);

}  // namespace gbl
