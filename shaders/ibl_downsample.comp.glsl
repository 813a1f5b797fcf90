#version 450
// IBL pre-computation, step 2: the source cube's mip chain, each texel the mean of the 2x2
// texels above it (a box filter per face: what filtered importance sampling reads by lod).
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba32f) uniform readonly image2DArray src;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2DArray dst;
layout(push_constant) uniform Params { uint dstSize; } pc;

void main() {
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= pc.dstSize || id.y >= pc.dstSize) return;
    ivec3 s = ivec3(id.xy * 2u, id.z);
    vec4 c = imageLoad(src, s) + imageLoad(src, s + ivec3(1, 0, 0)) + imageLoad(src, s + ivec3(0, 1, 0)) +
             imageLoad(src, s + ivec3(1, 1, 0));
    imageStore(dst, ivec3(id), c * 0.25);
}
