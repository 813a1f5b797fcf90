// OpenEXR in and out. Reads go through the generic FrameBuffer API with FLOAT slices, so float
// files stay bit exact and half files (DWAA/DWAB, PIZ, ...) are widened by OpenEXR itself.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <mutex>
#include <stdexcept>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfThreading.h>
#include <Imath/half.h>

#include "error.h"
#include "exr_probe.h"
#include "file_io.h"
#include "image_io.h"
#include "memory_budget.h"
#include "parallel_for.h"

namespace gbl {
namespace {

// Iex messages can span lines; a UserError is one line.
std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    return text;
}

std::string channelList(const Imf::ChannelList& channels) {
    std::string names;
    for (auto it = channels.begin(); it != channels.end(); ++it) names += (names.empty() ? "" : ",") + std::string(it.name());
    return names.empty() ? "none" : names;
}

// Runs an OpenEXR read and turns its exceptions (Iex::BaseExc is a std::exception) into a
// UserError that names the file.
template <class Fn>
Image guardedRead(const std::string& path, Fn&& read) {
    try {
        return read();
    } catch (const UserError&) {
        throw;
    } catch (const std::exception& e) {
        throwUserError(path + ": cannot read OpenEXR file (" + oneLine(e.what()) +
                       "); check that it is a complete, valid .exr");
    }
}

// The file is opened only after probeExr has held its header against its size, and the frame
// buffer is checked against the memory budget before it exists.
void requireDecodeMemory(const std::string& path, const ExrProbe& p, double bytesPerPixel) {
    requireMemory(double(p.width) * double(p.height) * bytesPerPixel,
                  escapeText(path) + ": reading its " + std::to_string(p.width) + "x" + std::to_string(p.height) +
                      " pixels",
                  "give a smaller image (crop or scale it), or raise GBL_MEMORY_BUDGET on a machine with more memory");
}

void requireComplete(const std::string& path, Imf::InputFile& file, const ExrProbe& p) {
    if (!file.isComplete())
        throwUserError(escapeText(path) + ": its header claims " + std::to_string(p.width) + "x" +
                       std::to_string(p.height) + " pixels, but pixel data is missing (a truncated file, or a "
                       "header that does not match it); re-export it");
}

// Read band by band into memory reserved up front: the image's pages are touched only as rows
// arrive, so a file whose chunks run out (or lie) fails after using what it really held, not the
// whole frame its header claimed.
Image readFloatChannels(Imf::InputFile& file, const std::vector<std::string>& names, const ExrProbe& p) {
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1;
    const int height = window.max.y - window.min.y + 1;
    Image image;
    image.width = width;
    image.height = height;
    image.channels = int(names.size());
    const size_t rowFloats = size_t(width) * names.size();
    image.pixels.reserve(rowFloats * size_t(height));
    const size_t xStride = sizeof(float) * names.size();
    // Bands of whole chunks, about 16 MiB each: a chunk decoded twice would cost its time twice.
    const int chunkLines = std::max(p.linesPerChunk, 1);
    const int wanted = int(std::clamp<size_t>((size_t(16) << 20) / (rowFloats * sizeof(float)), 1, size_t(height)));
    const int bandRows = (wanted + chunkLines - 1) / chunkLines * chunkLines;
    for (int first = 0; first < height; first += bandRows) {
        const int rows = std::min(bandRows, height - first);
        const size_t offset = image.pixels.size();
        image.pixels.resize(offset + rowFloats * size_t(rows));
        const Imath::Box2i band(Imath::V2i(window.min.x, window.min.y + first),
                                Imath::V2i(window.max.x, window.min.y + first + rows - 1));
        Imf::FrameBuffer frame;
        for (size_t c = 0; c < names.size(); ++c)
            frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + offset + c, band, xStride,
                                                    xStride * size_t(width)));
        file.setFrameBuffer(frame);
        file.readPixels(band.min.y, band.max.y);
    }
    return image;
}

