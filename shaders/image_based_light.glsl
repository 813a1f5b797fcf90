// Image-based lighting, included by the lighting pass after sampleEnvironment() and the IBL
// bindings (environmentCube, prefilteredCube, brdfLut, frame) are declared. The single place
// where IBL enters the lighting pass. Specular mode = GBL_IBL_ACTIVE_MODE (IblMode in
// src/shading/ibl_precompute.h); diffuse (SH9 irradiance, Lambert) for every mode when frame.environment.w.
//
// The mode is the define GBL_IBL_MODE where the pipeline is built for one (the renderer's are:
// src/render/lighting_pass.cpp), so the other modes' code (ground truth's MIS loop,
// split-sum-shader's two sample loops, ...) is gone before the driver compiles the shader; that
// compile is most of a first run on llvmpipe, which JIT-compiles every branch (issue 14). Without
// the define the mode is read from frame.environment.z at run time, every mode compiled in.
//
//   0 ground-truth      the integral of [Karis13 SpecularIBL] (environment-cube mip 0, exact Schlick,
//                       Smith-Schlick k = alpha/2), estimated by specularIBLGroundTruthMis: frame.ibl.x
//                       steps per batch, each one GGX and one environment-CDF sample combined by the
//                       power heuristic; the lighting pass runs batches until the noise target is met
//                       (src/render/renderer.cpp), each batch with its own random rotation
//                       (iblBatchKey).
//   1 split-sum-shader  both sums in the shader, per pixel with the real N and V (no n = v = r):
//                       (sum L(l) NoL / sum NoL) * (f0 A + B), A, B = integrateBRDF(roughness, NoV),
//                       frame.ibl.x samples each -- row (b) of the seed's figure.
//   2 split-sum         pre-filtered cube at mipFromRoughness + LUT, UE4's shipping
//                       EnvBRDF (f0 A + saturate(50 f0.g) B, the 2% rule) -- row (c).
//   3 envbrdf-approx    pre-filtered cube * UE4 mobile EnvBRDFApprox. Rules: roughness >= 0.999
//                       takes the fully-rough shortcut (diffuse += 0.45 f0, no specular);
//                       otherwise an F0 that is grey and within 0.002 of 0.04 in every channel
//                       (UE4's default dielectric, the only F0 EnvBRDFApproxNonmetal is a fit for)
//                       uses EnvBRDFApproxNonmetal; everything else the general EnvBRDFApprox.
//                       The rule reads F0 only, so it works for layouts that do not store metallic.
//   4 bo2               pre-filtered cube * Black Ops 2 EnvironmentBRDF(g, NoV, f0), g from ibl_math.glsl's
//                       bo2GlossFromRoughness (log2(2/alpha^2 - 2)/13, the Blinn-Phong power match).
#ifndef GBL_IMAGE_BASED_LIGHT_GLSL
#define GBL_IMAGE_BASED_LIGHT_GLSL

#define GBL_IBL_GROUND_TRUTH 0
#define GBL_IBL_SPLIT_SUM_SHADER 1
#define GBL_IBL_SPLIT_SUM 2
#define GBL_IBL_ENVBRDF_APPROX 3
#define GBL_IBL_BO2 4

#ifdef GBL_IBL_MODE
#define GBL_IBL_ACTIVE_MODE GBL_IBL_MODE
#else
#define GBL_IBL_ACTIVE_MODE int(frame.environment.z)
#endif

vec3 sampleEnvironmentLod(vec3 dir, float lod) {
    return textureLod(environmentCube, dir, lod).rgb * frame.environment.x;
}
#define GBL_IBL_HAS_ENVIRONMENT
#include "environment_sampling.glsl"
#define GBL_IBL_HAS_ENVIRONMENT_SAMPLING
#include "ibl_math.glsl"

// The ground truth's random rotation for this pixel and batch (set by the lighting pass's main).
uvec3 iblBatchKey = uvec3(0u);

