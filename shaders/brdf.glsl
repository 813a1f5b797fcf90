// brdf.glsl -- the UE4 (SIGGRAPH 2013) shading model: every BRDF term as a choice.
// Include file (GLSL 450, no #version). The C++ mirror is src/shading/brdf.h / src/shading/brdf.cpp, with the
// same names and the same math, line for line; keep the two in step.
//
// Sources:
//   [Karis13]  B. Karis, "Real Shading in Unreal Engine 4", SIGGRAPH 2013 course notes.
//   [Walter07] B. Walter et al., "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007.
//   [Schlick94] C. Schlick, "An Inexpensive BRDF Model for Physically-based Rendering", 1994.
//   [Seed]     ../shared/seed/000_807e17994f774a43.txt (digest: ../shared/seed/DIGEST.md).
//   [glTF-B]   glTF 2.0 Specification, Appendix B "BRDF Implementation" (specification/2.0/
//              Specification.adoc, sections "Specular BRDF", "Fresnel", "Metal BRDF and Dielectric BRDF").
//   [Viewer]   the Khronos glTF Sample Viewer, npm @khronosgroup/gltf-viewer 1.1.0, whose shaders
//              are strings in dist/gltf-viewer.module.js: brdfShader (line 3802: V_GGX, D_GGX,
//              F_Schlick, BRDF_lambertian), punctualShader (3810: getRangeAttenuation,
//              getSpotAttenuation), pbrShader (3800: main's punctual loop).
//
// Conventions:
//   roughness is UE4's perceptual roughness in [0,1]; alpha = roughness^2 everywhere.
//   All cosines (NoH, NoV, NoL, VoH) are clamped to [0,1] by the caller or by evaluateDirectLight.
//   Which Smith-Schlick k each path uses:
//     analytic (punctual/directional) lights: k = (roughness + 1)^2 / 8  -> gSmithSchlickAnalytic
//     image-based lighting (ibl_math.glsl: SpecularIBL ground truth, IntegrateBRDF / the LUT):
//                                             k = alpha / 2               -> gSmithSchlickIbl
//   [Karis13] p.3: the (roughness+1)/2 remap "is only for analytic light sources"; with IBL
//   it makes glancing angles too dark.
//   Default Fresnel: FRESNEL_KARIS, the exp2 form UE4 shipped in 2013 [Karis13] (the seed's
//   own exp2 form FRESNEL_SEED is measurably worse; see the error bounds below).
#ifndef GBL_BRDF_GLSL
#define GBL_BRDF_GLSL

// ---- choices (int constants shared with src/shading/brdf.h; brdf_test checks that they agree) ----
const int NDF_GGX = 0;                    // the only D: GGX / Trowbridge-Reitz
const int GEOMETRY_SMITH_SCHLICK_ANALYTIC = 0;  // k = (roughness+1)^2/8
const int GEOMETRY_SMITH_SCHLICK_IBL = 1;       // k = alpha/2
const int FRESNEL_SCHLICK = 0;            // exact Schlick: (1-c)^5
const int FRESNEL_KARIS = 1;              // 2^((-5.55473 c - 6.98316) c)
const int FRESNEL_SEED = 2;               // 2^(-9.60232 c^8 - 8.58092 c)
const int DIFFUSE_LAMBERT = 0;            // the only diffuse: Lambert
const int FRESNEL_DEFAULT = FRESNEL_KARIS;
// The direct lights' BRDF (render/compare --brdf; RenderSettings::brdf, GBL_BRDF_MODEL):
const int BRDF_UE4 = 0;   // [Karis13]: Smith-Schlick with the analytic k, the Fresnel mode, Lambert added
const int BRDF_GLTF = 1;  // [glTF-B] as the Khronos glTF Sample Viewer computes it (evaluateDirectLightGltf)

const float kPi = 3.14159265358979323846;
// evaluateDirectLight clamps roughness to at least this: at roughness 0 the GGX lobe is a delta
// and D(NoH=1) = 0/0. 0.045 keeps alpha^2 = 4.1e-6 well above float's 1-NoH^2 rounding.
const float kMinDirectRoughness = 0.045;
// BRDF_GLTF clamps roughness to at least this instead: [Viewer] clamps none (perceptualRoughness
// in [0,1]) and its D_GGX is 0/0 where NoH rounds to 1 at roughness 0; 0.001 is its floor of the
// anisotropic lobe's alpha (brdfShader BRDF_specularGGXAnisotropy: clamp(alphaRoughness, 0.001, 1)).
// Below roughness ~0.0156 alpha^2 - 1 rounds to -1 in float, so D is alpha^2 / (pi sin^4(theta_h))
// on both sides and the floor moves only pixels whose NoH rounds to 1.
const float kMinGltfRoughness = 0.001;

