// ibl_math.glsl -- image-based lighting maths of UE4 (SIGGRAPH 2013) and Black Ops 2's analytic
// environment BRDF. Include file (GLSL 450, no #version). Include brdf.glsl first.
// The C++ mirror is src/shading/ibl_math.h / src/shading/ibl_math.cpp (same names, same math;
// specularIBLGroundTruthMis too, checked against it by ibl_ground_truth_test GroundTruthMisMatchesCpuTwin).
//
// Sources:
//   [Karis13]   B. Karis, "Real Shading in Unreal Engine 4", SIGGRAPH 2013 course notes
//               (ImportanceSampleGGX, SpecularIBL, PrefilterEnvMap, IntegrateBRDF).
//   [Karis14]   B. Karis, "Physically Based Shading on Mobile", 2014 (EnvBRDFApprox).
//   [Lazarov13] D. Lazarov, "Getting More Physical in Call of Duty: Black Ops II", SIGGRAPH 2013.
//   [KC08]      J. Krivanek, M. Colbert, "Real-time Shading with Filtered Importance Sampling",
//               EGSR 2008 (the mip level of a sample).
//   [HH64]      J. Hammersley, D. Handscomb, "Monte Carlo Methods", 1964 (Hammersley points);
//               radical inverse by bit reversal as in H. Warren, "Hacker's Delight", ch. 7.
//   [Heitz18]   E. Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), 2018.
//   [Heitz14]   E. Heitz, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs",
//               JCGT 3(2), 2014 (exact Smith G1 of GGX).
//   [Walter07]  B. Walter et al., "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007.
//   [Seed]      ../shared/seed/000_807e17994f774a43.txt, digest ../shared/seed/DIGEST.md.
//
// Environment access: the functions that read an environment (specularIBLGroundTruth,
// prefilterEnvMap, prefilterEnvMapFiltered) are compiled only when the includer has defined
//     vec3 sampleEnvironmentLod(vec3 dir, float lod)   // radiance along world dir at mip lod
// and then `#define GBL_IBL_HAS_ENVIRONMENT` before including this file. Everything else
// (Hammersley, importance sampling, IntegrateBRDF, the analytic fits) needs no binding.
//
// Conventions:
//   G in every IBL integral is Smith-Schlick with k = alpha/2 (gSmithSchlickIbl), as [Karis13]
//   prescribes for IBL; analytic lights use (roughness+1)^2/8 (see brdf.glsl).
//   Mip <-> roughness of the pre-filtered cube: linear, roughness = mip / (mipCount - 1).
//   Black Ops 2 gloss from roughness: through the Blinn-Phong power, g = log2(2/alpha^2 - 2)/13
//   (bo2GlossFromRoughness; src/shading/ibl_math.h has the measurements against g = 1 - roughness).
//   BRDF LUT (src/shading/ibl_brdf_lut.h): u = NoV, v = roughness, so sample it at vec2(NoV, roughness).
#ifndef GBL_IBL_GLSL
#define GBL_IBL_GLSL

#ifndef GBL_BRDF_GLSL
#error "ibl_math.glsl needs brdf.glsl: include brdf.glsl first"
#endif

const uint kIblDefaultSamples = 1024u;   // the seed's NumSamples
// NoV is clamped to at least this in the IBL integrals: the seed divides by NoV.
const float kMinIblNoV = 1e-4;

// Base-2 radical inverse (van der Corput) of i by reversing its 32 bits [HH64], [Warren ch. 7].
// Returns the top 24 reversed bits times 2^-24: exact for i < 2^24, always in [0, 1).
float radicalInverseVdC(uint bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits >> 8u) * 5.9604644775390625e-8;  // 2^-24
}

// i-th of N Hammersley points [HH64]: (i/N, radicalInverse(i)); in [0,1)^2 for i < N <= 2^24.
vec2 hammersley(uint i, uint N) {
    return vec2(float(i) / float(N), radicalInverseVdC(i));
}

