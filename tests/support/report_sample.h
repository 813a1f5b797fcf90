#pragma once
// A sample ReportModel for the report tests: every field set (no defaults left), two IBL modes,
// a failed run, a run identical to the reference (PSNR = +inf), an attribute measured only for
// one material class, text that needs escaping; and small PNGs for every image it names.
#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include "bandwidth.h"
#include "image_io.h"
#include "report_model.h"

namespace gbl::test {

inline ScalarStats sampleStats(double base) {
    ScalarStats s;
    s.count = size_t(1000 + base * 100);
    s.mean = base;
    s.rms = base * 1.25;
    s.p99 = base * 3.5;
    s.max = base * 9.0;
    return s;
}

inline FrameTraffic sampleFrame(uint32_t w, uint32_t h, int samples, double bytesPerPixel) {
    FrameTraffic f;
    f.width = w;
    f.height = h;
    f.samples = samples;
    f.geometryWriteBytes = double(w) * h * samples * bytesPerPixel;
    f.lightingReadBytes = f.geometryWriteBytes;
    f.lightBufferBytes = 12345.5;
    f.totalBytes = f.geometryWriteBytes + f.lightingReadBytes + f.lightBufferBytes;
    f.litOutputBytes = double(w) * h * 8;
    f.onChipExternalBytes = f.litOutputBytes;
    return f;
}

// `name`, `bytes`, FLIP mean and PSNR (tone-mapped) drive the table and the plot.
inline RunReport sampleRun(const std::string& name, const std::string& ibl, int bytes, double flip, double psnr) {
    RunReport r;
    r.layout = name;
    r.title = "Layout " + name + " <as shipped>";
    r.source = "Someone & Other, \"A talk\", GDC 2013";
    r.pipeline = "deferred-shading";
    r.iblMode = ibl;
    r.bytesPerPixel = {bytes - 4, 4, 0, bytes};
    r.bandwidth = {sampleFrame(64, 36, 1, bytes), sampleFrame(1920, 1080, 1, bytes), sampleFrame(1920, 1080, 4, bytes)};
    for (ErrorAttribute a : kErrorAttributes) {
        const double base = 0.001 * (1 + int(a)) * bytes / 10.0 + flip;
        AttributeErrors& e = r.attributes[a];
        e.all = AttributeStats{sampleStats(base), std::nullopt};
        e.metal = AttributeStats{sampleStats(base * 2), std::nullopt};
        e.dielectric = AttributeStats{sampleStats(base / 2), std::nullopt};
        if (errorAttributeIsColor(a)) {
            e.all->rmse = base / 10;
            e.metal->rmse = base / 5;
            e.dielectric->rmse = base / 20;
        }
    }
    r.attributes[ErrorAttribute::Depth].metal.reset();  // absent: only one class measured
    r.image = ImageErrors{flip * 2, psnr + 3, flip, psnr, flip * 40, flip * 6, flip, flip / 2};
    r.times = PassTimes{0.5 + bytes / 100.0, 1.25, "llvmpipe (LLVM 15.0.6, 256 bits)"};
    const std::string dir = "runs/" + name + "-" + ibl + "/";
    r.images = {dir + "render.png", dir + "render.exr", dir + "render_log.png", dir + "error_heatmap.png", dir + "flip.png", dir + "normal_error.png",
                dir + "difference.png", dir + "errors.exr",
                {ReportCrop{8, 4, 16, 12, dir + "crop0_reference.png", dir + "crop0_layout.png", dir + "crop0_heat.png"}}};
    return r;
}

inline ReportModel sampleReport() {
    ReportModel m;
    m.run.scene = "DamagedHelmet.gltf";
    m.run.environment = "studio_small_03_1k.hdr";
    m.run.width = 64;
    m.run.height = 36;
    m.run.device = {"llvmpipe (LLVM 15.0.6, 256 bits)", "llvmpipe Mesa 22.3.6", "cpu"};
    m.run.date = "2024-05-01T12:00:00Z";
    m.run.commandLine = "gbufferlab compare --layouts all --ibl split-sum,none --out \"my report\"";
    m.run.iblModes = {"split-sum", "none"};
    m.run.notes = {"3 ringing texels clamped to 0 in the environment map"};
    m.reference.layout = "reference-float";
    m.reference.images = {
        {"split-sum", "reference/split-sum/render.png", "reference/split-sum/render.exr", "reference/split-sum/log.png"},
        {"none", "reference/none/render.png", "reference/none/render.exr", "reference/none/log.png"}};
    m.runs.push_back(sampleRun("ue4", "split-sum", 20, 0.0213, 41.5));
    m.runs.push_back(sampleRun("compact-octahedral", "split-sum", 12, 0.0561, 33.25));
    m.runs.push_back(sampleRun("fat-naive", "split-sum", 44, 0.0, INFINITY));  // identical to the reference
    m.runs.push_back(sampleRun("ryse", "split-sum", 16, 0.0710, 30.0));          // dominated by compact-octahedral
    m.runs.push_back(sampleRun("ue4", "none", 20, 0.0155, 44.75));
    m.runs.push_back(sampleRun("compact-octahedral", "none", 12, 0.0402, 36.0));
    RunReport failed = sampleRun("broken<layout>", "split-sum", 24, 0, 0);
    failed.status = RunStatus::Failed;
    failed.error = "shaders/encodings.glsl:12: error: 'octEncode' : no matching overloaded function <script>x</script>";
    failed.pipeline = "deferred-lighting";
    failed.bytesPerPixel = {16, 4, 8, 28};
    failed.attributes = {};
    failed.image.reset();
    failed.times.reset();
    failed.images = {};
    m.runs.push_back(failed);
    return m;
}

// Writes a small PNG for every PNG path the model names (distinct colours per file).
inline void writeSampleImages(const std::filesystem::path& dir, const ReportModel& m) {
    std::set<std::string> paths;
    for (const ReferenceImage& r : m.reference.images) paths.insert({r.render, r.hdrPreview});
    for (const RunReport& r : m.runs) {
        for (const std::string* p : {&r.images.render, &r.images.hdrPreview, &r.images.errorHeatmap, &r.images.flip, &r.images.normalError,
                                     &r.images.difference})
            if (!p->empty()) paths.insert(*p);
        for (const ReportCrop& c : r.images.crops)
            for (const std::string* p : {&c.reference, &c.layout, &c.heat}) paths.insert(*p);
    }
    int k = 0;
    for (const std::string& p : paths) {
        Image8 image{64, 36, 3, {}};
        image.pixels.resize(64 * 36 * 3);
        for (int y = 0; y < 36; ++y)
            for (int x = 0; x < 64; ++x) {
                unsigned char* px = &image.pixels[(size_t(y) * 64 + x) * 3];
                px[0] = (unsigned char)(x * 4 + k * 37);
                px[1] = (unsigned char)(y * 7 + k * 11);
                px[2] = (unsigned char)(128 + 127 * std::sin(0.2 * (x + y) + k));
            }
        std::filesystem::create_directories((dir / p).parent_path());
        writePng((dir / p).string(), image);
        ++k;
    }
}

}  // namespace gbl::test
