// The visibility buffer's id target (layout pipeline = "visibility-buffer"; Burns & Hunt, JCGT
// 2013), included by the wiring generated from the layout (src/codec/visibility_wiring.cpp), which
// first defines GBL_VIS_ID_WORDS (1: R32_UINT, 2: R32G32_UINT), GBL_VIS_TRIANGLE_BITS,
// GBL_VIS_DRAW_BITS, GBL_VIS_ALPHA_MASK_BIT (0 or 1), GBL_VIS_DRAW_OFFSET,
// GBL_VIS_CLUSTERS (0 or 1), GBL_VIS_CLUSTER_TRIANGLES and, for a depth word, GBL_VIS_DEPTH_WORD.
// The ids fill one little-endian bit string (word 0 = bits 0..31): the triangle id from bit 0,
// the draw id (+ GBL_VIS_DRAW_OFFSET) above it, and the alpha-mask flag in the top bit of the ids.
// With 23 / 8 / 1 in R32_UINT this is The Forge's packVisBufData: ((drawId << 23) & 0x7F800000) |
// (triangleId & 0x007FFFFF), bit 31 for alpha-tested geometry (ConfettiFX/The-Forge,
// Examples_3/Visibility_Buffer, visibilityBuffer_pass.frag).
// With clusters (Nanite, Bevy's meshlets: 128 triangles) the draw field holds a cluster: the
// renderer splits each draw into clusters of GBL_VIS_CLUSTER_TRIANGLES triangles (cluster c of a
// draw: its triangles [c n, c n + n)) numbered in draw order, pushes each draw's first cluster as
// its id, and binds the cluster table (draw, first triangle) for the resolve. With a depth word
// the ids fill word 0 and word 1 holds the window depth's float bits: UE 5's Nanite
// ((cluster + 1) << 7 | triangle, asuint(DeviceZ)) and Bevy 0.16's meshlets (cluster << 7 |
// triangle, bitcast<u32>(position.z)), resolved there by a 64-bit atomic max. gbufferlab's
// geometry pass keeps the rasteriser's depth test (reversed Z, GREATER) instead, which keeps the
// same nearest fragment for opaque geometry (layouts/README.md, "Visibility buffer").
// The C++ twin: src/codec/visibility_wiring.h (packVisibilityIds, unpackVisibilityIds).
#ifndef GBL_VISIBILITY_BUFFER_GLSL
#define GBL_VISIBILITY_BUFFER_GLSL

#ifdef GBL_VIS_DEPTH_WORD
#define GBL_VIS_BITS 32u  // the ids take word 0; word 1 is depth
#else
#define GBL_VIS_BITS (32u * uint(GBL_VIS_ID_WORDS))
#endif

uint gblLowMask(uint count) { return count >= 32u ? 0xFFFFFFFFu : (1u << count) - 1u; }

// `count` (1..32) bits of `value` into the bit string at `first`, straddling the words if need be.
uvec2 gblPutBits(uvec2 words, uint value, uint first, uint count) {
    value &= gblLowMask(count);
    if (first >= 32u) return uvec2(words.x, words.y | (value << (first - 32u)));
    words.x |= value << first;
    if (first + count > 32u) words.y |= value >> (32u - first);
    return words;
}

uint gblGetBits(uvec2 words, uint first, uint count) {
    uint v = first >= 32u ? words.y >> (first - 32u) : words.x >> first;
    if (first < 32u && first + count > 32u) v |= words.y << (32u - first);
    return v & gblLowMask(count);
}

// The fragment's (draw or cluster, triangle) from its draw's id (the pushed draw.material.y: the
// draw's index, or with clusters its first cluster) and gl_PrimitiveID.
uvec2 visibilityFields(uint firstId, uint primitive) {
#if GBL_VIS_CLUSTERS
    return uvec2(firstId + primitive / GBL_VIS_CLUSTER_TRIANGLES, primitive % GBL_VIS_CLUSTER_TRIANGLES);
#else
    return uvec2(firstId, primitive);
#endif
}

