#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : enable  // the visibility buffer's resolve indexes textures per pixel
// The lighting pass: decode the layout's G-buffer with its generated readGBuffer(), rebuild the
// position from depth, and shade with the UE4 model: direct lights + image-based light.
// Pixels with no geometry show the environment.
#include "shared_types.h"
#include "surface.glsl"
#include "brdf.glsl"
#include "brdf_layers.glsl"
// The material layers some material of the scene has (brdf_layers.glsl GBL_LAYER_*; the renderer's
// define from src/render/gpu_scene.h sceneLayers): a scene without them compiles none of their code.
#ifndef GBL_LAYERS
#define GBL_LAYERS 0
#endif
// The direct lights' Fresnel (brdf.glsl FRESNEL_*): GBL_FRESNEL_MODE where the pipeline is built for
// one (src/render/lighting_pass.cpp: constant-folded before the driver compiles, as GBL_IBL_MODE
// in image_based_light.glsl), else frame.shading.x at run time.
#ifdef GBL_FRESNEL_MODE
#define GBL_ACTIVE_FRESNEL GBL_FRESNEL_MODE
#else
#define GBL_ACTIVE_FRESNEL int(frame.shading.x)
#endif
// The direct lights' BRDF (brdf.glsl BRDF_UE4 / BRDF_GLTF): GBL_BRDF_MODEL where the pipeline is
// built for one, else frame.shading.z at run time, as the Fresnel above.
#ifdef GBL_BRDF_MODEL
#define GBL_ACTIVE_BRDF GBL_BRDF_MODEL
#else
#define GBL_ACTIVE_BRDF int(frame.shading.z)
#endif
#include "environment_map.glsl"
#define GBUFFER_READ 1
#define GBL_GEOMETRY_MASK 1  // checkerboard chroma skips neighbours without geometry
#include "gbuffer_wiring.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = 1) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = 2) uniform sampler2D depthTexture;
layout(set = 0, binding = 3) uniform sampler2D environmentEquirect;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D hdrOutput;
layout(set = 0, binding = 5) uniform samplerCube environmentCube;  // box-filtered mips (ground truth: mip 0)
layout(set = 0, binding = 6) uniform samplerCube prefilteredCube;  // roughness = mip / (mips - 1)
layout(set = 0, binding = 7) uniform sampler2D brdfLut;            // (A, B) at uv = (NoV, roughness)
// emissive = "forward": the emissive the G-buffer pass wrote into scene colour, unquantised, as
// UE4's base pass does (without EMISSIVE_FORWARD the depth is bound here, unread).
layout(set = 0, binding = 8) uniform sampler2D sceneColorEmissive;

#include "normal_space.glsl"
#ifdef GBL_VISIBILITY_BUFFER  // defined by a visibility-buffer layout's wiring: readGBuffer rebuilds the Surface
#include "visibility_resolve.glsl"
#endif

// The pixel's window depth: the depth attachment's, or where the ids hold it (a depth word:
// Nanite, Bevy's meshlets, which rasterise without a depth attachment) word 1 of the ids.
float gblSceneDepth(ivec2 p) {
#ifdef GBL_VIS_DEPTH_WORD
    return gblVisibilityDepth(p);
#else
    return texelFetch(depthTexture, p, 0).r;
#endif
}
bool gblHasGeometry(ivec2 p) { return gblSceneDepth(p) != frame.shading.y; }
layout(std430, set = 0, binding = 10) readonly buffer EnvironmentSampling { float environmentSampling[]; };
// Ground truth's progressive accumulation (Welford): rgb = mean radiance of the batches so far,
// a = sum of squared deviations of the batch luminances from their mean (M2).
layout(set = 0, binding = 11, rgba32f) uniform image2D accumulation;
layout(push_constant) uniform Batch { uint batchIndex; } batch;  // 0, 1, ... (ground truth only)
// The sheen's directional albedo E(NoV, sheen roughness), src/shading/sheen_albedo.h's table
// (R32F, bilinear, clamp to edge; 1 x 1 where the scene has no sheen).
layout(set = 0, binding = 12) uniform sampler2D sheenAlbedoLut;
float sheenAlbedo(float NoX, float sheenRoughness) { return textureLod(sheenAlbedoLut, vec2(NoX, sheenRoughness), 0.0).r; }

vec3 sampleEnvironment(vec3 direction) {
    return textureLod(environmentEquirect, directionToEquirectUv(direction), 0.0).rgb * frame.environment.x;
}

#include "image_based_light.glsl"

