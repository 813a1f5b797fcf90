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
};
#endif
