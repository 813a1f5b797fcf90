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

// kz2_log_power: Killzone 2's specular power (RT2.b), "stored as log2(original)/10.5" (Valient,
// "Deferred Rendering in Killzone 2", Develop 2007, the G-buffer slides' notes): an 8-bit unorm g
// read as the Blinn-Phong power n = 2^(10.5 g), 1 (g = 0) to 2^10.5 = 1448.15 (g = 1). The talk
// gives no conversion to a microfacet roughness; gbufferlab's is cry_gloss_power's (Walter et al.
// 2007, n = 2/alpha^2 - 2 with alpha = roughness^2): roughness = (2 / (n + 2))^(1/4), so code 0
// decodes to 0.90360200 (n = 1) and code 255 to 0.19270985 (n = 1448.15); roughness outside
// [0.1927, 0.9036] clamps to those ends, and inside the round trip's error is at most 0.0019 (half
// a code; measured over 10^6 roughnesses). Table based and exact like cry_gloss_power:
// kKz2PowerRoughness[k] = float(roughness(k/255)), kKz2PowerEncodeThresholds[i] = the largest
// float <= roughness((i + 0.5)/255) (both in double; they decrease with i), so the code = the
// number of thresholds >= roughness = round(255 log2(2/roughness^4 - 2) / 10.5), ties up, exactly.
// tests/encoding/engine_encodings_test.cpp (Kz2LogPower.TablesMatchTheMapping) recomputes them.
const float kKz2PowerRoughness[256] = float[256](
    0.903602, 0.9014349, 0.899232, 0.89699304, 0.8947181, 0.8924071, 0.89006, 0.8876769,
    0.88525766, 0.8828024, 0.88031125, 0.87778425, 0.8752215, 0.87262315, 0.86998934, 0.86732024,
    0.8646161, 0.8618771, 0.8591035, 0.8562956, 0.85345364, 0.850578, 0.84766895, 0.8447269,
    0.84175223, 0.83874536, 0.83570665, 0.8326366, 0.82953566, 0.82640433, 0.8232431, 0.82005244,
    0.81683296, 0.81358516, 0.8103097, 0.8070071, 0.803678, 0.800323, 0.7969427, 0.79353786,
    0.790109, 0.78665686, 0.78318214, 0.7796855, 0.77616763, 0.77262926, 0.7690711, 0.76549387,
    0.7618983, 0.75828505, 0.754655, 0.75100875, 0.7473472, 0.7436709, 0.73998076, 0.7362774,
    0.73256165, 0.72883415, 0.72509575, 0.72134715, 0.7175891, 0.71382225, 0.7100474, 0.7062653,
    0.7024765, 0.6986819, 0.69488204, 0.69107777, 0.6872696, 0.6834583, 0.6796446, 0.675829,
    0.67201227, 0.66819495, 0.66437775, 0.66056126, 0.6567461, 0.6529328, 0.649122, 0.6453142,
    0.64151007, 0.6377101, 0.6339148, 0.6301247, 0.6263403, 0.62256217, 0.61879075, 0.6150265,
    0.61126983, 0.6075213, 0.6037812, 0.60005015, 0.5963284, 0.5926164, 0.5889146, 0.5852232,
    0.58154273, 0.5778735, 0.5742158, 0.57057005, 0.5669365, 0.5633154, 0.55970716, 0.556112,
    0.55253017, 0.548962, 0.54540765, 0.54186743, 0.5383416, 0.5348303, 0.53133374, 0.5278522,
    0.5243858, 0.52093476, 0.51749927, 0.5140794, 0.51067543, 0.50728744, 0.50391555, 0.5005599,
    0.49722072, 0.493898, 0.49059188, 0.4873025, 0.48402992, 0.48077425, 0.47753555, 0.47431388,
    0.4711094, 0.46792203, 0.46475196, 0.46159914, 0.4584637, 0.45534563, 0.45224497, 0.44916177,
    0.44609603, 0.4430478, 0.44001704, 0.43700385, 0.43400815, 0.43103, 0.42806938, 0.42512628,
    0.4222007, 0.41929263, 0.41640204, 0.41352895, 0.41067326, 0.40783504, 0.4050142, 0.4022107,
    0.39942458, 0.39665574, 0.39390415, 0.3911698, 0.38845256, 0.3857525, 0.38306952, 0.38040355,
    0.37775454, 0.3751225, 0.37250727, 0.36990887, 0.36732724, 0.36476228, 0.36221397, 0.3596822,
    0.35716695, 0.3546681, 0.35218567, 0.3497195, 0.34726954, 0.34483576, 0.34241807, 0.3400164,
    0.33763063, 0.33526075, 0.33290666, 0.33056828, 0.32824552, 0.32593834, 0.32364663, 0.32137033,
    0.31910935, 0.31686363, 0.31463304, 0.31241757, 0.31021708, 0.30803153, 0.30586082, 0.30370486,
    0.3015636, 0.29943693, 0.29732475, 0.29522702, 0.29314363, 0.2910745, 0.28901958, 0.28697878,
    0.28495196, 0.2829391, 0.2809401, 0.27895483, 0.2769833, 0.27502534, 0.27308092, 0.27114993,
    0.2692323, 0.26732796, 0.26543683, 0.26355878, 0.26169378, 0.2598417, 0.25800255, 0.25617614,
    0.25436243, 0.2525614, 0.25077286, 0.24899681, 0.24723314, 0.24548177, 0.24374264, 0.24201566,
    0.24030074, 0.23859781, 0.2369068, 0.23522761, 0.23356019, 0.23190445, 0.2302603, 0.22862768,
    0.22700652, 0.22539672, 0.22379823, 0.22221096, 0.22063483, 0.2190698, 0.21751574, 0.21597262,
    0.21444035, 0.21291886, 0.21140808, 0.20990792, 0.20841834, 0.20693924, 0.20547056, 0.20401224,
    0.2025642, 0.20112635, 0.19969866, 0.19828103, 0.1968734, 0.19547571, 0.19408788, 0.19270985);

