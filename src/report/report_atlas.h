#pragma once
// The report's atlas view (issue 15): every compared layout in one table, grouped by engine family
// (layout_atlas.h), with its year, bytes per pixel, each attribute's bits and encoding, and its
// error against the float reference (FLIP mean and tone-mapped PSNR of its run under the first IBL
// mode). report.html shows it as a table, report.json holds it as "atlas" (docs/report-schema.md).
#include <optional>
#include <string>
#include <vector>

#include "layout_atlas.h"
#include "report_model.h"

namespace gbl {

struct AtlasRow {
    AtlasEntry entry;
    std::string iblMode;  // the run the errors come from ("" when the layout has no run)
    std::optional<double> flipMean;        // LDR-FLIP mean
    std::optional<double> psnrToneMapped;  // dB; +inf when identical to the reference
    // compare --temporal N: flipMean is the resolve's; this frame 0's alone. Ranks: 1 + the atlas
    // rows of lower FLIP mean, by each (0: no value).
    std::optional<double> flipMeanSingleFrame;
    int rank = 0, rankSingleFrame = 0;
};

struct AtlasRowGroup {
    std::string family;
    std::vector<AtlasRow> rows;
};

// model.atlas grouped (groupAtlas), each row joined with its layout's run: the first IBL mode's
// (model.run.iblModes), else its first run; no errors when that run failed.
std::vector<AtlasRowGroup> atlasRows(const ReportModel& model);

// Appends the atlas section; nothing when model.atlas is empty.
void writeAtlasHtml(std::string& out, const ReportModel& model);

}  // namespace gbl
