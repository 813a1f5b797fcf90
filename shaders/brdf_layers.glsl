// brdf_layers.glsl -- the material layers of glTF 2.0's PBR extensions over the UE4 base BRDF of
// brdf.glsl: clear coat, sheen and anisotropy. Include file (GLSL 450, no #version); include
// brdf.glsl first. The C++ mirror is src/shading/brdf_layers.h / brdf_layers.cpp (same names, same
// math, line for line); tests/shading/brdf_layers_test.cpp holds both to implementations written
// from the specification texts, and the GLSL to the C++.
//
// The base stays UE4's (Lambert + GGX D, Smith-Schlick with the analytic k, Karis' Fresnel); the
// layers follow the glTF specifications:
//   [glTF-B]  glTF 2.0 Specification, Appendix B "BRDF Implementation": specular_brdf = V D with
//             GGX D and the height-correlated Smith visibility
//             V = 1 / (2 (|NoV| sqrt(a^2 + (1 - a^2) NoL^2) + |NoL| sqrt(a^2 + (1 - a^2) NoV^2))).
//   [Coat]    KHR_materials_clearcoat README, "Layering" and "Emission":
//             coated = mix(material, clearcoat_brdf, clearcoat * fc), fc = 0.04 + 0.96 (1 - |V.Nc|)^5
//             (the coat's Fresnel with n.v, not v.h, "to make the material energy conserving with a
//             simple layering function"), clearcoat_brdf = specular_brdf(Nc, clearcoatRoughness^2);
//             emission * (1 - clearcoat * fc).
//   [Sheen]   KHR_materials_sheen README, "Implementation Notes": the Charlie distribution and
//             visibility of Conty & Kulla, "Production Friendly Microfacet Sheen BRDF" (Sony
//             Imageworks, 2017), alpha_g = sheenRoughness^2, and the albedo scaling of the base,
//             min(1 - max3(sheenColor) E(NoV), 1 - max3(sheenColor) E(NoL)), E the sheen BRDF's
//             directional albedo (src/shading/sheen_albedo.h builds its table).
//   [Aniso]   KHR_materials_anisotropy README: alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha,
//             Burley's anisotropic GGX D and the anisotropic height-correlated V of its sample
//             implementation (with its clamp of V to [0, 1]); the tangent rotated by
//             anisotropyRotation (material_eval.glsl); for image-based light the bent normal of its
//             "Image-based lighting" section.
//
// Layering order [Sheen]: "If clearcoat is active at the same time, clearcoat is layered on top of
// sheen": coat(sheen(base)). A layer whose amount is 0 leaves the base bit for bit (the functions
// test for it), so a pixel without layers shades as brdf.glsl alone shades it.
#ifndef GBL_BRDF_LAYERS_GLSL
#define GBL_BRDF_LAYERS_GLSL

#ifndef GBL_BRDF_GLSL
#error "brdf_layers.glsl needs brdf.glsl: include brdf.glsl first"
#endif

// The scene's layers, a bit each (the renderer's GBL_LAYERS define: only the layers some material
// of the scene has are compiled into the passes; src/render/gpu_scene.h sceneLayerFlags).
#define GBL_LAYER_COAT 1
#define GBL_LAYER_SHEEN 2
#define GBL_LAYER_ANISOTROPY 4

const float kCoatF0 = 0.04;  // ((1 - ior) / (1 + ior))^2 at the coat's fixed ior 1.5 [Coat]
// Sheen roughness is clamped to at least this: at 0 the Charlie lobe is a delta (1/alpha_g
// overflows). The same floor as the base's kMinDirectRoughness (Filament's MIN_PERCEPTUAL_ROUGHNESS).
const float kMinSheenRoughness = 0.045;
// NoV floor of the sheen terms: the Charlie visibility divides by 4 NoV NoL [Sheen].
const float kMinSheenNoV = 1e-4;

// One pixel's layers in the lighting pass (built from a decoded Surface: lighting_pass.comp.glsl
// gblLayersOf). Amounts of 0 mean "no such layer".
struct Layers {
    float coat;            // [0,1]
    float coatRoughness;   // perceptual, [0,1]
    vec3 coatNormal;       // unit; the base normal where the G-buffer holds none
    vec3 sheenColor;       // linear, >= 0
    float sheenRoughness;  // perceptual, [0,1]
    float anisotropy;      // strength in [0,1]; 0 where no tangent is known
    vec3 anisotropyT;      // unit, orthogonal to N: the direction highlights stretch along
    vec3 anisotropyB;      // cross(N, anisotropyT)
};

