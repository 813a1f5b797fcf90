#pragma once
// What the renderer needs from a G-buffer layout: the render targets it writes (UINT formats,
// so the shader's packed words reach memory untouched), the depth format, and the GLSL that
// writes and reads them. The GLSL defines, under GBUFFER_WRITE, the fragment outputs and
// `void writeGBuffer(Surface s, ivec2 pixel)`; under GBUFFER_READ, `usampler2D`s at set 1,
// binding i (one per target) and `Surface readGBuffer(ivec2 pixel)`.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

namespace gbl {

class CpuCodec;

struct GBufferWiring {
    std::string layoutName;
    std::vector<std::string> targetNames;
    std::vector<VkFormat> targetFormats;  // as rendered (UINT)
    VkFormat depthFormat = VK_FORMAT_D32_SFLOAT;
    bool reversedZ = false;
    std::string glsl;
    // Per target, the 4 uint words it is cleared with (clearWords in cpu_codec.h: the layout's
    // [clear] values through its own encoders); all 0 for a target rendered in its native format.
    std::vector<std::array<uint32_t, 4>> targetClearWords;
    // emissive = "forward": the G-buffer does not store emissive and readGBuffer returns 0. As
    // UE4's base pass writes emissive into SceneColor, the G-buffer pass also writes the surface's
    // emissive, unquantised (RGBA32F), into one more colour attachment after the layout's targets
    // (GLSL: `gblSceneColorEmissive` at location targetFormats.size()); the lighting pass adds it.
    // It is scene colour, not G-buffer: it is not in the layout's bytes per pixel.
    bool emissiveForward = false;
    // A field is encoded with normal_bestfit: the G-buffer pass reads the best-fit table
    // (best_fit_normals.h); for the others the renderer binds a placeholder and never generates it.
    bool bestFitTable = false;
    // Deferred lighting's material pass: the renderer runs a second geometry pass compiled with
    // MATERIAL_PASS_WRITE into these targets (float32 bits, see wiring_codegen.h) and binds them
    // for readGBuffer at set 2, binding i.
    bool materialPass = false;
    std::vector<VkFormat> materialTargetFormats;
    // Deferred lighting's light buffers (light_buffer_wiring.h): the generated GLSL, included by
    // the lighting pass as "light_buffers.glsl" with LIGHT_PRE_PASS defined, and the 32-bit words
    // per pixel of all buffers, stored at set 0, binding 8. Empty / 0 for deferred shading.
    std::string lightBufferGlsl;
    int lightBufferWordsPerPixel = 0;
    // The layout's [space] (layout.h StoredSpace, as an int: 0 world Y-up, 1 world Z-up, 2 view):
    // the passes compile with GBL_NORMAL_SPACE / GBL_POSITION_SPACE set to these, and
    // shaders/normal_space.glsl transforms around the generated writeGBuffer / readGBuffer.
    int normalSpace = 0;
    int positionSpace = 2;
    bool storesPosition = false;  // the lighting uses the decoded position instead of depth's
    bool storesDepth = false;     // the lighting and decode read the pixel's depth from the G-buffer
                                  // (Surface.position.z) instead of the depth attachment (Bevy WebGL2)
    // Stencil extras (layout [depth] stencil), one per field: the G-buffer pass writes, per draw,
    // the reference OR over fields of (value & mask) << shift, value = the material's
    // (Material::stencilValues) or else the declared one, with stencil op REPLACE and write mask
    // stencilWriteMask (the bits the fields occupy).
    struct StencilField {
        std::string attribute;  // layout-language name, e.g. "indoor"
        uint32_t shift = 0, mask = 0;  // the piece's first stencil bit and its width's mask
        uint32_t valueShift = 0;       // the value's bits this piece takes start here (low bits first)
        uint32_t value = 0;            // the declared value (whole, before valueShift)
    };
    std::vector<StencilField> stencilFields;
    uint32_t stencilWriteMask = 0;
    // A visibility buffer (layout pipeline "visibility-buffer", visibility_wiring.h): the one
    // target, "ids", holds triangle and draw ids (shaders/visibility_buffer.glsl), not attributes;
    // the G-buffer pass writes them and readGBuffer rebuilds the Surface from the triangle
    // (shaders/visibility_resolve.glsl), which needs the scene's geometry, materials and textures
    // bound in set 1 after the ids (renderer_passes.h).
    struct VisibilityIds {
        int triangleBits = 0, drawBits = 0;
        bool alphaMaskBit = false;
        int words = 1;                  // 1: R32_UINT, 2: R32G32_UINT
        uint32_t drawOffset = 0;        // [ids] draw_offset: added to the draw (or cluster) field
        uint32_t clusterTriangles = 0;  // [ids] cluster_triangles: 0 = the draw field holds the draw
        bool depthWord = false;         // [ids] depth_word = 1: word 1 holds the depth's float bits
    };
    bool visibilityBuffer = false;
    VisibilityIds visibilityIds;
    // The layout's CPU codec (cpu_codec.h) where it decodes these targets exactly as readGBuffer
    // does (gpu_cpu_bits_test: within 4 ulps): every target UINT (not --native-formats, where the
    // hardware quantises), not a visibility buffer (its readGBuffer resolves triangles), every
    // stored attribute decodable. Null otherwise. The renderer may decode with it on the host
    // instead of running the decode pass (RenderSettings::decodeOnCpu).
    std::shared_ptr<const CpuCodec> cpuDecoder;
};

// The stencil reference a draw of a material with these per-material values writes (see
// GBufferWiring::stencilFields).
inline uint32_t stencilReference(const GBufferWiring& w,
                                 const std::vector<std::pair<std::string, uint32_t>>& materialValues) {
    uint32_t ref = 0;
    for (const GBufferWiring::StencilField& f : w.stencilFields) {
        uint32_t v = f.value;
        for (const auto& [name, value] : materialValues)
            if (name == f.attribute) v = value;
        ref |= ((v >> f.valueShift) & f.mask) << f.shift;
    }
    return ref;
}

// The float reference: layouts/reference.toml (every attribute as 32-bit float bits in RGBA32_UINT
// targets) through generateWiring (wiring_codegen.h).
GBufferWiring makeReferenceWiring();
// The reference of a scene whose materials have the layers `sceneLayers` (loadReferenceLayout).
GBufferWiring makeReferenceWiring(int sceneLayers);

}  // namespace gbl
