#pragma once
// Facts about a layout that both of its interpreters need, the generated GLSL (wiring_codegen.h)
// and the CPU mirror (cpu_codec.h): the words each target renders to, the material pass's float
// slots, the order fallbacks are applied in, and the Surface member each attribute fills.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "layout.h"

namespace gbl {

// 32-bit words per pixel of a target as rendered (1 for targets of <= 32 bits).
int wordsPerPixel(const Target& target);
VkFormat uintFormatOf(const Target& target);
// A target's texels as downloaded (`pixels` of them) as its words: wordsPerPixel words per pixel.
// Texels narrower than a word (R8_UINT, R16_UINT: Bevy's pass id, Granite's RG8) are widened, one
// zero-extended little-endian word each, as the CPU codec holds them.
std::vector<uint32_t> texelsToWords(const std::vector<uint8_t>& bytes, size_t pixels);
// The nominal format as a VkFormat (VK_FORMAT_UNDEFINED when unknown).
VkFormat vkFormatFromName(const std::string& name);
// Material pass (deferred lighting): the float slots of the attributes whose fallback is
// material_pass, packed 4 per R32G32B32A32_UINT material target.
struct MaterialSlot {
    Attribute attribute;
    int components;
    int firstFloat;  // float index over all material targets (target = index / 4, channel = index % 4)
};
std::vector<MaterialSlot> materialPassSlots(const Layout& layout);
int materialTargetCount(const Layout& layout);

// The layout's fallbacks in an order where each one's inputs are stored or already derived.
// Throws std::logic_error on a cycle (validation rules those out).
std::vector<const Fallback*> orderedFallbacks(const Layout& layout);
// The attributes a derived fallback's formula reads (none for constants, forward, material pass).
std::vector<Attribute> fallbackInputs(FallbackKind kind);

// Surface member name of a shading / geometry attribute ("baseColor"); nullptr for extras and
// for `depth`, which is no member of its own (an exported Surface gives it one, `depth`).
const char* surfaceMemberName(Attribute a);
// The attributes with a Surface member, in the Surface's order (shaders/surface.glsl): the shading
// attributes, position, the layers. (The Surface's last member, shadingModel, is no attribute yet.)
const std::vector<Attribute>& surfaceAttributes();
// Where gbufferlab's own Surface holds an attribute: its member, or for a stored window `depth`
// "position.z" (a layout stores position or depth, not both: the Surface keeps its 36 floats, the
// shape the CPU codec's transposes and the bit tests share). The lighting and decode passes read
// it back as the pixel's depth. nullptr for extras.
const char* surfaceSlotName(Attribute a);

}  // namespace gbl
