#include "visibility_wiring.h"

#include <sstream>

#include "glsl_text.h"
#include "wiring_plan.h"

namespace gbl {

namespace {

// How many distinct ids `bits` bits hold (2^bits, exactly, up to 2^32).
unsigned long long idCapacity(int bits) { return 1ull << bits; }

}  // namespace

std::string generateVisibilityWiringGlsl(const Layout& layout) {
    const VisibilityIds& ids = layout.ids;
    std::ostringstream o;
    o << "// generated from the layout '" << glslCommentText(layout.name) << "' by gbufferlab -- do not edit\n";
    o << "// " << glslCommentText(layout.title) << " (" << pipelineName(layout.pipeline) << ")\n";
    o << "#define GBL_VISIBILITY_BUFFER 1\n";
    o << "#define GBL_VIS_ID_WORDS " << ids.bits / 32 << "\n";
    o << "#define GBL_VIS_TRIANGLE_BITS " << ids.triangleBits << "u\n";
    o << "#define GBL_VIS_DRAW_BITS " << ids.drawBits << "u\n";
    o << "#define GBL_VIS_ALPHA_MASK_BIT " << (ids.alphaMaskBit ? 1 : 0) << "\n";
    o << "#include \"visibility_buffer.glsl\"\n";
    return o.str();
}

GBufferWiring generateVisibilityWiring(const Layout& layout) {
    GBufferWiring w;
    w.layoutName = layout.name;
    w.targetNames = {"ids"};
    w.targetFormats = {layout.ids.bits == 64 ? VK_FORMAT_R32G32_UINT : VK_FORMAT_R32_UINT};
    // Cleared to 0: a pixel without geometry is told by its depth, as in every layout.
    w.targetClearWords = {std::array<uint32_t, 4>{0, 0, 0, 0}};
    w.depthFormat = vkFormatFromName(layout.depth.format);
    w.reversedZ = layout.depth.reversedZ;
    w.glsl = generateVisibilityWiringGlsl(layout);
    w.visibilityBuffer = true;
    w.visibilityIds = {layout.ids.triangleBits, layout.ids.drawBits, layout.ids.alphaMaskBit};
    // Nothing is stored in another space: the resolve's Surface (its position included, the ray's
    // hit) is already in gbufferlab's world, so normal_space.glsl must leave it as it is.
    w.normalSpace = int(StoredSpace::WorldYUp);
    w.positionSpace = int(StoredSpace::WorldYUp);
    return w;
}

std::string visibilityCapacityProblem(const GBufferWiring& wiring, size_t draws, size_t maxTrianglesPerDraw) {
    if (!wiring.visibilityBuffer) return "";
    const GBufferWiring::VisibilityIds& ids = wiring.visibilityIds;
    const std::string layout = "layout '" + wiring.layoutName + "': ";
    if (draws > idCapacity(ids.drawBits))
        return layout + "the scene has " + std::to_string(draws) + " draws but " + std::to_string(ids.drawBits) +
               "-bit draw ids hold " + std::to_string(idCapacity(ids.drawBits)) +
               "; use visibility-64 (32-bit draw ids) or more draw_bits in [ids]";
    if (maxTrianglesPerDraw > idCapacity(ids.triangleBits))
        return layout + "a draw of the scene has " + std::to_string(maxTrianglesPerDraw) + " triangles but " +
               std::to_string(ids.triangleBits) + "-bit triangle ids hold " +
               std::to_string(idCapacity(ids.triangleBits)) +
               "; use visibility-64 (32-bit triangle ids) or more triangle_bits in [ids]";
    return "";
}

}  // namespace gbl
