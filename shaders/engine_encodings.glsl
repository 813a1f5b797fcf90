// gbufferlab encoding primitives, section 8: packings of shipped engines. GLSL 450 include file (no #version).
// One family of shaders/encodings.glsl, which includes the families in order and states the
// contract they all keep (include encodings.glsl, not this file). C++ mirror: src/encoding/encodings.{h,cpp},
// same names; tests: tests/encoding/engine_encodings_test.cpp.

#ifndef GBL_ENGINE_ENCODINGS_GLSL
#define GBL_ENGINE_ENCODINGS_GLSL

// ---------------------------------------------------------------------------------------------
// 8. Packings of shipped engines (docs: layouts/README.md, "Codes of each encoding").
// ---------------------------------------------------------------------------------------------

// encodeRgb9e5: linear RGB >= 0 -> (r, g, b mantissas of 9 bits, shared exponent of 5 bits), the
// shared-exponent format of EXT_texture_shared_exponent / Vulkan's E5B9G9R9_UFLOAT_PACK32 (Vulkan
// spec, "Shared Exponent"): N = 9, B = 15, exp = max(-B - 1, floor(log2(max))) + 1 + B, one more
// when the largest mantissa rounds up to 2^N; mantissas floor(c / 2^(exp - B - N) + 0.5). Bevy's
// deferred G-buffer stores emissive this way (bevy_pbr rgb9e5.wgsl follows the same spec). floor(log2)
// is read from the float's exponent bits and every scale is an exact power of two, so the codes are
// exact. Range [0, 65408] (beyond clamps, negative -> 0). Error per channel <= half a step of the
// brightest channel: 2^(exp - 25); relative to max(r, g, b) <= 2^-9.
uvec4 encodeRgb9e5(vec3 c) {
    precise vec3 rgb = clamp(c, vec3(0.0), vec3(65408.0));
    precise float m = max(rgb.x, max(rgb.y, rgb.z));
    int e = max(-16, int((floatBitsToUint(m) >> 23u) & 0xffu) - 127) + 16;
    precise float scale = uintBitsToFloat(uint(151 - e) << 23u);  // 2^(B + N - exp)
    precise float top = floor(m * scale + 0.5);
    if (top >= 512.0) {
        e += 1;
        scale *= 0.5;
    }
    precise vec3 q = floor(rgb * scale + 0.5);
    return uvec4(uint(q.x), uint(q.y), uint(q.z), uint(e));
}

// decodeRgb9e5: mantissa * 2^(exp - B - N); exact.
vec3 decodeRgb9e5(uvec4 code) {
    float scale = uintBitsToFloat(uint(int(code.w & 31u) + 103) << 23u);
    return vec3(float(code.x & 511u), float(code.y & 511u), float(code.z & 511u)) * scale;
}

