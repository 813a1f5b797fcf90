#include "visibility_wiring.h"

#include <algorithm>
#include <cstring>
#include <sstream>

#include "glsl_text.h"
#include "wiring_plan.h"

namespace gbl {

namespace {

// How many distinct values `bits` bits hold (2^bits, exactly, up to 2^32).
unsigned long long idCapacity(int bits) { return 1ull << bits; }

// The bits the ids fill: the whole target, or word 0 where word 1 holds depth.
int idBits(const GBufferWiring::VisibilityIds& ids) { return ids.depthWord ? 32 : 32 * ids.words; }

uint32_t lowMask(int count) { return count >= 32 ? 0xFFFFFFFFu : (1u << count) - 1u; }

// As visibility_buffer.glsl's gblPutBits / gblGetBits: `count` (1..32) bits at `first` of the
// little-endian bit string of two words, straddling them if need be.
void putBits(std::array<uint32_t, 2>& w, uint32_t value, int first, int count) {
    value &= lowMask(count);
    if (first >= 32) {
        w[1] |= value << (first - 32);
        return;
    }
    w[0] |= value << first;
    if (first + count > 32) w[1] |= value >> (32 - first);
}

uint32_t getBits(const std::array<uint32_t, 2>& w, int first, int count) {
    uint32_t v = first >= 32 ? w[1] >> (first - 32) : w[0] >> first;
    if (first < 32 && first + count > 32) v |= w[1] << (32 - first);
    return v & lowMask(count);
}

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
    o << "#define GBL_VIS_DRAW_OFFSET " << ids.drawOffset << "u\n";
    o << "#define GBL_VIS_CLUSTERS " << (ids.clusterTriangles > 0 ? 1 : 0) << "\n";
    o << "#define GBL_VIS_CLUSTER_TRIANGLES " << ids.clusterTriangles << "u\n";
    if (ids.depthWord >= 0) o << "#define GBL_VIS_DEPTH_WORD 1\n";
    o << "#include \"visibility_buffer.glsl\"\n";
    return o.str();
}

GBufferWiring generateVisibilityWiring(const Layout& layout) {
    GBufferWiring w;
    w.layoutName = layout.name;
    w.targetNames = {"ids"};
    w.targetFormats = {layout.ids.bits == 64 ? VK_FORMAT_R32G32_UINT : VK_FORMAT_R32_UINT};
    // Cleared to 0: a pixel without geometry is told by its depth, as in every layout (with a
    // depth word, by word 1's 0.0, the reversed-Z far plane: Nanite and Bevy clear to 0 too).
    w.targetClearWords = {std::array<uint32_t, 4>{0, 0, 0, 0}};
    w.depthFormat = vkFormatFromName(layout.depth.format);
    w.reversedZ = layout.depth.reversedZ;
    w.glsl = generateVisibilityWiringGlsl(layout);
    w.visibilityBuffer = true;
    w.visibilityIds.triangleBits = layout.ids.triangleBits;
    w.visibilityIds.drawBits = layout.ids.drawBits;
    w.visibilityIds.alphaMaskBit = layout.ids.alphaMaskBit;
    w.visibilityIds.words = layout.ids.bits == 64 ? 2 : 1;
    w.visibilityIds.drawOffset = layout.ids.drawOffset;
    w.visibilityIds.clusterTriangles = layout.ids.clusterTriangles;
    w.visibilityIds.depthWord = layout.ids.depthWord >= 0;
    // Nothing is stored in another space: the resolve's Surface (its position included, the ray's
    // hit) is already in gbufferlab's world, so normal_space.glsl must leave it as it is.
    w.normalSpace = int(StoredSpace::WorldYUp);
    w.positionSpace = int(StoredSpace::WorldYUp);
    return w;
}

std::string visibilityCapacityProblem(const GBufferWiring& wiring, const std::vector<size_t>& drawTriangles) {
    if (!wiring.visibilityBuffer) return "";
    const GBufferWiring::VisibilityIds& ids = wiring.visibilityIds;
    const std::string layout = "layout '" + wiring.layoutName + "': ";
    // The draw field stores index + offset, so it holds 2^bits - offset indices.
    const unsigned long long fieldIds = idCapacity(ids.drawBits) - ids.drawOffset;
    const std::string offsetNote = ids.drawOffset ? " (with draw_offset " + std::to_string(ids.drawOffset) + ")" : "";
    if (ids.clusterTriangles > 0) {
        unsigned long long clusters = 0;
        for (size_t t : drawTriangles) clusters += (t + ids.clusterTriangles - 1) / ids.clusterTriangles;
        if (clusters > fieldIds)
            return layout + "the scene has " + std::to_string(clusters) + " clusters of up to " +
                   std::to_string(ids.clusterTriangles) + " triangles but " + std::to_string(ids.drawBits) +
                   "-bit cluster ids" + offsetNote + " hold " + std::to_string(fieldIds) +
                   "; use visibility-64 (32-bit draw ids) or more draw_bits in [ids]";
        return "";
    }
    size_t maxTriangles = 0;
    for (size_t t : drawTriangles) maxTriangles = std::max(maxTriangles, t);
    if (drawTriangles.size() > fieldIds)
        return layout + "the scene has " + std::to_string(drawTriangles.size()) + " draws but " +
               std::to_string(ids.drawBits) + "-bit draw ids" + offsetNote + " hold " + std::to_string(fieldIds) +
               "; use visibility-64 (32-bit draw ids) or more draw_bits in [ids]";
    if (maxTriangles > idCapacity(ids.triangleBits))
        return layout + "a draw of the scene has " + std::to_string(maxTriangles) + " triangles but " +
               std::to_string(ids.triangleBits) + "-bit triangle ids hold " +
               std::to_string(idCapacity(ids.triangleBits)) +
               "; use visibility-64 (32-bit triangle ids), more triangle_bits, or clusters (cluster_triangles) in "
               "[ids]";
    return "";
}

std::vector<uint32_t> visibilityFirstIds(const GBufferWiring::VisibilityIds& ids,
                                         const std::vector<size_t>& drawTriangles) {
    std::vector<uint32_t> first(drawTriangles.size());
    uint64_t next = 0;
    for (size_t i = 0; i < drawTriangles.size(); ++i) {
        first[i] = uint32_t(ids.clusterTriangles ? next : i);
        if (ids.clusterTriangles) next += (drawTriangles[i] + ids.clusterTriangles - 1) / ids.clusterTriangles;
    }
    return first;
}

std::vector<std::array<uint32_t, 2>> visibilityClusterTable(uint32_t clusterTriangles,
                                                            const std::vector<size_t>& drawTriangles) {
    std::vector<std::array<uint32_t, 2>> table;
    if (clusterTriangles == 0) return table;
    for (size_t i = 0; i < drawTriangles.size(); ++i)
        for (size_t first = 0; first < drawTriangles[i]; first += clusterTriangles)
            table.push_back({uint32_t(i), uint32_t(first)});
    return table;
}

VisibilityFields visibilityFields(const GBufferWiring::VisibilityIds& ids, uint32_t firstId, uint32_t primitive) {
    if (ids.clusterTriangles == 0) return {firstId, primitive};
    return {firstId + primitive / ids.clusterTriangles, primitive % ids.clusterTriangles};
}

std::array<uint32_t, 2> packVisibilityIds(const GBufferWiring::VisibilityIds& ids, uint32_t draw, uint32_t triangle,
                                          bool alphaMasked, float depth) {
    std::array<uint32_t, 2> w{0, 0};
    putBits(w, triangle, 0, ids.triangleBits);
    putBits(w, draw + ids.drawOffset, ids.triangleBits, ids.drawBits);  // wraps mod 2^32, as uint in GLSL
    if (ids.alphaMaskBit && alphaMasked) putBits(w, 1u, idBits(ids) - 1, 1);
    if (ids.depthWord) std::memcpy(&w[1], &depth, 4);  // floatBitsToUint
    return w;
}

std::array<uint32_t, 3> unpackVisibilityIds(const GBufferWiring::VisibilityIds& ids, std::array<uint32_t, 2> words) {
    const uint32_t alpha = ids.alphaMaskBit ? getBits(words, idBits(ids) - 1, 1) : 0u;
    return {getBits(words, ids.triangleBits, ids.drawBits) - ids.drawOffset, getBits(words, 0, ids.triangleBits),
            alpha};
}

}  // namespace gbl