// GGX half-vector sample around N [Karis13, ImportanceSampleGGX; Walter07 eqs. 35-36]:
// a = roughness^2, phi = 2 pi Xi.x, cos(theta) = sqrt((1 - Xi.y) / (1 + (a^2 - 1) Xi.y)),
// tangent frame from up = |N.z| < 0.999 ? +z : +x. pdf(H) = D(H) (N.H).
vec3 importanceSampleGGX(vec2 Xi, float roughness, vec3 N) {
    float a = roughness * roughness;
    float phi = 2.0 * kPi * Xi.x;
    float cosTheta = sqrt((1.0 - Xi.y) / (1.0 + (a * a - 1.0) * Xi.y));
    float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
    vec3 H = vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
    vec3 up = abs(N.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 tangentX = normalize(cross(up, N));
    vec3 tangentY = cross(N, tangentX);
    return tangentX * H.x + tangentY * H.y + N * H.z;
}

// Solid-angle pdf of L = reflect(-V, H) when H ~ D(H)(N.H) [Karis13 SpecularIBL comment,
// Walter07 eq. 14]: D NoH / (4 VoH).
float pdfGgxReflection(float NoH, float VoH, float roughness) {
    return dGgx(NoH, roughness) * NoH / (4.0 * VoH);
}

// Filtered importance sampling [KC08, sec. 3]: the mip level whose texel solid angle matches
// the sample's, lod = 0.5 log2(Os / Op), Os = 1 / (N p), Op = 4 pi / (6 w^2), w = face size
// of mip 0 in texels, p the sample's solid-angle pdf. Clamped below at 0 (no bias added);
// the caller clamps above at its last mip.
float filteredSampleLod(float pdf, float numSamples, float faceSize) {
    float omegaS = 1.0 / (numSamples * pdf);
    float omegaP = 4.0 * kPi / (6.0 * faceSize * faceSize);
    return max(0.5 * log2(omegaS / omegaP), 0.0);
}

// Mip of the pre-filtered cube for a roughness: linear, mip = roughness (mipCount - 1).
// (Not given in the UE4 slides, as the seed notes; our choice: even steps in perceptual
// roughness, trivially invertible. Mip 0 is the mirror level.)
float mipFromRoughness(float roughness, float mipCount) {
    return roughness * max(mipCount - 1.0, 0.0);
}

// Inverse of mipFromRoughness: roughness = mip / (mipCount - 1) (0 when mipCount <= 1).
float roughnessFromMip(float mip, float mipCount) {
    return mipCount > 1.0 ? mip / (mipCount - 1.0) : 0.0;
}

// [Karis13, IntegrateBRDF]: the environment BRDF (A, B), with
// integral of f cos = f0 A + B for Schlick's Fresnel. N = (0,0,1) (the seed leaves it
// undefined), V = (sqrt(1 - NoV^2), 0, NoV); G = Smith-Schlick with k = alpha/2 (IBL).
vec2 integrateBRDF(float roughness, float NoV, uint numSamples) {
    NoV = max(NoV, kMinIblNoV);
    vec3 V = vec3(sqrt(1.0 - NoV * NoV), 0.0, NoV);
    vec3 N = vec3(0.0, 0.0, 1.0);
    float A = 0.0;
    float B = 0.0;
    for (uint i = 0u; i < numSamples; i++) {
        vec2 Xi = hammersley(i, numSamples);
        vec3 H = importanceSampleGGX(Xi, roughness, N);
        vec3 L = 2.0 * dot(V, H) * H - V;
        float NoL = clamp(L.z, 0.0, 1.0);
        float NoH = clamp(H.z, 0.0, 1.0);
        float VoH = clamp(dot(V, H), 0.0, 1.0);
        if (NoL > 0.0) {
            float G = gSmithSchlickIbl(roughness, NoV, NoL);
            float G_Vis = G * VoH / (NoH * NoV);
            float Fc = fresnelWeightSchlick(VoH);
            A += (1.0 - Fc) * G_Vis;
            B += Fc * G_Vis;
        }
    }
    return vec2(A, B) / float(numSamples);
}

vec2 integrateBRDF(float roughness, float NoV) {
    return integrateBRDF(roughness, NoV, kIblDefaultSamples);
}

// Exact Smith G1 of GGX [Walter07 eq. 34], [Heitz14 eq. 72]: 2 NoV / (NoV + sqrt(a^2 + (1 - a^2) NoV^2)),
// a = roughness^2. The normalisation of the visible-normal distribution below (not the BRDF's G).
float g1SmithGgxExact(float NoV, float roughness) {
    float a = roughness * roughness;
    float a2 = a * a;
    return 2.0 * NoV / (NoV + sqrt(a2 + (1.0 - a2) * NoV * NoV));
}

// GGX visible-normal sample [Heitz18, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4),
// listing 1], isotropic alpha = roughness^2, in the tangent frame N = +z with V in the xz plane
// (V.y = 0, V.x >= 0), so T1 = +y. pdf(H) = G1(V) max(VoH, 0) D(H) / NoV with the exact Smith G1.
vec3 importanceSampleVisibleGGX(vec2 Xi, float roughness, vec3 V) {
    float a = roughness * roughness;
    vec3 Vh = normalize(vec3(a * V.x, 0.0, V.z));
    vec3 T1 = vec3(0.0, 1.0, 0.0);
    vec3 T2 = cross(Vh, T1);
    float r = sqrt(Xi.x);
    float phi = 2.0 * kPi * Xi.y;
    float t1 = r * cos(phi);
    float t2 = r * sin(phi);
    float s = 0.5 * (1.0 + Vh.z);
    t2 = (1.0 - s) * sqrt(max(1.0 - t1 * t1, 0.0)) + s * t2;
    vec3 Nh = t1 * T1 + t2 * T2 + sqrt(max(1.0 - t1 * t1 - t2 * t2, 0.0)) * Vh;
    return normalize(vec3(a * Nh.x, a * Nh.y, max(Nh.z, 0.0)));
}

// The environment BRDF (A, B) of integrateBRDF -- the same integral, the same BRDF (Smith-Schlick
// k = alpha/2, exact Schlick Fresnel) -- estimated with visible-normal sampling [Heitz18]: with
// L = reflect(-V, H), f NoL / pdf(L) = F G_SmithSchlick(V, L) / G1_SmithGGX(V), bounded, so
// grazing NoV converges where the seed's D(H) NoH sampling (weights ~ 1/NoV) does not.
// Points: ((i + 0.5) / N, radicalInverseVdC(i)) (Hammersley at mid-points).
// The default BRDF LUT (src/shading/ibl_brdf_lut.h): 4096 samples, max error 3.1e-4 over the 128 x 128 grid
// against an adaptive quadrature (tests/shading/brdf_lut_test.cpp, BrdfLut.ConvergedOverWholeGrid).
vec2 integrateBRDFVisible(float roughness, float NoV, uint numSamples) {
    NoV = max(NoV, kMinIblNoV);
    vec3 V = vec3(sqrt(1.0 - NoV * NoV), 0.0, NoV);
    float g1V = g1SmithGgxExact(NoV, roughness);
    float A = 0.0;
    float B = 0.0;
    for (uint i = 0u; i < numSamples; i++) {
        vec2 Xi = vec2((float(i) + 0.5) / float(numSamples), radicalInverseVdC(i));
        vec3 H = importanceSampleVisibleGGX(Xi, roughness, V);
        float VoH = clamp(dot(V, H), 0.0, 1.0);
        float NoL = 2.0 * VoH * H.z - NoV;
        if (NoL > 0.0) {
            float w = gSmithSchlickIbl(roughness, NoV, min(NoL, 1.0)) / g1V;
            float Fc = fresnelWeightSchlick(VoH);
            A += (1.0 - Fc) * w;
            B += Fc * w;
        }
    }
    return vec2(A, B) / float(numSamples);
}

// UE4's shipping EnvBRDF on a LUT value AB [Karis13 / Seed, EnvBRDF]:
// f0 AB.x + saturate(50 f0.g) AB.y -- "anything less than 2% is physically impossible and is
// instead considered to be shadowing".
vec3 envBRDF(vec3 specularColor, vec2 AB) {
    return specularColor * AB.x + clamp(50.0 * specularColor.g, 0.0, 1.0) * AB.y;
}

// UE4 mobile analytic environment BRDF [Karis14], [Seed, EnvBRDFApprox], a refit of
// Black Ops 2's a004 curve. Max abs error against our LUT over NoV, roughness in [0,1]:
// see src/shading/ibl_math.h (asserted in ibl_math_test).
vec3 envBRDFApprox(vec3 specularColor, float roughness, float NoV) {
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = roughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * NoV)) * r.x + r.y;
    vec2 AB = vec2(-1.04, 1.04) * a004 + r.zw;
    return specularColor * AB.x + AB.y;
}

