// gbufferlab encoding primitives, sections 5-8: colour transforms, chroma checkerboard, roughness maps, UE4 specular colour and depth. GLSL 450 include file (no #version).
// One family of shaders/encodings.glsl, which includes the families in order and states the
// contract they all keep (include encodings.glsl, not this file). C++ mirror: src/encoding/encodings.{h,cpp},
// same names; tests: tests/encoding/color_encodings_test.cpp.

#ifndef GBL_COLOR_ENCODINGS_GLSL
#define GBL_COLOR_ENCODINGS_GLSL

// ---------------------------------------------------------------------------------------------
// 5. Colour transforms (float -> float; quantise Y with quantizeUnorm, the chroma of the YCbCr
//    family with quantizeChroma, YCoCg's with quantizeUnorm as the paper does).
// ---------------------------------------------------------------------------------------------

// rgbToYCbCr: ITU-R BT.601 full range (JPEG/JFIF), rgb in [0,1]^3 -> (Y, Cb+0.5, Cr+0.5) in
// [0,1]^3. Cb = (B - Y) / 1.772, Cr = (R - Y) / 1.402. Used by Crysis 3 for albedo and specular
// (Sousa et al., "The Rendering Technologies of Crysis 3", GDC 2013).
// Error: the pair is exact up to float rounding (max 2.6e-7); 8 bits per code: max abs 0.0054,
// CIEDE2000 mean 0.17, max 6.3 (darks; ycbcr_sqrt: max 1.3).
vec3 rgbToYCbCr(vec3 c) {
    precise float y = 0.299 * c.r + 0.587 * c.g + 0.114 * c.b;
    precise float cb = (c.b - y) * 0.5643341 + 0.5;
    precise float cr = (c.r - y) * 0.7132668 + 0.5;
    return vec3(y, cb, cr);
}

vec3 yCbCrToRgb(vec3 c) {
    float r = c.x + (c.z - 0.5) * 1.402;
    float b = c.x + (c.y - 0.5) * 1.772;
    float g = (c.x - 0.299 * r - 0.114 * b) / 0.587;
    return vec3(r, g, b);
}

// lumaBt601: the Y of rgbToYCbCr (Crysis 3 stores only the specular colour's luminance).
float lumaBt601(vec3 c) {
    precise float y = 0.299 * c.r + 0.587 * c.g + 0.114 * c.b;
    return y;
}

// rgbToYCbCrSqrt: YCbCr of sqrt(rgb) (a gamma-2 pre-transform that spends codes on darks);
// yCbCrSqrtToRgb squares after the inverse matrix. Source: Sousa et al., Crysis 3, GDC 2013;
// Schulz, "Moving to the Next Generation - The Rendering Technology of Ryse", GDC 2014.
// Error, 8 bits per code: max abs 0.011 (brights), but darks (< 0.05) 0.0024 vs YCbCr's 0.0054;
// CIEDE2000 mean 0.20, max 1.3.
vec3 rgbToYCbCrSqrt(vec3 c) {
    precise vec3 s = vec3(sqrt(max(c.r, 0.0)), sqrt(max(c.g, 0.0)), sqrt(max(c.b, 0.0)));
    return rgbToYCbCr(s);
}

vec3 yCbCrSqrtToRgb(vec3 c) {
    vec3 s = max(yCbCrToRgb(c), vec3(0.0));
    return s * s;
}

// rgbToYCoCg: YCoCg with Co, Cg offset by 0.5, all in [0,1] for rgb in [0,1]^3.
// Source: Malvar & Sullivan, JVT-I014 (2003); Mavridis & Papaioannou, "The Compact YCoCg Frame
// Buffer", JCGT 1(1), 2012. Exact inverse in real arithmetic (float: max 1.5e-7); 8 bits per
// code: max abs 0.0058, CIEDE2000 mean 0.17, max 5.3.
vec3 rgbToYCoCg(vec3 c) {
    precise float y = 0.25 * c.r + 0.5 * c.g + 0.25 * c.b;
    precise float co = 0.5 * c.r - 0.5 * c.b + 0.5;
    precise float cg = -0.25 * c.r + 0.5 * c.g - 0.25 * c.b + 0.5;
    return vec3(y, co, cg);
}

