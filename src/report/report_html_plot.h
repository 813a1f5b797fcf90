#pragma once
// The report page's error-against-bytes plot (an inline SVG per image metric and axis scale),
// written by report_html_plot.cpp for report_html.cpp. Internal to the report library.
//
// Each point is a layout run, coloured by IBL mode, linked to its section. The Pareto fronts are
// drawn per IBL mode and per pipeline kind: deferred shading and deferred lighting share one
// (both store a G-buffer), visibility buffers have their own, so that a visibility buffer's few
// bytes of ids cannot hide the G-buffer layouts' front. A visibility buffer shows two markers:
// its ids and depth, and, joined by a dashed line, the bytes the verdict counts for it
// (budget_verdict.h: half its modelled vertex fetches added); its front runs through the second.
// Labels are placed by plot_labels.h: none overlaps another or a marker.
#include <functional>
#include <string>
#include <vector>

#include "report_model.h"

namespace gbl {

struct PlotSpec {
    const char* id;          // figure id: plot-<id>
    const char* yLabel;
    bool higherIsBetter;
    bool yFromZero;          // linear scale only
    bool logY;               // a logarithmic error axis; values <= 0 go to a "0" lane under it
    double ImageErrors::*field;
    std::function<std::string(double)> format;
    // compare --temporal N: the value of the run's first frame alone (RunReport::singleFrame)
    // instead of its resolve's.
    bool singleFrame = false;
    // The x axis: "" the table's bytes per pixel; a GPU class ("desktop-dcc", "mali-afbc") its
    // effective bytes (RunReport::effective; runs without them are left out).
    const char* xClass = "";
};

// Appends the plot of `spec.field` against bytes per pixel. `runIds` are the runs' section ids,
// parallel to model.runs (each point links to its run).
void writePlot(std::string& out, const ReportModel& model, const std::vector<std::string>& runIds,
               const PlotSpec& spec, bool hidden);

}  // namespace gbl
