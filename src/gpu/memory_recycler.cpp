#include "memory_recycler.h"

#include <cstring>

namespace gbl {

VkDeviceMemory MemoryRecycler::take(uint32_t memoryType, VkDeviceSize size, void** mapped) {
    *mapped = nullptr;
    if (!on_) return VK_NULL_HANDLE;
    std::lock_guard lock(mutex_);
    for (size_t i = parked_.size(); i-- > 0;) {  // the most recently parked first (warm in caches)
        const Block b = parked_[i];
        if (b.type != memoryType || b.size != size) continue;
        parked_.erase(parked_.begin() + std::ptrdiff_t(i));
        (b.host ? hostBytes_ : deviceBytes_) -= b.size;
        ++reused_;
        *mapped = b.mapped;
        return b.memory;
    }
    return VK_NULL_HANDLE;
}

bool MemoryRecycler::park(VkDeviceMemory memory, uint32_t memoryType, VkDeviceSize size, void* mapped,
                          bool hostVisible) {
    if (!on_ || !memory || size == 0) return false;
    std::lock_guard lock(mutex_);
    VkDeviceSize& used = hostVisible ? hostBytes_ : deviceBytes_;
    if (used + size > (hostVisible ? kParkedHostBytes : kParkedDeviceBytes)) return false;
    used += size;
    if (poisonTypes_ & (1u << memoryType)) {
        void* p = mapped;
        if (p || vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, &p) == VK_SUCCESS) {
            std::memset(p, 0xFF, size_t(size));
            if (!mapped) vkUnmapMemory(device_, memory);
        }
    }
    parked_.push_back({memory, memoryType, size, mapped, hostVisible});
    return true;
}

void MemoryRecycler::clear() {
    std::lock_guard lock(mutex_);
    for (const Block& b : parked_) vkFreeMemory(device_, b.memory, nullptr);  // unmaps too
    parked_.clear();
    deviceBytes_ = hostBytes_ = 0;
}

uint64_t MemoryRecycler::reused() const {
    std::lock_guard lock(mutex_);
    return reused_;
}

}  // namespace gbl