// E(n) from the SH9 coefficients (cosine convolution folded in), clamped at 0 against ringing.
vec3 irradianceFromSh(vec3 n) {
    vec3 e = frame.irradianceSh[0].rgb * 0.282095;
    e += frame.irradianceSh[1].rgb * (0.488603 * n.y);
    e += frame.irradianceSh[2].rgb * (0.488603 * n.z);
    e += frame.irradianceSh[3].rgb * (0.488603 * n.x);
    e += frame.irradianceSh[4].rgb * (1.092548 * n.x * n.y);
    e += frame.irradianceSh[5].rgb * (1.092548 * n.y * n.z);
    e += frame.irradianceSh[6].rgb * (0.315392 * (3.0 * n.z * n.z - 1.0));
    e += frame.irradianceSh[7].rgb * (1.092548 * n.x * n.z);
    e += frame.irradianceSh[8].rgb * (0.546274 * (n.x * n.x - n.y * n.y));
    return max(e, vec3(0.0)) * frame.environment.x;
}

vec3 prefilteredRadiance(vec3 R, float roughness) {
    float lod = mipFromRoughness(roughness, frame.environment.y);
    return textureLod(prefilteredCube, R, lod).rgb * frame.environment.x;
}

// The first split sum evaluated per pixel: GGX-importance-sampled radiance around the real N
// and V, weighted by NoL (PrefilterEnvMap without n = v = r).
vec3 prefilteredRadianceInShader(vec3 N, vec3 V, float roughness, uint numSamples) {
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < numSamples; i++) {
        vec3 H = importanceSampleGGX(hammersley(i, numSamples), roughness, N);
        vec3 L = 2.0 * dot(V, H) * H - V;
        float NoL = clamp(dot(N, L), 0.0, 1.0);
        if (NoL > 0.0) {
            sum += sampleEnvironmentLod(L, 0.0) * NoL;
            weight += NoL;
        }
    }
    return weight > 0.0 ? sum / weight : vec3(0.0);
}

vec3 evaluateImageBasedLight(Surface s, vec3 N, vec3 V) {
    const int mode = GBL_IBL_ACTIVE_MODE;
    uint samples = uint(frame.ibl.x);
    float roughness = clamp(s.roughness, 0.0, 1.0);
    float NoV = max(clamp(dot(N, V), 0.0, 1.0), kMinIblNoV);
    vec3 R = reflect(-V, N);
    vec3 diffuseColor = s.diffuseColor;
    vec3 specularColor = s.specularColor;
    vec3 specular = vec3(0.0);
    if (mode == GBL_IBL_GROUND_TRUTH) {
        specular = specularIBLGroundTruthMis(specularColor, roughness, N, V, samples,
                                             randomShift(iblBatchKey.x, iblBatchKey.y, iblBatchKey.z * 2u),
                                             randomShift(iblBatchKey.x, iblBatchKey.y, iblBatchKey.z * 2u + 1u));
    } else if (mode == GBL_IBL_SPLIT_SUM_SHADER) {
        vec2 AB = integrateBRDF(roughness, NoV, samples);
        specular = prefilteredRadianceInShader(N, V, roughness, samples) * (specularColor * AB.x + AB.y);
    } else if (mode == GBL_IBL_SPLIT_SUM) {
        vec2 AB = texture(brdfLut, vec2(NoV, roughness)).rg;
        specular = prefilteredRadiance(R, roughness) * envBRDF(specularColor, AB);
    } else if (mode == GBL_IBL_ENVBRDF_APPROX) {
        if (roughness >= 0.999) {
            envBRDFApproxFullyRough(diffuseColor, specularColor);
        } else {
            bool nonmetal = all(lessThanEqual(abs(specularColor - vec3(0.04)), vec3(0.002)));
            vec3 brdf = nonmetal ? vec3(envBRDFApproxNonmetal(roughness, NoV))
                                 : envBRDFApprox(specularColor, roughness, NoV);
            specular = prefilteredRadiance(R, roughness) * brdf;
        }
    } else {
        specular = prefilteredRadiance(R, roughness) * environmentBRDF(bo2GlossFromRoughness(roughness), NoV, specularColor);
    }
    vec3 diffuse = frame.environment.w > 0.5 ? diffuseColor * (1.0 / kPi) * irradianceFromSh(N) : vec3(0.0);
    return diffuse + specular;
}