// [Karis14], [Seed, EnvBRDFApproxNonmetal]: envBRDFApprox with specularColor = 0.04, up to
// rounding (the a004 curve itself).
float envBRDFApproxNonmetal(float roughness, float NoV) {
    const vec2 c0 = vec2(-1.0, -0.0275);
    const vec2 c1 = vec2(1.0, 0.0425);
    vec2 r = roughness * c0 + c1;
    return min(r.x * r.x, exp2(-9.28 * NoV)) * r.x + r.y;
}

// [Karis14], [Seed]: UE4 mobile's fully-rough shortcut (roughness == 1): skip the fit, move
// 45% of the specular colour into diffuse, and drop specular.
void envBRDFApproxFullyRough(inout vec3 diffuseColor, inout vec3 specularColor) {
    diffuseColor += specularColor * 0.45;
    specularColor = vec3(0.0);
}

// ---- Black Ops 2 [Lazarov13], [Seed]: integral of BRDF_env cos = rf0 a1 + (1 - rf0) a0,
// g = gloss in [0,1]. The fits and the folded EnvironmentBRDF, as printed in the seed.
// a0: fit of the rf0 = 0 curve.
float bo2A0(float g, float NoV) {
    float t1 = 11.4 * g * g * g + 0.1;
    float t2 = NoV + (0.1 - 0.09 * g);
    return (1.0 - exp(-t1 * t2)) * 1.32 * exp2(-10.3 * NoV);
}

