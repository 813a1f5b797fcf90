#include "compare_compression.h"

#include <algorithm>

#include "stage_clock.h"

namespace gbl::compare {

CompressionCapture::CompressionCapture(const Layout& layout, uint32_t width, uint32_t height)
    : width_(width), height_(height) {
    auto add = [&](const std::string& name, const std::string& format, const TexelLayout& texels) {
        compressors_.push_back(std::make_unique<TargetCompressor>(name, format, texels, width, height));
        nextRow_.push_back(0);
        wordsPerPixel_.push_back(texels.wordsPerPixel);
    };
    if (layout.pipeline == Pipeline::VisibilityBuffer) add("ids", layout.ids.format, texelLayoutOfIds(layout.ids));
    else
        for (const Target& t : layout.targets) add(t.name, t.format, texelLayoutOf(t));
}

std::function<void(size_t, uint32_t, uint32_t, const std::vector<uint32_t>&)> CompressionCapture::callback() {
    return [this](size_t target, uint32_t firstRow, uint32_t rows, const std::vector<uint32_t>& words) {
        take(target, firstRow, rows, words);
    };
}

void CompressionCapture::take(size_t target, uint32_t firstRow, uint32_t rows, const std::vector<uint32_t>& words) {
    if (target >= compressors_.size()) return;  // a target the model does not cover (none today)
    ScopedStage timed(Stage::Metrics);
    // A band's halo repeats rows fed already; a later frame (compare --temporal) all of them.
    const uint32_t from = std::max(firstRow, nextRow_[target]);
    const uint32_t end = firstRow + rows;
    if (from >= end || from != nextRow_[target]) return;
    const size_t rowWords = size_t(width_) * size_t(wordsPerPixel_[target]);
    if (words.size() < size_t(rows) * rowWords) return;
    compressors_[target]->addRows(words.data() + size_t(from - firstRow) * rowWords, end - from);
    nextRow_[target] = end;
}

std::optional<FrameCompression> CompressionCapture::finish() {
    if (compressors_.empty()) return std::nullopt;
    for (uint32_t next : nextRow_)
        if (next != height_) return std::nullopt;
    ScopedStage timed(Stage::Metrics);
    FrameCompression f;
    f.width = width_;
    f.height = height_;
    for (auto& c : compressors_) f.targets.push_back(c->finish());
    return f;
}

}  // namespace gbl::compare