float max3(vec3 v) { return max(max(v.x, v.y), v.z); }

// ---- clear coat ----

// [Coat] the coat's n.v as the specification takes it, |V.Nc| (a coat normal map may turn Nc away
// from V: the mirrored angle, not a grazing one).
float coatNoV(vec3 Nc, vec3 V) { return min(abs(dot(Nc, V)), 1.0); }

// [Coat] the layering weight's Fresnel, with the specification's |V.Nc|: 0.04 + 0.96 (1 - NcoV)^5.
float coatFresnel(float NcoV) {
    return kCoatF0 + (1.0 - kCoatF0) * fresnelWeightSchlick(NcoV);
}

// visSmithGgxCorrelated ([glTF-B]'s height-correlated Smith visibility) is brdf.glsl's.

// The coat's BRDF without its Fresnel (which is the layering weight) [Coat], [glTF-B]: D V.
float coatSpecular(float NcoH, float NcoV, float NcoL, float coatRoughness) {
    return dGgx(NcoH, coatRoughness) * visSmithGgxCorrelated(NcoV, NcoL, coatRoughness);
}

// ---- sheen ----

// [Sheen] the Charlie distribution, alpha_g = sheenRoughness^2:
// (2 + 1/alpha_g) sin(theta_h)^(1/alpha_g) / (2 pi). sheenRoughness >= kMinSheenRoughness.
float dCharlie(float NoH, float sheenRoughness) {
    float alphaG = sheenRoughness * sheenRoughness;
    float invR = 1.0 / alphaG;
    float sin2h = max(1.0 - NoH * NoH, 0.0);
    return (2.0 + invR) * pow(sin2h, invR * 0.5) / (2.0 * kPi);
}

// [Sheen] the fitted curve of the Charlie lambda.
float sheenLambdaCurve(float x, float alphaG) {
    float oneMinusAlphaSq = (1.0 - alphaG) * (1.0 - alphaG);
    float a = mix(21.5473, 25.3245, oneMinusAlphaSq);
    float b = mix(3.82987, 3.32435, oneMinusAlphaSq);
    float c = mix(0.19823, 0.16801, oneMinusAlphaSq);
    float d = mix(-1.97760, -1.27393, oneMinusAlphaSq);
    float e = mix(-4.32054, -4.85967, oneMinusAlphaSq);
    return a / (1.0 + b * pow(x, c)) + d * x + e;
}

// [Sheen] lambda_sheen: exp(l(cos)) below cos 0.5, else exp(2 l(0.5) - l(1 - cos)).
float lambdaSheen(float cosTheta, float alphaG) {
    return abs(cosTheta) < 0.5 ? exp(sheenLambdaCurve(cosTheta, alphaG))
                               : exp(2.0 * sheenLambdaCurve(0.5, alphaG) - sheenLambdaCurve(1.0 - cosTheta, alphaG));
}

// [Sheen] the Charlie visibility 1 / ((1 + lambda(NoV) + lambda(NoL)) 4 NoV NoL). NoV, NoL > 0.
float visCharlie(float NoV, float NoL, float sheenRoughness) {
    float alphaG = sheenRoughness * sheenRoughness;
    return 1.0 / ((1.0 + lambdaSheen(NoV, alphaG) + lambdaSheen(NoL, alphaG)) * (4.0 * NoV * NoL));
}

// The sheen BRDF D V (no Fresnel, [Sheen]); times sheenColor and NoL by the caller.
float sheenBrdf(float NoH, float NoV, float NoL, float sheenRoughness) {
    float r = max(sheenRoughness, kMinSheenRoughness);
    return dCharlie(NoH, r) * visCharlie(max(NoV, kMinSheenNoV), NoL, r);
}

// [Sheen] the base's albedo scaling under a sheen of colour c, from the sheen's directional albedo
// towards V and towards L: min(1 - max3(c) E(NoV), 1 - max3(c) E(NoL)).
float sheenAlbedoScaling(vec3 sheenColor, float albedoV, float albedoL) {
    float m = max3(sheenColor);
    return min(1.0 - m * albedoV, 1.0 - m * albedoL);
}