// a1: fit of the rf0 = 1 curve.
float bo2A1(float g, float NoV) {
    float t1 = max(1.336 - 0.486 * g, 1.0);
    float t2 = 0.06 + 3.25 * g + 12.8 * g * g * g;
    float t3 = NoV + min(0.125 - 0.1 * g, 0.1);
    return min(t1 - exp2(-t2 * t3), 1.0);
}

// a0f: cheaper a0.
float bo2A0f(float g, float NoV) {
    float t1 = 0.095 + g * (0.6 + 4.19 * g);
    float t2 = NoV + 0.025;
    return t1 * t2 * exp2(1.0 - 14.0 * NoV);
}

// a1f: cheaper a1.
float bo2A1f(float g, float NoV) {
    float t1 = 9.5 * g * NoV;
    return 0.4 + 0.6 * (1.0 - exp2(-t1));
}

// a004: fit of the rf0 = 0.04 curve (replaces a0: a0 was too bright for dielectrics).
float bo2A004(float g, float NoV) {
    float t = min(0.475 * g, exp2(-9.28 * NoV));
    return (t + 0.0275) * g + 0.015;
}

// a1vf: very cheap a1 (gloss only).
float bo2A1vf(float g) {
    return 0.25 * g + 0.75;
}

// a0r: a0 recovered from a004 and a1vf, (a004 - 0.04 a1vf) / 0.96.
float bo2A0r(float g, float NoV) {
    return (bo2A004(g, NoV) - bo2A1vf(g) * 0.04) / 0.96;
}