// Luminance/chroma files (Y, RY, BY) need OpenEXR's RGBA conversion; it yields half precision.
Image readViaRgba(const std::string& path, const ExrProbe& p) {
    requireDecodeMemory(path, p, sizeof(Imf::Rgba) + 3 * sizeof(float));
    Imf::RgbaInputFile file(path.c_str());
    if (!file.isComplete())
        throwUserError(escapeText(path) + ": its header claims " + std::to_string(p.width) + "x" +
                       std::to_string(p.height) + " pixels, but pixel data is missing (a truncated file, or a "
                       "header that does not match it); re-export it");
    const Imath::Box2i window = file.dataWindow();
    const int width = window.max.x - window.min.x + 1;
    const int height = window.max.y - window.min.y + 1;
    std::vector<Imf::Rgba> rgba(size_t(width) * size_t(height));
    // OpenEXR addresses pixels from a base where (0,0) would be; shift by integer arithmetic so
    // no out-of-range pointer is ever formed in our code.
    const intptr_t origin = intptr_t(window.min.x) + intptr_t(window.min.y) * width;
    auto* base = reinterpret_cast<Imf::Rgba*>(reinterpret_cast<intptr_t>(rgba.data()) - origin * intptr_t(sizeof(Imf::Rgba)));
    file.setFrameBuffer(base, 1, size_t(width));
    file.readPixels(window.min.y, window.max.y);
    Image image(width, height, 3);
    for (size_t i = 0; i < rgba.size(); ++i) {
        image.pixels[i * 3 + 0] = float(rgba[i].r);
        image.pixels[i * 3 + 1] = float(rgba[i].g);
        image.pixels[i * 3 + 2] = float(rgba[i].b);
    }
    return image;
}

}  // namespace

Image readExr(const std::string& path) {
    return guardedRead(path, [&]() -> Image {
        const ExrProbe p = probeExr(path);
        {
            Imf::InputFile file(path.c_str());
            const auto& channels = file.header().channels();
            const auto has = [&](const char* name) { return channels.findChannel(name) != nullptr; };
            if (has("R") && has("G") && has("B")) {
                requireDecodeMemory(path, p, 3 * sizeof(float));
                requireComplete(path, file, p);
                return readFloatChannels(file, {"R", "G", "B"}, p);
            }
            if (!has("Y"))
                throwUserError(path + ": OpenEXR file has channels " + channelList(channels) +
                               " but no R,G,B or Y; export a flat RGB .exr (no layers)");
            if (!has("RY") && !has("BY")) {  // plain grayscale: shown as gray, at full precision
                requireDecodeMemory(path, p, 4 * sizeof(float));
                requireComplete(path, file, p);
                const Image gray = readFloatChannels(file, {"Y"}, p);
                Image rgb(gray.width, gray.height, 3);
                for (size_t i = 0; i < gray.pixels.size(); ++i)
                    rgb.pixels[i * 3] = rgb.pixels[i * 3 + 1] = rgb.pixels[i * 3 + 2] = gray.pixels[i];
                return rgb;
            }
        }
        return readViaRgba(path, p);  // luminance + chroma
    });
}

Image readExrChannels(const std::string& path, const std::vector<std::string>& channelNames) {
    return guardedRead(path, [&]() -> Image {
        const ExrProbe p = probeExr(path);
        Imf::InputFile file(path.c_str());
        const auto& channels = file.header().channels();
        for (const auto& name : channelNames)
            if (!channels.findChannel(name))
                throwUserError(path + ": OpenEXR file has no channel '" + name + "' (it has " + channelList(channels) +
                               "); write it with that channel or ask for another");
        requireDecodeMemory(path, p, double(channelNames.size()) * sizeof(float));
        requireComplete(path, file, p);
        return readFloatChannels(file, channelNames, p);
    });
}

std::vector<std::string> readExrChannelNames(const std::string& path) {
    std::vector<std::string> names;
    guardedRead(path, [&]() -> Image {
        names = probeExr(path).channels;
        return Image();
    });
    return names;
}

const char* exrPixelTypeName(ExrPixelType type) { return type == ExrPixelType::Half ? "half" : "float32"; }

float clampToHalfRange(float v) { return std::isfinite(v) ? std::clamp(v, -kHalfMax, kHalfMax) : v; }

