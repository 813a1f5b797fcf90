#version 450
#extension GL_GOOGLE_include_directive : require
// IBL pre-computation, step 1: resample the equirect environment into mip 0 of a cube map
// (bilinear lookups of the lat-long map at each cube texel centre's direction).
// Vulkan cube layers: 0 +X, 1 -X, 2 +Y, 3 -Y, 4 +Z, 5 -Z (src/shading/ibl_precompute.cpp: cubeTexelDirection
// is the C++ mirror of cubeDirection below).
#include "environment_map.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D equirect;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2DArray cubeMip0;
layout(push_constant) uniform Params { uint faceSize; } pc;

#include "cube_face.glsl"

void main() {
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= pc.faceSize || id.y >= pc.faceSize) return;
    vec2 st = (vec2(id.xy) + 0.5) / float(pc.faceSize) * 2.0 - 1.0;
    vec3 dir = normalize(cubeDirection(id.z, st));
    vec3 c = textureLod(equirect, directionToEquirectUv(dir), 0.0).rgb;
    imageStore(cubeMip0, ivec3(id), vec4(c, 1.0));
}