vec3 yCoCgToRgb(vec3 c) {
    float co = c.y - 0.5;
    float cg = c.z - 0.5;
    float t = c.x - cg;
    return vec3(t + co, c.x + cg, t - co);
}

// ---------------------------------------------------------------------------------------------
// 6. Chroma checkerboard. Source: Mavridis & Papaioannou, "The Compact YCoCg Frame Buffer",
// JCGT 1(1), 2012, section 3 and listing 1. Each pixel stores Y and one chroma: the first
// (Cb / Co) where (x+y) is even, the second (Cr / Cg) where it is odd.
// ---------------------------------------------------------------------------------------------

// 29.5/255: codes 30 or more apart are an edge (the paper's THRESH, 30/255), decided as the
// integers are whatever the last bits of the float difference (src/encoding/encodings.h).
const float kChromaEdgeThreshold = 0.115686275;

bool chromaIsSecond(ivec2 pixel) { return ((pixel.x + pixel.y) & 1) != 0; }

// chromaForPixel: the chroma this pixel stores, from (first, second) = (Cb, Cr) or (Co, Cg).
float chromaForPixel(ivec2 pixel, vec2 chroma) { return chromaIsSecond(pixel) ? chroma.y : chroma.x; }

// reconstructChroma: the paper's edge-directed filter. The 4 direct neighbours (order: +x, -x,
// +y, -y) hold the other chroma; each gets weight 1 - step(29.5/255, |Yn - Yc|) (1 when its luma
// is fewer than 30 codes away), times `covered` (1 where the neighbour has geometry, 0 where it holds
// only the clear value: a silhouette never takes its chroma from the background). Their weighted
// mean is the missing chroma; when all 4 weights are 0 the first covered neighbour in that order
// is used alone (the paper's listing takes +x alone), and when no neighbour is covered the
// chroma is neutral (0.5). Returns (centre's own chroma, reconstructed other chroma). At image
// borders fetch the missing neighbour mirrored (x = -1 reads x = 1): a replicated (clamped)
// fetch would read the centre's own chroma kind.
// CryEngine 3 reconstructs the same way, edge-directed on luminance (Sousa et al., "The
// Rendering Technologies of Crysis 3", GDC 2013, after Mavridis & Papaioannou 2012); the sky and
// other pixels without G-buffer data are excluded as here.
vec2 reconstructChroma(float lumaCentre, float chromaCentre, vec4 lumaNeighbours, vec4 chromaNeighbours,
                       vec4 covered) {
    vec4 w = covered * (vec4(1.0) - step(vec4(kChromaEdgeThreshold), abs(lumaNeighbours - vec4(lumaCentre))));
    float total = w.x + w.y + w.z + w.w;
    if (total == 0.0) {
        float nx = 1.0 - covered.x, ny = 1.0 - covered.y, nz = 1.0 - covered.z;
        w = covered * vec4(1.0, nx, nx * ny, nx * ny * nz);
        total = w.x + w.y + w.z + w.w;
        if (total == 0.0) return vec2(chromaCentre, 0.5);
    }
    float other = (w.x * chromaNeighbours.x + w.y * chromaNeighbours.y + w.z * chromaNeighbours.z +
                   w.w * chromaNeighbours.w) / total;
    return vec2(chromaCentre, other);
}

// reconstructChroma with the pixel: returns (first, second) = (Cb, Cr) or (Co, Cg).
// Error, 8 bits per code, on a synthetic image of 16x16 random flat blocks (3:1 with a ramp):
// CIEDE2000 mean 0.6, p99 9, max 42 (block corners, where no neighbour shares the centre's hue).
vec2 reconstructChroma(ivec2 pixel, float lumaCentre, float chromaCentre, vec4 lumaNeighbours,
                       vec4 chromaNeighbours, vec4 covered) {
    vec2 c = reconstructChroma(lumaCentre, chromaCentre, lumaNeighbours, chromaNeighbours, covered);
    return chromaIsSecond(pixel) ? vec2(c.y, c.x) : c;
}

