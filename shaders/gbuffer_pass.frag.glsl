#version 450
#extension GL_GOOGLE_include_directive : require
// The G-buffer pass: evaluate the glTF material into a Surface, then hand it to the layout's
// generated writeGBuffer(), the single funnel through which every material writes the G-buffer.
// A visibility-buffer layout (its wiring defines GBL_VISIBILITY_BUFFER) writes only which
// triangle of which draw is visible (visibility_buffer.glsl); its lighting pass evaluates the
// material instead (visibility_resolve.glsl).
#include "shared_types.h"
#include "surface.glsl"
#include "material.glsl"
#include "normal_space.glsl"
// The frame index of compare --temporal (RenderSettings::frameIndex), for a dither that moves with
// time (a field's dither_per_frame); the generated wiring calls it only for such a field.
uint gblFrameIndex() { return frame.band.z; }
#define GBUFFER_WRITE 1
#include "gbuffer_wiring.glsl"

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv;
layout(location = 4) in vec2 inUv1;  // TEXCOORD_1 (0 where the primitive has none)

void main() {
    if (alphaTestDiscards(inUv, inUv1)) discard;
#ifdef GBL_VISIBILITY_BUFFER
    // gl_PrimitiveID counts the draw's triangles from its firstIndex (Vulkan: vkCmdDrawIndexed);
    // draw.material.y is the draw's id: its index in GpuScene::draws, or with clusters its first
    // cluster (recordGBufferPass). gl_FragCoord.z goes to a depth word where the layout has one.
    writeVisibilityIds(uint(draw.material.y), uint(gl_PrimitiveID),
                       materials[draw.material.x].alphaMaskCutoff.x != 0.0, gl_FragCoord.z);
#else
    Surface s = evaluateMaterial(inWorldPosition, inNormal, inTangent, inUv, inUv1, gl_FrontFacing);
    Surface stored = gblSurfaceToStored(s);  // into the layout's [space]
#ifdef GBL_STORES_DEPTH
    // A stored window depth (Bevy on WebGL2: in.frag_coord.z) rides in position.z (wiring_plan.h).
    stored.position = vec3(0.0, 0.0, gl_FragCoord.z);
#endif
    writeGBuffer(stored, ivec2(gl_FragCoord.xy));
#endif
}