// GGX / Trowbridge-Reitz normal distribution, alpha = roughness^2 [Karis13 eq. 3], [Walter07 eq. 33]:
//   D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2);  integral of D(h)(n.h) over the
//   hemisphere is 1 (brdf_test checks it numerically). Undefined (0/0) at roughness 0, NoH 1.
//   In float, d cancels near NoH = 1: relative error ~1.2e-7 / alpha^2 at the peak.
float dGgx(float NoH, float roughness) {
    float a = roughness * roughness;
    float a2 = a * a;
    float d = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

// Schlick's k for analytic lights [Karis13 eq. 4]: k = (roughness + 1)^2 / 8.
float kSmithSchlickAnalytic(float roughness) {
    float r = roughness + 1.0;
    return r * r / 8.0;
}

// Schlick's k for image-based lighting [Karis13 p.3, "k = alpha/2" without the remap].
float kSmithSchlickIbl(float roughness) {
    float a = roughness * roughness;
    return a / 2.0;
}

// Schlick's approximation of the Smith G1 term [Schlick94], [Karis13 eq. 4]:
//   G1(v) = (n.v) / ((n.v)(1 - k) + k).
float g1SmithSchlick(float NoX, float k) {
    return NoX / (NoX * (1.0 - k) + k);
}

// Smith G = G1(l) G1(v) with a given k [Karis13 eq. 4].
float gSmithSchlick(float NoV, float NoL, float k) {
    return g1SmithSchlick(NoV, k) * g1SmithSchlick(NoL, k);
}

// Smith-Schlick G for analytic lights, k = (roughness+1)^2/8 [Karis13 eq. 4]. Used by evaluateDirectLight.
float gSmithSchlickAnalytic(float roughness, float NoV, float NoL) {
    return gSmithSchlick(NoV, NoL, kSmithSchlickAnalytic(roughness));
}

// Smith-Schlick G for IBL, k = alpha/2 [Karis13 p.3]. Used by ibl_math.glsl (ground truth and LUT).
float gSmithSchlickIbl(float roughness, float NoV, float NoL) {
    return gSmithSchlick(NoV, NoL, kSmithSchlickIbl(roughness));
}

// G / (4 (n.l)(n.v)) with the n.l and n.v of G1 cancelled algebraically [Karis13 eq. 4 rearranged]:
//   1 / (4 ((n.l)(1-k)+k) ((n.v)(1-k)+k)). Finite at n.v = 0 whenever k > 0.
float visSmithSchlick(float NoV, float NoL, float k) {
    return 0.25 / ((NoL * (1.0 - k) + k) * (NoV * (1.0 - k) + k));
}

// Fresnel weights: F = f0 + (1 - f0) * w(c), c = v.h. Max |w - (1-c)^5| over c in [0,1],
// measured and asserted in brdf_test: FRESNEL_KARIS 3.77e-3 (c = 0.055), FRESNEL_SEED 3.88e-2
// (c = 0.100).
// Exact Schlick weight [Schlick94]: (1 - c)^5.
float fresnelWeightSchlick(float VoH) {
    float m = 1.0 - VoH;
    float m2 = m * m;
    return m2 * m2 * m;
}

// Karis' spherical-Gaussian exp2 weight [Karis13 eq. 5]: 2^((-5.55473 c - 6.98316) c).
float fresnelWeightKaris(float VoH) {
    return exp2((-5.55473 * VoH - 6.98316) * VoH);
}

// The seed's exp2 weight [Seed, "F(theta)"]: 2^(-9.60232 c^8 - 8.58092 c).
float fresnelWeightSeed(float VoH) {
    float c2 = VoH * VoH;
    float c4 = c2 * c2;
    float c8 = c4 * c4;
    return exp2(-9.60232 * c8 - 8.58092 * VoH);
}

// Weight chosen at run time (FRESNEL_*; an unknown value falls back to exact Schlick).
float fresnelWeight(int mode, float VoH) {
    if (mode == FRESNEL_KARIS) return fresnelWeightKaris(VoH);
    if (mode == FRESNEL_SEED) return fresnelWeightSeed(VoH);
    return fresnelWeightSchlick(VoH);
}

// Exact Schlick Fresnel [Schlick94]: f0 + (1 - f0)(1 - c)^5.
vec3 fSchlick(vec3 f0, float VoH) {
    return f0 + (vec3(1.0) - f0) * fresnelWeightSchlick(VoH);
}

// Schlick Fresnel with Karis' exp2 power [Karis13 eq. 5] (UE4's 2013 default).
vec3 fSchlickKaris(vec3 f0, float VoH) {
    return f0 + (vec3(1.0) - f0) * fresnelWeightKaris(VoH);
}

// Schlick Fresnel with the seed's exp2 power [Seed].
vec3 fSchlickSeed(vec3 f0, float VoH) {
    return f0 + (vec3(1.0) - f0) * fresnelWeightSeed(VoH);
}

// Fresnel chosen at run time (FRESNEL_*).
vec3 fresnel(int mode, vec3 f0, float VoH) {
    return f0 + (vec3(1.0) - f0) * fresnelWeight(mode, VoH);
}

// Lambert diffuse [Karis13 eq. 1]: c_diff / pi.
vec3 diffuseLambert(vec3 diffuseColor) {
    return diffuseColor / kPi;
}

// Cook-Torrance specular BRDF [Karis13 eq. 2]: D F G / (4 (n.l)(n.v)), here D * Vis * F with
// the analytic-light k. Cosines already clamped to [0,1].
vec3 specularGgx(float NoH, float NoV, float NoL, float VoH, vec3 specularColor, float roughness,
                 int fresnelMode) {
    float D = dGgx(NoH, roughness);
    float Vis = visSmithSchlick(NoV, NoL, kSmithSchlickAnalytic(roughness));
    vec3 F = fresnel(fresnelMode, specularColor, VoH);
    return D * Vis * F;
}

// Radiance reflected towards V from one analytic light of radiance (irradiance at normal
// incidence) lightRadiance arriving from L [Karis13 sec. "Shading Model"]:
//   (Lambert + GGX D * Smith-Schlick(analytic k) * Fresnel) * lightRadiance * (n.l).
// N, V, L unit, V and L pointing away from the surface. Roughness is clamped to
// kMinDirectRoughness. Diffuse and specular are simply added, as in UE4 (no (1-F) weighting).
vec3 evaluateDirectLightMode(vec3 N, vec3 V, vec3 L, vec3 diffuseColor, vec3 specularColor,
                             float roughness, vec3 lightRadiance, int fresnelMode) {
    float NoL = clamp(dot(N, L), 0.0, 1.0);
    if (NoL <= 0.0) return vec3(0.0);
    vec3 Hu = V + L;  // unnormalised half vector; zero when V = -L (then NoH = VoH = 0)
    vec3 H = Hu * inversesqrt(max(dot(Hu, Hu), 1e-12));
    float NoV = clamp(dot(N, V), 0.0, 1.0);
    float NoH = clamp(dot(N, H), 0.0, 1.0);
    float VoH = clamp(dot(V, H), 0.0, 1.0);
    float r = max(roughness, kMinDirectRoughness);
    vec3 brdf = diffuseLambert(diffuseColor) +
                specularGgx(NoH, NoV, NoL, VoH, specularColor, r, fresnelMode);
    return brdf * lightRadiance * NoL;
}

// evaluateDirectLightMode with the default Fresnel (FRESNEL_DEFAULT = FRESNEL_KARIS).
vec3 evaluateDirectLight(vec3 N, vec3 V, vec3 L, vec3 diffuseColor, vec3 specularColor,
                         float roughness, vec3 lightRadiance) {
    return evaluateDirectLightMode(N, V, L, diffuseColor, specularColor, roughness, lightRadiance,
                                   FRESNEL_DEFAULT);
}

// ---- BRDF_GLTF: the glTF 2.0 specification's BRDF [glTF-B] as [Viewer] computes it ----

// [glTF-B] "Specular BRDF": the height-correlated Smith visibility of GGX, G / (4 |NoL| |NoV|) =
// 0.5 / (NoV sqrt(a^2 + (1 - a^2) NoL^2) + NoL sqrt(a^2 + (1 - a^2) NoV^2)), alpha = roughness^2
// ([Viewer] brdfShader V_GGX, the same sum). Cosines in [0,1]; 0 where both are 0.
float visSmithGgxCorrelated(float NoV, float NoL, float roughness) {
    float a = roughness * roughness;
    float a2 = a * a;
    float gv = NoL * sqrt(a2 + (1.0 - a2) * NoV * NoV);
    float gl = NoV * sqrt(a2 + (1.0 - a2) * NoL * NoL);
    float d = gv + gl;
    return d > 0.0 ? 0.5 / d : 0.0;
}

// [glTF-B] "Fresnel", fresnel_mix: the dielectric's Fresnel f0 + (1 - f0)(1 - |VoH|)^5 with f90 = 1,
// the weight of its specular over its diffuse ([Viewer] pbrShader: F_Schlick(f0_dielectric *
// specularWeight, f90_dielectric, VdotH), f90_dielectric = 1 without KHR_materials_specular).
float gltfDielectricFresnel(float dielectricF0, float VoH) {
    return dielectricF0 + (1.0 - dielectricF0) * fresnelWeightSchlick(VoH);
}

// Radiance towards V from one punctual light from L under the glTF BRDF [glTF-B]:
//   material = mix(dielectric_brdf, metal_brdf, metallic),
//   dielectric_brdf = mix(diffuse_brdf(baseColor), specular_brdf, F_dielectric),
//   metal_brdf = specular_brdf * F_Schlick(baseColor),  specular_brdf = D Vis (GGX, height-correlated),
// written with the Surface's diffuseColor = baseColor (1 - metallic) and specularColor =
// mix(dielectricF0, baseColor, metallic): (1 - m) F_dielectric + m F_metal = F_Schlick(specularColor)
// (f90 = 1 in both), so material = diffuse_brdf(diffuseColor) (1 - F_dielectric) + D Vis
// F_Schlick(specularColor) -- the same function, each term as [Viewer] pbrShader rounds it up to
// the order of the sums. Times lightRadiance (the light's intensity at the point) and NoL.
// N, V, L unit, V and L pointing away from the surface; roughness floored to kMinGltfRoughness.
vec3 evaluateDirectLightGltf(vec3 N, vec3 V, vec3 L, vec3 diffuseColor, vec3 specularColor, float dielectricF0,
                             float roughness, vec3 lightRadiance) {
    float NoL = clamp(dot(N, L), 0.0, 1.0);
    if (NoL <= 0.0) return vec3(0.0);
    vec3 Hu = V + L;
    vec3 H = Hu * inversesqrt(max(dot(Hu, Hu), 1e-12));
    float NoV = clamp(dot(N, V), 0.0, 1.0);
    float NoH = clamp(dot(N, H), 0.0, 1.0);
    float VoH = clamp(dot(V, H), 0.0, 1.0);
    float r = max(roughness, kMinGltfRoughness);
    float D = dGgx(NoH, r);
    float Vis = visSmithGgxCorrelated(NoV, NoL, r);
    vec3 F = fSchlick(specularColor, VoH);
    float Fd = gltfDielectricFresnel(dielectricF0, VoH);
    vec3 brdf = diffuseLambert(diffuseColor) * (1.0 - Fd) + D * Vis * F;
    return brdf * lightRadiance * NoL;
}

// KHR_lights_punctual's range window on the inverse square (its README, "Range Property":
// clamp(1 - (d / range)^4, 0, 1) / d^2), per BRDF: BRDF_GLTF as the README and [Viewer]
// punctualShader getRangeAttenuation write it; BRDF_UE4 squares the window as UE4 does
// ([Karis13] eq. 9: saturate(1 - (d/r)^4)^2 / (d^2 + 1), without the + 1).
float lightRangeWindow(float d2, float range, int brdfModel) {
    if (range <= 0.0) return 1.0;
    float r = d2 / (range * range);
    float window = clamp(1.0 - r * r, 0.0, 1.0);
    return brdfModel == BRDF_GLTF ? window : window * window;
}

#endif  // GBL_BRDF_GLSL