const float kKz2PowerEncodeThresholds[255] = float[255](
    0.9025229, 0.90033793, 0.898117, 0.8958601, 0.8935671, 0.89123803, 0.8888729, 0.88647175,
    0.8840345, 0.88156134, 0.8790522, 0.8765073, 0.8739267, 0.8713106, 0.86865914, 0.8659725,
    0.8632509, 0.86049455, 0.85770375, 0.8548788, 0.85201997, 0.8491276, 0.846202, 0.8432436,
    0.84025276, 0.8372299, 0.8341755, 0.8310899, 0.8279737, 0.8248274, 0.82165134, 0.8184462,
    0.81521255, 0.8119508, 0.8086617, 0.8053458, 0.8020037, 0.79863596, 0.79524326, 0.7918263,
    0.78838575, 0.78492224, 0.78143644, 0.7779291, 0.77440095, 0.77085257, 0.76728475, 0.7636983,
    0.7600938, 0.75647205, 0.75283384, 0.74917984, 0.7455108, 0.7418275, 0.7381306, 0.73442096,
    0.7306993, 0.72696626, 0.7232227, 0.71946925, 0.7157067, 0.71193576, 0.7081572, 0.70437163,
    0.7005799, 0.6967825, 0.6929804, 0.68917406, 0.6853643, 0.6815517, 0.67773694, 0.6739207,
    0.6701036, 0.6662863, 0.6624694, 0.65865344, 0.65483916, 0.651027, 0.6472177, 0.64341164,
    0.6396095, 0.6358118, 0.63201904, 0.62823176, 0.62445045, 0.62067556, 0.61690766, 0.61314714,
    0.6093945, 0.6056501, 0.6019145, 0.59818804, 0.59447116, 0.59076416, 0.58706754, 0.5833816,
    0.57970667, 0.5760432, 0.5723914, 0.5687517, 0.56512433, 0.5615096, 0.5579079, 0.5543194,
    0.55074435, 0.54718304, 0.5436357, 0.54010266, 0.5365841, 0.53308016, 0.5295911, 0.5261171,
    0.52265835, 0.51921505, 0.5157873, 0.5123754, 0.5089794, 0.50559944, 0.50223565, 0.49888825,
    0.49555728, 0.49224284, 0.4889451, 0.4856641, 0.48239997, 0.47915277, 0.47592258, 0.47270948,
    0.46951354, 0.46633482, 0.46317336, 0.46002924, 0.45690247, 0.4537931, 0.45070118, 0.44762668,
    0.4445697, 0.44153023, 0.43850824, 0.43550378, 0.43251687, 0.4295475, 0.42659563, 0.4236613,
    0.42074448, 0.41784513, 0.4149633, 0.4120989, 0.40925196, 0.40642244, 0.4036103, 0.4008155,
    0.398038, 0.39527777, 0.3925348, 0.389809, 0.3871004, 0.38440886, 0.38173437, 0.3790769,
    0.37643638, 0.37381276, 0.37120596, 0.36861596, 0.36604267, 0.36348605, 0.360946, 0.3584225,
    0.35591546, 0.35342482, 0.3509505, 0.34849247, 0.34605062, 0.3436249, 0.34121522, 0.3388215,
    0.3364437, 0.3340817, 0.3317355, 0.32940495, 0.32709, 0.32479054, 0.32250655, 0.32023793,
    0.31798458, 0.31574643, 0.3135234, 0.31131545, 0.30912244, 0.3069443, 0.304781, 0.3026324,
    0.30049843, 0.298379, 0.29627407, 0.29418352, 0.29210728, 0.2900453, 0.28799742, 0.2859636,
    0.28394377, 0.28193784, 0.27994573, 0.27796733, 0.27600262, 0.27405143, 0.27211374, 0.27018943,
    0.26827848, 0.26638073, 0.26449615, 0.26262465, 0.26076612, 0.25892052, 0.25708774, 0.25526768,
    0.25346032, 0.25166553, 0.24988328, 0.24811342, 0.24635592, 0.24461068, 0.24287763, 0.24115668,
    0.23944777, 0.23775081, 0.23606573, 0.23439243, 0.23273085, 0.23108092, 0.22944255, 0.22781567,
    0.2262002, 0.22459607, 0.2230032, 0.22142151, 0.21985093, 0.21829139, 0.21674281, 0.21520512,
    0.21367826, 0.21216212, 0.21065666, 0.2091618, 0.20767747, 0.2062036, 0.2047401, 0.20328693,
    0.20184399, 0.20041123, 0.19898859, 0.19757596, 0.19617331, 0.19478056, 0.19339764);

