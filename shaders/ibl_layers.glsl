// ibl_layers.glsl -- image-based light on the layers of brdf_layers.glsl: the sampling and the
// integrals each IBL mode needs for clear coat, sheen and anisotropy (image_based_light.glsl puts
// them together per mode). Include file (GLSL 450, no #version); include brdf.glsl,
// brdf_layers.glsl and ibl_math.glsl first. The C++ mirror is src/shading/ibl_layers.h /
// ibl_layers.cpp (same names, same math); tests/shading/ibl_layers_test.cpp holds the ground truth
// to an independent quadrature of the layered BRDF and the GLSL to the C++.
//
// Sources:
//   [Walter07]  B. Walter et al., "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007
//               (GGX sampling; the slope form of the anisotropic case: the isotropic sample's slopes
//               stretched by alpha_t, alpha_b, pdf D(H) NoH).
//   [Veach97]   E. Veach, PhD thesis, Stanford 1997, ch. 9 (multiple importance sampling, power heuristic).
//   [PBRT3]     Pharr, Jakob, Humphreys, "Physically Based Rendering", 3rd ed., sec. 13.6.3 (cosine-weighted
//               hemisphere sampling by Malley's method).
//   The layers' BRDFs and their layering: brdf_layers.glsl ([Coat], [Sheen], [Aniso]).
//
// Needs, besides ibl_math.glsl's hooks: with GBL_IBL_HAS_SHEEN_ALBEDO the includer's
//     float sheenAlbedo(float NoX, float sheenRoughness)   // E of the sheen BRDF (sheen_albedo.h's table)
// for the ground truth's sheen.
#ifndef GBL_IBL_LAYERS_GLSL
#define GBL_IBL_LAYERS_GLSL

#ifndef GBL_BRDF_LAYERS_GLSL
#error "ibl_layers.glsl needs brdf_layers.glsl: include it first"
#endif
#ifndef GBL_IBL_GLSL
#error "ibl_layers.glsl needs ibl_math.glsl: include it first"
#endif

// Anisotropic GGX half vector around N [Walter07]: the isotropic sample's slope
// sqrt(u / (1 - u)) (cos phi, sin phi) stretched by (alpha_t, alpha_b) along (T, B), so that
// pdf(H) = D_aniso(H) NoH. With alpha_t = alpha_b = alpha it is importanceSampleGGX's lobe.
vec3 importanceSampleGGXAnisotropic(vec2 Xi, float at, float ab, vec3 N, vec3 T, vec3 B) {
    float phi = 2.0 * kPi * Xi.x;
    float s = sqrt(Xi.y / max(1.0 - Xi.y, 1e-7));
    vec3 H = T * (at * s * cos(phi)) + B * (ab * s * sin(phi)) + N;
    return normalize(H);
}

// Cosine-weighted direction around N [PBRT3 13.6.3], tangent frame as importanceSampleGGX's;
// pdf NoL / pi.
vec3 sampleCosineHemisphere(vec2 Xi, vec3 N) {
    float r = sqrt(Xi.y);
    float phi = 2.0 * kPi * Xi.x;
    vec3 up = abs(N.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 tangentX = normalize(cross(up, N));
    vec3 tangentY = cross(N, tangentX);
    return tangentX * (r * cos(phi)) + tangentY * (r * sin(phi)) + N * sqrt(max(1.0 - Xi.y, 0.0));
}

#ifdef GBL_IBL_HAS_ENVIRONMENT

// The first split sum of an anisotropic lobe, per pixel (split-sum-shader): radiance of L =
// reflect(-V, H), H ~ the anisotropic GGX lobe, weighted by NoL.
vec3 prefilteredRadianceInShaderAnisotropic(vec3 N, vec3 V, vec3 T, vec3 B, float at, float ab, uint numSamples) {
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < numSamples; i++) {
        vec3 H = importanceSampleGGXAnisotropic(hammersley(i, numSamples), at, ab, N, T, B);
        vec3 L = 2.0 * dot(V, H) * H - V;
        float NoL = clamp(dot(N, L), 0.0, 1.0);
        if (NoL > 0.0) {
            sum += sampleEnvironmentLod(L, 0.0) * NoL;
            weight += NoL;
        }
    }
    return weight > 0.0 ? sum / weight : vec3(0.0);
}