// Gamma 2.2 (not sRGB), 8 bits: code = round(255 x^(1/2.2)), as Bevy's deferred G-buffer stores
// base colour (pow(c, 1/2.2) packed with pack4x8unorm, decoded with pow(v, 2.2)). Exact and table
// based like srgb8, so that GPU and CPU agree: kGamma22Decode[i] = float((i/255)^2.2),
// kGamma22EncodeThresholds[i] = the smallest float >= ((i + 0.5)/255)^2.2 (computed in double;
// tests/encoding/engine_encodings_test.cpp recomputes both). Error of the round trip over [0,1]:
// at most half a code in the gamma domain; near 0 its steps are far finer than sRGB's (the first
// is 5.1e-6, sRGB's 3.0e-4), near 1 a little coarser.
const float kGamma22Decode[256] = float[256](
    0.0, 5.077052e-06, 2.3328004e-05, 5.6921766e-05, 0.00010718736, 0.00017512398, 0.00026154376, 0.00036713626,
    0.0004925038, 0.00063818286, 0.0008046585, 0.0009923743, 0.0012017395, 0.0014331345, 0.0016869153, 0.001963416,
    0.0022629532, 0.0025858255, 0.0029323183, 0.0033027031, 0.0036972396, 0.004116177, 0.004559755, 0.0050282036,
    0.005521745, 0.0060405936, 0.0065849572, 0.007155037, 0.0077510276, 0.008373118, 0.009021492, 0.009696329,
    0.010397802, 0.011126082, 0.011881335, 0.01266372, 0.013473397, 0.014310519, 0.015175238, 0.0160677,
    0.016988052, 0.017936433, 0.018912984, 0.019917838, 0.020951131, 0.022012996, 0.023103556, 0.024222942,
    0.025371278, 0.026548684, 0.02775528, 0.028991187, 0.03025652, 0.03155139, 0.032875918, 0.034230206,
    0.03561437, 0.037028514, 0.038472746, 0.03994717, 0.04145189, 0.04298701, 0.044552628, 0.046148844,
    0.047775753, 0.04943346, 0.05112205, 0.052841626, 0.054592278, 0.0563741, 0.05818718, 0.060031608,
    0.061907474, 0.06381487, 0.06575388, 0.06772459, 0.069727086, 0.07176145, 0.073827766, 0.07592612,
    0.07805659, 0.08021926, 0.0824142, 0.08464151, 0.086901255, 0.08919351, 0.09151835, 0.09387587,
    0.09626612, 0.0986892, 0.10114516, 0.1036341, 0.106156066, 0.10871115, 0.11129942, 0.113920934,
    0.11657578, 0.119264014, 0.12198571, 0.12474094, 0.12752979, 0.13035227, 0.13320851, 0.13609855,
    0.13902245, 0.14198029, 0.14497213, 0.14799802, 0.15105805, 0.15415226, 0.15728073, 0.16044351,
    0.16364068, 0.16687228, 0.17013837, 0.17343904, 0.17677432, 0.1801443, 0.183549, 0.1869885,
    0.19046287, 0.19397217, 0.19751643, 0.20109573, 0.20471013, 0.20835966, 0.2120444, 0.2157644,
    0.21951972, 0.22331041, 0.22713652, 0.23099813, 0.23489526, 0.23882799, 0.24279635, 0.24680042,
    0.25084025, 0.25491586, 0.25902733, 0.2631747, 0.26735806, 0.27157742, 0.27583283, 0.28012437,
    0.28445205, 0.28881598, 0.29321614, 0.29765263, 0.30212548, 0.30663475, 0.3111805, 0.31576276,
    0.32038155, 0.32503697, 0.32972902, 0.3344578, 0.33922333, 0.34402567, 0.34886482, 0.3537409,
    0.3586539, 0.3636039, 0.36859092, 0.37361503, 0.37867627, 0.38377464, 0.38891026, 0.3940831,
    0.3992933, 0.40454084, 0.40982574, 0.41514808, 0.42050794, 0.4259053, 0.43134022, 0.43681276,
    0.44232294, 0.44787085, 0.45345646, 0.4590799, 0.46474114, 0.47044024, 0.47617728, 0.48195225,
    0.4877652, 0.4936162, 0.49950528, 0.5054325, 0.51139784, 0.5174014, 0.52344316, 0.5295232,
    0.5356416, 0.54179835, 0.5479935, 0.5542271, 0.56049913, 0.5668097, 0.57315886, 0.57954663,
    0.58597296, 0.59243804, 0.5989418, 0.6054843, 0.6120656, 0.6186857, 0.6253447, 0.63204265,
    0.63877946, 0.64555526, 0.6523701, 0.659224, 0.66611695, 0.6730491, 0.68002033, 0.6870308,
    0.69408053, 0.7011695, 0.7082978, 0.7154654, 0.72267246, 0.7299189, 0.7372048, 0.7445302,
    0.75189507, 0.7592996, 0.7667436, 0.7742273, 0.7817507, 0.78931373, 0.79691654, 0.8045591,
    0.8122415, 0.8199637, 0.82772577, 0.8355278, 0.8433697, 0.85125166, 0.8591736, 0.8671355,
    0.87513757, 0.8831797, 0.89126205, 0.8993845, 0.9075472, 0.91575015, 0.92399335, 0.93227684,
    0.9406007, 0.94896495, 0.95736957, 0.96581465, 0.9743002, 0.98282623, 0.99139285, 1.0);

