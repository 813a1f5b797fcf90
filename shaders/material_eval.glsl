// glTF 2.0 metallic-roughness material (+ KHR_materials_specular, _ior, _emissive_strength,
// _clearcoat, _sheen, _anisotropy, KHR_texture_transform) -> Surface: the one material
// evaluation, shared by the G-buffer pass (material.glsl: the rasteriser's implicit derivatives)
// and the visibility buffer's resolve (visibility_resolve.glsl: analytic derivatives, textureGrad).
// The includer defines GBL_SAMPLE_TEXTURE_SLOT(slot, index, uv), texture `index`'s value at uv
// (index is never GBL_NO_TEXTURE), before including this file. `slot` names the material's
// texture slot (BASE_COLOR, ..., ANISOTROPY: shared_types.h GBL_SLOT_*, src/render/gpu_scene.h),
// so a resolve may test only that slot's textures.
//
// Compiled per scene (the renderer's defines, src/render/gpu_scene.h sceneShaderFeatures):
//   GBL_LAYERS         the layers some material has (brdf_layers.glsl GBL_LAYER_* bits); without
//                      one its Surface members are 0 ("no layer") and none of its code is compiled.
//   GBL_UV_TRANSFORMS  1 where some slot has KHR_texture_transform or samples TEXCOORD_1; without
//                      it every slot samples uv0 as it is.
// A scene with neither compiles what this file compiled before the extensions.
#ifndef GBL_MATERIAL_EVAL_GLSL
#define GBL_MATERIAL_EVAL_GLSL

#ifndef GBL_LAYERS
#define GBL_LAYERS 0
#endif
#ifndef GBL_UV_TRANSFORMS
#define GBL_UV_TRANSFORMS 0
#endif

// A macro, not a function: `slot` is a name the includer's macro may paste. Only the chosen
// operand of ?: is evaluated, as in the function this was.
#define sampleMaterialTexture(slot, index, uv, fallback) \
    ((index) == GBL_NO_TEXTURE ? (fallback) : GBL_SAMPLE_TEXTURE_SLOT(slot, index, uv))

// The uv a slot samples: TEXCOORD_<texCoord>, through its KHR_texture_transform (the README's
// translation * rotation * scale; src/scene/scene.h TextureTransform has the rotation's sense).
// The includer samples a transformed slot with explicit gradients: it defines
// GBL_SLOT_UV_GRADIENTS(pick1, m2, uv0, uv1), the gradients of the set's uv (pick1: 1 for
// TEXCOORD_1, else 0) times the slot's 2x2 matrix, for the sample that follows (the resolve from
// its ray differentials, the G-buffer pass from dFdx / dFdy of the interpolated sets). Implicit
// derivatives of the transformed uv itself would be undefined where a pixel quad straddles a
// triangle edge: the transform is read from the material buffer, which lavapipe's helper lanes
// read as 0 (a transformed uv read a 1 x 1 mip along a quad's diagonal). Branch-free: every slot
// computes offset + matrix * uv, which for a slot without a transform (identity, offset 0) is uv.
vec2 materialSlotUv(GpuMaterial m, int slot, vec2 uv0, vec2 uv1) {
#if GBL_UV_TRANSFORMS
    vec4 t = m.uvTransforms[2 * slot + 1];
    vec4 r = m.uvTransforms[2 * slot];
    float pick1 = step(0.5, t.z);
    mat2 a = mat2(r.xy, r.zw);
#ifdef GBL_SLOT_UV_GRADIENTS
    GBL_SLOT_UV_GRADIENTS(pick1, a, uv0, uv1);
#endif
    return a * mix(uv0, uv1, pick1) + t.xy;
#else
    return uv0;
#endif
}

// glTF alphaMode MASK (glTF 2.0, 3.9.4): true where the fragment is cut out.
bool materialAlphaTestDiscards(GpuMaterial m, vec2 uv, vec2 uv1) {
    if (m.alphaMaskCutoff.x == 0.0) return false;
    vec2 uvBase = materialSlotUv(m, GBL_SLOT_BASE_COLOR, uv, uv1);
    float alpha = m.baseColorFactor.a * sampleMaterialTexture(BASE_COLOR, m.textures0.x, uvBase, vec4(1.0)).a;
    return alpha < m.alphaMaskCutoff.y;
}

