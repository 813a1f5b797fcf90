#pragma once
// report.html's "Material layers" section (issue 40): per run, each layer attribute's mean error
// over the pixels whose reference carries the layer, and LDR-FLIP per layer class with its tied
// rank within the class (ReportModel::classSignificance). Nothing in a scene without layers.
#include <string>

#include "report_model.h"

namespace gbl {

void writeLayerSection(std::string& out, const ReportModel& model);

}  // namespace gbl
