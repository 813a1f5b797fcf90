// codec_tables.glsl -- where the encodings' exact 8-bit tables are read (sRGB in
// scalar_encodings.glsl, CryEngine's gloss in color_encodings.glsl, gamma 2.2, HDRP's fast sRGB
// and Killzone 2's specular power in engine_encodings.glsl): GBL_CODEC_TABLE(array, offset, i) is
// array[i].
//
// A pass that defines GBL_CODEC_TABLES_SET and GBL_CODEC_TABLES_BINDING reads them from a
// storage buffer there instead (the renderer's G-buffer pass: set 0; its lighting and decode
// passes: set 1; binding kCodecTablesBinding of src/encoding/codec_tables.h, which fills it from
// the C++ twins of the same tables). The values are the same floats; the difference is the driver's compile: a constant
// array indexed with a run-time code is copied into per-invocation memory, element by element,
// at every call, and llvmpipe (lavapipe 22.3) spent about 30 s JIT-compiling the three sRGB
// decodes of one ue4 lighting shader (0.5 s with this buffer; measured with GBL_WARM_UP_LOG=1,
// issue 14). The offsets below are codec_tables.h's (CodecTables.OffsetsMatchTheShader).
#ifndef GBL_CODEC_TABLES_GLSL
#define GBL_CODEC_TABLES_GLSL

#define GBL_CODEC_TABLE_SRGB_DECODE 0u
#define GBL_CODEC_TABLE_SRGB_ENCODE 256u
#define GBL_CODEC_TABLE_CRY_GLOSS_DECODE 512u
#define GBL_CODEC_TABLE_CRY_GLOSS_ENCODE 768u
#define GBL_CODEC_TABLE_GAMMA22_DECODE 1024u
#define GBL_CODEC_TABLE_GAMMA22_ENCODE 1280u
#define GBL_CODEC_TABLE_SRGB_FAST_HDRP_ENCODE 1536u
#define GBL_CODEC_TABLE_KZ2_POWER_DECODE 1792u
#define GBL_CODEC_TABLE_KZ2_POWER_ENCODE 2048u

#ifdef GBL_CODEC_TABLES_SET
layout(std430, set = GBL_CODEC_TABLES_SET, binding = GBL_CODEC_TABLES_BINDING) readonly buffer GblCodecTables {
    float gblCodecTables[];
};
#define GBL_CODEC_TABLE(array, offset, i) gblCodecTables[(offset) + (i)]
#else
#define GBL_CODEC_TABLE(array, offset, i) array[i]
#endif

#endif  // GBL_CODEC_TABLES_GLSL