float roundToHalf(float v) { return float(half(clampToHalfRange(v))); }

ExrPixelType readExrPixelType(const std::string& path) {
    bool allHalf = true, any = false;
    guardedRead(path, [&]() -> Image {
        const ExrProbe p = probeExr(path);
        any = !p.channels.empty();
        allHalf = p.bytesPerPixel == 2 * int(p.channels.size());
        return Image();
    });
    return any && allHalf ? ExrPixelType::Half : ExrPixelType::Float32;
}

void writeExr(const std::string& path, const Image& image, const std::vector<std::string>& channelNames,
              ExrPixelType type) {
    static const std::vector<std::vector<std::string>> kDefaults = {{"Y"}, {"R", "G"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
        image.pixels.size() != image.pixelCount() * size_t(image.channels))
        throw std::invalid_argument("writeExr " + path + ": inconsistent image (" + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + "x" + std::to_string(image.channels) + ", " +
                                    std::to_string(image.pixels.size()) + " floats)");
    const auto& names = channelNames.empty() ? kDefaults[size_t(image.channels - 1)] : channelNames;
    if (names.size() != size_t(image.channels))
        throw std::invalid_argument("writeExr " + path + ": " + std::to_string(names.size()) + " channel names for " +
                                    std::to_string(image.channels) + " channels");

    Imf::Header header(image.width, image.height);
    // PIZ (wavelet + Huffman, lossless for half and float alike): compare's 1080p render.exr (RGBA
    // half) wrote in about 175 ms against 315 ms with ZIP at OpenEXR's default level 4, for 13%
    // more bytes (2-core machine under load; RLE: 83 ms, 51% more). The files are written beside
    // the renders, so their CPU time is taken from the passes and the metrics.
    header.compression() = Imf::PIZ_COMPRESSION;
    Imf::FrameBuffer frame;
    // Half: converted here (with the clamp roundToHalf documents), not by OpenEXR, whose
    // float -> half conversion turns values beyond 65504 into infinity.
    std::vector<half> halves;
    if (type == ExrPixelType::Half) {
        halves.resize(image.pixels.size());
        for (size_t i = 0; i < halves.size(); ++i) halves[i] = half(clampToHalfRange(image.pixels[i]));
    }
    const Imf::PixelType pixelType = type == ExrPixelType::Half ? Imf::HALF : Imf::FLOAT;
    const size_t valueBytes = type == ExrPixelType::Half ? sizeof(half) : sizeof(float);
    const size_t xStride = valueBytes * size_t(image.channels);
    // OpenEXR's Slice takes char* for reading and writing alike; it only reads here.
    char* base = type == ExrPixelType::Half ? reinterpret_cast<char*>(halves.data())
                                            : reinterpret_cast<char*>(const_cast<float*>(image.pixels.data()));
    for (size_t c = 0; c < names.size(); ++c) {
        if (header.channels().findChannel(names[c]))
            throw std::invalid_argument("writeExr " + path + ": channel name '" + names[c] + "' given twice");
        header.channels().insert(names[c], Imf::Channel(pixelType));
        frame.insert(names[c], Imf::Slice(pixelType, base + c * valueBytes, xStride, xStride * size_t(image.width)));
    }
    // OpenEXR compresses its blocks of 32 scanlines (PIZ) on its global thread pool when a file
    // is given threads: a 4K render.exr is otherwise one core's 0.3 s at the end of a GPU compare.
    static std::once_flag poolStarted;
    std::call_once(poolStarted, [] { Imf::setGlobalThreadCount(std::min(hardwareThreads(), 16)); });
    writeViaTemporary(path, [&](const std::filesystem::path& tmp) {
        try {
            Imf::OutputFile file(tmp.c_str(), header, Imf::globalThreadCount());
            file.setFrameBuffer(frame);
            file.writePixels(image.height);
        } catch (const std::exception& e) {
            throwUserError(path + ": cannot write OpenEXR file (" + oneLine(e.what()) +
                           "); check that the directory exists, is writable and has space");
        }
    });
}

}  // namespace gbl