// The sheen's first split sum per pixel: radiance weighted by the sheen lobe, sum L_i w / sum w,
// w = sheenBrdf NoL / pdf = pi sheenBrdf over cosine-weighted directions. Times sheenColor E(NoV)
// (the second sum, E from the table) it is the Monte Carlo estimate of the sheen's reflection.
vec3 sheenRadianceInShader(vec3 N, vec3 V, float sheenRoughness, uint numSamples) {
    float NoV = clamp(dot(N, V), 0.0, 1.0);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < numSamples; i++) {
        vec3 L = sampleCosineHemisphere(hammersley(i, numSamples), N);
        float NoL = clamp(dot(N, L), 0.0, 1.0);
        if (NoL > 0.0) {
            vec3 H = normalize(V + L);
            float w = sheenBrdf(clamp(dot(N, H), 0.0, 1.0), NoV, NoL, sheenRoughness);
            sum += sampleEnvironmentLod(L, 0.0) * w;
            weight += w;
        }
    }
    return weight > 0.0 ? sum / weight : vec3(0.0);
}

#endif  // GBL_IBL_HAS_ENVIRONMENT

#if defined(GBL_IBL_HAS_ENVIRONMENT_SAMPLING) && defined(GBL_IBL_HAS_SHEEN_ALBEDO)

