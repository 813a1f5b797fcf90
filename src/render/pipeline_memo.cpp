#include "pipeline_memo.h"

#include "shader_cache.h"

namespace gbl {

namespace {

void append(std::string& key, const std::string& part) {
    key += std::to_string(part.size());
    key += ':';
    key += part;
}

void destroyEntry(VkDevice device, MemoPipeline& e) noexcept {
    if (e.pipeline) vkDestroyPipeline(device, e.pipeline, nullptr);
    if (e.layout) vkDestroyPipelineLayout(device, e.layout, nullptr);
    for (VkDescriptorSetLayout l : e.setLayouts)
        if (l) vkDestroyDescriptorSetLayout(device, l, nullptr);
    e = MemoPipeline{};
}

}  // namespace

PassPipeline PipelineMemo::getOrBuild(VkDevice device, const std::string& key,
                                      const std::function<MemoPipeline()>& build) {
    {
        std::lock_guard lock(mutex_);
        const auto it = entries_.find(key);
        if (it != entries_.end()) return {&it->second, false};
    }
    MemoPipeline built = build();  // unlocked: other threads build other pipelines meanwhile
    std::lock_guard lock(mutex_);
    const auto [it, inserted] = entries_.emplace(key, built);
    if (!inserted) destroyEntry(device, built);
    return {&it->second, inserted};
}

bool PipelineMemo::firstUse(const MemoPipeline* entry) {
    std::lock_guard lock(mutex_);
    const bool first = used_.insert(entry).second;
    if (!first) ++shaderCacheCounters().pipelinesReused;  // a later pass of the same wiring
    return first;
}

size_t PipelineMemo::size() const {
    std::lock_guard lock(mutex_);
    return entries_.size();
}

void PipelineMemo::destroy(VkDevice device) noexcept {
    std::lock_guard lock(mutex_);
    for (auto& [key, e] : entries_) destroyEntry(device, e);
    entries_.clear();
    used_.clear();
}

std::string shaderMemoKey(const ShaderSource& source) {
    std::string key = "stage " + std::to_string(int(source.stage)) + ";";
    for (const auto& [name, value] : source.defines) {
        append(key, name);
        append(key, value);
    }
    append(key, source.text);
    for (const auto& [name, text] : source.virtualFiles) {
        append(key, name);
        append(key, text);
    }
    return key;
}

}  // namespace gbl