// ---------------------------------------------------------------------------------------------
// 7. Roughness maps (scalar transforms, quantise with quantizeUnorm).
// ---------------------------------------------------------------------------------------------

// glossFromRoughness / roughnessFromGloss: gloss = 1 - roughness (CryEngine glossiness).
float glossFromRoughness(float r) {
    precise float g = 1.0 - r;
    return g;
}
float roughnessFromGloss(float g) { return 1.0 - g; }

// reflectanceFromSpecular: Filament's (and Bevy's) reflectance r, with F0 = 0.16 r^2, from UE's
// scalar specular s, with F0 = 0.08 s: r = sqrt(s / 2) (0.5 -> 0.5, F0 0.04 in both). Quantise
// with quantizeUnorm; specularFromReflectance = 2 r^2. Error in specular <= 4 r / (2 (2^b - 1)),
// <= 0.0056 at 8 bits (r = 0.707 at s = 1). sqrt is exact (IEEE), so the codes match the CPU's.
float reflectanceFromSpecular(float s) {
    precise float h = clamp(s, 0.0, 1.0) * 0.5;
    return sqrt(h);
}
float specularFromReflectance(float r) { return 2.0 * r * r; }
// Bevy's WebGL2 read of its 4-bit reflectance: saturate(r - 0.03333333333), half a 4-bit step low
// (the CPU mirror's comment says more).
float specularFromReflectanceBevyWebgl2(float r) { return specularFromReflectance(clamp(r - 0.03333333333, 0.0, 1.0)); }

// smoothnessFromRoughnessCry: s = 1 - sqrt(r); roughnessFromSmoothnessCry: r = (1 - s)^2.
// Source: Schulz, "Moving to the Next Generation - The Rendering Technology of Ryse", GDC 2014.
// With 8-bit unorm s: max roughness error 0.0039 (near r = 1), 0.5/255^2 near r = 0.
float smoothnessFromRoughnessCry(float r) {
    precise float s = 1.0 - sqrt(max(r, 0.0));
    return s;
}
float roughnessFromSmoothnessCry(float s) { return (1.0 - s) * (1.0 - s); }

