#include "error_images.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>

#include "color_map.h"
#include "error.h"
#include "file_io.h"
#include "image_io.h"
#include "parallel_invoke.h"

namespace gbl {
namespace {

std::string fmt(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

std::string titled(const ErrorImageOptions& o, const std::string& title) {
    return o.label.empty() ? title : o.label + ": " + title;
}

void requireMap(const Image& image, const char* what) {
    if (image.empty()) throwUserError(std::string("error images: the ") + what + " map is missing; compute the run "
                                      "metrics with RunMetricsOptions::maps set");
}

// `colourMapped`: a heat map (a 256-colour table, a NaN grey, legend text), or the amplified
// difference (black but for sparse noise), written by encodePngColourMapped: indexed when it has
// at most 256 colours, else RGB with the None filter at level 6; the same pixels in 40-60% of the
// bytes (png_writer.h).
std::string writePngAt(const std::filesystem::path& dir, const std::string& prefix, const char* name, const Image8& img,
                       bool colourMapped = false) {
    const std::string rel = prefix + name;
    const std::filesystem::path full = dir / rel;
    std::error_code ec;
    std::filesystem::create_directories(full.parent_path(), ec);
    if (colourMapped) writeColourMappedPng(full.string(), img);
    else writePng(full.string(), img);
    return rel;
}

float heatMaxOf(const ErrorImageOptions& o) { return o.heatMax > 0.0f ? o.heatMax : 0.1f; }
float amplificationOf(const ErrorImageOptions& o) { return o.amplification > 0.0f ? o.amplification : 8.0f; }
float normalScaleOf(const ErrorImageOptions& o, const RunMetrics& m) {
    return std::max(o.normalMinScaleDeg, float(m.normal.all.error.p99));
}
std::string heatTitle(const ErrorImageOptions& o) {
    return titled(o, "RELATIVE LUMINANCE ERROR, 0-" + fmt("%g", 100.0 * heatMaxOf(o)) + "% (CLIPPED)");
}
std::string flipTitle(const ErrorImageOptions& o, const RunMetrics& m) {
    return titled(o, "LDR-FLIP  MEAN " + fmt("%.4f", m.image.flipMean));
}
std::string normalTitle(const ErrorImageOptions& o, const RunMetrics& m) {
    return titled(o, "NORMAL ERROR (\u00b0)  MEAN " + fmt("%.3g", m.normal.all.error.mean) + "  P99 " +
                         fmt("%.3g", m.normal.all.error.p99));
}
std::string differenceTitle(const ErrorImageOptions& o) {
    return titled(o, "ABS(TEST - REF) X " + fmt("%g", amplificationOf(o)) + ", TONE-MAPPED");
}

}  // namespace


std::vector<std::string> ErrorImagePaths::all() const {
    std::vector<std::string> out;
    for (const std::string* p : {&render, &heatmap, &flip, &normalError, &difference, &errorsExr})
        if (!p->empty()) out.push_back(*p);
    return out;
}

Image8 srgbFloatTo8(const Image& srgb) {
    if (srgb.channels != 1 && srgb.channels < 3)
        throwUserError("srgbFloatTo8: image has " + std::to_string(srgb.channels) + " channels; need 1, 3 or 4");
    Image8 out{srgb.width, srgb.height, 3, std::vector<unsigned char>(srgb.pixelCount() * 3)};
    const size_t ch = size_t(srgb.channels);
    for (size_t i = 0; i < srgb.pixelCount(); ++i)
        for (size_t c = 0; c < 3; ++c) {
            float v = srgb.pixels[i * ch + (ch == 1 ? 0 : c)];
            v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
            out.pixels[i * 3 + c] = static_cast<unsigned char>(std::floor(v * 255.0f + 0.5f));
        }
    return out;
}

Image8 heatMapImage(const Image& scalar, float lo, float hi, std::string_view title, const Image* background,
                    const std::vector<uint8_t>* measured) {
    Image8 map = applyColorMap(scalar, lo, hi);
    if (measured && !measured->empty()) {
        if (measured->size() != scalar.pixelCount())
            throwUserError("heat map: the mask has " + std::to_string(measured->size()) + " entries for " +
                           std::to_string(scalar.pixelCount()) + " pixels");
        const bool dim = background && !background->empty() && background->width == scalar.width &&
                         background->height == scalar.height && (background->channels == 1 || background->channels >= 3);
        for (size_t i = 0; i < scalar.pixelCount(); ++i) {
            if ((*measured)[i]) continue;
            unsigned char g = 128;
            if (dim) {
                const size_t ch = size_t(background->channels);
                const float* p = &background->pixels[i * ch];
                float y = ch == 1 ? p[0] : 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
                y = std::isnan(y) ? 0.0f : std::clamp(y, 0.0f, 1.0f);
                g = static_cast<unsigned char>(std::floor((0.12f + 0.3f * y) * 255.0f + 0.5f));  // dim grey
            }
            map.pixels[i * 3 + 0] = map.pixels[i * 3 + 1] = map.pixels[i * 3 + 2] = g;
        }
    }
    return titledPicture(map, title, true, lo, hi);
}

Image8 amplifiedDifferenceImage(const Image& referenceSrgb, const Image& testSrgb, float k, std::string_view title) {
    if (referenceSrgb.width != testSrgb.width || referenceSrgb.height != testSrgb.height ||
        referenceSrgb.channels < 3 || testSrgb.channels < 3)
        throwUserError("difference image: the tone-mapped images differ in size or are not RGB");
    Image8 map{referenceSrgb.width, referenceSrgb.height, 3,
               std::vector<unsigned char>(referenceSrgb.pixelCount() * 3)};
    const size_t rc = size_t(referenceSrgb.channels), tc = size_t(testSrgb.channels);
    for (size_t i = 0; i < referenceSrgb.pixelCount(); ++i)
        for (size_t c = 0; c < 3; ++c) {
            float d = k * std::abs(testSrgb.pixels[i * tc + c] - referenceSrgb.pixels[i * rc + c]);
            d = std::isnan(d) ? 1.0f : std::min(d, 1.0f);
            map.pixels[i * 3 + c] = static_cast<unsigned char>(std::floor(d * 255.0f + 0.5f));
        }
    return titledPicture(map, title, false, 0.0f, 1.0f);
}

std::vector<std::string> errorExrChannels(const RunErrorMaps& m) {
    std::vector<std::string> names;
    auto add = [&](const Image& image, const char* name) {
        if (!image.empty()) names.push_back(name);
    };
    add(m.flip, "flip");
    add(m.hdrFlip, "hdr_flip");
    if (!m.absLinear.empty()) {
        names.push_back("abs_r");
        names.push_back("abs_g");
        names.push_back("abs_b");
    }
    add(m.relLuminance, "rel_luminance");
    add(m.normalDeg, "normal_deg");
    add(m.baseColorDe, "base_color_de");
    add(m.diffuseColorDe, "diffuse_de");
    add(m.specularColorDe, "specular_de");
    add(m.roughnessAbs, "roughness_abs");
    add(m.metallicAbs, "metallic_abs");
    add(m.occlusionAbs, "occlusion_abs");
    add(m.depthRel, "depth_rel");
    if (!m.measured.empty()) names.push_back("measured");
    return names;
}

void writeErrorExr(const std::filesystem::path& path, const RunErrorMaps& m, ExrPixelType type) {
    requireMap(m.flip, "FLIP");
    const int w = m.flip.width, h = m.flip.height;
    const size_t n = m.flip.pixelCount();
    // Planar float copies, one per channel (Slices read them in place).
    std::vector<std::pair<std::string, std::vector<float>>> planes;
    auto addPlane = [&](const Image& image, const char* name, int channel) {
        if (image.empty()) return;
        if (image.width != w || image.height != h || channel >= image.channels)
            throwUserError(std::string("error EXR: the ") + name + " map has the wrong size");
        std::vector<float> plane(n);
        for (size_t i = 0; i < n; ++i) plane[i] = image.pixels[i * size_t(image.channels) + size_t(channel)];
        planes.emplace_back(name, std::move(plane));
    };
    addPlane(m.flip, "flip", 0);
    addPlane(m.hdrFlip, "hdr_flip", 0);
    addPlane(m.absLinear, "abs_r", 0);
    addPlane(m.absLinear, "abs_g", 1);
    addPlane(m.absLinear, "abs_b", 2);
    addPlane(m.relLuminance, "rel_luminance", 0);
    addPlane(m.normalDeg, "normal_deg", 0);
    addPlane(m.baseColorDe, "base_color_de", 0);
    addPlane(m.diffuseColorDe, "diffuse_de", 0);
    addPlane(m.specularColorDe, "specular_de", 0);
    addPlane(m.roughnessAbs, "roughness_abs", 0);
    addPlane(m.metallicAbs, "metallic_abs", 0);
    addPlane(m.occlusionAbs, "occlusion_abs", 0);
    addPlane(m.depthRel, "depth_rel", 0);
    if (!m.measured.empty()) {
        if (m.measured.size() != n) throwUserError("error EXR: the measured mask has the wrong size");
        std::vector<float> plane(n);
        for (size_t i = 0; i < n; ++i) plane[i] = m.measured[i] ? 1.0f : 0.0f;
        planes.emplace_back("measured", std::move(plane));
    }

    Imf::Header header(w, h);
    // PIZ (lossless): a 1080p file of compare's 14 half planes wrote in about 360 ms against 720 ms
    // with ZIP level 1, for 11% more bytes (2-core machine under load; exr_io.cpp writeExr).
    header.compression() = Imf::PIZ_COMPRESSION;
    Imf::FrameBuffer frame;
    // Half: converted plane by plane here (image_io.h clampToHalfRange: no overflow to infinity).
    std::vector<std::vector<half>> halfPlanes;
    for (auto& [name, plane] : planes) {
        if (type == ExrPixelType::Half) {
            std::vector<half>& hp = halfPlanes.emplace_back(plane.size());
            for (size_t i = 0; i < plane.size(); ++i) hp[i] = half(clampToHalfRange(plane[i]));
            std::vector<float>().swap(plane);
            header.channels().insert(name, Imf::Channel(Imf::HALF));
            frame.insert(name, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(hp.data()), sizeof(half),
                                          sizeof(half) * size_t(w)));
            continue;
        }
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        frame.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(plane.data()), sizeof(float),
                                      sizeof(float) * size_t(w)));
    }
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    writeViaTemporary(path, [&](const std::filesystem::path& tmp) {
        try {
            Imf::OutputFile file(tmp.c_str(), header);
            file.setFrameBuffer(frame);
            file.writePixels(h);
        } catch (const std::exception& e) {
            throwUserError(path.string() + ": cannot write OpenEXR file (" + e.what() +
                           "); check that the directory exists, is writable and has space");
        }
    });
}