// Black Ops 2 EnvironmentBRDF [Lazarov13], [Seed]: saturate(a0r + rf0 (a1vf - a0r)), with the
// constants folded into one vec4 as in the seed.
vec3 environmentBRDF(float g, float NoV, vec3 rf0) {
    vec4 t = vec4(1.0 / 0.96, 0.475, (0.0275 - 0.25 * 0.04) / 0.96, 0.25);
    t *= vec4(g, g, g, g);
    t += vec4(0.0, 0.0, (0.015 - 0.75 * 0.04) / 0.96, 0.75);
    float a0 = t.x * min(t.y, exp2(-9.28 * NoV)) + t.z;
    float a1 = t.w;
    return clamp(vec3(a0) + rf0 * (a1 - a0), 0.0, 1.0);
}

// Gloss for Black Ops 2 from UE4 roughness, linear: g = 1 - roughness (what UE4 mobile's
// refit of the same curves uses: r.x = 1 - Roughness in envBRDFApprox).
float glossFromRoughnessLinear(float roughness) {
    return 1.0 - roughness;
}

// Gloss through the Blinn-Phong power [Lazarov13]: BO2 stores n = 2^(13 g) (1..8192); the
// GGX-equivalent power is n = 2 / alpha^2 - 2 (the Phong/Beckmann match of [Walter07] sec. 5.2, applied to GGX
// as in B. Karis, "Specular BRDF Reference", 2013),
// so g = log2(2 / alpha^2 - 2) / 13, clamped to [0,1].
float glossFromRoughnessBlinnPhong(float roughness) {
    float a = roughness * roughness;
    float n = 2.0 / max(a * a, 1e-8) - 2.0;
    return clamp(log2(max(n, 1.0)) / 13.0, 0.0, 1.0);
}

// The mapping environmentBRDF is driven with: the Blinn-Phong-power one, which fits our LUT
// better than 1 - roughness (measured in src/shading/ibl_math.h) and is what "gloss" means in [Lazarov13].
float bo2GlossFromRoughness(float roughness) {
    return glossFromRoughnessBlinnPhong(roughness);
}

// ---- functions that read the environment ----
#ifdef GBL_IBL_HAS_ENVIRONMENT

// Ground truth [Karis13, SpecularIBL]: importance-sampled integral of L_i f cos over the
// hemisphere of N, with F = (1 - Fc) f0 + Fc, Fc = (1 - VoH)^5 (exact Schlick) and G with
// k = alpha/2 (IBL). Each sample: EnvMap(L) F G VoH / (NoH NoV) (= L_i f NoL / pdf).
// Samples mip 0 of the environment.
vec3 specularIBLGroundTruth(vec3 specularColor, float roughness, vec3 N, vec3 V, uint numSamples) {
    vec3 specularLighting = vec3(0.0);
    float NoV = max(clamp(dot(N, V), 0.0, 1.0), kMinIblNoV);
    for (uint i = 0u; i < numSamples; i++) {
        vec2 Xi = hammersley(i, numSamples);
        vec3 H = importanceSampleGGX(Xi, roughness, N);
        vec3 L = 2.0 * dot(V, H) * H - V;
        float NoL = clamp(dot(N, L), 0.0, 1.0);
        float NoH = clamp(dot(N, H), 0.0, 1.0);
        float VoH = clamp(dot(V, H), 0.0, 1.0);
        if (NoL > 0.0) {
            vec3 sampleColor = sampleEnvironmentLod(L, 0.0);
            float G = gSmithSchlickIbl(roughness, NoV, NoL);
            float Fc = fresnelWeightSchlick(VoH);
            vec3 F = (1.0 - Fc) * specularColor + Fc;
            specularLighting += sampleColor * F * G * VoH / (NoH * NoV);
        }
    }
    return specularLighting / float(numSamples);
}

vec3 specularIBLGroundTruth(vec3 specularColor, float roughness, vec3 N, vec3 V) {
    return specularIBLGroundTruth(specularColor, roughness, N, V, kIblDefaultSamples);
}