uint encodeKz2LogPower(float r) {
    uint lo = 0u;
    uint hi = 255u;
    for (int i = 0; i < 8; ++i) {
        uint mid = (lo + hi) >> 1u;
        if (GBL_CODEC_TABLE(kKz2PowerEncodeThresholds, GBL_CODEC_TABLE_KZ2_POWER_ENCODE, mid) >= r) lo = mid + 1u; else hi = mid;
    }
    return lo;
}

float decodeKz2LogPower(uint code) { return GBL_CODEC_TABLE(kKz2PowerRoughness, GBL_CODEC_TABLE_KZ2_POWER_DECODE, code & 255u); }

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

// ---------------------------------------------------------------------------------------------
// Material layers as the engines store them (issue 40; layouts/README.md, "Codes of each encoding").
// ---------------------------------------------------------------------------------------------

// unorm_round_even: saturate(x) * (2^bits - 1) rounded to the nearest code with ties to even, as
// WGSL's round() does: Bevy 0.19's clear-coat strength, u32(round(saturate(clearcoat) * 15.0))
// (bevyengine/bevy v0.19.0 c6f634ca, crates/bevy_pbr/src/deferred/pbr_deferred_functions.wgsl:42;
// pull request 23359). quantizeUnorm rounds ties up: 0.3 * 15 = 4.5 is code 4 here, 5 there.
// Decoded as unorm, code / (2^bits - 1) (:115). Error <= half a step.
uint quantizeUnormRoundEven(float x, uint bits) {
    precise float s = float((1u << bits) - 1u);
    precise float q = roundEven(clamp(x, 0.0, 1.0) * s);
    return min(uint(q), (1u << bits) - 1u);
}