// cry_gloss_power: CryENGINE 3's gloss, read as the engine used it (Crysis 2's slim G-buffer,
// RT1.a). The engine turns the 8-bit gloss g into a normalised Blinn-Phong power
//     n = exp2(10 g + 1)                 (2 .. 2048)
// -- the mapping used in CryENGINE 3-era deferred-lighting shaders; the seed (DIGEST.md) gives no
// gloss-to-power formula and Sousa et al. 2011 name gloss without one, so this is an assumption
// stated here and in layouts/crysis2-slim*.toml. gbufferlab's BRDF is GGX with alpha =
// roughness^2 (UE4), so the power is converted with the Phong / Beckmann equivalence of Walter
// et al. 2007 ("Microfacet Models for Refraction through Rough Surfaces", EGSR: n = 2/alpha^2 - 2),
// taking Beckmann's alpha as GGX's (the usual approximation; the lobes differ in their tails):
//     alpha = sqrt(2 / (n + 2)),  roughness = sqrt(alpha),
// and encoding inverts it: g = (log2(2 / roughness^4 - 2) - 1) / 10, rounded to 8 bits.
// Range: code 255 (g = 1, n = 2048) decodes to roughness 0.17673357, code 0 (g = 0, n = 2) to
// 0.84089643; roughness outside [0.1767, 0.8409] clamps to those ends (the engine's range: a
// mirror or a fully rough surface cannot be stored). Inside it the round trip's error is at most
// 0.0018 in roughness (half a gloss step; measured over 200001 roughnesses). Table based and
// exact, like sRGB: kCryGlossRoughness[k] = float(roughness(k / 255)); kCryGlossEncodeThresholds[i]
// = the largest float <= the roughness whose gloss is (i + 0.5) / 255 (both in double; they
// decrease with i). The code = the number of thresholds >= roughness = round(255 g) with ties up,
// exactly, for every float. Generated in double precision; tests/encoding/color_encodings_test.cpp
// (CryGlossPower.TablesMatchTheMapping) recomputes every entry. 8 bits only.
const float kCryGlossRoughness[256] = float[256](
    0.840896428, 0.838024735, 0.835124314, 0.83219552, 0.829238772, 0.826254427, 0.823243082, 0.820205033,
    0.817140758, 0.814050853, 0.810935676, 0.807795882, 0.804631829, 0.801444173, 0.79823339, 0.795000017,
    0.791744709, 0.788468003, 0.785170436, 0.781852603, 0.77851516, 0.775158703, 0.771783829, 0.768391132,
    0.76498127, 0.761554897, 0.758112609, 0.754655004, 0.751182735, 0.747696519, 0.744196951, 0.740684628,
    0.737160265, 0.733624518, 0.730077922, 0.726521194, 0.722954929, 0.719379783, 0.715796411, 0.71220541,
    0.708607435, 0.705003023, 0.701392889, 0.697777629, 0.694157779, 0.690533936, 0.686906755, 0.683276772,
    0.679644585, 0.676010728, 0.672375798, 0.668740332, 0.665104806, 0.661469877, 0.65783596, 0.654203653,
    0.650573432, 0.646945715, 0.643321097, 0.639699996, 0.636082947, 0.63247031, 0.628862619, 0.625260234,
    0.62166357, 0.618073165, 0.614489317, 0.610912442, 0.607342958, 0.603781223, 0.600227594, 0.596682429,
    0.593146086, 0.589618862, 0.586101115, 0.582593203, 0.579095304, 0.575607836, 0.572131038, 0.568665206,
    0.565210581, 0.561767459, 0.55833602, 0.554916561, 0.551509261, 0.548114419, 0.544732213, 0.541362882,
    0.538006544, 0.534663439, 0.531333745, 0.52801764, 0.524715304, 0.521426797, 0.518152416, 0.51489222,
    0.51164639, 0.508414984, 0.505198181, 0.50199604, 0.498808771, 0.495636404, 0.492479056, 0.489336818,
    0.48620978, 0.483098, 0.480001599, 0.476920575, 0.473855048, 0.470805079, 0.467770696, 0.464751959,
    0.461748898, 0.458761573, 0.455790013, 0.452834219, 0.449894279, 0.446970165, 0.444061905, 0.44116956,
    0.43829307, 0.435432494, 0.432587802, 0.429759026, 0.426946133, 0.424149156, 0.421368033, 0.418602824,
    0.415853441, 0.413119912, 0.410402209, 0.40770033, 0.405014187, 0.402343839, 0.399689198, 0.397050232,
    0.394426942, 0.391819268, 0.389227182, 0.386650622, 0.384089589, 0.381544024, 0.379013866, 0.376499087,
    0.373999625, 0.371515423, 0.369046479, 0.366592705, 0.364154041, 0.361730456, 0.359321862, 0.356928259,
    0.354549527, 0.352185667, 0.349836558, 0.347502172, 0.345182449, 0.342877358, 0.340586752, 0.338310659,
    0.336048961, 0.333801597, 0.331568509, 0.329349667, 0.327144921, 0.324954301, 0.322777659, 0.320614964,
    0.318466157, 0.316331178, 0.314209908, 0.312102288, 0.310008287, 0.307927847, 0.305860817, 0.303807199,
    0.301766902, 0.299739838, 0.297725946, 0.295725167, 0.293737441, 0.29176265, 0.289800763, 0.287851691,
    0.285915375, 0.283991724, 0.28208068, 0.280182183, 0.278296143, 0.276422501, 0.274561167, 0.272712082,
    0.270875186, 0.26905039, 0.267237604, 0.265436828, 0.263647914, 0.261870831, 0.26010552, 0.258351862,
    0.256609827, 0.254879355, 0.253160328, 0.251452714, 0.249756455, 0.248071447, 0.246397629, 0.244734943,
    0.243083313, 0.24144268, 0.23981297, 0.238194108, 0.236586049, 0.234988689, 0.233401999, 0.231825888,
    0.230260298, 0.228705168, 0.227160424, 0.225626007, 0.224101841, 0.222587869, 0.221084028, 0.219590247,
    0.218106464, 0.21663262, 0.215168655, 0.21371448, 0.212270066, 0.210835338, 0.20941022, 0.20799467,
    0.206588611, 0.205191985, 0.203804746, 0.202426821, 0.201058134, 0.199698657, 0.198348314, 0.19700703,
    0.195674777, 0.194351465, 0.193037063, 0.191731513, 0.190434724, 0.189146668, 0.187867284, 0.186596498,
    0.18533428, 0.184080556, 0.182835281, 0.18159838, 0.180369809, 0.179149523, 0.177937463, 0.176733568);