// ---- anisotropy ----

// [Aniso] alpha_t along the anisotropy direction: mix(alpha, 1, strength^2), alpha = roughness^2.
float anisotropicAlphaT(float roughness, float anisotropy) {
    float a = roughness * roughness;
    return mix(a, 1.0, anisotropy * anisotropy);
}

// [Aniso] Burley's anisotropic GGX, 1 / (pi at ab ((h.t/at)^2 + (h.b/ab)^2 + (h.n)^2)^2), written as
// the specification's sample implementation writes it.
float dGgxAnisotropic(float NoH, float ToH, float BoH, float at, float ab) {
    float a2 = at * ab;
    vec3 f = vec3(ab * ToH, at * BoH, a2 * NoH);
    float w2 = a2 / dot(f, f);
    return a2 * w2 * w2 / kPi;
}

// [Aniso] the anisotropic height-correlated Smith visibility of the specification's sample
// implementation, clamped to [0, 1] as it is.
float visGgxAnisotropic(float NoL, float NoV, float BoV, float ToV, float ToL, float BoL, float at, float ab) {
    float ggxV = NoL * length(vec3(at * ToV, ab * BoV, NoV));
    float ggxL = NoV * length(vec3(at * ToL, ab * BoL, NoL));
    float v = 0.5 / (ggxV + ggxL);
    return clamp(v, 0.0, 1.0);
}

// Direct light on the anisotropic base: (Lambert + D_aniso V_aniso F) lightRadiance NoL, the
// specification's BRDF_specularAnisotropicGGX with the base's Fresnel mode (F is the base's, only
// the microfacet lobe changes). Roughness clamped to kMinDirectRoughness as the isotropic base.
// Its visibility is the specification's height-correlated Smith, not UE4's Schlick-Smith with the
// analytic k: at strength -> 0 the lobe tends to GGX with that visibility, not to the UE4 base, so
// a layout that drops a weak anisotropy is charged that difference too (the specification defines
// the anisotropic lobe whole; UE4 itself switches to a joint Smith for anisotropy).
vec3 evaluateDirectLightAnisotropicMode(vec3 N, vec3 V, vec3 L, vec3 T, vec3 B, float anisotropy,
                                        vec3 diffuseColor, vec3 specularColor, float roughness,
                                        vec3 lightRadiance, int fresnelMode) {
    float NoL = clamp(dot(N, L), 0.0, 1.0);
    if (NoL <= 0.0) return vec3(0.0);
    vec3 Hu = V + L;
    vec3 H = Hu * inversesqrt(max(dot(Hu, Hu), 1e-12));
    float NoV = clamp(dot(N, V), 0.0, 1.0);
    float NoH = clamp(dot(N, H), 0.0, 1.0);
    float VoH = clamp(dot(V, H), 0.0, 1.0);
    float r = max(roughness, kMinDirectRoughness);
    float ab = r * r;
    float at = anisotropicAlphaT(r, anisotropy);
    float D = dGgxAnisotropic(NoH, dot(T, H), dot(B, H), at, ab);
    float Vis = visGgxAnisotropic(NoL, NoV, dot(B, V), dot(T, V), dot(T, L), dot(B, L), at, ab);
    vec3 F = fresnel(fresnelMode, specularColor, VoH);
    vec3 brdf = diffuseLambert(diffuseColor) + D * Vis * F;
    return brdf * lightRadiance * NoL;
}

// ---- the layered direct light ----

// [Coat] emission under the coat: emission * (1 - clearcoat * fc(NcoV)).
vec3 coatedEmission(vec3 emission, Layers ly, vec3 V) {
    if (ly.coat <= 0.0) return emission;
    return emission * (1.0 - ly.coat * coatFresnel(coatNoV(ly.coatNormal, V)));
}

// [Aniso] "Image-based lighting": the bent normal for one pre-filtered look-up of an anisotropic
// lobe. B = anisotropyB (the direction of the base roughness). Returns the reflection vector.
vec3 anisotropicReflection(vec3 N, vec3 V, vec3 B, float anisotropy, float roughness) {
    vec3 bent = cross(cross(B, V), B);
    bent = dot(bent, bent) > 1e-12 ? normalize(bent) : N;  // V along B: no plane to bend in
    float t = 1.0 - anisotropy * (1.0 - roughness);
    float a = t * t * t * t;
    bent = normalize(mix(bent, N, a));
    vec3 R = reflect(-V, bent);
    return normalize(mix(R, bent, roughness * roughness));
}

