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
#include "file_io.h"
#include "image_io.h"
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

Image readFloatChannels(Imf::InputFile& file, const std::vector<std::string>& names) {
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1;
    const int height = window.max.y - window.min.y + 1;
    Image image(width, height, int(names.size()));
    Imf::FrameBuffer frame;
    const size_t xStride = sizeof(float) * names.size();
    for (size_t c = 0; c < names.size(); ++c)
        frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, window, xStride, xStride * size_t(width)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return image;
}

// Luminance/chroma files (Y, RY, BY) need OpenEXR's RGBA conversion; it yields half precision.
Image readViaRgba(const std::string& path) {
    Imf::RgbaInputFile file(path.c_str());
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
        requireRegularFile(path);  // OpenEXR would block on a FIFO
        {
            Imf::InputFile file(path.c_str());
            const auto& channels = file.header().channels();
            const auto has = [&](const char* name) { return channels.findChannel(name) != nullptr; };
            if (has("R") && has("G") && has("B")) return readFloatChannels(file, {"R", "G", "B"});
            if (!has("Y"))
                throwUserError(path + ": OpenEXR file has channels " + channelList(channels) +
                               " but no R,G,B or Y; export a flat RGB .exr (no layers)");
            if (!has("RY") && !has("BY")) {  // plain grayscale: shown as gray, at full precision
                const Image gray = readFloatChannels(file, {"Y"});
                Image rgb(gray.width, gray.height, 3);
                for (size_t i = 0; i < gray.pixels.size(); ++i)
                    rgb.pixels[i * 3] = rgb.pixels[i * 3 + 1] = rgb.pixels[i * 3 + 2] = gray.pixels[i];
                return rgb;
            }
        }
        return readViaRgba(path);  // luminance + chroma
    });
}

Image readExrChannels(const std::string& path, const std::vector<std::string>& channelNames) {
    return guardedRead(path, [&]() -> Image {
        requireRegularFile(path);
        Imf::InputFile file(path.c_str());
        const auto& channels = file.header().channels();
        for (const auto& name : channelNames)
            if (!channels.findChannel(name))
                throwUserError(path + ": OpenEXR file has no channel '" + name + "' (it has " + channelList(channels) +
                               "); write it with that channel or ask for another");
        return readFloatChannels(file, channelNames);
    });
}

std::vector<std::string> readExrChannelNames(const std::string& path) {
    std::vector<std::string> names;
    guardedRead(path, [&]() -> Image {
        Imf::InputFile file(path.c_str());
        const auto& channels = file.header().channels();
        for (auto it = channels.begin(); it != channels.end(); ++it) names.push_back(it.name());
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
        requireRegularFile(path);
        Imf::InputFile file(path.c_str());
        const auto& channels = file.header().channels();
        for (auto it = channels.begin(); it != channels.end(); ++it) {
            any = true;
            allHalf = allHalf && it.channel().type == Imf::HALF;
        }
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
