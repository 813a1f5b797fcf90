// Image-based lighting, included by the lighting pass after sampleEnvironment() is defined.
// Placeholder until the IBL issue lands: no environment light on surfaces, so the backbone
// renders direct light only. Keep this the single place where IBL enters the lighting pass.
#ifndef GBL_IMAGE_BASED_LIGHT_GLSL
#define GBL_IMAGE_BASED_LIGHT_GLSL
vec3 evaluateImageBasedLight(Surface s, vec3 N, vec3 V) {
    return vec3(0.0);
}
#endif