ErrorImagePaths errorImagePaths(const std::string& prefix, const RunErrorMaps& maps, bool errorExr) {
    ErrorImagePaths p;
    p.render = prefix + "render.png";
    p.heatmap = prefix + "error_heatmap.png";
    p.flip = prefix + "flip.png";
    if (!maps.normalDeg.empty()) p.normalError = prefix + "normal_error.png";
    p.difference = prefix + "difference.png";
    if (errorExr) p.errorsExr = prefix + "errors.exr";
    return p;
}

ErrorImagePaths writeErrorImages(const std::filesystem::path& dir, const std::string& prefix, const RunErrorMaps& maps,
                                 const RunMetrics& metrics, const ErrorImageOptions& o) {
    requireMap(maps.testSrgb, "tone-mapped render");
    if (!maps.referenceSrgb) throwUserError("error images: the tone-mapped reference map is missing");
    requireMap(*maps.referenceSrgb, "tone-mapped reference");
    requireMap(maps.relLuminance, "relative luminance error");
    requireMap(maps.flip, "FLIP");
    // The files are independent: encode them side by side (PNG deflate is single-threaded).
    ErrorImagePaths paths;
    std::vector<std::function<void()>> writes;
    writes.push_back([&] { paths.render = writePngAt(dir, prefix, "render.png", srgbFloatTo8(maps.testSrgb)); });

    writes.push_back([&] {
        paths.heatmap = writePngAt(dir, prefix, "error_heatmap.png",
                                   heatMapImage(maps.relLuminance, 0.0f, heatMaxOf(o), heatTitle(o)), true);
    });
    writes.push_back([&] {
        paths.flip = writePngAt(dir, prefix, "flip.png", heatMapImage(maps.flip, 0.0f, 1.0f, flipTitle(o, metrics)), true);
    });
    if (!maps.normalDeg.empty()) {
        writes.push_back([&] {
            paths.normalError =
                writePngAt(dir, prefix, "normal_error.png",
                           heatMapImage(maps.normalDeg, 0.0f, normalScaleOf(o, metrics), normalTitle(o, metrics),
                                        maps.referenceSrgb.get(), &maps.measured), true);
        });
    }
    writes.push_back([&] {
        paths.difference = writePngAt(dir, prefix, "difference.png",
                                      amplifiedDifferenceImage(*maps.referenceSrgb, maps.testSrgb, amplificationOf(o),
                                                               differenceTitle(o)), true);
    });

    if (o.writeErrorExr)
        writes.push_back([&] {
            writeErrorExr(dir / (prefix + "errors.exr"), maps, o.exrType);
            paths.errorsExr = prefix + "errors.exr";
        });
    parallelInvoke(writes);
    return paths;
}