// coat_roughness_bevy: Bevy 0.19's clear-coat perceptual roughness, clamped to [0, 0.5] and
// spread over the codes: u32(round(clamp(r, 0.0, 0.5) * 30.0)) at 4 bits (30 = 2 (2^4 - 1)), ties
// to even (pbr_deferred_functions.wgsl:43-44); read back f32(code) / 30.0 (:116). A coat rougher
// than 0.5 reads 0.5 ("greater than 0.5 and the specular lobe is so diffuse, you can't tell it's
// there", the pull request). Error inside [0, 0.5] <= half a step, 1/60 at 4 bits.
uint encodeCoatRoughnessBevy(float r, uint bits) {
    precise float s = float(((1u << bits) - 1u) * 2u);
    precise float q = roundEven(clamp(r, 0.0, 0.5) * s);
    return min(uint(q), (1u << bits) - 1u);
}

float decodeCoatRoughnessBevy(uint code, uint bits) { return float(code) / float(((1u << bits) - 1u) * 2u); }

// unorm_signed: x in [-1, 1] stored as the unorm of x * 0.5 + 0.5 and read back code / (2^bits - 1)
// * 2 - 1: UE's EncodeWorldTangentAndAnisotropy, Anisotropy * 0.5 + 0.5 into GBufferF.a, and its
// read InGBufferF.a * 2 - 1 (UE 5.3.2, DeferredShadingCommon.ush:222-228, 1018). x * 0.5 is exact,
// so a fused multiply-add gives the same code. 0 has no code of its own: it reads 1 / (2^bits - 1).
uint quantizeUnormSigned(float x, uint bits) { return quantizeUnorm(x * 0.5 + 0.5, bits); }

float dequantizeUnormSigned(uint code, uint bits) { return dequantizeUnorm(code, bits) * 2.0 - 1.0; }