const float kCryGlossEncodeThresholds[255] = float[255](
    0.839464188, 0.836578071, 0.833663404, 0.830720544, 0.827749968, 0.824752092, 0.821727335, 0.818676114,
    0.815598965, 0.812496364, 0.809368789, 0.806216836, 0.803040862, 0.799841583, 0.796619475, 0.793375075,
    0.790108979, 0.786821723, 0.783513963, 0.780186296, 0.776839256, 0.773473501, 0.770089626, 0.766688287,
    0.76327008, 0.75983566, 0.756385624, 0.752920628, 0.749441326, 0.745948374, 0.74244231, 0.738923907,
    0.735393763, 0.731852472, 0.72830075, 0.724739134, 0.721168399, 0.71758908, 0.714001775, 0.710407197,
    0.706805944, 0.703198612, 0.699585855, 0.695968211, 0.692346275, 0.688720703, 0.685092032, 0.681460857,
    0.677827775, 0.674193323, 0.670558035, 0.66692251, 0.663287222, 0.65965271, 0.656019568, 0.652388215,
    0.648759186, 0.645132959, 0.641510069, 0.637890935, 0.634276032, 0.630665779, 0.627060652, 0.623461127,
    0.619867563, 0.616280377, 0.612699986, 0.609126747, 0.605561078, 0.602003336, 0.598453879, 0.594913125,
    0.591381252, 0.587858796, 0.584345877, 0.580842912, 0.577350259, 0.573868096, 0.570396721, 0.566936433,
    0.56348753, 0.560050189, 0.556624711, 0.553211331, 0.54981029, 0.546421707, 0.543045938, 0.539683044,
    0.536333323, 0.532996893, 0.529673934, 0.526364684, 0.523069263, 0.519787848, 0.5165205, 0.513267457,
    0.510028839, 0.506804705, 0.503595233, 0.500400543, 0.497220695, 0.494055837, 0.49090603, 0.487771392,
    0.484651953, 0.481547862, 0.47845915, 0.475385875, 0.472328097, 0.469285905, 0.46625936, 0.463248432,
    0.460253239, 0.457273781, 0.454310119, 0.451362252, 0.44843021, 0.445514053, 0.442613721, 0.439729303,
    0.43686077, 0.434008151, 0.431171417, 0.428350568, 0.425545633, 0.422756582, 0.419983417, 0.417226136,
    0.41448468, 0.411759079, 0.409049273, 0.406355262, 0.403677046, 0.401014537, 0.398367733, 0.395736605,
    0.393121123, 0.390521258, 0.38793695, 0.385368168, 0.382814854, 0.380277008, 0.377754539, 0.375247419,
    0.372755617, 0.370279044, 0.36781767, 0.365371466, 0.362940341, 0.360524267, 0.358123183, 0.355737031,
    0.353365719, 0.35100925, 0.348667502, 0.346340477, 0.344028056, 0.341730237, 0.339446902, 0.337177992,
    0.334923476, 0.332683265, 0.3304573, 0.328245521, 0.326047838, 0.323864222, 0.321694553, 0.319538832,
    0.317396939, 0.315268815, 0.31315437, 0.311053604, 0.308966368, 0.306892633, 0.304832339, 0.302785367,
    0.300751686, 0.298731238, 0.296723902, 0.29472965, 0.292748421, 0.290780097, 0.288824618, 0.286881924,
    0.284951955, 0.283034623, 0.281129867, 0.279237598, 0.277357757, 0.275490284, 0.273635089, 0.271792084,
    0.269961238, 0.268142492, 0.266335696, 0.264540881, 0.262757897, 0.260986686, 0.259227216, 0.257479399,
    0.255743146, 0.254018396, 0.25230509, 0.250603169, 0.248912543, 0.247233137, 0.245564893, 0.24390775,
    0.242261618, 0.240626454, 0.239002183, 0.23738873, 0.235786021, 0.23419401, 0.232612625, 0.231041774,
    0.229481429, 0.227931499, 0.226391926, 0.224862635, 0.223343581, 0.221834674, 0.220335871, 0.218847111,
    0.217368305, 0.215899393, 0.214440346, 0.212991059, 0.211551487, 0.210121572, 0.208701253, 0.207290456,
    0.205889121, 0.204497188, 0.203114614, 0.201741323, 0.200377241, 0.199022338, 0.197676525, 0.196339771,
    0.195012003, 0.193693161, 0.192383185, 0.191082016, 0.189789608, 0.188505888, 0.187230811, 0.185964316,
    0.184706345, 0.183456853, 0.18221578, 0.180983052, 0.179758638, 0.178542465, 0.177334487);

