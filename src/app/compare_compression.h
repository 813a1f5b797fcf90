#pragma once
// compare: the framebuffer-compression model on the words a run wrote (measure/
// framebuffer_compression.h). A capture is handed to the render (RenderSettings::onTargetWords),
// takes each target's rows as they are read back (whole frames, or bands with their halos:
// every row once, top to bottom) and gives the frame's compressed sizes.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "framebuffer_compression.h"
#include "layout.h"
#include "renderer.h"

namespace gbl::compare {

class CompressionCapture {
public:
    CompressionCapture(const Layout& layout, uint32_t width, uint32_t height);
    // The callback for RenderSettings::onTargetWords (this must outlive the renders).
    std::function<void(size_t, uint32_t, uint32_t, const std::vector<uint32_t>&)> callback();
    // Every row of every target seen: the frame's sizes; else (a run that failed) nothing.
    std::optional<FrameCompression> finish();

private:
    void take(size_t target, uint32_t firstRow, uint32_t rows, const std::vector<uint32_t>& words);
    uint32_t width_, height_;
    std::vector<std::unique_ptr<TargetCompressor>> compressors_;
    std::vector<uint32_t> nextRow_;  // per target: the first row not yet fed
    std::vector<int> wordsPerPixel_;
};

}  // namespace gbl::compare
