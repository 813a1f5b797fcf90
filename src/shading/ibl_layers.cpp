// C++ mirror of shaders/ibl_layers.glsl. Keep line for line in step with the shader.
//   [Walter07] Walter et al., EGSR 2007 (GGX sampling, stretched slopes for the anisotropic lobe).
//   [Veach97]  Veach, PhD thesis 1997, ch. 9 (MIS, power heuristic).
//   [PBRT3]    Pharr et al., 3rd ed., 13.6.3 (cosine-weighted hemisphere).
#include "ibl_layers.h"

#include <algorithm>
#include <cmath>

#include "brdf.h"
#include "environment_sampling.h"

namespace gbl::shading {

namespace {
glm::vec2 fractGlslLayers(glm::vec2 x) { return x - glm::floor(x); }
glm::vec3 reflectAbout(glm::vec3 V, glm::vec3 H) { return 2.0f * glm::dot(V, H) * H - V; }
}  // namespace

glm::vec3 importanceSampleGGXAnisotropic(glm::vec2 Xi, float at, float ab, glm::vec3 N, glm::vec3 T, glm::vec3 B) {
    float phi = 2.0f * kPi * Xi.x;
    float s = std::sqrt(Xi.y / std::max(1.0f - Xi.y, 1e-7f));
    glm::vec3 H = T * (at * s * std::cos(phi)) + B * (ab * s * std::sin(phi)) + N;
    return glm::normalize(H);
}

glm::vec3 sampleCosineHemisphere(glm::vec2 Xi, glm::vec3 N) {
    float r = std::sqrt(Xi.y);
    float phi = 2.0f * kPi * Xi.x;
    glm::vec3 up = std::abs(N.z) < 0.999f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    glm::vec3 tangentX = glm::normalize(glm::cross(up, N));
    glm::vec3 tangentY = glm::cross(N, tangentX);
    return tangentX * (r * std::cos(phi)) + tangentY * (r * std::sin(phi)) + N * std::sqrt(std::max(1.0f - Xi.y, 0.0f));
}

glm::vec3 prefilteredRadianceInShaderAnisotropic(const EnvironmentLodFn& sampleEnvironmentLod, glm::vec3 N,
                                                 glm::vec3 V, glm::vec3 T, glm::vec3 B, float at, float ab,
                                                 uint32_t numSamples) {
    glm::vec3 sum(0.0f);
    float weight = 0.0f;
    for (uint32_t i = 0; i < numSamples; i++) {
        glm::vec3 H = importanceSampleGGXAnisotropic(hammersley(i, numSamples), at, ab, N, T, B);
        glm::vec3 L = reflectAbout(V, H);
        float NoL = saturate(glm::dot(N, L));
        if (NoL > 0.0f) {
            sum += sampleEnvironmentLod(L, 0.0f) * NoL;
            weight += NoL;
        }
    }
    return weight > 0.0f ? sum / weight : glm::vec3(0.0f);
}

glm::vec3 sheenRadianceInShader(const EnvironmentLodFn& sampleEnvironmentLod, glm::vec3 N, glm::vec3 V,
                                float sheenRoughness, uint32_t numSamples) {
    float NoV = saturate(glm::dot(N, V));
    glm::vec3 sum(0.0f);
    float weight = 0.0f;
    for (uint32_t i = 0; i < numSamples; i++) {
        glm::vec3 L = sampleCosineHemisphere(hammersley(i, numSamples), N);
        float NoL = saturate(glm::dot(N, L));
        if (NoL > 0.0f) {
            glm::vec3 H = glm::normalize(V + L);
            float w = sheenBrdf(saturate(glm::dot(N, H)), NoV, NoL, sheenRoughness);
            sum += sampleEnvironmentLod(L, 0.0f) * w;
            weight += w;
        }
    }
    return weight > 0.0f ? sum / weight : glm::vec3(0.0f);
}

glm::vec3 iblGroundTruthLayeredMis(const EnvironmentLodFn& sampleEnvironmentLod,
                                   const std::vector<float>& environmentSampling, const SheenAlbedoFn& sheenAlbedo,
                                   glm::vec3 diffuseColor, glm::vec3 specularColor, float roughness, glm::vec3 N,
                                   glm::vec3 V, const Layers& ly, uint32_t numSamples, glm::vec4 shiftsBaseEnv,
                                   glm::vec4 shiftsCoatSheen) {
    const glm::vec2 shiftBase(shiftsBaseEnv.x, shiftsBaseEnv.y), shiftEnv(shiftsBaseEnv.z, shiftsBaseEnv.w);
    const glm::vec2 shiftCoat(shiftsCoatSheen.x, shiftsCoatSheen.y), shiftSheen(shiftsCoatSheen.z, shiftsCoatSheen.w);
    glm::vec3 sum(0.0f);
    float NoV = std::max(saturate(glm::dot(N, V)), kMinIblNoV);
    bool coat = ly.coat > 0.0f;
    bool aniso = ly.anisotropy > 0.0f;
    float sheenMax = max3(ly.sheenColor);
    bool sheen = sheenMax > 0.0f;
    glm::vec3 Nc = ly.coatNormal;
    float NcoV = std::max(coatNoV(Nc, V), kMinIblNoV);
    float fc = coat ? ly.coat * coatFresnel(NcoV) : 0.0f;
    float under = 1.0f - fc;
    float sheenV = sheen ? sheenAlbedo(NoV, ly.sheenRoughness) : 0.0f;
    float ab = roughness * roughness;
    float at = aniso ? anisotropicAlphaT(roughness, ly.anisotropy) : ab;
    bool baseEnv = roughness >= kMinMisRoughness;
    bool coatEnv = coat && ly.coatRoughness >= kMinMisRoughness;
    for (uint32_t i = 0; i < numSamples; i++) {
        glm::vec2 Xi = hammersley(i, numSamples);
        glm::vec3 H = aniso ? importanceSampleGGXAnisotropic(fractGlslLayers(Xi + shiftBase), at, ab, N, ly.anisotropyT,
                                                             ly.anisotropyB)
                            : importanceSampleGGX(fractGlslLayers(Xi + shiftBase), roughness, N);
        glm::vec3 L = reflectAbout(V, H);
        float NoL = saturate(glm::dot(N, L));
        float NoH = saturate(glm::dot(N, H));
        float VoH = saturate(glm::dot(V, H));
        if (NoL > 0.0f && NoH > 0.0f && VoH > 0.0f) {
            float Fw = fresnelWeightSchlick(VoH);
            glm::vec3 F = (1.0f - Fw) * specularColor + Fw;
            float scale =
                under * (sheen ? sheenAlbedoScaling(ly.sheenColor, sheenV, sheenAlbedo(NoL, ly.sheenRoughness)) : 1.0f);
            float value;
            float pdf;
            if (aniso) {
                float Vis = visGgxAnisotropic(NoL, NoV, glm::dot(ly.anisotropyB, V), glm::dot(ly.anisotropyT, V),
                                              glm::dot(ly.anisotropyT, L), glm::dot(ly.anisotropyB, L), at, ab);
                value = 4.0f * Vis * NoL * VoH / NoH;
                pdf = baseEnv ? dGgxAnisotropic(NoH, glm::dot(ly.anisotropyT, H), glm::dot(ly.anisotropyB, H), at, ab) *
                                    NoH / (4.0f * VoH)
                              : 0.0f;
            } else {
                value = gSmithSchlickIbl(roughness, NoV, NoL) * VoH / (NoH * NoV);
                pdf = baseEnv ? pdfGgxReflection(NoH, VoH, roughness) : 0.0f;
            }
            float w = baseEnv ? powerHeuristic(pdf, environmentDirectionPdf(environmentSampling, L)) : 1.0f;
            sum += (w * scale * value) * sampleEnvironmentLod(L, 0.0f) * F;
        }
        if (coat) {
            glm::vec3 Hc = importanceSampleGGX(fractGlslLayers(Xi + shiftCoat), ly.coatRoughness, Nc);
            glm::vec3 Lc = reflectAbout(V, Hc);
            float NcoL = saturate(glm::dot(Nc, Lc));
            float NcoH = saturate(glm::dot(Nc, Hc));
            float VoHc = saturate(glm::dot(V, Hc));
            if (NcoL > 0.0f && NcoH > 0.0f && VoHc > 0.0f) {
                float value = 4.0f * visSmithGgxCorrelated(NcoV, NcoL, ly.coatRoughness) * NcoL * VoHc / NcoH;
                float w = coatEnv ? powerHeuristic(pdfGgxReflection(NcoH, VoHc, ly.coatRoughness),
                                                   environmentDirectionPdf(environmentSampling, Lc))
                                  : 1.0f;
                sum += (w * fc * value) * sampleEnvironmentLod(Lc, 0.0f);
            }
        }
        if (sheen) {
            glm::vec3 Ls = sampleCosineHemisphere(fractGlslLayers(Xi + shiftSheen), N);
            float NoLs = saturate(glm::dot(N, Ls));
            if (NoLs > 0.0f) {
                glm::vec3 Hs = glm::normalize(V + Ls);
                float pdf = NoLs / kPi;
                glm::vec3 value =
                    ly.sheenColor * (sheenBrdf(saturate(glm::dot(N, Hs)), NoV, NoLs, ly.sheenRoughness) * kPi) -
                    diffuseColor * std::max(sheenMax * sheenV, sheenMax * sheenAlbedo(NoLs, ly.sheenRoughness));
                float w = powerHeuristic(pdf, environmentDirectionPdf(environmentSampling, Ls));
                sum += (w * under) * value * sampleEnvironmentLod(Ls, 0.0f);
            }
        }
        if (!(baseEnv || coatEnv || sheen)) continue;
        float pdfEnv;
        glm::vec3 Le = sampleEnvironmentDirection(environmentSampling, fractGlslLayers(Xi + shiftEnv), pdfEnv);
        if (!(pdfEnv > 0.0f)) continue;
        glm::vec3 radiance = sampleEnvironmentLod(Le, 0.0f) / pdfEnv;
        glm::vec3 He = glm::normalize(V + Le);
        float VoHe = std::clamp(glm::dot(V, He), 1e-6f, 1.0f);
        float NoLe = glm::dot(N, Le);
        if (NoLe > 0.0f) {
            NoLe = std::min(NoLe, 1.0f);
            float NoHe = saturate(glm::dot(N, He));
            if (baseEnv) {
                float Fw = fresnelWeightSchlick(VoHe);
                glm::vec3 F = (1.0f - Fw) * specularColor + Fw;
                float scale = under * (sheen ? sheenAlbedoScaling(ly.sheenColor, sheenV,
                                                                  sheenAlbedo(NoLe, ly.sheenRoughness))
                                             : 1.0f);
                float fNoL;
                float pdf;
                if (aniso) {
                    float D = dGgxAnisotropic(NoHe, glm::dot(ly.anisotropyT, He), glm::dot(ly.anisotropyB, He), at, ab);
                    fNoL = D *
                           visGgxAnisotropic(NoLe, NoV, glm::dot(ly.anisotropyB, V), glm::dot(ly.anisotropyT, V),
                                             glm::dot(ly.anisotropyT, Le), glm::dot(ly.anisotropyB, Le), at, ab) *
                           NoLe;
                    pdf = D * NoHe / (4.0f * VoHe);
                } else {
                    float D = dGgx(NoHe, roughness);
                    fNoL = D * gSmithSchlickIbl(roughness, NoV, NoLe) / (4.0f * NoV);
                    pdf = D * NoHe / (4.0f * VoHe);
                }
                sum += (powerHeuristic(pdfEnv, pdf) * scale * fNoL) * radiance * F;
            }
            if (sheen) {
                glm::vec3 value =
                    ly.sheenColor * (sheenBrdf(NoHe, NoV, NoLe, ly.sheenRoughness) * NoLe) -
                    diffuseColor * ((1.0f / kPi) * NoLe *
                                    std::max(sheenMax * sheenV, sheenMax * sheenAlbedo(NoLe, ly.sheenRoughness)));
                sum += (powerHeuristic(pdfEnv, NoLe / kPi) * under) * value * radiance;
            }
        }
        float NcoLe = glm::dot(Nc, Le);
        if (coatEnv && NcoLe > 0.0f) {
            NcoLe = std::min(NcoLe, 1.0f);
            float NcoHe = saturate(glm::dot(Nc, He));
            float D = dGgx(NcoHe, ly.coatRoughness);
            float fNoL = D * visSmithGgxCorrelated(NcoV, NcoLe, ly.coatRoughness) * NcoLe;
            sum += (powerHeuristic(pdfEnv, D * NcoHe / (4.0f * VoHe)) * fc * fNoL) * radiance;
        }
    }
    return sum / float(numSamples);
}

}  // namespace gbl::shading