#if GBL_LAYERS != 0
// ---- the layers (brdf_layers.glsl, ibl_layers.glsl): compiled only for a scene that has them ----
// The lighting pass defines sheenAlbedo(NoX, sheenRoughness) from its table (binding 12).
#define GBL_IBL_HAS_SHEEN_ALBEDO
#include "ibl_layers.glsl"

// The coat's reflection of the environment, per mode, as the specification layers it: the coat's
// lobe without Fresnel (F = 1: f0 A + B with f0 = 1, the fits at f0 = 1) times its layering weight
// clearcoat * fc(NcoV) [Coat], the Fresnel with n.v outside the integral as the specification writes
// it (the ground truth integrates the same). The lobe's own first sum as the base's (pre-filtered
// cube at the coat roughness around Rc = reflect(-V, Nc), or per pixel); its second from the base's
// tables and fits (Smith-Schlick k = alpha/2, where the direct coat has the height-correlated Smith).
vec3 coatImageBasedLight(int mode, Layers ly, vec3 V, float weight, uint samples) {
    vec3 Nc = ly.coatNormal;
    float r = clamp(ly.coatRoughness, 0.0, 1.0);
    float NcoV = max(coatNoV(Nc, V), kMinIblNoV);
    vec3 Rc = reflect(-V, Nc);
    vec3 lobe;
    if (mode == GBL_IBL_SPLIT_SUM_SHADER) {
        vec2 AB = integrateBRDF(r, NcoV, samples);
        lobe = prefilteredRadianceInShader(Nc, V, r, samples) * (AB.x + AB.y);
    } else if (mode == GBL_IBL_SPLIT_SUM) {
        vec2 AB = texture(brdfLut, vec2(NcoV, r)).rg;
        lobe = prefilteredRadiance(Rc, r) * (AB.x + AB.y);
    } else if (mode == GBL_IBL_ENVBRDF_APPROX) {
        lobe = prefilteredRadiance(Rc, r) * envBRDFApprox(vec3(1.0), r, NcoV);
    } else {
        lobe = prefilteredRadiance(Rc, r) * environmentBRDF(bo2GlossFromRoughness(r), NcoV, vec3(1.0));
    }
    return weight * lobe;
}