const float kGamma22EncodeThresholds[255] = float[255](
    1.1049576e-06, 1.2388319e-05, 3.8113572e-05, 7.9902675e-05, 0.00013889262, 0.00021597801, 0.00031190403, 0.0004273133,
    0.000562773, 0.00071879255, 0.0008958351, 0.0010943264, 0.0013146607, 0.0015572055, 0.0018223056, 0.0021102862,
    0.0024214545, 0.0027561022, 0.0031145078, 0.0034969365, 0.0039036432, 0.0043348717, 0.0047908565, 0.005271824,
    0.005777993, 0.0063095735, 0.006866771, 0.0074497815, 0.0080587985, 0.008694009, 0.009355592, 0.010043725,
    0.010758582, 0.011500327, 0.012269126, 0.013065138, 0.013888518, 0.01473942, 0.015617993, 0.016524382,
    0.017458731, 0.01842118, 0.019411866, 0.020430923, 0.021478485, 0.02255468, 0.023659639, 0.024793483,
    0.02595634, 0.027148327, 0.028369563, 0.029620169, 0.030900257, 0.032209944, 0.033549335, 0.03491855,
    0.03631769, 0.037746865, 0.03920618, 0.040695738, 0.042215645, 0.043766003, 0.045346905, 0.046958458,
    0.048600752, 0.050273888, 0.051977962, 0.053713065, 0.055479288, 0.057276726, 0.05910547, 0.06096561,
    0.06285723, 0.06478042, 0.06673527, 0.06872186, 0.07074028, 0.072790615, 0.07487293, 0.07698734,
    0.0791339, 0.08131269, 0.08352381, 0.08576733, 0.08804332, 0.09035186, 0.09269302, 0.0950669,
    0.097473554, 0.09991307, 0.102385506, 0.10489095, 0.10742947, 0.11000113, 0.11260602, 0.11524419,
    0.11791572, 0.12062068, 0.12335914, 0.12613116, 0.12893683, 0.13177618, 0.1346493, 0.13755627,
    0.14049713, 0.14347196, 0.14648081, 0.14952378, 0.15260088, 0.15571222, 0.15885784, 0.1620378,
    0.16525216, 0.16850102, 0.17178439, 0.17510235, 0.17845498, 0.18184231, 0.18526441, 0.18872134,
    0.19221316, 0.19573992, 0.1993017, 0.20289855, 0.2065305, 0.21019763, 0.2139, 0.21763764,
    0.22141065, 0.22521904, 0.2290629, 0.23294225, 0.23685718, 0.24080771, 0.24479392, 0.24881586,
    0.25287357, 0.25696713, 0.26109654, 0.26526192, 0.26946324, 0.27370062, 0.2779741, 0.2822837,
    0.2866295, 0.29101154, 0.29542986, 0.29988453, 0.3043756, 0.3089031, 0.31346706, 0.31806758,
    0.3227047, 0.32737842, 0.33208886, 0.33683598, 0.3416199, 0.34644064, 0.35129827, 0.3561928,
    0.36112428, 0.3660928, 0.37109834, 0.376141, 0.38122082, 0.38633782, 0.39149204, 0.39668357,
    0.4019124, 0.4071786, 0.41248226, 0.41782334, 0.42320192, 0.42861807, 0.4340718, 0.43956316,
    0.4450922, 0.45065895, 0.45626348, 0.4619058, 0.46758598, 0.47330403, 0.47906002, 0.48485398,
    0.49068597, 0.49655598, 0.5024641, 0.5084104, 0.5143948, 0.5204175, 0.5264784, 0.53257763,
    0.53871524, 0.5448912, 0.5511055, 0.5573583, 0.56364965, 0.5699795, 0.57634795, 0.58275497,
    0.5892007, 0.5956851, 0.60220826, 0.60877013, 0.6153708, 0.6220104, 0.6286888, 0.6354062,
    0.6421625, 0.64895785, 0.6557922, 0.6626656, 0.66957814, 0.6765298, 0.68352073, 0.6905508,
    0.69762015, 0.7047288, 0.71187675, 0.71906406, 0.72629076, 0.7335569, 0.74086255, 0.7482077,
    0.7555924, 0.76301664, 0.7704805, 0.7779841, 0.7855273, 0.7931102, 0.8007329, 0.8083953,
    0.8160976, 0.8238398, 0.8316218, 0.8394438, 0.8473057, 0.8552076, 0.8631496, 0.8711316,
    0.87915367, 0.8872159, 0.89531827, 0.90346086, 0.9116437, 0.91986674, 0.9281301, 0.9364338,
    0.9447778, 0.95316225, 0.9615871, 0.9700524, 0.9785582, 0.98710454, 0.99569136);