uvec2 packVisibilityIds(uint drawId, uint triangleId, bool alphaMasked, float depth) {
    uvec2 w = gblPutBits(uvec2(0u), triangleId, 0u, GBL_VIS_TRIANGLE_BITS);
    w = gblPutBits(w, drawId + GBL_VIS_DRAW_OFFSET, GBL_VIS_TRIANGLE_BITS, GBL_VIS_DRAW_BITS);
#if GBL_VIS_ALPHA_MASK_BIT
    if (alphaMasked) w = gblPutBits(w, 1u, GBL_VIS_BITS - 1u, 1u);
#endif
#ifdef GBL_VIS_DEPTH_WORD
    w.y = floatBitsToUint(depth);
#endif
    return w;
}

// x draw (or cluster) id, offset removed (an empty pixel's 0 wraps to 0xFFFFFFFF with offset 1,
// as UE's UnpackVisPixel); y triangle id (within the cluster); z alpha-mask flag.
uvec3 unpackVisibilityIds(uvec2 w) {
    uint alpha = 0u;
#if GBL_VIS_ALPHA_MASK_BIT
    alpha = gblGetBits(w, GBL_VIS_BITS - 1u, 1u);
#endif
    return uvec3(gblGetBits(w, GBL_VIS_TRIANGLE_BITS, GBL_VIS_DRAW_BITS) - GBL_VIS_DRAW_OFFSET,
                 gblGetBits(w, 0u, GBL_VIS_TRIANGLE_BITS), alpha);
}

#ifdef GBUFFER_WRITE
#if GBL_VIS_ID_WORDS == 1
layout(location = 0) out uint gblVisibilityIds;
#else
layout(location = 0) out uvec2 gblVisibilityIds;
#endif
// `firstId`: the draw's id (draw.material.y), `primitive`: gl_PrimitiveID, `depth`: gl_FragCoord.z.
void writeVisibilityIds(uint firstId, uint primitive, bool alphaMasked, float depth) {
    uvec2 f = visibilityFields(firstId, primitive);
    uvec2 w = packVisibilityIds(f.x, f.y, alphaMasked, depth);
#if GBL_VIS_ID_WORDS == 1
    gblVisibilityIds = w.x;
#else
    gblVisibilityIds = w;
#endif
}
#endif  // GBUFFER_WRITE

#ifdef GBUFFER_READ
// What the resolve reads besides the ids, in set 1 after the id target (renderer_passes.h,
// kVisibility*Binding): the scene's vertices (GpuScene's Vertex, 12 floats), indices, draws
// (DrawConstants: model, normal matrix, material = (material, draw, firstIndex, vertexOffset)),
// materials and textures; with clusters the cluster table (binding 6).
layout(set = 1, binding = 0) uniform usampler2D gblIdTarget;
layout(std430, set = 1, binding = 1) readonly buffer GblVertices { float gblVertexFloats[]; };
layout(std430, set = 1, binding = 2) readonly buffer GblIndices { uint gblIndices[]; };
layout(std430, set = 1, binding = 3) readonly buffer GblDraws { DrawConstants gblDraws[]; };
layout(std430, set = 1, binding = 4) readonly buffer GblMaterials { GpuMaterial gblMaterials[]; };
layout(set = 1, binding = 5) uniform sampler2D gblTextures[TEXTURE_COUNT];

#if GBL_VIS_CLUSTERS
// Per cluster: (draw, first triangle in the draw) (visibilityClusterTable, visibility_wiring.h).
layout(std430, set = 1, binding = 6) readonly buffer GblClusters { uvec2 gblClusters[]; };
#endif

// x draw, y triangle within the draw, z alpha-mask flag.
uvec3 readVisibilityIds(ivec2 pixel) {
    uvec3 ids = unpackVisibilityIds(texelFetch(gblIdTarget, pixel, 0).xy);
#if GBL_VIS_CLUSTERS
    uvec2 cluster = gblClusters[ids.x];
    ids.xy = uvec2(cluster.x, cluster.y + ids.y);
#endif
    return ids;
}

#ifdef GBL_VIS_DEPTH_WORD
// The window depth the geometry pass wrote into word 1 (0.0 where nothing was drawn: the clear).
float gblVisibilityDepth(ivec2 pixel) { return uintBitsToFloat(texelFetch(gblIdTarget, pixel, 0).y); }
#endif

// Defined by visibility_resolve.glsl, which the passes include once their FrameConstants exist.
Surface readGBuffer(ivec2 pixel);
#endif  // GBUFFER_READ

#endif