// unorm_sqrt (8 bits): UE's EncodeSubsurfaceColor, sqrt(saturate(c)) into a UNORM byte, read back
// Square(CustomData.rgb) by ExtractSubsurfaceColor (UE 5.3.2 DeferredShadingCommon.ush:189-192,
// 1031-1034): the Cloth model's fuzz colour (ShadingModelsMaterial.ush:133-139). The code is
// round(255 sqrt(x)), found as the number of thresholds <= x, kUnormSqrtEncodeThresholds[k] = the
// smallest float >= ((k + 0.5) / 255)^2, exact (GLSL leaves sqrt's precision to the driver; the
// table keeps GPU and CPU to the bit). Error: half a code in sqrt(x), times 2 sqrt(x): <= 1/255.
const float kUnormSqrtEncodeThresholds[255] = float[255](
    3.8446756e-06, 3.460208e-05, 9.6116884e-05, 0.0001883891, 0.0003114187, 0.0004652057, 0.0006497501, 0.00086505193,
    0.0011111111, 0.0013879278, 0.0016955017, 0.0020338332, 0.0024029221, 0.0028027683, 0.003233372, 0.003694733,
    0.0041868514, 0.004709727, 0.0052633607, 0.005847751, 0.006462899, 0.007108805, 0.0077854674, 0.008492888,
    0.009231065, 0.010000001, 0.010799693, 0.011630143, 0.01249135, 0.013383315, 0.014306037, 0.015259516,
    0.016243754, 0.017258748, 0.018304499, 0.019381009, 0.020488275, 0.0216263, 0.02279508, 0.023994619,
    0.025224915, 0.026485968, 0.027777778, 0.029100347, 0.030453673, 0.031837758, 0.033252597, 0.034698196,
    0.03617455, 0.03768166, 0.039219532, 0.04078816, 0.042387545, 0.044017687, 0.045678586, 0.047370244,
    0.049092658, 0.05084583, 0.05262976, 0.054444447, 0.05628989, 0.05816609, 0.06007305, 0.06201077,
    0.063979246, 0.065978475, 0.06800846, 0.07006921, 0.07216071, 0.074282974, 0.07643599, 0.07861976,
    0.0808343, 0.08307959, 0.08535564, 0.08766244, 0.09, 0.09236833, 0.0947674, 0.097197235,
    0.099657826, 0.10214917, 0.104671285, 0.10722415, 0.10980777, 0.112422146, 0.11506729, 0.11774318,
    0.12044983, 0.12318724, 0.1259554, 0.12875433, 0.13158402, 0.13444445, 0.13733564, 0.1402576,
    0.1432103, 0.14619377, 0.14920801, 0.15225299, 0.15532872, 0.15843523, 0.16157249, 0.16474049,
    0.16793926, 0.17116879, 0.17442907, 0.17772011, 0.18104191, 0.18439446, 0.18777779, 0.19119185,
    0.19463669, 0.19811228, 0.20161861, 0.20515572, 0.20872357, 0.21232219, 0.21595156, 0.21961169,
    0.22330259, 0.22702423, 0.23077664, 0.23455979, 0.23837371, 0.24221839, 0.24609382, 0.25,
    0.25393698, 0.25790468, 0.26190314, 0.26593235, 0.26999232, 0.27408305, 0.27820456, 0.2823568,
    0.2865398, 0.29075357, 0.29499808, 0.29927337, 0.30357942, 0.3079162, 0.31228375, 0.31668207,
    0.3211111, 0.32557094, 0.33006153, 0.33458287, 0.33913496, 0.3437178, 0.34833142, 0.3529758,
    0.3576509, 0.3623568, 0.36709344, 0.37186083, 0.376659, 0.3814879, 0.38634756, 0.391238,
    0.39615917, 0.40111113, 0.40609384, 0.41110727, 0.4161515, 0.42122647, 0.4263322, 0.4314687,
    0.4366359, 0.4418339, 0.44706267, 0.45232219, 0.45761248, 0.4629335, 0.4682853, 0.47366783,
    0.47908112, 0.4845252, 0.49, 0.4955056, 0.50104195, 0.506609, 0.51220685, 0.5178355,
    0.52349484, 0.52918494, 0.53490585, 0.54065746, 0.5464399, 0.552253, 0.55809695, 0.5639716,
    0.569877, 0.5758132, 0.58178014, 0.5877778, 0.59380627, 0.59986544, 0.6059554, 0.61207616,
    0.61822766, 0.62440985, 0.63062286, 0.6368666, 0.64314115, 0.64944637, 0.6557824, 0.6621492,
    0.66854674, 0.67497504, 0.6814341, 0.6879239, 0.6944445, 0.7009958, 0.7075779, 0.7141907,
    0.7208343, 0.72750866, 0.73421377, 0.7409497, 0.7477163, 0.7545137, 0.7613418, 0.7682007,
    0.7750904, 0.7820108, 0.78896195, 0.7959439, 0.8029566, 0.81, 0.81707424, 0.8241792,
    0.8313149, 0.83848137, 0.8456786, 0.8529066, 0.86016536, 0.8674548, 0.8747751, 0.88212615,
    0.8895079, 0.89692044, 0.90436375, 0.91183776, 0.9193426, 0.92687815, 0.9344445, 0.9420416,
    0.94966936, 0.95732796, 0.9650173, 0.97273743, 0.9804883, 0.9882699, 0.9960823
);

uint encodeUnormSqrt(float x) {
    uint lo = 0u;
    uint hi = 255u;
    for (int i = 0; i < 8; ++i) {
        uint mid = (lo + hi) >> 1u;
        if (kUnormSqrtEncodeThresholds[mid] <= x) lo = mid + 1u; else hi = mid;
    }
    return lo;
}

float decodeUnormSqrt(uint code) {
    precise float d = dequantizeUnorm(code & 255u, 8u);
    precise float s = d * d;
    return s;
}

