// The G-buffer pass's material bindings: the draw's glTF material evaluated into a Surface by
// material_eval.glsl (shared with the visibility buffer's resolve), sampled with the
// rasteriser's implicit derivatives.
#ifndef GBL_MATERIAL_GLSL
#define GBL_MATERIAL_GLSL

layout(set = 0, binding = 0) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = 1) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 2) uniform sampler2D textures[TEXTURE_COUNT];
layout(push_constant) uniform Draw { DrawConstants draw; };

// What a slot samples: with GBL_MATERIAL_SLOTS, the renderer's GBL_MATERIAL_SLOT_<slot> (nothing
// where no material of the scene binds a texture to the slot, else the bound one by a constant
// index, or the material's index where several are bound: src/render/gbuffer_pass.cpp
// addMaterialSlotDefines says why); without it, the material's index in every slot.
#ifdef GBL_MATERIAL_SLOTS
#define GBL_SAMPLE_TEXTURE_SLOT(slot, index, uv) GBL_MATERIAL_SLOT_##slot(index, uv)
#elif defined(GBL_UV_TRANSFORMS) && GBL_UV_TRANSFORMS
#define GBL_SAMPLE_TEXTURE_SLOT(slot, index, uv) textureGrad(textures[index], uv, gblUvDx, gblUvDy)
#else
#define GBL_SAMPLE_TEXTURE_SLOT(slot, index, uv) texture(textures[index], uv)
#endif
#if defined(GBL_UV_TRANSFORMS) && GBL_UV_TRANSFORMS
// A scene with KHR_texture_transform (or TEXCOORD_1): every slot samples with the gradients of its
// own uv, the interpolated set's screen derivatives through the slot's matrix (material_eval.glsl
// materialSlotUv says why not the transformed uv's implicit ones); the renderer's slot macros
// then call textureGrad (src/render/gbuffer_pass.cpp addMaterialSlotDefines).
vec2 gblUvDx, gblUvDy;
#define GBL_SLOT_UV_GRADIENTS(pick1, m2, uv0, uv1) \
    gblUvDx = (m2) * mix(dFdx(uv0), dFdx(uv1), (pick1)); \
    gblUvDy = (m2) * mix(dFdy(uv0), dFdy(uv1), (pick1))
#endif
#include "material_eval.glsl"

bool alphaTestDiscards(vec2 uv, vec2 uv1) { return materialAlphaTestDiscards(materials[draw.material.x], uv, uv1); }

Surface evaluateMaterial(vec3 worldPosition, vec3 normal, vec4 tangent, vec2 uv, vec2 uv1, bool frontFacing) {
    return evaluateMaterialOf(materials[draw.material.x], worldPosition, normal, tangent, uv, uv1, frontFacing);
}
#endif
