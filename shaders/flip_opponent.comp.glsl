#version 450
#extension GL_GOOGLE_include_directive : require
// FLIP (Andersson et al., HPG 2020), per image, step 1 (twin of measure/flip.cpp toLinearPlanes +
// rgbToOpponent): the input as linear RGB in [0,1], then YyCxCz and the normalised luminance into
// planes u0..u3. u6: 0 the reference image, 1 the test image. mode 0 (LDR-FLIP of compare's PNGs):
// tone-mapped to 8-bit sRGB at exposure f0 exactly as toneMapToSrgb8, then decoded to linear;
// mode 1 (one HDR-FLIP exposure, Andersson et al. EG 2021): flipToneMap(max(x, 0) * f0).
#include "eval_common.glsl"
#include "flip_common.glsl"

float srgbToLinearF(float v) {
    v = clamp(v, 0.0, 1.0);
    return v <= 0.04045 ? v * (1.0 / 12.92) : pow((v + 0.055) * (1.0 / 1.055), 2.4);
}

vec3 inputAt(uint i) {
    ivec2 p = ivec2(i % pc.width, i / pc.width);
    return (pc.u6 == 0u ? imageLoad(refHdr, p) : imageLoad(testHdr, p)).rgb;
}
void store(uint i, vec3 rgb) {
    float X = dot(flipM(0), rgb) * kernels[KC_IW + 0];
    float Y = dot(flipM(1), rgb) * kernels[KC_IW + 1];
    float Z = dot(flipM(2), rgb) * kernels[KC_IW + 2];
    planes[pc.u0].v[i] = 116.0 * Y - 16.0;
    planes[pc.u1].v[i] = 500.0 * (X - Y);
    planes[pc.u2].v[i] = 200.0 * (Y - Z);
    planes[pc.u3].v[i] = Y;
}

// One loop per mode: llvmpipe runs both sides of a branch under a lane mask, so with the mode
// tested inside one loop every pixel paid for both tone mappings.
void main() {
    const uint n = pc.width * pc.height;
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    if (pc.mode == 0u) {
        for (uint i = invocation(); i < n; i += total) {
            vec3 s = vec3(toneMap8(inputAt(i), pc.f0)) / 255.0;
            vec3 rgb;
            for (int c = 0; c < 3; ++c) rgb[c] = srgbToLinearF(s[c]);
            store(i, rgb);
        }
    } else {
        for (uint i = invocation(); i < n; i += total) {
            vec3 x = inputAt(i), rgb;
            for (int c = 0; c < 3; ++c) rgb[c] = flipToneMap((x[c] >= 0.0 ? x[c] : 0.0) * pc.f0);
            store(i, rgb);
        }
    }
}