// ---- BRDF_GLTF: the layers as the Khronos glTF Sample Viewer layers them ----
// [Viewer] = npm @khronosgroup/gltf-viewer 1.1.0, dist/gltf-viewer.module.js: brdfShader (line 3802),
// punctualShader (3810), pbrShader (3800: main's punctual loop). The layering order and formulas are
// the ones above; what differs is where the viewer clamps:
//   sheen   D_Charlie and V_Sheen floor sheenRoughness at 1e-6 (not 0.045) and V_Sheen clamps the
//           visibility to [0, 1] with NdotV unfloored;
//   coat    the coat's n.v is clampedDot(Nc, v) (not |Nc.v|), its roughness unfloored;
//   aniso   alpha_b = clamp(alpha, 0.001, 1), NdotH clamped to [0.001, 1], NdotV unclamped.
const float kMinGltfSheenRoughness = 0.000001;  // [Viewer] brdfShader V_Sheen, D_Charlie

// [Sheen] D V of the sheen lobe with [Viewer]'s clamps (V_Sheen clamp(..., 0, 1)). NoL > 0.
float sheenBrdfGltf(float NoH, float NoV, float NoL, float sheenRoughness) {
    float r = max(sheenRoughness, kMinGltfSheenRoughness);
    return dCharlie(NoH, r) * clamp(visCharlie(NoV, NoL, r), 0.0, 1.0);
}

// [Aniso] the anisotropic lobe under the glTF base (evaluateDirectLightGltf's diffuse and Fresnel),
// with [Viewer] brdfShader BRDF_specularGGXAnisotropy's clamps.
vec3 evaluateDirectLightAnisotropicGltf(vec3 N, vec3 V, vec3 L, vec3 T, vec3 B, float anisotropy, vec3 diffuseColor,
                                        vec3 specularColor, float dielectricF0, float roughness, vec3 lightRadiance) {
    float NoL = clamp(dot(N, L), 0.0, 1.0);
    if (NoL <= 0.0) return vec3(0.0);
    vec3 Hu = V + L;
    vec3 H = Hu * inversesqrt(max(dot(Hu, Hu), 1e-12));
    float VoH = clamp(dot(V, H), 0.0, 1.0);
    float at = anisotropicAlphaT(roughness, anisotropy);
    float ab = clamp(roughness * roughness, 0.001, 1.0);
    float NoH = clamp(dot(N, H), 0.001, 1.0);
    float D = dGgxAnisotropic(NoH, dot(T, H), dot(B, H), at, ab);
    float Vis = visGgxAnisotropic(NoL, dot(N, V), dot(B, V), dot(T, V), dot(T, L), dot(B, L), at, ab);
    vec3 F = fSchlick(specularColor, VoH);
    float Fd = gltfDielectricFresnel(dielectricF0, VoH);
    vec3 brdf = diffuseLambert(diffuseColor) * (1.0 - Fd) + D * Vis * F;
    return brdf * lightRadiance * NoL;
}

// The coat's n.v under BRDF_GLTF: [Viewer] pbrShader clampedDot(clearcoatNormal, v).
float coatNoVGltf(vec3 Nc, vec3 V) { return clamp(dot(Nc, V), 0.0, 1.0); }