// evaluateImageBasedLight over the layers of `ly` (coat(sheen(base)), brdf_layers.glsl), every mode:
//   ground-truth      iblGroundTruthLayeredMis: the layered BRDF integrated (base specular, coat,
//                     sheen, and the sheen's per-direction scaling of the diffuse), plus the SH9
//                     diffuse under the coat's weight.
//   split-sum-shader  the base's first sum per pixel (an anisotropic lobe sampled as such), the
//                     sheen's per pixel over its own lobe (sheenRadianceInShader) times c E(NoV), the
//                     coat's as the base's.
//   split-sum, envbrdf-approx, bo2: one pre-filtered look-up per lobe: the base's along the
//                     anisotropic bent normal's reflection where anisotropic [Aniso], the sheen's
//                     along R at the sheen roughness times c E(NoV) (Filament's sheen IBL), the coat's
//                     along Rc; each mode's own environment BRDF for base and coat.
// Under the sheen the base (diffuse and specular) is scaled by 1 - max3(c) E(NoV), the
// specification's single-look-up form for indirect light [Sheen]; under the coat everything by
// 1 - clearcoat fc(NcoV) [Coat]. Without layers: evaluateImageBasedLight.
vec3 evaluateImageBasedLightLayered(Surface s, vec3 N, vec3 V, Layers ly) {
    const int mode = GBL_IBL_ACTIVE_MODE;
    uint samples = uint(frame.ibl.x);
    float roughness = clamp(s.roughness, 0.0, 1.0);
    float NoV = max(clamp(dot(N, V), 0.0, 1.0), kMinIblNoV);
    bool aniso = ly.anisotropy > 0.0;
    vec3 diffuseColor = s.diffuseColor;
    vec3 specularColor = s.specularColor;
    bool diffuseOn = frame.environment.w > 0.5;
    float sheenMax = max3(ly.sheenColor);
    float sheenV = sheenMax > 0.0 ? sheenAlbedo(NoV, ly.sheenRoughness) : 0.0;
    float fc = ly.coat > 0.0 ? ly.coat * coatFresnel(max(coatNoV(ly.coatNormal, V), kMinIblNoV)) : 0.0;
    if (mode == GBL_IBL_GROUND_TRUTH) {
        uint k2 = iblBatchKey.z * 2u;
        uint xl = iblBatchKey.x ^ 0x5bd1e995u;  // the coat's and sheen's streams, apart from the base's
        vec3 layered = iblGroundTruthLayeredMis(
            diffuseOn ? diffuseColor : vec3(0.0), specularColor, roughness, N, V, ly, samples,
            vec4(randomShift(iblBatchKey.x, iblBatchKey.y, k2), randomShift(iblBatchKey.x, iblBatchKey.y, k2 + 1u)),
            vec4(randomShift(xl, iblBatchKey.y, k2), randomShift(xl, iblBatchKey.y, k2 + 1u)));
        vec3 diffuse = diffuseOn ? diffuseColor * (1.0 / kPi) * irradianceFromSh(N) : vec3(0.0);
        return diffuse * (1.0 - fc) + layered;
    }
    vec3 R = aniso ? anisotropicReflection(N, V, ly.anisotropyB, ly.anisotropy, roughness) : reflect(-V, N);
    vec3 specular = vec3(0.0);
    vec3 sheen = vec3(0.0);
    if (mode == GBL_IBL_SPLIT_SUM_SHADER) {
        vec2 AB = integrateBRDF(roughness, NoV, samples);
        vec3 radiance = aniso ? prefilteredRadianceInShaderAnisotropic(N, V, ly.anisotropyT, ly.anisotropyB,
                                                                       anisotropicAlphaT(roughness, ly.anisotropy),
                                                                       roughness * roughness, samples)
                              : prefilteredRadianceInShader(N, V, roughness, samples);
        specular = radiance * (specularColor * AB.x + AB.y);
        if (sheenMax > 0.0) sheen = ly.sheenColor * sheenV * sheenRadianceInShader(N, V, ly.sheenRoughness, samples);
    } else {
        if (mode == GBL_IBL_SPLIT_SUM) {
            vec2 AB = texture(brdfLut, vec2(NoV, roughness)).rg;
            specular = prefilteredRadiance(R, roughness) * envBRDF(specularColor, AB);
        } else if (mode == GBL_IBL_ENVBRDF_APPROX) {
            if (roughness >= 0.999) {
                envBRDFApproxFullyRough(diffuseColor, specularColor);
            } else {
                bool nonmetal = all(lessThanEqual(abs(specularColor - vec3(0.04)), vec3(0.002)));
                vec3 brdf = nonmetal ? vec3(envBRDFApproxNonmetal(roughness, NoV))
                                     : envBRDFApprox(specularColor, roughness, NoV);
                specular = prefilteredRadiance(R, roughness) * brdf;
            }
        } else {
            specular = prefilteredRadiance(R, roughness) * environmentBRDF(bo2GlossFromRoughness(roughness), NoV, specularColor);
        }
        if (sheenMax > 0.0)
            sheen = ly.sheenColor * sheenV * prefilteredRadiance(reflect(-V, N), clamp(ly.sheenRoughness, 0.0, 1.0));
    }
    vec3 diffuse = diffuseOn ? diffuseColor * (1.0 / kPi) * irradianceFromSh(N) : vec3(0.0);
    vec3 color = diffuse + specular;
    if (sheenMax > 0.0) color = sheen + color * (1.0 - sheenMax * sheenV);
    if (ly.coat > 0.0) color = color * (1.0 - fc) + coatImageBasedLight(mode, ly, V, fc, samples);
    return color;
}
#endif  // GBL_LAYERS != 0

#endif
