// light_pre_pass.glsl -- deferred lighting (light pre-pass), included by lighting_pass.comp.glsl
// when the layout's pipeline is "deferred-lighting" (LIGHT_PRE_PASS, with the generated
// light_buffers.glsl: src/codec/light_buffer_wiring.h). Two steps of the engine, per pixel:
//
// 1. Lighting: reads only what the slim G-buffer holds -- the normal, the roughness its gloss
//    encodes, and depth (the position) -- never a material colour. Each light adds to the light
//    buffers, quantised through their declared encodings light by light (blending stores at the
//    buffer's precision):
//      diffuse  light  += E n.l / pi                        (Lambert, albedo applied later)
//      specular light  += E n.l D(h) Vis(l, v)              (GGX D, Smith-Schlick Vis, F = 1:
//                                                            the G-buffer holds no F0)
//    with E the light's radiance at the pixel. The words are stored for read-back.
// 2. Material pass (the combine): the scene's material colours meet the decoded light buffers,
//      colour = diffuse_colour * diffuse light + F * specular light + IBL * occlusion
//    F = F0 (the material's specular colour) for [material_pass] fresnel = "none", or Schlick
//    with F0 at n.v for "schlick_nv" (per-light v.h is gone by then). Luminance-only specular
//    (Engel's light pre-pass) takes the diffuse light's chromaticity (lightFromBuffers).
//    Image-based light is applied here, with the material's F0 and the decoded roughness, as the
//    engine applies its environment probes in the material pass (image_based_light.glsl).
// Sources: Sousa, Kasyan, Schulz, "Secrets of CryENGINE 3 Graphics Technology", SIGGRAPH 2011;
// W. Engel, "Light Pre-Pass Renderer", 2008, and "Designing a Renderer for Multiple Lights: The
// Light Pre-Pass Renderer", ShaderX7, 2009.

layout(set = 0, binding = 9) writeonly buffer LightBufferWords { uint lightBufferWords[]; };

void storeLightBufferWords(ivec2 pixel, uint w[LIGHT_BUFFER_WORDS]) {
    uint base = (uint(pixel.y) * frame.extent.x + uint(pixel.x)) * uint(LIGHT_BUFFER_WORDS);
    for (int i = 0; i < LIGHT_BUFFER_WORDS; ++i) lightBufferWords[base + uint(i)] = w[i];
}

void clearLightBufferWords(ivec2 pixel) {
    uint w[LIGHT_BUFFER_WORDS];
    for (int i = 0; i < LIGHT_BUFFER_WORDS; ++i) w[i] = 0u;
    storeLightBufferWords(pixel, w);
}

// Step 1: N, roughness and position come from the G-buffer and depth only.
void accumulateLights(vec3 N, float roughness, vec3 position, vec3 V, inout vec4 ch[LIGHT_BUFFER_COUNT],
                      inout uint w[LIGHT_BUFFER_WORDS]) {
    float r = max(roughness, kMinDirectRoughness);
    float k = kSmithSchlickAnalytic(r);
    float NoV = clamp(dot(N, V), 0.0, 1.0);
    for (uint i = 0u; i < frame.extent.z; ++i) {
        vec3 L;
        vec3 radiance = lightRadianceAndDirection(lights[i], position, L);
        float NoL = clamp(dot(N, L), 0.0, 1.0);
        if (NoL <= 0.0) continue;
        vec3 Hu = V + L;
        vec3 H = Hu * inversesqrt(max(dot(Hu, Hu), 1e-12));
        float NoH = clamp(dot(N, H), 0.0, 1.0);
        vec3 E = radiance * NoL;
        accumulateLight(ch, w, E / kPi, E * (dGgx(NoH, r) * visSmithSchlick(NoV, NoL, k)));
    }
}

// Step 2: the material pass.
vec3 materialPassCombine(Surface s, vec3 N, vec3 V, vec4 ch[LIGHT_BUFFER_COUNT]) {
    vec3 diffuseLight, specularLight;
    lightFromBuffers(ch, diffuseLight, specularLight);
    vec3 F = s.specularColor;
#if LPP_FRESNEL == 1
    F = fresnel(GBL_ACTIVE_FRESNEL, s.specularColor, clamp(dot(N, V), 0.0, 1.0));
#endif
    return s.diffuseColor * diffuseLight + F * specularLight + evaluateImageBasedLight(s, N, V) * s.occlusion;
}

vec3 shadeLightPrePass(ivec2 pixel, Surface s, vec3 N, vec3 V, vec3 position) {
    vec4 ch[LIGHT_BUFFER_COUNT];
    for (int b = 0; b < LIGHT_BUFFER_COUNT; ++b) ch[b] = vec4(0.0);
    uint w[LIGHT_BUFFER_WORDS];
    for (int i = 0; i < LIGHT_BUFFER_WORDS; ++i) w[i] = 0u;
    accumulateLights(N, s.roughness, position, V, ch, w);
    storeLightBufferWords(pixel, w);
    return materialPassCombine(s, N, V, ch);
}
