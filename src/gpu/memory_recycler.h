#pragma once
// Device memory kept for reuse instead of freed, on a GPU.
//
// compare renders the same frames again and again (every layout, every view): each render made
// and freed its targets, decoded surfaces and read-back staging. On an H200 at 3840x2160 the
// rendering and read-back stages took 1.0 s for 0.28 s of GPU passes: a driver that zeroes and
// maps hundreds of MB per allocation pays for it every time. Here a freed block is parked and the
// next allocation of the same memory type and size takes it back.
//
// Contract:
// - Only blocks of exactly the asked size and memory type are reused (renders repeat their sizes;
//   no block is split). Host-visible blocks stay mapped: the mapping comes back with the block.
// - The contents of a reused block are whatever was last written: as for vkAllocateMemory, whose
//   contents are undefined, every user writes before it reads.
// - Off on a CPU device (lavapipe), whose allocations are the process's heap and whose 4K peak
//   memory is a goal (bench/README.md): there every free is a vkFreeMemory, as before.
// - Parked memory is bounded (kParkedDeviceBytes / kParkedHostBytes); past that, frees free.
// - Thread-safe: one mutex.
#include <cstdint>
#include <mutex>
#include <vector>

#include <vulkan/vulkan.h>

namespace gbl {

class MemoryRecycler {
public:
    static constexpr VkDeviceSize kParkedDeviceBytes = VkDeviceSize(4) << 30;
    static constexpr VkDeviceSize kParkedHostBytes = VkDeviceSize(1) << 30;

    void enable(VkDevice device, bool on) { device_ = device, on_ = on; }
    bool enabled() const { return on_; }
    // Tests: every parked block that can be mapped (hostVisibleTypes: bit per memory type) is
    // filled with 0xFF bytes (NaN floats, all-ones words), so a render that reads memory it did
    // not write first differs from one on fresh memory.
    void poisonParked(uint32_t hostVisibleTypes) { poisonTypes_ = hostVisibleTypes; }
    // A parked block of this type and size, or VK_NULL_HANDLE; *mapped gets its mapping (or null).
    VkDeviceMemory take(uint32_t memoryType, VkDeviceSize size, void** mapped);
    // Parks the block (true) or declines (false: the caller frees it). hostVisible: counted
    // against the host bound.
    bool park(VkDeviceMemory memory, uint32_t memoryType, VkDeviceSize size, void* mapped, bool hostVisible);
    // Frees every parked block (before the device is destroyed).
    void clear();
    uint64_t reused() const;

private:
    struct Block {
        VkDeviceMemory memory;
        uint32_t type;
        VkDeviceSize size;
        void* mapped;
        bool host;
    };
    mutable std::mutex mutex_;
    std::vector<Block> parked_;
    VkDeviceSize deviceBytes_ = 0, hostBytes_ = 0;
    uint64_t reused_ = 0;
    VkDevice device_ = VK_NULL_HANDLE;
    bool on_ = false;
    uint32_t poisonTypes_ = 0;
};

}  // namespace gbl