uint encodeGamma22(float x) {
    uint lo = 0u;
    uint hi = 255u;
    for (int i = 0; i < 8; ++i) {
        uint mid = (lo + hi) >> 1u;
        if (GBL_CODEC_TABLE(kGamma22EncodeThresholds, GBL_CODEC_TABLE_GAMMA22_ENCODE, mid) <= x) lo = mid + 1u; else hi = mid;
    }
    return lo;
}

float decodeGamma22(uint code) { return GBL_CODEC_TABLE(kGamma22Decode, GBL_CODEC_TABLE_GAMMA22_DECODE, code & 255u); }

// sRGB 8-bit as HDRP writes fresnel0 (specular colour) into GBuffer2, a UNORM target, "a fast
// encode/decode sRGB to keep precision" (HDRP 13.0.0 c667268a Runtime/Material/Lit/Lit.hlsl:660-661;
// decoded at :839): FastLinearToSRGB(c) = saturate(1.055 c^0.416666667 - 0.055), sRGB's power
// segment without its linear toe (needle-mirror/com.unity.render-pipelines.core 13.0.0 6363fa25
// ShaderLibrary/Color.hlsl:166-179), and FastSRGBToLinear(x) = x (x (x 0.305306011 + 0.682171111)
// + 0.012522878), a cubic fit (:151-159), not the inverse: code 56 (F0 0.04) reads back 0.038883
// where srgb8 reads 0.039546. Encoded exactly, table based like srgb8 (HDRP's pow on a GPU is not
// correctly rounded; GPU and CPU agree here): code = round(255 FastLinearToSRGB(x)) in exact
// arithmetic, ties up, = the number of thresholds <= |x| (FastLinearToSRGB's PositivePow is
// pow(abs(x), y), core Common.hlsl:648: a negative input encodes as its magnitude, as in HDRP),
// kSrgbFastHdrpEncodeThresholds[i] = the
// smallest float >= (((i + 0.5)/255 + 0.055) / 1.055)^2.4. Below the toe (x < 0.0031308) the codes
// differ from srgb8's, by up to 3 (x = 0.001: 1 here, 3 in srgb8); above it they are srgb8's. The
// decode is the cubic in float, no contraction. Error of the round trip over [0,1]: max abs 0.0049
// (at 0.835: the cubic's own misfit plus half a code; srgb8: 0.0045).
const float kSrgbFastHdrpEncodeThresholds[255] = float[255](
    0.00090693554, 0.0010640782, 0.0012360533, 0.0014232361, 0.0016259883, 0.0018446593, 0.002079588, 0.002331102,
    0.0025995201, 0.0028851526, 0.003188301, 0.0035092595, 0.003848315, 0.0042057484, 0.004581833, 0.0049768374,
    0.0053910245, 0.005824651, 0.0062779696, 0.0067512277, 0.0072446684, 0.007758531, 0.0082930485, 0.008848454,
    0.009424971, 0.0100228265, 0.010642237, 0.011283422, 0.0119465925, 0.01263196, 0.013339732, 0.014070112,
    0.014823304, 0.015599503, 0.01639891, 0.017221717, 0.018068116, 0.018938296, 0.019832443, 0.020750746,
    0.021693384, 0.022660539, 0.023652392, 0.024669116, 0.025710888, 0.026777884, 0.027870271, 0.028988222,
    0.030131903, 0.031301484, 0.032497123, 0.03371899, 0.034967244, 0.036242045, 0.037543554, 0.03887193,
    0.04022732, 0.04160989, 0.043019786, 0.044457164, 0.045922175, 0.047414966, 0.04893569, 0.050484486,
    0.05206151, 0.0536669, 0.055300802, 0.05696336, 0.058654718, 0.060375012, 0.062124386, 0.063902974,
    0.06571092, 0.06754836, 0.06941541, 0.07131224, 0.07323896, 0.07519571, 0.07718262, 0.07919982,
    0.08124745, 0.083325624, 0.08543449, 0.08757416, 0.08974477, 0.091946445, 0.0941793, 0.09644348,
    0.098739095, 0.10106628, 0.10342514, 0.105815805, 0.10823841, 0.11069305, 0.11317987, 0.11569897,
    0.11825049, 0.12083452, 0.1234512, 0.12610064, 0.12878296, 0.13149826, 0.13424668, 0.1370283,
    0.13984329, 0.14269169, 0.14557366, 0.14848931, 0.15143874, 0.15442206, 0.1574394, 0.16049084,
    0.1635765, 0.1666965, 0.16985095, 0.17303993, 0.17626357, 0.17952198, 0.18281525, 0.1861435,
    0.18950684, 0.19290535, 0.19633916, 0.19980836, 0.20331305, 0.20685335, 0.21042934, 0.21404114,
    0.21768886, 0.22137257, 0.2250924, 0.22884843, 0.23264077, 0.23646952, 0.24033478, 0.24423665,
    0.24817522, 0.2521506, 0.25616285, 0.26021212, 0.2642985, 0.26842204, 0.2725829, 0.2767811,
    0.28101683, 0.2852901, 0.28960103, 0.29394975, 0.2983363, 0.3027608, 0.30722338, 0.31172407,
    0.31626296, 0.3208402, 0.32545584, 0.33011, 0.33480275, 0.3395342, 0.34430438, 0.34911346,
    0.3539615, 0.35884857, 0.3637748, 0.36874023, 0.373745, 0.37878916, 0.38387278, 0.388996,
    0.3941589, 0.39936155, 0.40460402, 0.40988642, 0.41520885, 0.42057136, 0.42597407, 0.43141705,
    0.43690038, 0.44242412, 0.44798842, 0.45359334, 0.45923892, 0.46492532, 0.47065255, 0.47642073,
    0.48222995, 0.48808026, 0.49397177, 0.49990457, 0.50587875, 0.51189435, 0.5179514, 0.5240502,
    0.5301906, 0.5363727, 0.54259676, 0.5488627, 0.55517066, 0.5615207, 0.56791294, 0.5743474,
    0.58082414, 0.58734334, 0.59390503, 0.6005093, 0.60715616, 0.61384577, 0.62057817, 0.6273534,
    0.63417166, 0.64103293, 0.6479373, 0.6548849, 0.66187567, 0.66890985, 0.6759874, 0.68310845,
    0.6902731, 0.6974814, 0.7047334, 0.71202916, 0.7193689, 0.72675246, 0.7341801, 0.74165183,
    0.74916774, 0.7567279, 0.7643323, 0.7719812, 0.7796745, 0.78741235, 0.7951948, 0.8030219,
    0.81089383, 0.8188106, 0.8267722, 0.83477885, 0.84283054, 0.8509273, 0.8590693, 0.8672565,
    0.8754891, 0.8837671, 0.89209056, 0.9004596, 0.9088742, 0.91733456, 0.9258407, 0.9343926,
    0.9429904, 0.9516342, 0.96032405, 0.96906, 0.97784215, 0.98667055, 0.99554527);