#if GBL_LAYERS != 0
// The pixel's layers from its decoded Surface. What the layout does not store decodes as 0, "no
// layer": no coat, black sheen, no anisotropy; a zero coat normal is the base normal (Bevy's coat
// reuses it), a zero or normal-parallel tangent leaves the base isotropic (no direction to stretch
// along). The tangent is made orthogonal to the shading normal (Gram-Schmidt). Layers the scene
// has none of are constants here, and their code folds away.
Layers gblLayersOf(Surface s, vec3 N) {
    Layers ly;
    ly.coat = (GBL_LAYERS & GBL_LAYER_COAT) != 0 ? clamp(s.coat, 0.0, 1.0) : 0.0;
    ly.coatRoughness = clamp(s.coatRoughness, 0.0, 1.0);
    ly.coatNormal = dot(s.coatNormal, s.coatNormal) > 0.0 ? normalize(s.coatNormal) : N;
    ly.sheenColor = (GBL_LAYERS & GBL_LAYER_SHEEN) != 0 ? max(s.sheenColor, vec3(0.0)) : vec3(0.0);
    ly.sheenRoughness = clamp(s.sheenRoughness, 0.0, 1.0);
    vec3 t = s.anisotropyDirection - N * dot(N, s.anisotropyDirection);
    float tt = dot(t, t);
    bool aniso = (GBL_LAYERS & GBL_LAYER_ANISOTROPY) != 0 && tt > 1e-12;
    ly.anisotropy = aniso ? clamp(s.anisotropyStrength, 0.0, 1.0) : 0.0;
    ly.anisotropyT = aniso ? t * inversesqrt(tt) : vec3(0.0);
    ly.anisotropyB = cross(N, ly.anisotropyT);
    return ly;
}
#endif

// BRDF_GLTF's dielectric f0: the grey F0 UE4's scalar specular stands for (material_eval.glsl:
// s.specular = mean(dielectricF0) / 0.08; exact for the grey F0 of every material without
// KHR_materials_specular's specularColor, which the glTF assets here do not use).
float gblDielectricF0(Surface s) { return 0.08 * s.specular; }

vec3 worldPositionFromDepth(ivec2 pixel, float depth) {
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(frame.extent.xy) * 2.0 - 1.0;
    vec4 world = frame.invViewProj * vec4(ndc, depth, 1.0);
    return world.xyz / world.w;
}

vec3 lightRadianceAndDirection(GpuLight light, vec3 position, out vec3 L) {
    vec3 radiance = light.colorIntensity.rgb * light.colorIntensity.a;
    if (int(light.positionType.w) == GBL_LIGHT_DIRECTIONAL) {
        L = -normalize(light.directionRange.xyz);
        return radiance;
    }
    vec3 toLight = light.positionType.xyz - position;
    float d2 = max(dot(toLight, toLight), 1e-8);
    L = toLight * inversesqrt(d2);
    // KHR_lights_punctual: inverse-square falloff, windowed to zero at `range` (UE4's squared
    // window, or the README's under BRDF_GLTF: brdf.glsl lightRangeWindow).
    float falloff = 1.0 / d2;
    falloff *= lightRangeWindow(d2, light.directionRange.w, GBL_ACTIVE_BRDF);
    if (int(light.positionType.w) == GBL_LIGHT_SPOT) {
        // KHR_lights_punctual: cd = cos(angle to the axis), a = saturate(cd * scale + offset), a^2:
        // 1 inside the inner cone, 0 outside the outer, smooth between.
        float cd = dot(light.directionRange.xyz, -L);
        float a = clamp(cd * light.spotCone.x + light.spotCone.y, 0.0, 1.0);
        falloff *= a * a;
    }
    return radiance * falloff;
}

#ifdef LIGHT_PRE_PASS
#include "light_buffers.glsl"    // generated: the layout's light buffers (light_buffer_wiring.h)
#include "light_pre_pass.glsl"   // deferred lighting: light buffers, then the material pass
#endif

