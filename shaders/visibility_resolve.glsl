// The visibility buffer's resolve: the Surface of a pixel rebuilt from the triangle its ids name
// (Burns & Hunt, "The Visibility Buffer", JCGT 2013; The Forge's shadeVisibilityBuffer). Included
// by the lighting and decode passes after `frame` (FrameConstants) is declared.
// Neighbouring pixels may use different materials, so the texture index is not dynamically
// uniform. With GBL_NONUNIFORM_TEXTURE_INDEXING (the device has Vulkan 1.2's
// shaderSampledImageArrayNonUniformIndexing) the array is indexed with nonuniformEXT; without it
// (lavapipe in Mesa 22.3 reports it false) each candidate texture is tested with a constant index
// and the one that matches is sampled, the "waterfall" without subgroup operations: legal
// everywhere, and the same texel values (same image, sampler and gradients). The candidates of a
// slot are the textures some material of the scene binds to it (GBL_RESOLVE_SLOT_<slot>, from
// the renderer: gpu_scene.h's texturesBySlot), not every texture: lavapipe runs both sides of a
// branch under a lane mask, so every candidate is sampled for every pixel. On the built-in scene
// (6 textures, 7 slots) that is 6 samples per pixel instead of 42: its lighting pass at 1080p
// took 615-620 -> 277-321 ms (visibility-32), with the same pixels.
//
// 1. Fetch the triangle's three vertices and transform them as gbuffer_pass.vert.glsl does.
// 2. Intersect the camera ray through the pixel's centre with the triangle's plane: the hit's
//    barycentrics interpolate normal, tangent and uv, perspective-correct by construction (the
//    rasteriser's interpolation gives the same values).
// 3. UV derivatives per pixel, analytic: the ray differentials of Igehy ("Tracing Ray
//    Differentials", SIGGRAPH 1999) carried onto the plane, dP/dx = t dD/dx + D dt/dx with
//    dt/dx = -t (dD/dx . n) / (D . n), then through the barycentrics, which are linear in P.
//    These are the derivatives the rasteriser's 2x2 quads approximate by finite differences, so
//    texture LOD may differ where uv curves within a quad and across triangle edges.
// 4. The material through material_eval.glsl, the G-buffer pass's own code, with textureGrad.
#ifndef GBL_VISIBILITY_RESOLVE_GLSL
#define GBL_VISIBILITY_RESOLVE_GLSL

vec2 gblUvDx, gblUvDy;  // the derivatives of the uv the next texture sample reads
vec2 gblUv0Dx, gblUv0Dy, gblUv1Dx, gblUv1Dy;  // the pixel's derivatives of TEXCOORD_0 and _1
// material_eval.glsl's hook before each slot's sample: the set's gradients through the slot's
// KHR_texture_transform (its 2x2 matrix; the offset does not move a derivative).
#define GBL_SLOT_UV_GRADIENTS(pick1, m2, uv0, uv1) \
    gblUvDx = (m2) * mix(gblUv0Dx, gblUv1Dx, (pick1)); \
    gblUvDy = (m2) * mix(gblUv0Dy, gblUv1Dy, (pick1))

#ifdef GBL_NONUNIFORM_TEXTURE_INDEXING
#define GBL_SAMPLE_TEXTURE_SLOT(slot, index, uv) textureGrad(gblTextures[nonuniformEXT(index)], uv, gblUvDx, gblUvDy)
#else
#define GBL_RESOLVE_TRY(i) \
    if (index == i) texel = textureGrad(gblTextures[i], uv, gblUvDx, gblUvDy);
#define GBL_RESOLVE_SLOT_FUNCTION(slot) \
    vec4 gblResolveTexture_##slot(int index, vec2 uv) { \
        vec4 texel = vec4(0.0); \
        GBL_RESOLVE_SLOT_##slot \
        return texel; \
    }
GBL_RESOLVE_SLOT_FUNCTION(BASE_COLOR)
GBL_RESOLVE_SLOT_FUNCTION(METALLIC_ROUGHNESS)
GBL_RESOLVE_SLOT_FUNCTION(NORMAL)
GBL_RESOLVE_SLOT_FUNCTION(OCCLUSION)
GBL_RESOLVE_SLOT_FUNCTION(EMISSIVE)
GBL_RESOLVE_SLOT_FUNCTION(SPECULAR)
GBL_RESOLVE_SLOT_FUNCTION(SPECULAR_COLOR)
GBL_RESOLVE_SLOT_FUNCTION(CLEARCOAT)
GBL_RESOLVE_SLOT_FUNCTION(CLEARCOAT_ROUGHNESS)
GBL_RESOLVE_SLOT_FUNCTION(CLEARCOAT_NORMAL)
GBL_RESOLVE_SLOT_FUNCTION(SHEEN_COLOR)
GBL_RESOLVE_SLOT_FUNCTION(SHEEN_ROUGHNESS)
GBL_RESOLVE_SLOT_FUNCTION(ANISOTROPY)
#define GBL_SAMPLE_TEXTURE_SLOT(slot, index, uv) gblResolveTexture_##slot(index, uv)
#endif
#include "material_eval.glsl"

struct GblVertex {
    vec3 position;
    vec3 normal;
    vec4 tangent;
    vec2 uv;
    vec2 uv1;
};