// The layers over a base lobe's radiance `color` ([Sheen] then [Coat]: coat(sheen(base))), as
// evaluateDirectLightLayeredMode and evaluateDirectLightLayeredGltf share it. `gltf` picks the
// Sample Viewer's three choices (its sheen clamps, the coat's clamped n.v, the roughness floor
// kMinGltfRoughness); otherwise sheenBrdf, |n.v| and kMinDirectRoughness.
vec3 layerOverBase(vec3 color, vec3 N, vec3 V, vec3 L, Layers ly, float sheenAlbedoV, float sheenAlbedoL,
                   vec3 lightRadiance, bool gltf) {
    vec3 Hu = V + L;
    vec3 H = Hu * inversesqrt(max(dot(Hu, Hu), 1e-12));
    if (max3(ly.sheenColor) > 0.0) {
        float NoL = clamp(dot(N, L), 0.0, 1.0);
        vec3 sheen = vec3(0.0);
        if (NoL > 0.0) {
            float NoH = clamp(dot(N, H), 0.0, 1.0), NoV = clamp(dot(N, V), 0.0, 1.0);
            float lobe = gltf ? sheenBrdfGltf(NoH, NoV, NoL, ly.sheenRoughness) : sheenBrdf(NoH, NoV, NoL, ly.sheenRoughness);
            sheen = ly.sheenColor * (lobe * NoL) * lightRadiance;
        }
        color = sheen + color * sheenAlbedoScaling(ly.sheenColor, sheenAlbedoV, sheenAlbedoL);
    }
    if (ly.coat > 0.0) {
        vec3 Nc = ly.coatNormal;
        float NcoL = clamp(dot(Nc, L), 0.0, 1.0);
        float NcoV = gltf ? coatNoVGltf(Nc, V) : coatNoV(Nc, V);
        float fc = ly.coat * coatFresnel(NcoV);
        float coat = 0.0;
        if (NcoL > 0.0)
            coat = coatSpecular(clamp(dot(Nc, H), 0.0, 1.0), NcoV, NcoL,
                                max(ly.coatRoughness, gltf ? kMinGltfRoughness : kMinDirectRoughness)) * NcoL;
        color = color * (1.0 - fc) + (fc * coat) * lightRadiance;
    }
    return color;
}

// Radiance towards V from one analytic light from L over every layer of `ly`: the base (UE4's, or
// the anisotropic lobe where ly.anisotropy > 0), under the sheen (albedo-scaled, [Sheen]), under
// the coat ([Coat]). sheenAlbedoV / sheenAlbedoL: E(NoV), E(NoL) of the sheen at its roughness
// (the caller's table look-ups; unread without sheen). Without layers: evaluateDirectLightMode,
// bit for bit.
vec3 evaluateDirectLightLayeredMode(vec3 N, vec3 V, vec3 L, vec3 diffuseColor, vec3 specularColor, float roughness,
                                    Layers ly, float sheenAlbedoV, float sheenAlbedoL, vec3 lightRadiance,
                                    int fresnelMode) {
    vec3 color = ly.anisotropy > 0.0
                     ? evaluateDirectLightAnisotropicMode(N, V, L, ly.anisotropyT, ly.anisotropyB, ly.anisotropy,
                                                          diffuseColor, specularColor, roughness, lightRadiance,
                                                          fresnelMode)
                     : evaluateDirectLightMode(N, V, L, diffuseColor, specularColor, roughness, lightRadiance,
                                               fresnelMode);
    return layerOverBase(color, N, V, L, ly, sheenAlbedoV, sheenAlbedoL, lightRadiance, false);
}

// evaluateDirectLightLayeredMode's layering over the glTF base: coat(sheen(base)) [Sheen], [Coat].
vec3 evaluateDirectLightLayeredGltf(vec3 N, vec3 V, vec3 L, vec3 diffuseColor, vec3 specularColor, float dielectricF0,
                                    float roughness, Layers ly, float sheenAlbedoV, float sheenAlbedoL,
                                    vec3 lightRadiance) {
    vec3 color = ly.anisotropy > 0.0
                     ? evaluateDirectLightAnisotropicGltf(N, V, L, ly.anisotropyT, ly.anisotropyB, ly.anisotropy,
                                                          diffuseColor, specularColor, dielectricF0, roughness,
                                                          lightRadiance)
                     : evaluateDirectLightGltf(N, V, L, diffuseColor, specularColor, dielectricF0, roughness,
                                               lightRadiance);
    return layerOverBase(color, N, V, L, ly, sheenAlbedoV, sheenAlbedoL, lightRadiance, true);
}

// [Coat] emission under the coat with [Viewer]'s n.v: emission * (1 - clearcoat * fc(clampedDot)).
vec3 coatedEmissionGltf(vec3 emission, Layers ly, vec3 V) {
    if (ly.coat <= 0.0) return emission;
    return emission * (1.0 - ly.coat * coatFresnel(coatNoVGltf(ly.coatNormal, V)));
}

#endif  // GBL_BRDF_LAYERS_GLSL