uint encodeSrgb8FastHdrp(float x) {
    float a = abs(x);
    uint lo = 0u;
    uint hi = 255u;
    for (int i = 0; i < 8; ++i) {
        uint mid = (lo + hi) >> 1u;
        if (GBL_CODEC_TABLE(kSrgbFastHdrpEncodeThresholds, GBL_CODEC_TABLE_SRGB_FAST_HDRP_ENCODE, mid) <= a) lo = mid + 1u; else hi = mid;
    }
    return lo;
}

float decodeSrgb8FastHdrp(uint code) {
    precise float c = dequantizeUnorm(code & 255u, 8u);
    precise float l = c * (c * (c * 0.305306011 + 0.682171111) + 0.012522878);
    return l;
}

// HDRP's GBuffer3 (B10G11R11_UFLOAT) with its AO tag. EncodeIntoGBuffer writes
// (bakeDiffuseLighting * AO + emissive) * exposure there, and where that is exactly (0, 0, 0) it
// writes AO_IN_GBUFFER3_TAG instead: r = 2048, g = surfaceData.ambientOcclusion, b = 1024; its
// DecodeFromGBuffer reads AO from g where r, b hold (2048, 1024), else emissive (and AO = 1)
// (HDRP 13.0.0 c667268a Runtime/Material/Lit/Lit.hlsl:686-705, 944-953; the same at
// Unity-Technologies/Graphics 1390609c). gbufferlab bakes nothing and its exposure is 1, so the
// test is on emissive alone. The tag's codes: 2048 = 2^11 is float11 exponent 11 + 15 = 26,
// mantissa 0: 26 << 6 = 0x680; 1024 = 2^10 is float10 exponent 25: 25 << 5 = 0x320. With r in
// bits 0..10, g in 11..21, b in 22..31 the word is 0xC8000680 | encodeFloat11(AO) << 11 (AO 1:
// 0xC81E0680; AO 0: 0xC8000680). An emissive whose codes are (2048, g, 1024) reads as a tag, as in
// HDRP (its comment: "Random TAG which we expect will never match provided emissive"). Error: as
// float11_11_10 for emissive; occlusion float11 (6-bit mantissa: 2^-7 relative, 2^-20 absolute
// below 2^-14), and occlusion reads 1 on emissive pixels.
const uint kHdrpAoTagR = 0x680u;  // encodeFloat11(2048.0)
const uint kHdrpAoTagB = 0x320u;  // encodeFloat10(1024.0)