// [Karis13, PrefilterEnvMap] with n = v = r: GGX-importance-sampled environment weighted by
// NoL, divided by the total weight (declared here; the seed forgets to). Mip 0 samples.
vec3 prefilterEnvMap(float roughness, vec3 R, uint numSamples) {
    vec3 N = R;
    vec3 V = R;
    vec3 prefilteredColor = vec3(0.0);
    float totalWeight = 0.0;
    for (uint i = 0u; i < numSamples; i++) {
        vec2 Xi = hammersley(i, numSamples);
        vec3 H = importanceSampleGGX(Xi, roughness, N);
        vec3 L = 2.0 * dot(V, H) * H - V;
        float NoL = clamp(dot(N, L), 0.0, 1.0);
        if (NoL > 0.0) {
            prefilteredColor += sampleEnvironmentLod(L, 0.0) * NoL;
            totalWeight += NoL;
        }
    }
    return totalWeight > 0.0 ? prefilteredColor / totalWeight : vec3(0.0);
}

vec3 prefilterEnvMap(float roughness, vec3 R) {
    return prefilterEnvMap(roughness, R, kIblDefaultSamples);
}

// prefilterEnvMap for few samples: each sample reads the mip filteredSampleLod gives for its
// pdf [KC08]; with n = v, NoH = VoH and pdf = D / 4. faceSize = mip-0 face width in texels.
vec3 prefilterEnvMapFiltered(float roughness, vec3 R, uint numSamples, float faceSize) {
    if (roughness <= 0.0) return sampleEnvironmentLod(R, 0.0);  // D is a delta: pdf undefined
    vec3 N = R;
    vec3 V = R;
    vec3 prefilteredColor = vec3(0.0);
    float totalWeight = 0.0;
    for (uint i = 0u; i < numSamples; i++) {
        vec2 Xi = hammersley(i, numSamples);
        vec3 H = importanceSampleGGX(Xi, roughness, N);
        vec3 L = 2.0 * dot(V, H) * H - V;
        float NoL = clamp(dot(N, L), 0.0, 1.0);
        if (NoL > 0.0) {
            float NoH = clamp(dot(N, H), 0.0, 1.0);
            float pdf = dGgx(NoH, roughness) / 4.0;
            float lod = filteredSampleLod(pdf, float(numSamples), faceSize);
            prefilteredColor += sampleEnvironmentLod(L, lod) * NoL;
            totalWeight += NoL;
        }
    }
    return totalWeight > 0.0 ? prefilteredColor / totalWeight : vec3(0.0);
}

#endif  // GBL_IBL_HAS_ENVIRONMENT

// ---- the converged ground truth: environment importance sampling + GGX, combined by MIS ----
// Needs, besides sampleEnvironmentLod, the includer's
//     vec3 sampleEnvironmentDirection(vec2 u, out float pdf)  // luminance-proportional direction
//     float environmentDirectionPdf(vec3 dir)                // its solid-angle pdf
// (shaders/environment_sampling.glsl) and `#define GBL_IBL_HAS_ENVIRONMENT_SAMPLING`.
#ifdef GBL_IBL_HAS_ENVIRONMENT_SAMPLING

// Below this roughness GGX is (nearly) a delta: environment samples cannot hit its lobe, and
// D overflows in float; such pixels use the BRDF samples alone (weight 1).
const float kMinMisRoughness = 0.02;

// PCG hash (M. O'Neill, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
// Algorithms for Random Number Generation", 2014; the RXS-M-XS output of Jarzynski & Olano,
// "Hash Functions for GPU Rendering", JCGT 9(3), 2020).
uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A random shift in [0,1)^2 from three integers (Cranley-Patterson rotation of the point set).
vec2 randomShift(uint a, uint b, uint c) {
    uint h = pcgHash(a ^ pcgHash(b ^ pcgHash(c)));
    uint h2 = pcgHash(h);
    return vec2(float(h >> 8u), float(h2 >> 8u)) * 5.9604644775390625e-8;  // 2^-24
}