void main() {
    // `outPixel` in the outputs (HDR, accumulation, light buffers: the render's rows, frame.band),
    // `pixel` in the frame and the G-buffer; the same for a whole frame.
    ivec2 outPixel = ivec2(gl_GlobalInvocationID.xy);
    if (outPixel.x >= int(frame.extent.x) || outPixel.y >= int(frame.band.y)) return;
    ivec2 pixel = outPixel + ivec2(0, int(frame.band.x));
    float depth = gblSceneDepth(pixel);
    if (depth == frame.shading.y) {  // cleared: no geometry here
        vec3 viewDir = normalize(worldPositionFromDepth(pixel, 0.5) - frame.cameraPosition.xyz);
        imageStore(hdrOutput, outPixel, vec4(sampleEnvironment(viewDir), 0.0));
#ifdef LIGHT_PRE_PASS
        clearLightBufferWords(outPixel);
#endif
        return;
    }
    Surface stored = readGBuffer(pixel);
#ifdef GBL_STORES_DEPTH
    // The layout's own depth word replaces the attachment's (Bevy on WebGL2, deferred_lighting.wgsl:
    // frag_coord.z from the G-buffer); coverage above still comes from the attachment.
    depth = stored.position.z;
#endif
    Surface s = gblSurfaceFromStored(stored);  // back to gbufferlab's world (Y-up)
#if defined(GBL_STORES_POSITION) || defined(GBL_VISIBILITY_BUFFER)
    // The layout stores position (fat-naive): light from the decoded, quantised position, not
    // from the one depth gives. A visibility buffer: from the camera ray's hit on the triangle.
    vec3 position = s.position;
#else
    vec3 position = worldPositionFromDepth(pixel, depth);
#endif
    vec3 V = normalize(frame.cameraPosition.xyz - position);
    vec3 N = normalize(s.normal);
#ifdef LIGHT_PRE_PASS
    vec3 color = shadeLightPrePass(outPixel, s, N, V, position);
#else
    vec3 color = vec3(0.0);
#if GBL_LAYERS != 0
    Layers ly = gblLayersOf(s, N);
    float sheenV = max3(ly.sheenColor) > 0.0 ? sheenAlbedo(clamp(dot(N, V), 0.0, 1.0), ly.sheenRoughness) : 0.0;
    for (uint i = 0u; i < frame.extent.z; ++i) {
        vec3 L;
        vec3 radiance = lightRadianceAndDirection(lights[i], position, L);
        float sheenL = max3(ly.sheenColor) > 0.0 ? sheenAlbedo(clamp(dot(N, L), 0.0, 1.0), ly.sheenRoughness) : 0.0;
        color += GBL_ACTIVE_BRDF == BRDF_GLTF
                     ? evaluateDirectLightLayeredGltf(N, V, L, s.diffuseColor, s.specularColor, gblDielectricF0(s),
                                                      s.roughness, ly, sheenV, sheenL, radiance)
                     : evaluateDirectLightLayeredMode(N, V, L, s.diffuseColor, s.specularColor, s.roughness, ly,
                                                      sheenV, sheenL, radiance, GBL_ACTIVE_FRESNEL);
    }
    iblBatchKey = uvec3(uint(pixel.x), uint(pixel.y), batch.batchIndex + uint(frame.ibl.z) * 0x10000u);
    color += evaluateImageBasedLightLayered(s, N, V, ly) * s.occlusion;
#else
    for (uint i = 0u; i < frame.extent.z; ++i) {
        vec3 L;
        vec3 radiance = lightRadianceAndDirection(lights[i], position, L);
        color += GBL_ACTIVE_BRDF == BRDF_GLTF
                     ? evaluateDirectLightGltf(N, V, L, s.diffuseColor, s.specularColor, gblDielectricF0(s),
                                               s.roughness, radiance)
                     : evaluateDirectLightMode(N, V, L, s.diffuseColor, s.specularColor, s.roughness, radiance,
                                               GBL_ACTIVE_FRESNEL);
    }
    iblBatchKey = uvec3(uint(pixel.x), uint(pixel.y), batch.batchIndex + uint(frame.ibl.z) * 0x10000u);
    color += evaluateImageBasedLight(s, N, V) * s.occlusion;
#endif
#endif
#if GBL_LAYERS != 0 && !defined(LIGHT_PRE_PASS)
    // Emission under the coat [Coat], the forward scene-colour emission too.
    color += GBL_ACTIVE_BRDF == BRDF_GLTF ? coatedEmissionGltf(s.emissive, ly, V) : coatedEmission(s.emissive, ly, V);
#ifdef EMISSIVE_FORWARD
    vec3 forwardEmission = texelFetch(sceneColorEmissive, pixel, 0).rgb;
    color += GBL_ACTIVE_BRDF == BRDF_GLTF ? coatedEmissionGltf(forwardEmission, ly, V)
                                          : coatedEmission(forwardEmission, ly, V);
#endif
#else
    color += s.emissive;
#ifdef EMISSIVE_FORWARD
    color += texelFetch(sceneColorEmissive, pixel, 0).rgb;
#endif
#endif
    if (GBL_IBL_ACTIVE_MODE == GBL_IBL_GROUND_TRUTH) {
        // Welford's update over batch means of the luminance (CIE Y of linear sRGB).
        const vec3 kY = vec3(0.2126, 0.7152, 0.0722);
        vec4 acc = batch.batchIndex == 0u ? vec4(0.0) : imageLoad(accumulation, outPixel);
        float y = dot(color, kY);
        float delta = y - dot(acc.rgb, kY);
        vec3 mean = acc.rgb + (color - acc.rgb) / float(batch.batchIndex + 1u);
        float m2 = acc.a + delta * (y - dot(mean, kY));
        imageStore(accumulation, outPixel, vec4(mean, m2));
        color = mean;
    }
    imageStore(hdrOutput, outPixel, vec4(color, 1.0));
}
