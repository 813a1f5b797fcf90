#include "gbuffer_wiring.h"

namespace gbl {

GBufferWiring makeReferenceWiring() {
    GBufferWiring w;
    w.layoutName = "reference";
    w.targetNames = {"normal_roughness", "base_color_metallic", "specular_color_occlusion", "emissive_specular",
                     "diffuse_color"};
    w.targetFormats.assign(5, VK_FORMAT_R32G32B32A32_UINT);
    w.depthFormat = VK_FORMAT_D32_SFLOAT;
    w.glsl = R"(// reference wiring: every attribute as float32 bits
#ifdef GBUFFER_WRITE
layout(location = 0) out uvec4 gbufferTarget0;
layout(location = 1) out uvec4 gbufferTarget1;
layout(location = 2) out uvec4 gbufferTarget2;
layout(location = 3) out uvec4 gbufferTarget3;
layout(location = 4) out uvec4 gbufferTarget4;
void writeGBuffer(Surface s, ivec2 pixel) {
    gbufferTarget0 = floatBitsToUint(vec4(s.normal, s.roughness));
    gbufferTarget1 = floatBitsToUint(vec4(s.baseColor, s.metallic));
    gbufferTarget2 = floatBitsToUint(vec4(s.specularColor, s.occlusion));
    gbufferTarget3 = floatBitsToUint(vec4(s.emissive, s.specular));
    gbufferTarget4 = floatBitsToUint(vec4(s.diffuseColor, 0.0));
}
#endif
#ifdef GBUFFER_READ
layout(set = 1, binding = 0) uniform usampler2D gbufferTarget0;
layout(set = 1, binding = 1) uniform usampler2D gbufferTarget1;
layout(set = 1, binding = 2) uniform usampler2D gbufferTarget2;
layout(set = 1, binding = 3) uniform usampler2D gbufferTarget3;
layout(set = 1, binding = 4) uniform usampler2D gbufferTarget4;
Surface readGBuffer(ivec2 pixel) {
    Surface s;
    vec4 t0 = uintBitsToFloat(texelFetch(gbufferTarget0, pixel, 0));
    vec4 t1 = uintBitsToFloat(texelFetch(gbufferTarget1, pixel, 0));
    vec4 t2 = uintBitsToFloat(texelFetch(gbufferTarget2, pixel, 0));
    vec4 t3 = uintBitsToFloat(texelFetch(gbufferTarget3, pixel, 0));
    vec4 t4 = uintBitsToFloat(texelFetch(gbufferTarget4, pixel, 0));
    s.normal = t0.xyz; s.roughness = t0.w;
    s.baseColor = t1.xyz; s.metallic = t1.w;
    s.specularColor = t2.xyz; s.occlusion = t2.w;
    s.emissive = t3.xyz; s.specular = t3.w;
    s.diffuseColor = t4.xyz;
    return s;
}
#endif
)";
    return w;
}

}  // namespace gbl