// UE's clear-coat bottom normal (CLEAR_COAT_BOTTOM_NORMAL, r.ClearCoatNormal = 1): GBufferA holds
// the top (coat) normal, CustomData.a and .z the octahedral delta of the bottom normal,
// (oct(bottom) - oct(top)) * 0.25 + 128/255 (ShadingModelsMaterial.ush:96-116), read back as
// oct = code / (2^bits - 1) * 4 - 512/255 + oct(top) and unfolded (ClearCoatCommon.ush:5-14).
// UE's octahedron (OctahedralCommon.ush:18-34): n.xy / |n|_1, folded where n.z <= 0 with
// select(n.xy >= 0, 1, -1); the unfold subtracts t = max(-z, 0) towards zero, then normalises.
// A zero vector folds from (0, 0) (engine_encodings.h's twin says why).
vec2 octEncodeUe(vec3 n) {
    precise float l1 = abs(n.x) + abs(n.y) + abs(n.z);
    precise float x = l1 > 0.0 ? n.x / l1 : 0.0;
    precise float y = l1 > 0.0 ? n.y / l1 : 0.0;
    if (n.z <= 0.0) {
        precise float fx = (1.0 - abs(y)) * (x >= 0.0 ? 1.0 : -1.0);
        precise float fy = (1.0 - abs(x)) * (y >= 0.0 ? 1.0 : -1.0);
        return vec2(fx, fy);
    }
    return vec2(x, y);
}

vec3 octDecodeUe(vec2 o) {
    precise vec3 n = vec3(o.x, o.y, 1.0 - abs(o.x) - abs(o.y));
    precise float t = max(-n.z, 0.0);
    n.x += n.x >= 0.0 ? -t : t;
    n.y += n.y >= 0.0 ? -t : t;
    return normalize(n);
}

uvec2 encodeNormalOctahedralDeltaUe(vec3 bottom, vec3 top, uint bits) {
    vec2 o1 = octEncodeUe(bottom);
    vec2 o2 = octEncodeUe(top);
    precise float dx = (o1.x - o2.x) * 0.25 + 128.0 / 255.0;
    precise float dy = (o1.y - o2.y) * 0.25 + 128.0 / 255.0;
    return uvec2(quantizeUnorm(dx, bits), quantizeUnorm(dy, bits));
}

vec3 decodeNormalOctahedralDeltaUe(uvec2 code, vec3 top, uint bits) {
    vec2 o2 = octEncodeUe(top);
    precise float ox = (dequantizeUnorm(code.x, bits) * 4.0 - 512.0 / 255.0) + o2.x;
    precise float oy = (dequantizeUnorm(code.y, bits) * 4.0 - 512.0 / 255.0) + o2.y;
    return octDecodeUe(vec2(ox, oy));
}

#endif  // GBL_ENGINE_ENCODINGS_GLSL

// anisotropy_angle_hdrp: HDRP Lit's anisotropic feature in GBuffer2.rgb (HDRP 13.0.0
// c667268a, Runtime/Material/Lit/Lit.hlsl:575-634 encode, :880-905 decode; core 13.0.0 6363fa25
// ShaderLibrary/CommonLighting.hlsl:442-459 GetLocalFrame, Common.hlsl:738 Remap01, :697-702, 722-725
// FastSign, Packing.hlsl:437-470 PackFloatInt). The tangent t is stored as its angle to the x axis
// of GetLocalFrame(normal), folded into the first quadrant, and the signed anisotropy absorbs the
// fold: AnisoGGX(a, b, g) == AnisoGGX(b, a, g + pi/2) (Lit.hlsl:585-596), so in the 2nd and 4th
// quadrants the stored anisotropy is 255 - round(a * 127.5 + 127.5), i.e. negated. Codes:
//   x  GBuffer2.g: Remap01(min(|sin|, |cos|), sqrt(2) 256/255, 0.5/255), written UNORM (quantizeUnorm)
//   y  GBuffer2.r: round(a * 127.5 + 127.5), HLSL round = ties to even (roundEven), 255 - it in Q2/Q4
//   z  GBuffer2.b bit 5: storeSin = (|sin| < |cos|) != quad2or4 (PackFloatInt8bit(metallic, storeSin,
//      8): the metallic is the layout's own 5-bit field in b[0:4])
// The encoder reads the unquantised normal (HDRP: surfaceData.normalWS), the decoder the decoded
// one (bsdfData.normalWS, Lit.hlsl:820). Constants are evaluated in float (HLSL folds its
// literals at compile time; that precision was not established: a tie could move by one code).
// Dot products are written out, unfused ((x + y) + z). The decode hands gbufferlab's attributes
// back canonically: strength |a| >= 0, and where a < 0 the direction is HDRP's bitangent
// cross(n, t) (Lit.hlsl:902: frame[1]), the axis the lobe is stretched along; the sign of the axis
// is immaterial to the anisotropic GGX and to the direction metric (an angle between lines).
// tests/encoding/layer_packings_test.cpp holds it to HDRP's arithmetic.
// GetLocalFrame's rows x, y (z is n): sz = FastSign(z) with -0 as +1, a = 1 / (sz + z).
void hdrpLocalFrame(vec3 n, out vec3 fx, out vec3 fy) {
    float sz = n.z >= 0.0 ? 1.0 : -1.0;
    precise float a = 1.0 / (sz + n.z);
    precise float ya = n.y * a;
    precise float b = n.x * ya;
    precise float c = n.x * sz;
    precise vec3 x = vec3(c * n.x * a - 1.0, sz * b, c);
    precise vec3 y = vec3(b, n.y * ya - sz, n.y);
    fx = x;
    fy = y;
}