GblVertex gblFetchVertex(uint index) {
    uint b = index * 14u;  // sizeof(Vertex) / 4 (src/scene/scene.h)
    GblVertex v;
    v.position = vec3(gblVertexFloats[b], gblVertexFloats[b + 1u], gblVertexFloats[b + 2u]);
    v.normal = vec3(gblVertexFloats[b + 3u], gblVertexFloats[b + 4u], gblVertexFloats[b + 5u]);
    v.tangent = vec4(gblVertexFloats[b + 6u], gblVertexFloats[b + 7u], gblVertexFloats[b + 8u], gblVertexFloats[b + 9u]);
    v.uv = vec2(gblVertexFloats[b + 10u], gblVertexFloats[b + 11u]);
    v.uv1 = vec2(gblVertexFloats[b + 12u], gblVertexFloats[b + 13u]);
    return v;
}

// The (unnormalised) world direction of the camera ray through image point `pixelPoint` (pixel
// units, pixel centres at +0.5). In view space the ray through NDC (x, y) is
// ((x + P[2][0]) / P[0][0], (y + P[2][1]) / P[1][1], -1) for gbufferlab's perspective (w = -z_view;
// reversed Z changes only the z row); the view matrix is rigid, so its 3x3 transpose takes it to world.
vec3 gblRayDirection(vec2 pixelPoint) {
    vec2 ndc = pixelPoint / vec2(frame.extent.xy) * 2.0 - 1.0;
    vec3 viewDir = vec3((ndc.x + frame.proj[2][0]) / frame.proj[0][0], (ndc.y + frame.proj[2][1]) / frame.proj[1][1], -1.0);
    return transpose(mat3(frame.view)) * viewDir;
}

Surface readGBuffer(ivec2 pixel) {
    uvec3 ids = readVisibilityIds(pixel);
    DrawConstants d = gblDraws[ids.x];
    uint firstIndex = uint(d.material.z) + 3u * ids.y;
    mat3 normalMatrix = mat3(d.normalMatrix[0].xyz, d.normalMatrix[1].xyz, d.normalMatrix[2].xyz);
    vec3 p[3], n[3];
    vec4 tg[3];
    vec2 uv[3], uvb[3];
    for (int k = 0; k < 3; ++k) {
        GblVertex v = gblFetchVertex(uint(int(gblIndices[firstIndex + uint(k)]) + d.material.w));
        p[k] = (d.model * vec4(v.position, 1.0)).xyz;
        n[k] = normalMatrix * v.normal;
        tg[k] = vec4(mat3(d.model) * v.tangent.xyz, v.tangent.w);
        uv[k] = v.uv;
        uvb[k] = v.uv1;
    }
    vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    vec3 plane = cross(e1, e2);
    float area2 = dot(plane, plane);
    // The dual basis of (e1, e2) in the plane: barycentric b1 = (P - p0) . c1, b2 = (P - p0) . c2.
    vec3 c1 = cross(e2, plane) / area2, c2 = cross(plane, e1) / area2;

    vec3 origin = frame.cameraPosition.xyz;
    vec2 centre = vec2(pixel) + 0.5;
    vec3 D = gblRayDirection(centre);
    vec3 dDdx = gblRayDirection(centre + vec2(1.0, 0.0)) - D;  // exact: D is affine in the pixel
    vec3 dDdy = gblRayDirection(centre + vec2(0.0, 1.0)) - D;
    float DoN = dot(D, plane);
    float t = dot(p[0] - origin, plane) / DoN;
    vec3 hit = origin + t * D;
    vec3 dPdx = t * (dDdx - D * (dot(dDdx, plane) / DoN));
    vec3 dPdy = t * (dDdy - D * (dot(dDdy, plane) / DoN));
    vec2 b = vec2(dot(hit - p[0], c1), dot(hit - p[0], c2));
    vec3 w = vec3(1.0 - b.x - b.y, b.x, b.y);
    vec2 dbdx = vec2(dot(dPdx, c1), dot(dPdx, c2));
    vec2 dbdy = vec2(dot(dPdy, c1), dot(dPdy, c2));
    gblUvDx = dbdx.x * (uv[1] - uv[0]) + dbdx.y * (uv[2] - uv[0]);
    gblUvDy = dbdy.x * (uv[1] - uv[0]) + dbdy.y * (uv[2] - uv[0]);
    gblUv0Dx = gblUvDx;
    gblUv0Dy = gblUvDy;
    gblUv1Dx = dbdx.x * (uvb[1] - uvb[0]) + dbdx.y * (uvb[2] - uvb[0]);
    gblUv1Dy = dbdy.x * (uvb[1] - uvb[0]) + dbdy.y * (uvb[2] - uvb[0]);

    vec3 normal = w.x * n[0] + w.y * n[1] + w.z * n[2];
    vec4 tangent = w.x * tg[0] + w.y * tg[1] + w.z * tg[2];
    vec2 texcoord = w.x * uv[0] + w.y * uv[1] + w.z * uv[2];
    vec2 texcoord1 = w.x * uvb[0] + w.y * uvb[1] + w.z * uvb[2];
    // Vulkan's rule with gbufferlab's y-flipped projection and VK_FRONT_FACE_COUNTER_CLOCKWISE:
    // a triangle whose right-handed normal faces the camera is front-facing.
    bool frontFacing = DoN < 0.0;
    return evaluateMaterialOf(gblMaterials[d.material.x], hit, normal, tangent, texcoord, texcoord1, frontFacing);
}
#endif