// Textures flagged sRGB use *_SRGB formats, so the sampler returns linear values already.
Surface evaluateMaterialOf(GpuMaterial m, vec3 worldPosition, vec3 normal, vec4 tangent, vec2 uv, vec2 uv1,
                           bool frontFacing) {
    Surface s;
    vec2 uvSlot = materialSlotUv(m, GBL_SLOT_BASE_COLOR, uv, uv1);
    vec4 base = m.baseColorFactor * sampleMaterialTexture(BASE_COLOR, m.textures0.x, uvSlot, vec4(1.0));
    uvSlot = materialSlotUv(m, GBL_SLOT_METALLIC_ROUGHNESS, uv, uv1);
    vec4 mr = sampleMaterialTexture(METALLIC_ROUGHNESS, m.textures0.y, uvSlot, vec4(1.0));
    s.baseColor = base.rgb;
    s.metallic = clamp(m.metallicRoughnessOcclusion.x * mr.b, 0.0, 1.0);
    s.roughness = clamp(m.metallicRoughnessOcclusion.y * mr.g, 0.0, 1.0);
    uvSlot = materialSlotUv(m, GBL_SLOT_OCCLUSION, uv, uv1);
    float occlusionTexel = sampleMaterialTexture(OCCLUSION, m.textures0.w, uvSlot, vec4(1.0)).r;
    s.occlusion = 1.0 + m.metallicRoughnessOcclusion.z * (occlusionTexel - 1.0);
    // KHR_materials_emissive_strength is folded into the factor (src/render/gpu_scene.cpp).
    uvSlot = materialSlotUv(m, GBL_SLOT_EMISSIVE, uv, uv1);
    s.emissive = m.emissiveNormalScale.rgb * sampleMaterialTexture(EMISSIVE, m.textures1.x, uvSlot, vec4(1.0)).rgb;

    // KHR_materials_specular with KHR_materials_ior: dielectric F0 = min(f0(ior) * specularColor, 1) * specular,
    // f0(ior) = ((ior - 1) / (ior + 1))^2, alphaMaskCutoff.z (0.04 at the default ior 1.5).
    uvSlot = materialSlotUv(m, GBL_SLOT_SPECULAR, uv, uv1);
    float specularWeight = m.specularColorSpecular.a * sampleMaterialTexture(SPECULAR, m.textures1.y, uvSlot, vec4(1.0)).a;
    uvSlot = materialSlotUv(m, GBL_SLOT_SPECULAR_COLOR, uv, uv1);
    vec3 specularTint = m.specularColorSpecular.rgb * sampleMaterialTexture(SPECULAR_COLOR, m.textures1.z, uvSlot, vec4(1.0)).rgb;
    vec3 dielectricF0 = min(vec3(m.alphaMaskCutoff.z) * specularTint, vec3(1.0)) * specularWeight;
    s.specularColor = mix(dielectricF0, s.baseColor, s.metallic);
    s.diffuseColor = s.baseColor * (1.0 - s.metallic);
    // UE4's scalar specular reproduces a grey dielectric F0: F0 = 0.08 * specular.
    s.specular = clamp(dot(dielectricF0, vec3(1.0 / 3.0)) / 0.08, 0.0, 1.0);

    vec3 n = normalize(normal);
    bool doubleSided = m.metallicRoughnessOcclusion.w > 0.5;
    if (doubleSided && !frontFacing) n = -n;
    vec3 geometricNormal = n;  // the coat's normal without a coat normal map [Coat]
    // The tangent frame of the normal maps (glTF 2.0, 3.7.2.1: B = cross(N, T) * w), and of the
    // anisotropy direction.
    vec3 t = normalize(tangent.xyz - n * dot(n, tangent.xyz));
    vec3 b = cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
    if (m.textures0.z != GBL_NO_TEXTURE) {
        uvSlot = materialSlotUv(m, GBL_SLOT_NORMAL, uv, uv1);
        vec3 tn = GBL_SAMPLE_TEXTURE_SLOT(NORMAL, m.textures0.z, uvSlot).xyz * 2.0 - 1.0;
        tn.xy *= m.emissiveNormalScale.a;
        n = normalize(t * tn.x + b * tn.y + n * tn.z);
    }
    s.normal = n;
    s.position = worldPosition;

    s.coat = 0.0;
    s.coatRoughness = 0.0;
    s.coatNormal = vec3(0.0);
    s.sheenColor = vec3(0.0);
    s.sheenRoughness = 0.0;
    s.anisotropyStrength = 0.0;
    s.anisotropyDirection = vec3(0.0);
    s.shadingModel = 0.0;
#if GBL_LAYERS != 0
    s.shadingModel = m.alphaMaskCutoff.w;
#if (GBL_LAYERS & 1) != 0  // GBL_LAYER_COAT
    // KHR_materials_clearcoat: clearcoat = factor * texture.r, roughness = factor * texture.g; the
    // coat's normal from clearcoatNormalTexture in the same tangent frame, or "If
    // clearcoatNormalTexture is not given, no normal mapping is applied to the clear coat layer".
    uvSlot = materialSlotUv(m, GBL_SLOT_CLEARCOAT, uv, uv1);
    float coat = m.clearcoat.x * sampleMaterialTexture(CLEARCOAT, m.textures1.w, uvSlot, vec4(1.0)).r;
    if (coat > 0.0) {
        uvSlot = materialSlotUv(m, GBL_SLOT_CLEARCOAT_ROUGHNESS, uv, uv1);
        s.coat = clamp(coat, 0.0, 1.0);
        s.coatRoughness = clamp(m.clearcoat.y * sampleMaterialTexture(CLEARCOAT_ROUGHNESS, m.textures2.x, uvSlot, vec4(1.0)).g,
                                0.0, 1.0);
        vec3 nc = geometricNormal;
        if (m.textures2.y != GBL_NO_TEXTURE) {
            uvSlot = materialSlotUv(m, GBL_SLOT_CLEARCOAT_NORMAL, uv, uv1);
            vec3 tn = GBL_SAMPLE_TEXTURE_SLOT(CLEARCOAT_NORMAL, m.textures2.y, uvSlot).xyz * 2.0 - 1.0;
            tn.xy *= m.clearcoat.z;
            nc = normalize(t * tn.x + b * tn.y + geometricNormal * tn.z);
        }
        s.coatNormal = nc;
    }
#endif
#if (GBL_LAYERS & 2) != 0  // GBL_LAYER_SHEEN
    // KHR_materials_sheen: colour = factor * texture.rgb (an sRGB texture), roughness = factor * texture.a.
    uvSlot = materialSlotUv(m, GBL_SLOT_SHEEN_COLOR, uv, uv1);
    vec3 sheenColor = m.sheen.rgb * sampleMaterialTexture(SHEEN_COLOR, m.textures2.z, uvSlot, vec4(1.0)).rgb;
    if (max(max(sheenColor.r, sheenColor.g), sheenColor.b) > 0.0) {
        uvSlot = materialSlotUv(m, GBL_SLOT_SHEEN_ROUGHNESS, uv, uv1);
        s.sheenColor = clamp(sheenColor, vec3(0.0), vec3(1.0));
        s.sheenRoughness = clamp(m.sheen.a * sampleMaterialTexture(SHEEN_ROUGHNESS, m.textures2.w, uvSlot, vec4(1.0)).a,
                                 0.0, 1.0);
    }
#endif
#if (GBL_LAYERS & 4) != 0  // GBL_LAYER_ANISOTROPY
    // KHR_materials_anisotropy: the texture's rg * 2 - 1 is the direction in the tangent frame
    // (without a texture, the default texel (1, 0.5, 1): +x, full strength), rotated
    // counter-clockwise by anisotropyRotation (m.anisotropy.yz = cos, sin); strength = factor * b.
    // The direction is made orthogonal to the shading normal (Gram-Schmidt), so that it and
    // B = cross(N, T) frame Burley's D.
    uvSlot = materialSlotUv(m, GBL_SLOT_ANISOTROPY, uv, uv1);
    vec3 at = sampleMaterialTexture(ANISOTROPY, m.textures3.x, uvSlot, vec4(1.0, 0.5, 1.0, 1.0)).rgb;
    float strength = clamp(m.anisotropy.x * at.b, 0.0, 1.0);
    vec2 d = at.rg * 2.0 - 1.0;
    d = dot(d, d) > 0.0 ? normalize(d) : vec2(1.0, 0.0);
    vec2 rotated = mat2(m.anisotropy.y, m.anisotropy.z, -m.anisotropy.z, m.anisotropy.y) * d;
    vec3 direction = t * rotated.x + b * rotated.y;
    direction -= n * dot(n, direction);
    if (strength > 0.0 && dot(tangent.xyz, tangent.xyz) > 0.0 && dot(direction, direction) > 1e-12) {
        s.anisotropyStrength = strength;
        s.anisotropyDirection = normalize(direction);
    }
#endif
#endif
    return s;
}
#endif