// Constants as float evaluates them step by step (written out: a GLSL compiler may fold its own
// expressions more precisely), the C++ twin's constexpr values:
const float kHdrpAngleScale = 1.41975951;     // float(sqrt(2)) * 256 / 255, Remap01's rcpLength
const float kHdrpAngleStart = 0.00196078443;  // 0.5 / 255, startTimesRcpLength
const float kHdrpAngleBias = 0.00138106791;   // 0.5 / 256 * float(rsqrt(2)) (Lit.hlsl:894)
const float kHdrpAngleStep = 0.70434463;      // 255 / 256 * float(rsqrt(2))

uvec3 encodeAnisotropyHdrp(vec3 t, float anisotropy, vec3 n) {
    vec3 fx, fy;
    hdrpLocalFrame(n, fx, fy);
    precise float sinFrame = t.x * fy.x + t.y * fy.y + t.z * fy.z;
    precise float cosFrame = t.x * fx.x + t.y * fx.y + t.z * fx.z;
    precise float product = sinFrame * cosFrame;
    bool quad2or4 = product < 0.0;
    precise float u = roundEven(clamp(anisotropy, -1.0, 1.0) * 127.5 + 127.5);
    uint strength = quad2or4 ? 255u - uint(u) : uint(u);
    bool storeSin = (abs(sinFrame) < abs(cosFrame)) != quad2or4;
    float sinOrCos = min(abs(sinFrame), abs(cosFrame));
    precise float remapped = clamp(sinOrCos * kHdrpAngleScale - kHdrpAngleStart, 0.0, 1.0);
    return uvec3(quantizeUnorm(remapped, 8u), strength, storeSin ? 1u : 0u);
}

// The stored anisotropy, r * 2 - 1 (Lit.hlsl:887), as gbufferlab's strength: its magnitude.
float decodeAnisotropyHdrpStrength(uvec3 code) {
    precise float a = dequantizeUnorm(code.y & 255u, 8u) * 2.0 - 1.0;
    return abs(a);
}

// The tangent rebuilt against the decoded normal's frame (Lit.hlsl:881-902), then the axis the
// lobe stretches along: the tangent where the stored anisotropy is >= 0 (code >= 128), else the
// bitangent cross(n, t).
vec3 decodeAnisotropyHdrp(uvec3 code, vec3 n) {
    vec3 fx, fy;
    hdrpLocalFrame(n, fx, fy);
    precise float sinOrCos = kHdrpAngleBias + kHdrpAngleStep * dequantizeUnorm(code.x & 255u, 8u);
    precise float cosOrSin = sqrt(1.0 - sinOrCos * sinOrCos);
    bool storeSin = (code.z & 1u) != 0u;
    float s = storeSin ? sinOrCos : cosOrSin;
    float c = storeSin ? cosOrSin : sinOrCos;
    precise vec3 t = vec3(s * fy.x + c * fx.x, s * fy.y + c * fx.y, s * fy.z + c * fx.z);
    if ((code.y & 255u) >= 128u) return t;
    precise vec3 b = vec3(n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x);
    return b;
}
