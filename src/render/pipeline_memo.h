#pragma once
// The pipelines a Renderer has built, kept for its lifetime and found again by what they were
// built from (issue 14: `compare --views 3` rebuilt every layout's pipelines per view and per IBL
// mode, 92 pipelines where 32 do). A pipeline depends on its shaders' full input (source, every
// included file, the defines) and the fixed-function state it was created with, never on the
// image size or the camera (uniforms and descriptors), so one built for a layout serves every
// view of that layout. The lighting pass's is built per IBL mode and Fresnel in a run of one mode
// (defines in its key, renderer_passes.h LightingVariant: llvmpipe JIT-compiles every branch, and
// the shader holding all the modes cost about 1.5x the one mode's), else once for all modes; the
// G-buffer, material and decode passes do not depend on the mode and serve all of them.
//
// Each entry owns its descriptor-set layouts and pipeline layout as well: a pass that borrows the
// pipeline binds its sets through the same pipeline layout the pipeline was created with.
// Thread-safe: pipelines may be built on several threads at once (Renderer::preparePipelines).
#include <cstddef>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "shader_compiler.h"
#include "vk_context.h"

namespace gbl {

struct MemoPipeline {
    std::vector<VkDescriptorSetLayout> setLayouts;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
};

// A memo's entry, and whether this call built it.
struct PassPipeline {
    const MemoPipeline* entry = nullptr;
    bool fresh = false;
};

class PipelineMemo {
public:
    // The entry under `key`, built by `build` when there is none. When two threads build the same
    // key at once, the first stored wins and the other's objects are destroyed. Entries never
    // move: the pointer stays valid until destroy().
    PassPipeline getOrBuild(VkDevice device, const std::string& key, const std::function<MemoPipeline()>& build);
    // True the first time it is asked for `entry`: the first pass to use a pipeline warms it up
    // (Renderer::render), whether it was built then or before (preparePipelines). Every later
    // use counts as a reuse (ShaderCacheCounters::pipelinesReused).
    bool firstUse(const MemoPipeline* entry);
    size_t size() const;
    void destroy(VkDevice device) noexcept;

private:
    mutable std::mutex mutex_;
    std::map<std::string, MemoPipeline> entries_;
    std::set<const MemoPipeline*> used_;
};

// The part of a memo key that a shader contributes: its stage, defines, text and the virtual
// files it may include (the generated wiring), each length-prefixed so no two inputs collide.
// Its display name is left out: two layouts with the same wiring share the pipeline.
std::string shaderMemoKey(const ShaderSource& source);

}  // namespace gbl