// The converged ground truth of the layered BRDF: the integral over the environment of
// coat(sheen(base)) (brdf_layers.glsl's layering, the base's specular lobe as the ground truth's
// BRDF: exact Schlick F and Smith-Schlick k = alpha/2, or the anisotropic lobe of [Aniso]),
// without the base's diffuse irradiance, which the caller takes from SH9 as every mode does and
// scales by (1 - coat fc): what this returns includes the part of the diffuse the sheen's albedo
// scaling removes, -(1 - coat fc) integral of L_i c_diff / pi NoL max(m E(NoV), m E(NoL)), so that
// the diffuse too is scaled per direction as the direct light scales it.
// Each lobe is its own two-technique MIS estimator [Veach97] (power heuristic) over one sample of
// its BRDF and one environment sample per step, the environment sample shared by the lobes:
//   base specular x (1 - coat fc) x sheen scaling(L):  GGX (or anisotropic GGX) | environment
//   coat  coat fc D V NcoL:                              GGX around Nc (coat roughness) | environment
//   sheen (1 - coat fc) (c sheenBrdf NoL - diffuse correction): cosine | environment
// A lobe whose roughness is below kMinMisRoughness uses its BRDF samples alone (as
// specularIBLGroundTruthMis). Unbiased: each lobe's techniques cover its support.
// shifts: (base, environment) and (coat, sheen) Cranley-Patterson rotations of the Hammersley set.
vec3 iblGroundTruthLayeredMis(vec3 diffuseColor, vec3 specularColor, float roughness, vec3 N, vec3 V, Layers ly,
                              uint numSamples, vec4 shiftsBaseEnv, vec4 shiftsCoatSheen) {
    vec3 sum = vec3(0.0);
    float NoV = max(clamp(dot(N, V), 0.0, 1.0), kMinIblNoV);
    bool coat = ly.coat > 0.0;
    bool aniso = ly.anisotropy > 0.0;
    float sheenMax = max3(ly.sheenColor);
    bool sheen = sheenMax > 0.0;
    vec3 Nc = ly.coatNormal;
    float NcoV = max(coatNoV(Nc, V), kMinIblNoV);
    float fc = coat ? ly.coat * coatFresnel(NcoV) : 0.0;
    float under = 1.0 - fc;  // what the coat lets through to the layers below
    float sheenV = sheen ? sheenAlbedo(NoV, ly.sheenRoughness) : 0.0;
    float ab = roughness * roughness;
    float at = aniso ? anisotropicAlphaT(roughness, ly.anisotropy) : ab;
    bool baseEnv = roughness >= kMinMisRoughness;
    bool coatEnv = coat && ly.coatRoughness >= kMinMisRoughness;
    for (uint i = 0u; i < numSamples; i++) {
        vec2 Xi = hammersley(i, numSamples);
        // Base specular, BRDF technique.
        vec3 H = aniso ? importanceSampleGGXAnisotropic(fract(Xi + shiftsBaseEnv.xy), at, ab, N, ly.anisotropyT,
                                                        ly.anisotropyB)
                       : importanceSampleGGX(fract(Xi + shiftsBaseEnv.xy), roughness, N);
        vec3 L = 2.0 * dot(V, H) * H - V;
        float NoL = clamp(dot(N, L), 0.0, 1.0);
        float NoH = clamp(dot(N, H), 0.0, 1.0);
        float VoH = clamp(dot(V, H), 0.0, 1.0);
        if (NoL > 0.0 && NoH > 0.0 && VoH > 0.0) {
            float Fw = fresnelWeightSchlick(VoH);
            vec3 F = (1.0 - Fw) * specularColor + Fw;
            float scale = under * (sheen ? sheenAlbedoScaling(ly.sheenColor, sheenV, sheenAlbedo(NoL, ly.sheenRoughness)) : 1.0);
            float value;  // f NoL / pdf without F
            float pdf;
            if (aniso) {
                float Vis = visGgxAnisotropic(NoL, NoV, dot(ly.anisotropyB, V), dot(ly.anisotropyT, V),
                                              dot(ly.anisotropyT, L), dot(ly.anisotropyB, L), at, ab);
                value = 4.0 * Vis * NoL * VoH / NoH;
                pdf = baseEnv ? dGgxAnisotropic(NoH, dot(ly.anisotropyT, H), dot(ly.anisotropyB, H), at, ab) * NoH /
                                    (4.0 * VoH)
                              : 0.0;
            } else {
                value = gSmithSchlickIbl(roughness, NoV, NoL) * VoH / (NoH * NoV);
                pdf = baseEnv ? pdfGgxReflection(NoH, VoH, roughness) : 0.0;
            }
            float w = baseEnv ? powerHeuristic(pdf, environmentDirectionPdf(L)) : 1.0;
            sum += (w * scale * value) * sampleEnvironmentLod(L, 0.0) * F;
        }
        // Coat, BRDF technique.
        if (coat) {
            vec3 Hc = importanceSampleGGX(fract(Xi + shiftsCoatSheen.xy), ly.coatRoughness, Nc);
            vec3 Lc = 2.0 * dot(V, Hc) * Hc - V;
            float NcoL = clamp(dot(Nc, Lc), 0.0, 1.0);
            float NcoH = clamp(dot(Nc, Hc), 0.0, 1.0);
            float VoHc = clamp(dot(V, Hc), 0.0, 1.0);
            if (NcoL > 0.0 && NcoH > 0.0 && VoHc > 0.0) {
                float value = 4.0 * visSmithGgxCorrelated(NcoV, NcoL, ly.coatRoughness) * NcoL * VoHc / NcoH;
                float w = coatEnv ? powerHeuristic(pdfGgxReflection(NcoH, VoHc, ly.coatRoughness), environmentDirectionPdf(Lc))
                                  : 1.0;
                sum += (w * fc * value) * sampleEnvironmentLod(Lc, 0.0);
            }
        }
        // Sheen and the diffuse's share of its albedo scaling, BRDF technique (cosine).
        if (sheen) {
            vec3 Ls = sampleCosineHemisphere(fract(Xi + shiftsCoatSheen.zw), N);
            float NoLs = clamp(dot(N, Ls), 0.0, 1.0);
            if (NoLs > 0.0) {
                vec3 Hs = normalize(V + Ls);
                float pdf = NoLs / kPi;
                // f / pdf: the sheen's c sheenBrdf NoL and the diffuse correction, over NoL / pi.
                vec3 value = ly.sheenColor * (sheenBrdf(clamp(dot(N, Hs), 0.0, 1.0), NoV, NoLs, ly.sheenRoughness) * kPi) -
                             diffuseColor * max(sheenMax * sheenV, sheenMax * sheenAlbedo(NoLs, ly.sheenRoughness));
                float w = powerHeuristic(pdf, environmentDirectionPdf(Ls));
                sum += (w * under) * value * sampleEnvironmentLod(Ls, 0.0);
            }
        }
        // The environment technique, one sample shared by the lobes.
        if (!(baseEnv || coatEnv || sheen)) continue;
        float pdfEnv;
        vec3 Le = sampleEnvironmentDirection(fract(Xi + shiftsBaseEnv.zw), pdfEnv);
        if (!(pdfEnv > 0.0)) continue;
        vec3 radiance = sampleEnvironmentLod(Le, 0.0) / pdfEnv;
        vec3 He = normalize(V + Le);
        float VoHe = clamp(dot(V, He), 1e-6, 1.0);
        float NoLe = dot(N, Le);
        if (NoLe > 0.0) {
            NoLe = min(NoLe, 1.0);
            float NoHe = clamp(dot(N, He), 0.0, 1.0);
            if (baseEnv) {
                float Fw = fresnelWeightSchlick(VoHe);
                vec3 F = (1.0 - Fw) * specularColor + Fw;
                float scale = under * (sheen ? sheenAlbedoScaling(ly.sheenColor, sheenV, sheenAlbedo(NoLe, ly.sheenRoughness)) : 1.0);
                float fNoL;  // f NoL without F
                float pdf;
                if (aniso) {
                    float D = dGgxAnisotropic(NoHe, dot(ly.anisotropyT, He), dot(ly.anisotropyB, He), at, ab);
                    fNoL = D * visGgxAnisotropic(NoLe, NoV, dot(ly.anisotropyB, V), dot(ly.anisotropyT, V),
                                                 dot(ly.anisotropyT, Le), dot(ly.anisotropyB, Le), at, ab) * NoLe;
                    pdf = D * NoHe / (4.0 * VoHe);
                } else {
                    float D = dGgx(NoHe, roughness);
                    fNoL = D * gSmithSchlickIbl(roughness, NoV, NoLe) / (4.0 * NoV);
                    pdf = D * NoHe / (4.0 * VoHe);
                }
                sum += (powerHeuristic(pdfEnv, pdf) * scale * fNoL) * radiance * F;
            }
            if (sheen) {
                vec3 value = ly.sheenColor * (sheenBrdf(NoHe, NoV, NoLe, ly.sheenRoughness) * NoLe) -
                             diffuseColor * ((1.0 / kPi) * NoLe *
                                             max(sheenMax * sheenV, sheenMax * sheenAlbedo(NoLe, ly.sheenRoughness)));
                sum += (powerHeuristic(pdfEnv, NoLe / kPi) * under) * value * radiance;
            }
        }
        float NcoLe = dot(Nc, Le);
        if (coatEnv && NcoLe > 0.0) {
            NcoLe = min(NcoLe, 1.0);
            float NcoHe = clamp(dot(Nc, He), 0.0, 1.0);
            float D = dGgx(NcoHe, ly.coatRoughness);
            float fNoL = D * visSmithGgxCorrelated(NcoV, NcoLe, ly.coatRoughness) * NcoLe;
            sum += (powerHeuristic(pdfEnv, D * NcoHe / (4.0 * VoHe)) * fc * fNoL) * radiance;
        }
    }
    return sum / float(numSamples);
}

#endif  // GBL_IBL_HAS_ENVIRONMENT_SAMPLING && GBL_IBL_HAS_SHEEN_ALBEDO

#endif  // GBL_IBL_LAYERS_GLSL
