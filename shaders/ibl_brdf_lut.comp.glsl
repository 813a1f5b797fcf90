#version 450
#extension GL_GOOGLE_include_directive : require
// IBL pre-computation: the split-sum environment-BRDF LUT [Karis13 IntegrateBRDF] on the GPU.
// Texel (x, y) = the estimator at roughness = (y + 0.5) / size, NoV = (x + 0.5) / size, samples:
// estimator 0 = integrateBRDF (the seed's), 1 = integrateBRDFVisible (visible normals, the default);
// the layout and enum of src/shading/ibl_brdf_lut.h (computeBrdfLutCpu), so the two compare texel by texel.
#include "brdf.glsl"
#include "ibl_math.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rg32f) uniform writeonly image2D lut;
layout(push_constant) uniform Params { uint size; uint numSamples; uint estimator; } pc;

void main() {
    uvec2 id = gl_GlobalInvocationID.xy;
    if (id.x >= pc.size || id.y >= pc.size) return;
    float NoV = (float(id.x) + 0.5) / float(pc.size);
    float roughness = (float(id.y) + 0.5) / float(pc.size);
    vec2 AB = pc.estimator == 1u ? integrateBRDFVisible(roughness, NoV, pc.numSamples)
                                 : integrateBRDF(roughness, NoV, pc.numSamples);
    imageStore(lut, ivec2(id), vec4(AB, 0.0, 0.0));
}