uint encodeCryGlossPower(float r) {
    uint lo = 0u;
    uint hi = 255u;
    for (int i = 0; i < 8; ++i) {
        uint mid = (lo + hi) >> 1u;
        if (GBL_CODEC_TABLE(kCryGlossEncodeThresholds, GBL_CODEC_TABLE_CRY_GLOSS_ENCODE, mid) >= r) lo = mid + 1u; else hi = mid;
    }
    return lo;
}
float decodeCryGlossPower(uint code) {
    return GBL_CODEC_TABLE(kCryGlossRoughness, GBL_CODEC_TABLE_CRY_GLOSS_DECODE, code & 255u);
}

// ---------------------------------------------------------------------------------------------
// 8. UE4 specular colour and depth.
// ---------------------------------------------------------------------------------------------

// specularColorUE4: F0 = mix(0.08 * specular, baseColor, metallic), written out as
// a * (1 - t) + b * t. Source: Epic Games, UE4 DeferredShadingCommon.ush, ComputeF0
// (Karis, "Real Shading in Unreal Engine 4", SIGGRAPH 2013).
vec3 specularColorUE4(vec3 baseColor, float metallic, float specular) {
    precise vec3 f0 = vec3(0.08 * specular) * (1.0 - metallic) + baseColor * metallic;
    return f0;
}

// quantizeDepth24: depth in [0,1] (clamped) -> 24-bit unorm code (D24), in float only.
// quantizeUnorm(d, 24) would be off by one for ~25% of depths (half of those in [0.5,1)):
// float32 holds 24 significant bits, so d * (2^24-1) + 0.5 rounds. Instead split exactly:
// h = d * 2^24 (exact), hi = floor(h) (exact), r = (h - hi) - d in (-1,1) (error <= 2^-25), and
// code = hi + floor(r + 0.5) = round(d * (2^24-1)), ties up. Error: |dequantizeDepth24(code) - d|
// <= 0.5 / (2^24-1) = 3.0e-8; the code equals exact rounding for every float in [2^-8, 1]
// (tested exhaustively) and every code survives decode + encode.
uint quantizeDepth24(float d) {
    precise float c = clamp(d, 0.0, 1.0);
    precise float h = c * 16777216.0;
    precise float hi = floor(h);
    precise float r = (h - hi) - c;
    precise float up = floor(r + 0.5);
    return uint(int(hi) + int(up));
}
float dequantizeDepth24(uint code) { return dequantizeUnorm(code & 0xffffffu, 24u); }

// positionFromDepth: uv in [0,1]^2 (texel centres, (0,0) = first row), depth in [0,1]
// (Vulkan clip z), ndc = (uv * 2 - 1, depth); returns the world position for the inverse of the
// same view-projection matrix used to render (its y convention decides which row is uv.y = 0).
vec3 positionFromDepth(vec2 uv, float depth, mat4 invViewProj) {
    vec4 ndc = vec4(uv.x * 2.0 - 1.0, uv.y * 2.0 - 1.0, depth, 1.0);
    vec4 p = invViewProj * ndc;
    return vec3(p.x / p.w, p.y / p.w, p.z / p.w);
}

#endif  // GBL_COLOR_ENCODINGS_GLSL