ErrorImagePaths writeErrorImageBodies(const std::filesystem::path& dir, const std::string& prefix,
                                      const ErrorImageBodies& b, const RunMetrics& metrics, const ErrorImageOptions& o) {
    if (b.render.pixels.empty() || b.heat.pixels.empty() || b.flip.pixels.empty() || b.difference.pixels.empty())
        throwUserError("error images: a colour-mapped map is missing; evaluate the run with its images requested");
    ErrorImagePaths paths;
    std::vector<std::function<void()>> writes;
    writes.push_back([&] { paths.render = writePngAt(dir, prefix, "render.png", b.render); });
    writes.push_back([&] {
        paths.heatmap = writePngAt(dir, prefix, "error_heatmap.png",
                                   titledPicture(b.heat, heatTitle(o), true, 0.0f, heatMaxOf(o)), true);
    });
    writes.push_back([&] {
        paths.flip = writePngAt(dir, prefix, "flip.png", titledPicture(b.flip, flipTitle(o, metrics), true, 0.0f, 1.0f), true);
    });
    if (!b.normal.pixels.empty())
        writes.push_back([&] {
            paths.normalError = writePngAt(dir, prefix, "normal_error.png",
                                           titledPicture(b.normal, normalTitle(o, metrics), true, 0.0f,
                                                         normalScaleOf(o, metrics)), true);
        });
    writes.push_back([&] {
        paths.difference = writePngAt(dir, prefix, "difference.png",
                                      titledPicture(b.difference, differenceTitle(o), false, 0.0f, 1.0f), true);
    });
    parallelInvoke(writes);
    return paths;
}

}  // namespace gbl