uvec3 encodeFloat111110HdrpAoTag(vec3 e, float ao) {
    if (e.x == 0.0 && e.y == 0.0 && e.z == 0.0) return uvec3(kHdrpAoTagR, encodeFloat11(ao), kHdrpAoTagB);
    return uvec3(encodeFloat11(e.x), encodeFloat11(e.y), encodeFloat10(e.z));
}

bool isHdrpAoTag(uvec3 code) { return (code.x & 2047u) == kHdrpAoTagR && (code.z & 1023u) == kHdrpAoTagB; }

vec3 decodeFloat111110HdrpAoTag(uvec3 code) {
    if (isHdrpAoTag(code)) return vec3(0.0);
    return vec3(decodeFloat11(code.x), decodeFloat11(code.y), decodeFloat10(code.z));
}

float decodeHdrpAoTagOcclusion(uvec3 code) { return isHdrpAoTag(code) ? decodeFloat11(code.y) : 1.0; }

// Octahedral normals stored as two unorm codes of u = p * 0.5 + 0.5, p the octahedral point in
// [-1,1]^2, each engine's float arithmetic written out in its order (the engines' code is not
// copied; float32, no contraction), decoded by decodeNormalOctahedralUnorm (code / (2^bits - 1),
// unfolded as Cigolle et al. 2014; Bevy's octahedral_decode, Unity's UnpackNormalOctQuadEncode and
// niagara's decodeOct write the same unfold otherwise, so their directions agree up to rounding).
// tests/encoding/engine_packings_test.cpp holds each to a reimplementation from the engine's source.
//
// Bevy (bevyengine/bevy v0.16.0 e9418b38, the same since v0.12.0 bf30a25e):
//   octahedral_encode, crates/bevy_pbr/src/render/utils.wgsl:48-53: n / |n|_1 (divided), the
//   lower hemisphere (n.z < 0; -0 is kept) wrapped to (1 - |n.y|, 1 - |n.x|) times
//   select(-1, 1, n.xy > 0): a zero component wraps to -1 (octEncode's signNotZero gives +1,
//   so (0, 0, -1) is codes (0, 0) here, (2^b - 1, 2^b - 1) there); then n_xy * 0.5 + 0.5.
//   pack_24bit_normal_and_flags, crates/bevy_pbr/src/deferred/pbr_deferred_types.wgsl:39-43:
//   u32(saturate(u) * 4095 + 0.5), ROUNDED (= quantizeUnorm at 12 bits), u in bits 0-11, v in
//   12-23, flags in 24-31. (An unreleased commit of the PR, 08303b7a, truncated; 84c2913f,
//   before the merge, added the + 0.5.)
// Unity (needle-mirror/com.unity.render-pipelines.core 13.0.0 6363fa25, ShaderLibrary/Packing.hlsl):
//   PackNormalOctQuadEncode (:57-69): n *= rcp(|n.x| + |n.y| + |n.z|) (a multiply by the
//   reciprocal), t = saturate(-n.z), p = n.xy + (n.xy >= 0 ? t : -t); PackFloat2To888 (:543-552):
//   (uint2)(saturate(p * 0.5 + 0.5) * 4095.5), TRUNCATED, low bytes in R and G, the high nibbles
//   in B (u's low, v's high). URP's accurate G-buffer normals (com.unity.render-pipelines.universal
//   13.0.0 830d6315, ShaderLibrary/UnityGBuffer.hlsl:94-99, PackNormal) use exactly this.
// HDRP (needle-mirror/com.unity.render-pipelines.high-definition 13.0.0 c667268a,
//   Runtime/Material/NormalBuffer.hlsl:27-33, EncodeIntoNormalBuffer): first
//   n.z = CopySign(max(1/1024, |n.z|), n.z) (core Common.hlsl:697-702: -0 counts as +), n not
//   renormalised, then Unity's encoding: normals within 1/1024 of the equator move off it, e.g.
//   (0, 1, 0) is (2047, 4093) here and (2047, 4095) in URP's.
// Error (angle, mean / max, 12 bits, 300000 random normals; engine_encodings_test): Bevy (rounding)
// 0.021 / 0.058 deg, as normal_octahedral; Unity (truncation: up to a whole step in each of u, v)
// 0.029 / 0.105; HDRP as Unity, and max 0.113 within 1/1024 of the equator (the clamp's own shift
// of up to 1/1024 rad, partly cancelled).
vec2 octEncodeBevy(vec3 n) {
    precise float l1 = abs(n.x) + abs(n.y) + abs(n.z);
    precise float x = n.x / l1;
    precise float y = n.y / l1;
    precise float z = n.z / l1;
    float sx = x > 0.0 ? 1.0 : -1.0;
    float sy = y > 0.0 ? 1.0 : -1.0;
    precise vec2 wrap = vec2((1.0 - abs(y)) * sx, (1.0 - abs(x)) * sy);
    return z >= 0.0 ? vec2(x, y) : wrap;
}

