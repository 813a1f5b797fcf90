#pragma once
// A report crowded the way a real one is: the 19 layouts of `compare --size 320x180 --views 3`
// on the built-in scene (bytes per pixel, FLIP mean and PSNR as that run measured them), fourteen
// of them between 16 and 25 B/px and 0.008 and 0.012 FLIP, two outliers above 0.1, and two
// visibility buffers whose 8 and 12 B/px of ids would dominate every G-buffer layout (the first
// at FLIP 0.0002, as at 960x540, so the error axis spans three decades). Three views, so the
// table carries each value's spread.
#include <string>

#include "report_sample.h"

namespace gbl::test {

inline ReportModel crowdedReport() {
    struct Row {
        const char* layout;
        const char* pipeline;
        int bytes;
        double flip, psnr;
    };
    const Row rows[] = {
        {"bevy-deferred", "deferred-shading", 21, 0.0092, 51.50},
        {"compact-octahedral", "deferred-shading", 16, 0.0098, 51.59},
        {"crysis2-slim", "deferred-lighting", 24, 0.0115, 45.68},
        {"crysis2-slim-ps3", "deferred-lighting", 16, 0.0116, 45.68},
        {"crysis2-slim-x360", "deferred-lighting", 16, 0.0117, 45.67},
        {"crysis3-thin", "deferred-shading", 12, 0.0443, 30.13},
        {"fat-naive", "deferred-shading", 24, 0.0100, 49.94},
        {"granite", "deferred-shading", 18, 0.0099, 50.96},
        {"hdrp-lit", "deferred-shading", 21, 0.0082, 57.31},
        {"killzone2", "deferred-shading", 20, 0.1078, 21.60},
        {"niagara", "deferred-shading", 12, 0.1165, 21.42},
        {"ryse", "deferred-shading", 16, 0.0117, 55.05},
        {"ue4", "deferred-shading", 25, 0.0100, 51.55},
        {"ue5", "deferred-shading", 33, 0.0100, 51.55},
        {"ue5-16bit", "deferred-shading", 57, 0.0027, 52.53},
        {"urp-deferred", "deferred-shading", 17, 0.0105, 49.87},
        {"urp-deferred-accurate", "deferred-shading", 17, 0.0097, 50.16},
        {"visibility-32", "visibility-buffer", 8, 0.0002, 67.92},
        {"visibility-64", "visibility-buffer", 12, 0.0016, 67.92},
    };
    ReportModel m = sampleReport();
    m.run.iblModes = {"split-sum"};
    m.run.views = {"scene camera", "orbit about the scene's centre", "grazing view of the ground"};
    m.reference.images.resize(1);
    m.runs.clear();
    for (const Row& row : rows) {
        RunReport r = sampleRun(row.layout, "split-sum", row.bytes, row.flip, row.psnr);
        r.pipeline = row.pipeline;
        if (r.pipeline == std::string("visibility-buffer"))
            for (FrameTraffic& f : r.bandwidth) {
                f.vertexFetchBytes = double(f.width) * f.height * kVisibilityVertexBytes;
                f.totalBytes += f.vertexFetchBytes;
            }
        for (double scale : {0.9, 1.0, 1.1}) {  // the views: their mean is the run's value
            ViewMetrics v{r.attributes, r.image};
            v.image->flipMean *= scale;
            v.image->psnrToneMapped += (scale - 1.0) * 20.0;
            r.views.push_back(v);
        }
        m.runs.push_back(std::move(r));
    }
    return m;
}

}  // namespace gbl::test
