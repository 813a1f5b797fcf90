// Surface: every shading attribute the G-buffer pass produces and the lighting pass consumes.
// The C++ mirror is src/codec/surface.h (same member names and order).
#ifndef GBL_SURFACE_GLSL
#define GBL_SURFACE_GLSL
struct Surface {
    vec3 normal;         // world space (Y-up), unit; stored in the layout's [space] (normal_space.glsl)
    vec3 baseColor;      // linear
    float metallic;
    float roughness;     // perceptual; GGX alpha = roughness^2
    float specular;      // UE4 scalar specular: dielectric F0 = 0.08 * specular
    vec3 specularColor;  // F0, linear
    vec3 diffuseColor;   // Lambert albedo = baseColor * (1 - metallic)
    float occlusion;
    vec3 emissive;       // linear radiance
    vec3 position;       // world space (Y-up) in the passes; stored in the layout's [space] position
                         // space (normal_space.glsl); read back only where the layout stores it
    // The material layers of glTF's PBR extensions (brdf_layers.glsl). 0 everywhere is "no layer":
    // what a layout that does not store one decodes.
    float coat;                 // KHR_materials_clearcoat: clearcoat, [0,1]
    float coatRoughness;        // clearcoatRoughness, perceptual
    vec3 coatNormal;            // the coat's unit normal, in the normal's space; 0: the base normal
    vec3 sheenColor;            // KHR_materials_sheen: sheenColor, linear
    float sheenRoughness;       // sheenRoughness, perceptual
    float anisotropyStrength;   // KHR_materials_anisotropy: strength, [0,1]
    vec3 anisotropyDirection;   // the unit tangent highlights stretch along (rotation applied), in the
                                // normal's space, orthogonal to the normal; 0: none
    float shadingModel;         // reserved for the shading-model selector (the layers the material
                                // has, GBL_LAYER_* bits): set by the material, read by no pass yet
};
#endif