uvec2 encodeNormalOctahedralBevy(vec3 n, uint bits) {
    vec2 p = octEncodeBevy(n);
    precise float ux = p.x * 0.5 + 0.5;
    precise float uy = p.y * 0.5 + 0.5;
    return uvec2(quantizeUnorm(ux, bits), quantizeUnorm(uy, bits));
}

vec2 octEncodeUnity(vec3 n) {
    precise float r = 1.0 / (abs(n.x) + abs(n.y) + abs(n.z));
    precise float x = n.x * r;
    precise float y = n.y * r;
    precise float z = n.z * r;
    precise float t = clamp(-z, 0.0, 1.0);
    precise vec2 p = vec2(x + (x >= 0.0 ? t : -t), y + (y >= 0.0 ? t : -t));
    return p;
}

uvec2 encodeNormalOctahedralUnity(vec3 n, uint bits) {
    vec2 p = octEncodeUnity(n);
    precise float s = float((1u << bits) - 1u) + 0.5;
    precise float ux = clamp(p.x * 0.5 + 0.5, 0.0, 1.0);
    precise float uy = clamp(p.y * 0.5 + 0.5, 0.0, 1.0);
    precise float qx = floor(ux * s);
    precise float qy = floor(uy * s);
    return min(uvec2(uint(qx), uint(qy)), uvec2((1u << bits) - 1u));
}

uvec2 encodeNormalOctahedralHdrp(vec3 n, uint bits) {
    float az = max(1.0 / 1024.0, abs(n.z));
    float z = n.z >= 0.0 ? az : -az;
    return encodeNormalOctahedralUnity(vec3(n.x, n.y, z), bits);
}

vec3 decodeNormalOctahedralUnorm(uvec2 code, uint bits) {
    vec2 u = vec2(dequantizeUnorm(code.x, bits), dequantizeUnorm(code.y, bits));
    return normalize(octDecode(u * 2.0 - 1.0));
}

// encodeNormalXyFloat16: view-space x, y as two IEEE half floats, z = +sqrt(1 - x^2 - y^2) on
// decode (no sign bit: a view-space normal of a visible surface faces the camera, +z here).
// Killzone 2 (Valient, "Deferred Rendering in Killzone 2", Develop 2007): RT1 holds the view-space
// normal's X and Y as FP16. Error: float16's 2^-11 relative in x, y; normals facing away from the
// camera (z < 0, e.g. bent by normal maps at silhouettes) come back mirrored to z > 0.
uvec2 encodeNormalXyFloat16(vec3 n) { return uvec2(encodeFloat16(n.x), encodeFloat16(n.y)); }

vec3 decodeNormalXyFloat16(uvec2 code) {
    float x = decodeFloat16(code.x);
    float y = decodeFloat16(code.y);
    float z = sqrt(max(0.0, 1.0 - x * x - y * y));
    return normalize(vec3(x, y, z));
}

#endif  // GBL_ENGINE_ENCODINGS_GLSL
