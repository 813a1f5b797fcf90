#version 450
#extension GL_GOOGLE_include_directive : require
// IBL pre-computation, step 3: one mip of the pre-filtered specular cube, roughness =
// mip / (mipCount - 1) (ibl_math.glsl mipFromRoughness), n = v = r [Karis13 PrefilterEnvMap].
//   filtered == 1: prefilterEnvMapFiltered -- each sample reads the source mip whose texel solid
//                  angle matches the sample's [KC08]: few samples (default 64) suffice.
//   filtered == 0: prefilterEnvMap -- the seed's brute force, source mip 0 only (1024 samples).
#include "brdf.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform samplerCube sourceCube;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2DArray outputMip;
layout(push_constant) uniform Params {
    float roughness;
    uint numSamples;
    float sourceFaceSize;  // mip-0 face width of sourceCube in texels
    float maxLod;          // last mip of sourceCube
    uint outputSize;       // face width of this output mip
    uint filtered;
    float lodBias;         // added to every filtered sample's lod ([KC08] suggest 1); 0 for the brute force
} pc;

vec3 sampleEnvironmentLod(vec3 dir, float lod) {
    return textureLod(sourceCube, dir, min(lod + pc.lodBias, pc.maxLod)).rgb;
}
#define GBL_IBL_HAS_ENVIRONMENT
#include "ibl_math.glsl"

#include "cube_face.glsl"

void main() {
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= pc.outputSize || id.y >= pc.outputSize) return;
    vec2 st = (vec2(id.xy) + 0.5) / float(pc.outputSize) * 2.0 - 1.0;
    vec3 R = normalize(cubeDirection(id.z, st));
    vec3 c = pc.filtered != 0u ? prefilterEnvMapFiltered(pc.roughness, R, pc.numSamples, pc.sourceFaceSize)
                               : prefilterEnvMap(pc.roughness, R, pc.numSamples);
    imageStore(outputMip, ivec3(id), vec4(c, 1.0));
}