// Power heuristic, beta = 2 [Veach97, sec. 9.2.4]: the weight of a sample drawn from the technique
// with pdf `a` when the other one has pdf `b` (one sample of each per step).
float powerHeuristic(float a, float b) {
    float a2 = a * a;
    float d = a2 + b * b;
    return d > 0.0 ? a2 / d : 0.0;
}

// The same integral as specularIBLGroundTruth (L_i f cos over the hemisphere of N; exact Schlick
// F, Smith-Schlick G with k = alpha/2, environment mip 0), estimated with multiple importance
// sampling [Veach97, E. Veach, "Robust Monte Carlo Methods for Light Transport Simulation", PhD
// thesis, Stanford 1997, ch. 9]: each of numSamples steps takes one GGX half-vector sample (pdf
// D NoH / (4 VoH)) and one environment sample (luminance CDF, environmentDirectionPdf), each
// weighted by the power heuristic. The point set is Hammersley, Cranley-Patterson rotated by
// `shiftGgx` / `shiftEnv` (different per pixel and batch: independent batch means, so their
// spread estimates the noise). Unbiased: every direction the integrand reaches has a non-zero
// GGX pdf when roughness > 0.
vec3 specularIBLGroundTruthMis(vec3 specularColor, float roughness, vec3 N, vec3 V, uint numSamples,
                               vec2 shiftGgx, vec2 shiftEnv) {
    vec3 sum = vec3(0.0);
    float NoV = max(clamp(dot(N, V), 0.0, 1.0), kMinIblNoV);
    bool useEnvironment = roughness >= kMinMisRoughness;
    for (uint i = 0u; i < numSamples; i++) {
        vec2 Xi = hammersley(i, numSamples);
        // BRDF technique.
        vec3 H = importanceSampleGGX(fract(Xi + shiftGgx), roughness, N);
        vec3 L = 2.0 * dot(V, H) * H - V;
        float NoL = clamp(dot(N, L), 0.0, 1.0);
        float NoH = clamp(dot(N, H), 0.0, 1.0);
        float VoH = clamp(dot(V, H), 0.0, 1.0);
        if (NoL > 0.0 && NoH > 0.0 && VoH > 0.0) {
            float G = gSmithSchlickIbl(roughness, NoV, NoL);
            float Fc = fresnelWeightSchlick(VoH);
            vec3 F = (1.0 - Fc) * specularColor + Fc;
            float w = 1.0;
            if (useEnvironment) w = powerHeuristic(pdfGgxReflection(NoH, VoH, roughness), environmentDirectionPdf(L));
            sum += w * sampleEnvironmentLod(L, 0.0) * F * (G * VoH / (NoH * NoV));
        }
        if (!useEnvironment) continue;
        // Environment technique.
        float pdfEnv;
        vec3 Le = sampleEnvironmentDirection(fract(Xi + shiftEnv), pdfEnv);
        float NoLe = dot(N, Le);
        if (pdfEnv > 0.0 && NoLe > 0.0) {
            vec3 He = normalize(V + Le);
            float NoHe = clamp(dot(N, He), 0.0, 1.0);
            float VoHe = clamp(dot(V, He), 1e-6, 1.0);
            float D = dGgx(NoHe, roughness);
            float G = gSmithSchlickIbl(roughness, NoV, min(NoLe, 1.0));
            float Fc = fresnelWeightSchlick(VoHe);
            vec3 F = (1.0 - Fc) * specularColor + Fc;
            float w = powerHeuristic(pdfEnv, D * NoHe / (4.0 * VoHe));
            // f NoL = D G F / (4 NoV)
            sum += w * sampleEnvironmentLod(Le, 0.0) * F * (D * G / (4.0 * NoV * pdfEnv));
        }
    }
    return sum / float(numSamples);
}

#endif  // GBL_IBL_HAS_ENVIRONMENT_SAMPLING

#endif  // GBL_IBL_GLSL
