// glTF 2.0 metallic-roughness material (+ KHR_materials_specular) -> Surface: the one material
// evaluation, shared by the G-buffer pass (material.glsl: the rasteriser's implicit derivatives)
// and the visibility buffer's resolve (visibility_resolve.glsl: analytic derivatives, textureGrad).
// The includer defines GBL_SAMPLE_TEXTURE_SLOT(slot, index, uv), texture `index`'s value at uv
// (index is never GBL_NO_TEXTURE), before including this file. `slot` names the material's
// texture slot (BASE_COLOR, METALLIC_ROUGHNESS, NORMAL, OCCLUSION, EMISSIVE, SPECULAR,
// SPECULAR_COLOR: src/render/gpu_scene.h), so a resolve may test only that slot's textures.
#ifndef GBL_MATERIAL_EVAL_GLSL
#define GBL_MATERIAL_EVAL_GLSL

// A macro, not a function: `slot` is a name the includer's macro may paste. Only the chosen
// operand of ?: is evaluated, as in the function this was.
#define sampleMaterialTexture(slot, index, uv, fallback) \
    ((index) == GBL_NO_TEXTURE ? (fallback) : GBL_SAMPLE_TEXTURE_SLOT(slot, index, uv))

// glTF alphaMode MASK (glTF 2.0, 3.9.4): true where the fragment is cut out.
bool materialAlphaTestDiscards(GpuMaterial m, vec2 uv) {
    if (m.alphaMaskCutoff.x == 0.0) return false;
    float alpha = m.baseColorFactor.a * sampleMaterialTexture(BASE_COLOR, m.textures0.x, uv, vec4(1.0)).a;
    return alpha < m.alphaMaskCutoff.y;
}

// Textures flagged sRGB use *_SRGB formats, so the sampler returns linear values already.
Surface evaluateMaterialOf(GpuMaterial m, vec3 worldPosition, vec3 normal, vec4 tangent, vec2 uv, bool frontFacing) {
    Surface s;
    vec4 base = m.baseColorFactor * sampleMaterialTexture(BASE_COLOR, m.textures0.x, uv, vec4(1.0));
    vec4 mr = sampleMaterialTexture(METALLIC_ROUGHNESS, m.textures0.y, uv, vec4(1.0));
    s.baseColor = base.rgb;
    s.metallic = clamp(m.metallicRoughnessOcclusion.x * mr.b, 0.0, 1.0);
    s.roughness = clamp(m.metallicRoughnessOcclusion.y * mr.g, 0.0, 1.0);
    float occlusionTexel = sampleMaterialTexture(OCCLUSION, m.textures0.w, uv, vec4(1.0)).r;
    s.occlusion = 1.0 + m.metallicRoughnessOcclusion.z * (occlusionTexel - 1.0);
    s.emissive = m.emissiveNormalScale.rgb * sampleMaterialTexture(EMISSIVE, m.textures1.x, uv, vec4(1.0)).rgb;

    // KHR_materials_specular: dielectric F0 = min(0.04 * specularColor, 1) * specular.
    float specularWeight = m.specularColorSpecular.a * sampleMaterialTexture(SPECULAR, m.textures1.y, uv, vec4(1.0)).a;
    vec3 specularTint = m.specularColorSpecular.rgb * sampleMaterialTexture(SPECULAR_COLOR, m.textures1.z, uv, vec4(1.0)).rgb;
    vec3 dielectricF0 = min(vec3(0.04) * specularTint, vec3(1.0)) * specularWeight;
    s.specularColor = mix(dielectricF0, s.baseColor, s.metallic);
    s.diffuseColor = s.baseColor * (1.0 - s.metallic);
    // UE4's scalar specular reproduces a grey dielectric F0: F0 = 0.08 * specular.
    s.specular = clamp(dot(dielectricF0, vec3(1.0 / 3.0)) / 0.08, 0.0, 1.0);

    vec3 n = normalize(normal);
    bool doubleSided = m.metallicRoughnessOcclusion.w > 0.5;
    if (doubleSided && !frontFacing) n = -n;
    if (m.textures0.z != GBL_NO_TEXTURE) {
        vec3 t = normalize(tangent.xyz - n * dot(n, tangent.xyz));
        vec3 b = cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
        vec3 tn = GBL_SAMPLE_TEXTURE_SLOT(NORMAL, m.textures0.z, uv).xyz * 2.0 - 1.0;
        tn.xy *= m.emissiveNormalScale.a;
        n = normalize(t * tn.x + b * tn.y + n * tn.z);
    }
    s.normal = n;
    s.position = worldPosition;
    return s;
}
#endif
