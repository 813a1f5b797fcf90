// gbufferlab encoding primitives, GLSL 450 include file (no #version).
// Mirrored line for line in src/encodings.{h,cpp} (namespace gbl::enc) with the same names.
//
// Contract (why GPU and CPU agree to the bit):
// - Encoders map floats to integer codes and quantise with floor(x * s + 0.5), s = 2^bits - 1,
//   never round() / packUnorm*. They use only + - * / sqrt abs min max floor clamp and integer
//   ops, whose results IEEE 754 fixes exactly (llvmpipe: divps/sqrtps; C++: -ffp-contract=off).
//   Float intermediates of encoders are `precise` so that no driver reassociates or fuses them.
//   (quantizeDepth24 is the one exception: an exact float split, see there.) Checked once on
//   lavapipe (llvmpipe 15): 37.7M codes from every encoder bit-identical to the C++ mirror.
// - Decoders map codes to floats; they are compared with a tolerance (lavapipe: <= 1 ulp).
// - Inputs are finite; NaN is not expected (clamp of NaN is undefined in GLSL).
// Error bounds below were measured by tests/encoding/encodings_test.cpp (exhaustive where <= 16 bits per
// code, otherwise millions of random inputs); see `gbufferlab encodings` for mean / p99 / max.

#ifndef GBL_ENCODINGS_GLSL
#define GBL_ENCODINGS_GLSL

// ---------------------------------------------------------------------------------------------
// 1. Fixed point. Source: Vulkan spec, "Fixed-Point Data Conversions" (but ties round up).
// ---------------------------------------------------------------------------------------------

// quantizeUnorm: x in [0,1] (clamped) -> code in [0, 2^bits-1]; bits 1..24.
// Error: |dequantizeUnorm(code) - x| <= (0.5 + 2^(bits-24)) / (2^bits - 1): half a step, plus
// float's rounding of x * s (which can also turn a near-tie into a tie: the code may differ by
// one from rounding the exact product, e.g. x = 0.54705882f, 8 bits: 140, exact 139.4999..).
// The min() keeps 24 bits from overflowing (1.0 * 16777215 + 0.5 rounds to 2^24).
uint quantizeUnorm(float x, uint bits) {
    precise float s = float((1u << bits) - 1u);
    precise float q = floor(clamp(x, 0.0, 1.0) * s + 0.5);
    return min(uint(q), (1u << bits) - 1u);
}

// dequantizeUnorm: code in [0, 2^bits-1] -> [0,1]; exact inverse at every code.
float dequantizeUnorm(uint code, uint bits) {
    float s = float((1u << bits) - 1u);
    return float(code) / s;
}

// quantizeChroma: an offset chroma x in [0,1] (Cb + 0.5, Cr + 0.5; 0.5 = neutral) -> code in
// [0, 2^bits - 2]; bits 2..16. The codes are spread over 2^bits - 2 steps, so that the neutral
// chroma 0.5 has a code of its own, the midpoint 2^(bits-1) - 1 (127 at 8 bits), and decodes to
// exactly 0.5: grey (and every metal's diffuse colour, 0) reads back without a tint. The top code
// 2^bits - 1 is unused (it decodes to just above 1). This is CryEngine's MIDPOINT_8_BIT =
// 127/255 (its DecodeColorYCC: chroma = code / MIDPOINT_8_BIT - 1, i.e. 2 Cb in [-1, 1]).
// quantizeUnorm's 0.5 falls between codes 127 and 128 and rounds to 128: +0.002 of chroma.
// Error: |dequantizeChroma(code) - x| <= (0.5 + 2^(bits-24)) / (2^bits - 2).
uint quantizeChroma(float x, uint bits) {
    precise float s = float((1u << bits) - 2u);
    precise float q = floor(clamp(x, 0.0, 1.0) * s + 0.5);
    return uint(q);
}

// dequantizeChroma: code in [0, 2^bits - 2] -> [0,1]; the midpoint decodes to exactly 0.5.
float dequantizeChroma(uint code, uint bits) {
    float s = float((1u << bits) - 2u);
    return float(code) / s;
}

// quantizeSnorm: x in [-1,1] (clamped) -> two's complement code in the low `bits` bits,
// symmetric: -1 -> -(2^(bits-1)-1), +1 -> 2^(bits-1)-1; bits 2..24.
// Error: |dequantizeSnorm(code) - x| <= (0.5 + 2^(bits-24)) / (2^(bits-1) - 1).
uint quantizeSnorm(float x, uint bits) {
    precise float s = float((1u << (bits - 1u)) - 1u);
    precise float q = floor(clamp(x, -1.0, 1.0) * s + 0.5);
    return uint(int(q)) & ((1u << bits) - 1u);
}

// dequantizeSnorm: low `bits` bits, two's complement -> [-1,1]; -2^(bits-1) decodes to -1.
float dequantizeSnorm(uint code, uint bits) {
    float s = float((1u << (bits - 1u)) - 1u);
    int c = int(code << (32u - bits)) >> (32u - bits);
    return max(float(c) / s, -1.0);
}

// ---------------------------------------------------------------------------------------------
// 2. Small floats, integer bit operations on the IEEE 754 binary32 pattern, round to nearest
//    even. Source: IEEE 754-2008; Vulkan spec, "Unsigned 11-Bit / 10-Bit Floating-Point
//    Numbers" (B10G11R11_UFLOAT). Overflow clamps to the largest finite value (our choice;
//    no Inf is produced from finite input), Inf and NaN input also give the largest finite.
// ---------------------------------------------------------------------------------------------

// encodeSmallFloatMagnitude: a = bits of a float >= 0 (sign clear) -> 5-bit exponent (bias 15) |
// mantissaBits mantissa, subnormals included; mantissaBits 1..10.
uint encodeSmallFloatMagnitude(uint a, uint mantissaBits) {
    uint shift = 23u - mantissaBits;
    uint maxFinite = (30u << mantissaBits) | ((1u << mantissaBits) - 1u);
    uint overflow = 0x47000000u | (((2u << mantissaBits) - 1u) << (shift - 1u));
    if (a >= overflow) return maxFinite;
    if (a >= 0x38800000u) {
        uint odd = (a >> shift) & 1u;
        return (a - 0x38000000u + ((1u << (shift - 1u)) - 1u) + odd) >> shift;
    }
    uint e = a >> 23u;
    uint sub = 136u - mantissaBits - e;
    if (sub > 24u) return 0u;
    uint m = (a & 0x7fffffu) | 0x800000u;
    uint q = m >> sub;
    uint rem = m & ((1u << sub) - 1u);
    uint halfway = 1u << (sub - 1u);
    if (rem > halfway || (rem == halfway && (q & 1u) == 1u)) q += 1u;
    return q;
}

// decodeSmallFloatMagnitude: inverse of the above (exponent 31 gives Inf / NaN); exact.
float decodeSmallFloatMagnitude(uint code, uint mantissaBits) {
    uint e = code >> mantissaBits;
    uint mant = code & ((1u << mantissaBits) - 1u);
    if (e == 0u) return float(mant) * uintBitsToFloat((113u - mantissaBits) << 23u);
    if (e == 31u) return uintBitsToFloat(0x7f800000u | (mant << (23u - mantissaBits)));
    return uintBitsToFloat(((e + 112u) << 23u) | (mant << (23u - mantissaBits)));
}

// encodeFloat16: IEEE binary16 (16 bits), |x| <= 65504 exact-rounded, beyond clamps to +-65504.
// Error: relative <= 2^-11 for |x| >= 2^-14, absolute <= 2^-25 below. Bit-identical to a
// correctly rounded (RNE) conversion for all finite |x| < 65520.
uint encodeFloat16(float x) {
    uint a = floatBitsToUint(x);
    uint sign = (a >> 16u) & 0x8000u;
    return sign | encodeSmallFloatMagnitude(a & 0x7fffffffu, 10u);
}

// decodeFloat16: exact.
float decodeFloat16(uint code) {
    float m = decodeSmallFloatMagnitude(code & 0x7fffu, 10u);
    return (code & 0x8000u) != 0u ? -m : m;
}

// encodeFloat11: unsigned 11 bits (5e6m), [0, 65024]; negative (and -0) -> 0; above clamps.
// Error: relative <= 2^-7 for x >= 2^-14, absolute <= 2^-21 below.
uint encodeFloat11(float x) {
    uint a = floatBitsToUint(x);
    if (a >= 0x80000000u) return 0u;
    return encodeSmallFloatMagnitude(a, 6u);
}

// decodeFloat11: exact.
float decodeFloat11(uint code) { return decodeSmallFloatMagnitude(code & 0x7ffu, 6u); }

// encodeFloat10: unsigned 10 bits (5e5m), [0, 64512]; negative (and -0) -> 0; above clamps.
// Error: relative <= 2^-6 for x >= 2^-14, absolute <= 2^-20 below.
uint encodeFloat10(float x) {
    uint a = floatBitsToUint(x);
    if (a >= 0x80000000u) return 0u;
    return encodeSmallFloatMagnitude(a, 5u);
}

// decodeFloat10: exact.
float decodeFloat10(uint code) { return decodeSmallFloatMagnitude(code & 0x3ffu, 5u); }

// encodeFloat32 / decodeFloat32: the binary32 bits, lossless.
uint encodeFloat32(float x) { return floatBitsToUint(x); }
float decodeFloat32(uint code) { return uintBitsToFloat(code); }

// ---------------------------------------------------------------------------------------------
// 3. sRGB 8-bit, exact and table based. Source: IEC 61966-2-1 (sRGB) transfer function.
// kSrgbDecode[i] = float(linear(i/255)); kSrgbEncodeThresholds[i] = the smallest float >= the
// linear value whose sRGB encoding is (i+0.5)/255 (both computed in double). Generated by
// tests/encoding/encodings_test.cpp (DISABLED_PrintSrgbTables); the C++ arrays hold identical literals.
// ---------------------------------------------------------------------------------------------

const float kSrgbDecode[256] = float[256](
    0.0, 0.000303527, 0.000607054, 0.000910581, 0.001214108, 0.001517635, 0.001821162, 0.0021246888,
    0.002428216, 0.0027317428, 0.00303527, 0.0033465358, 0.0036765074, 0.004024717, 0.004391442, 0.0047769533,
    0.0051815165, 0.0056053917, 0.006048833, 0.0065120906, 0.00699541, 0.007499032, 0.008023193, 0.008568126,
    0.009134059, 0.009721218, 0.010329823, 0.010960094, 0.011612245, 0.012286488, 0.0129830325, 0.013702083,
    0.014443844, 0.015208514, 0.015996294, 0.016807375, 0.017641954, 0.01850022, 0.019382361, 0.020288562,
    0.02121901, 0.022173885, 0.023153367, 0.024157632, 0.02518686, 0.026241222, 0.027320892, 0.02842604,
    0.029556835, 0.030713445, 0.031896032, 0.033104766, 0.034339808, 0.035601314, 0.03688945, 0.038204372,
    0.039546236, 0.0409152, 0.04231141, 0.04373503, 0.045186203, 0.046665087, 0.048171826, 0.049706567,
    0.051269457, 0.052860647, 0.054480277, 0.05612849, 0.05780543, 0.059511237, 0.061246052, 0.063010015,
    0.064803265, 0.06662594, 0.06847817, 0.070360094, 0.07227185, 0.07421357, 0.07618538, 0.07818742,
    0.08021982, 0.08228271, 0.08437621, 0.08650046, 0.08865558, 0.09084171, 0.093058966, 0.09530747,
    0.09758735, 0.099898726, 0.10224173, 0.104616486, 0.107023105, 0.10946171, 0.11193243, 0.114435375,
    0.116970666, 0.11953843, 0.122138776, 0.12477182, 0.12743768, 0.13013647, 0.13286832, 0.13563333,
    0.13843161, 0.14126329, 0.14412847, 0.14702727, 0.14995979, 0.15292615, 0.15592647, 0.15896083,
    0.16202937, 0.1651322, 0.1682694, 0.17144111, 0.1746474, 0.17788842, 0.18116425, 0.18447499,
    0.18782078, 0.19120169, 0.19461784, 0.19806932, 0.20155625, 0.20507874, 0.20863687, 0.21223076,
    0.2158605, 0.2195262, 0.22322796, 0.22696587, 0.23074006, 0.23455058, 0.23839757, 0.24228112,
    0.24620132, 0.25015828, 0.2541521, 0.25818285, 0.26225066, 0.2663556, 0.2704978, 0.2746773,
    0.27889428, 0.28314874, 0.28744084, 0.29177064, 0.29613826, 0.30054379, 0.3049873, 0.30946892,
    0.31398872, 0.31854677, 0.3231432, 0.3277781, 0.33245152, 0.33716363, 0.34191442, 0.34670407,
    0.3515326, 0.35640013, 0.3613068, 0.3662526, 0.3712377, 0.37626213, 0.38132602, 0.38642943,
    0.39157248, 0.39675522, 0.40197778, 0.4072402, 0.4125426, 0.41788507, 0.42326766, 0.4286905,
    0.43415365, 0.43965718, 0.4452012, 0.4507858, 0.45641103, 0.462077, 0.4677838, 0.47353148,
    0.47932017, 0.48514995, 0.49102086, 0.49693298, 0.5028865, 0.50888133, 0.5149177, 0.52099556,
    0.5271151, 0.5332764, 0.5394795, 0.54572445, 0.55201143, 0.5583404, 0.5647115, 0.57112485,
    0.57758045, 0.58407843, 0.59061885, 0.59720176, 0.60382736, 0.61049557, 0.6172066, 0.6239604,
    0.63075715, 0.63759685, 0.6444797, 0.65140563, 0.65837485, 0.6653873, 0.67244315, 0.6795425,
    0.6866853, 0.69387174, 0.7011019, 0.70837575, 0.7156935, 0.7230551, 0.73046076, 0.7379104,
    0.7454042, 0.7529422, 0.7605245, 0.76815116, 0.7758222, 0.7835378, 0.7912979, 0.7991027,
    0.80695224, 0.8148466, 0.82278574, 0.8307699, 0.838799, 0.8468732, 0.8549926, 0.8631572,
    0.8713671, 0.8796224, 0.8879231, 0.8962694, 0.9046612, 0.91309863, 0.92158186, 0.9301109,
    0.9386857, 0.9473065, 0.9559733, 0.9646863, 0.9734453, 0.9822506, 0.9911021, 1.0);

const float kSrgbEncodeThresholds[255] = float[255](
    0.0001517635, 0.0004552905, 0.0007588175, 0.0010623445, 0.0013658715, 0.0016693985, 0.0019729256, 0.0022764525,
    0.0025799794, 0.0028835065, 0.003188301, 0.0035092595, 0.003848315, 0.0042057484, 0.004581833, 0.0049768374,
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

// encodeSrgb8: linear x (any float, clamps) -> 8-bit sRGB code = number of thresholds <= x.
// Exact: equals floor(255 * srgb(x) + 0.5) evaluated in exact arithmetic, for every float x.
// Cost: 8 steps of binary search, no pow.
uint encodeSrgb8(float x) {
    uint lo = 0u;
    uint hi = 255u;
    for (int i = 0; i < 8; ++i) {
        uint mid = (lo + hi) >> 1u;
        if (kSrgbEncodeThresholds[mid] <= x) lo = mid + 1u; else hi = mid;
    }
    return lo;
}

// Error of the round trip over linear [0,1]: max abs 0.0045, CIEDE2000 mean 0.14, max 0.82.
// decodeSrgb8: exact sRGB -> linear, correctly rounded to float.
float decodeSrgb8(uint code) { return kSrgbDecode[code & 255u]; }

// ---------------------------------------------------------------------------------------------
// 4. Unit normals. All take and return unit vectors (decoders normalise).
// ---------------------------------------------------------------------------------------------

// encodeNormalXyz: 3 x unorm(n*0.5+0.5), bits 2..16 per component.
// Error (angle, mean / max): 8 bits 0.17 / 0.39 deg, 10 bits 0.042 / 0.096, 16 bits 0.00066 / 0.0015.
uvec3 encodeNormalXyz(vec3 n, uint bits) {
    precise vec3 h = n * 0.5 + 0.5;
    return uvec3(quantizeUnorm(h.x, bits), quantizeUnorm(h.y, bits), quantizeUnorm(h.z, bits));
}

vec3 decodeNormalXyz(uvec3 code, uint bits) {
    vec3 v = vec3(dequantizeUnorm(code.x, bits), dequantizeUnorm(code.y, bits), dequantizeUnorm(code.z, bits));
    return normalize(v * 2.0 - 1.0);
}

// encodeNormalBestFit: CryEngine 3 best-fit normals, 3 x 8 bits, by table look-up as CryEngine
// shipped them. Source: Kaplanyan, "CryENGINE 3: Reaching the Speed of Light", SIGGRAPH 2010
// Advances course: the normal is scaled to the unit cube (q = n / max|n|), its two minor
// components index a 1024x1024 table that holds the best length, and q times that length is
// rounded to 8 bits. Here a decoded vector is d = 2*code - 255 (odd integers in [-255,255]); the
// length is the odd value k of the major component, d = 2 floor(q k / 2) + 1. The table
// (src/encoding/best_fit_normals.h, generated by one C++ function and uploaded as this SSBO)
// stores (255 - k) / 2 per texel of the triangle lo <= mid of q's sorted |components|, 4 entries
// per uint; each texel holds the k that the exhaustive search (encodeNormalBestFitSearch, CPU)
// picks at the texel's centre. Index and rounding use only abs, min, max, exact scaling by 1024
// and float->uint truncation, so the CPU mirror (encodings.h) finds the same texel and code.
// Error: mean 0.032 deg, p99 0.11, max 0.31 (the search: 0.028 / 0.11 / 0.31; 8-bit xyz
// 0.17 / 0.39). Measured by tests/encoding/encodings_test.cpp (BestFitTableErrorAgainstSearch).
// Only G-buffer writers (GBUFFER_WRITE) bind the table: set 0, binding GBL_BEST_FIT_TABLE_BINDING.
#define GBL_BEST_FIT_TABLE_SIZE 1024u
#ifndef GBL_BEST_FIT_TABLE_BINDING
#define GBL_BEST_FIT_TABLE_BINDING 15
#endif
#ifdef GBUFFER_WRITE
layout(std430, set = 0, binding = GBL_BEST_FIT_TABLE_BINDING) readonly buffer BestFitNormalTable {
    uint bestFitNormalTable[];
};

uvec3 encodeNormalBestFit(vec3 n) {
    precise float m = max(abs(n.x), max(abs(n.y), abs(n.z)));
    if (!(m > 0.0) || isinf(m) || isnan(n.x) || isnan(n.y) || isnan(n.z)) return uvec3(128u, 128u, 255u);
    precise vec3 q = vec3(n.x / m, n.y / m, n.z / m);
    vec3 a = abs(q);
    float lo = min(a.x, min(a.y, a.z));
    float mid = max(min(a.x, a.y), min(max(a.x, a.y), a.z));
    uint i = min(uint(mid * float(GBL_BEST_FIT_TABLE_SIZE)), GBL_BEST_FIT_TABLE_SIZE - 1u);
    uint j = min(uint(lo * float(GBL_BEST_FIT_TABLE_SIZE)), GBL_BEST_FIT_TABLE_SIZE - 1u);
    uint t = i * (i + 1u) / 2u + j;
    uint entry = (bestFitNormalTable[t >> 2u] >> ((t & 3u) * 8u)) & 0xffu;
    precise float k = float(255u - 2u * entry);
    precise float dx = 2.0 * floor(q.x * k * 0.5) + 1.0;
    precise float dy = 2.0 * floor(q.y * k * 0.5) + 1.0;
    precise float dz = 2.0 * floor(q.z * k * 0.5) + 1.0;
    return uvec3(uint(dx + 255.0) >> 1u, uint(dy + 255.0) >> 1u, uint(dz + 255.0) >> 1u);
}
#endif

vec3 decodeNormalBestFit(uvec3 code) {
    return normalize(vec3(code) / 255.0 * 2.0 - 1.0);
}

// encodeNormalXyZSign: unorm x, y (bits 2..16 each) + z-sign bit (code.z: 1 when n.z < 0).
// Source: Sousa et al., "The Rendering Technologies of Crysis 3", GDC 2013 (N.xy + Zsign).
// Error: poor near the equator (z ~ 0, where z = sqrt(1 - x^2 - y^2) is ill-conditioned):
// mean / max 8 bits 0.47 / 5.8 deg, 10 bits 0.14 / 2.9, 16 bits 0.0030 / 0.35.
uvec3 encodeNormalXyZSign(vec3 n, uint bits) {
    precise vec2 h = vec2(n.x * 0.5 + 0.5, n.y * 0.5 + 0.5);
    return uvec3(quantizeUnorm(h.x, bits), quantizeUnorm(h.y, bits), n.z < 0.0 ? 1u : 0u);
}

vec3 decodeNormalXyZSign(uvec3 code, uint bits) {
    float x = dequantizeUnorm(code.x, bits) * 2.0 - 1.0;
    float y = dequantizeUnorm(code.y, bits) * 2.0 - 1.0;
    float z = sqrt(max(0.0, 1.0 - x * x - y * y));
    return normalize(vec3(x, y, code.z != 0u ? -z : z));
}

// encodeNormalSpheremap: Lambert azimuthal equal-area projection, full sphere, 2 x unorm bits.
// Source: Pranckevicius, "Compact Normal Storage for Small G-Buffers" (2009), method #4.
// e = n.xy / sqrt(8 n.z + 8) + 0.5 lies in a disc of radius 0.5; n = -z maps to (1, 0.5).
// For n.z < 0 the same e is computed as n.xy / |n.xy| * sqrt((1 - n.z) / 8) (using
// 1 + z = (x^2 + y^2) / (1 - z)): 8 n.z + 8 cancels near -z, and the disc's rim (all of it
// is -z) turns that rounding error into degrees (10 deg at any bits, before this rewrite).
// Error: precision collapses towards -z, where one step at the rim spans 4 sqrt(step) rad:
// mean / max 8 bits 0.49 / 11.5 deg, 10 bits 0.12 / 5.5, 16 bits 0.0020 / 0.52.
uvec2 encodeNormalSpheremap(vec3 n, uint bits) {
    precise vec2 e = vec2(1.0, 0.5);
    precise float lxy = sqrt(n.x * n.x + n.y * n.y);
    if (n.z >= 0.0) {
        precise float f = sqrt(8.0 * n.z + 8.0);
        e = vec2(n.x / f + 0.5, n.y / f + 0.5);
    } else if (lxy > 0.0) {
        precise float r = sqrt((1.0 - n.z) * 0.125);
        e = vec2(n.x / lxy * r + 0.5, n.y / lxy * r + 0.5);
    }
    return uvec2(quantizeUnorm(e.x, bits), quantizeUnorm(e.y, bits));
}

vec3 decodeNormalSpheremap(uvec2 code, uint bits) {
    vec2 fenc = vec2(dequantizeUnorm(code.x, bits), dequantizeUnorm(code.y, bits)) * 4.0 - 2.0;
    float f = dot(fenc, fenc);
    float g = sqrt(max(1.0 - f / 4.0, 0.0));
    return normalize(vec3(fenc * g, 1.0 - f / 2.0));
}

// encodeNormalStereographic: stereographic projection from -z, scaled by 1/1.7777 into [0,1]^2,
// 2 x unorm bits. Source: Pranckevicius 2009, method #7. NOT a full-sphere mapping: directions
// with |n.x| or |n.y| > 1.7777 * (1 + n.z) (roughly > 120 deg from +z) clamp to the square's
// edge; meant for view-space normals. Error, z >= 0: mean / max 8 bits 0.46 / 1.13 deg (the max is
// +z itself: 2^b - 1 levels have no exact centre), 16 bits 0.0018 / 0.0044; over the whole
// sphere 8 bits: mean 3.6 deg, max 57 deg (the clamped back).
uvec2 encodeNormalStereographic(vec3 n, uint bits) {
    precise float d = max(n.z + 1.0, 0.000001);
    precise vec2 e = vec2(n.x / d / 1.7777 * 0.5 + 0.5, n.y / d / 1.7777 * 0.5 + 0.5);
    return uvec2(quantizeUnorm(e.x, bits), quantizeUnorm(e.y, bits));
}

vec3 decodeNormalStereographic(uvec2 code, uint bits) {
    vec2 e = vec2(dequantizeUnorm(code.x, bits), dequantizeUnorm(code.y, bits));
    vec3 nn = vec3(e * (2.0 * 1.7777) - 1.7777, 1.0);
    float g = 2.0 / dot(nn, nn);
    return normalize(vec3(vec2(nn.x, nn.y) * g, g - 1.0));
}

// Octahedral helpers. Source: Cigolle, Donow, Evangelakos, Mara, McGuire, Meyer, "A Survey of
// Efficient Representations for Independent Unit Vectors", JCGT 3(2), 2014, listings 1-2.
vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

// octEncode: unit n -> [-1,1]^2 (lower hemisphere folded over the diagonals).
vec2 octEncode(vec3 n) {
    precise float l1 = abs(n.x) + abs(n.y) + abs(n.z);
    precise vec2 p = vec2(n.x / l1, n.y / l1);
    precise vec2 folded = vec2(1.0 - abs(p.y), 1.0 - abs(p.x)) * signNotZero(p);
    return n.z <= 0.0 ? folded : p;
}

// octDecode: [-1,1]^2 -> direction (not normalised).
vec3 octDecode(vec2 e) {
    precise vec3 v = vec3(e.x, e.y, 1.0 - abs(e.x) - abs(e.y));
    precise vec2 folded = vec2(1.0 - abs(v.y), 1.0 - abs(v.x)) * signNotZero(vec2(v.x, v.y));
    return v.z < 0.0 ? vec3(folded, v.z) : v;
}

// encodeNormalOctahedral: octahedral, 2 x snorm bits (bits 2..16; Cigolle's "oct" 2*bits).
// Error (angle, mean / max): 8 bits 0.34 / 0.95 deg, 10 bits 0.084 / 0.24, 12 bits 0.021 / 0.059,
// 16 bits 0.0013 / 0.0037. Edge codes (x or y = +-max) pair up: (1, t) and (1, -t) are one direction.
uvec2 encodeNormalOctahedral(vec3 n, uint bits) {
    vec2 p = octEncode(n);
    return uvec2(quantizeSnorm(p.x, bits), quantizeSnorm(p.y, bits));
}

vec3 decodeNormalOctahedral(uvec2 code, uint bits) {
    return normalize(octDecode(vec2(dequantizeSnorm(code.x, bits), dequantizeSnorm(code.y, bits))));
}

// encodeNormalOctahedralPrecise: Cigolle's precise variant ("octP", listing 3): of the four
// floor/ceil neighbours of the quantised point, keep the code whose decoded direction is closest
// to n. Cigolle compares cos; we compare |v/|v| - n|^2 (same order, but float resolves it down
// to tiny angles where cos rounds to 1). First wins ties; the plain rounding is one of the four.
// Cost: 4 decodes. Error (mean / max): 8 bits 0.31 / 0.64 deg, 10 bits 0.078 / 0.16,
// 12 bits 0.020 / 0.040, 16 bits 0.0012 / 0.0025 (max ~2/3 of plain octahedral).
uvec2 encodeNormalOctahedralPrecise(vec3 n, uint bits) {
    vec2 p = octEncode(n);
    precise float s = float((1u << (bits - 1u)) - 1u);
    int top = int((1u << (bits - 1u)) - 1u);
    int bx = int(floor(clamp(p.x, -1.0, 1.0) * s));
    int by = int(floor(clamp(p.y, -1.0, 1.0) * s));
    ivec2 best = ivec2(bx, by);
    float bestErr = 8.0;
    for (int i = 0; i < 4; ++i) {
        ivec2 c = ivec2(min(bx + (i & 1), top), min(by + (i >> 1), top));
        precise vec3 v = octDecode(vec2(float(c.x) / s, float(c.y) / s));
        precise float len = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
        precise float ex = v.x / len - n.x;
        precise float ey = v.y / len - n.y;
        precise float ez = v.z / len - n.z;
        precise float err = ex * ex + ey * ey + ez * ez;
        if (err < bestErr) {
            bestErr = err;
            best = c;
        }
    }
    uint mask = (1u << bits) - 1u;
    return uvec2(uint(best.x) & mask, uint(best.y) & mask);
}

vec3 decodeNormalOctahedralPrecise(uvec2 code, uint bits) { return decodeNormalOctahedral(code, bits); }

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

const float kChromaEdgeThreshold = 0.11764706;  // 30/255, the paper's THRESH

bool chromaIsSecond(ivec2 pixel) { return ((pixel.x + pixel.y) & 1) != 0; }

// chromaForPixel: the chroma this pixel stores, from (first, second) = (Cb, Cr) or (Co, Cg).
float chromaForPixel(ivec2 pixel, vec2 chroma) { return chromaIsSecond(pixel) ? chroma.y : chroma.x; }

// reconstructChroma: the paper's edge-directed filter. The 4 direct neighbours (order: +x, -x,
// +y, -y) hold the other chroma; each gets weight 1 - step(30/255, |Yn - Yc|) (1 when its luma
// is within the threshold), times `covered` (1 where the neighbour has geometry, 0 where it holds
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
        if (kCryGlossEncodeThresholds[mid] >= r) lo = mid + 1u; else hi = mid;
    }
    return lo;
}
float decodeCryGlossPower(uint code) { return kCryGlossRoughness[code & 255u]; }

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
        if (kGamma22EncodeThresholds[mid] <= x) lo = mid + 1u; else hi = mid;
    }
    return lo;
}

float decodeGamma22(uint code) { return kGamma22Decode[code & 255u]; }

// Octahedral normals stored as unorm of p * 0.5 + 0.5 (p = octEncode(n) in [-1,1]^2), quantised
// by TRUNCATION with scale s, decoded as code / (2^bits - 1):
// - Bevy (pbr_deferred_types.wgsl, pack_24bit_nor_and_flags): u32(saturate(u) * 4095), s = 2^bits - 1;
// - Unity (core Packing.hlsl, PackFloat2To888; HDRP's normal buffer, URP's accurate G-buffer
//   normals): uint(u * 4095.5), s = 2^bits - 0.5.
// Truncation, not rounding: a code's error is up to one whole step (not half) in each of u, v.
// Error (angle, mean / max, 12 bits; `gbufferlab encodings`): Bevy 0.042 / 0.118 deg, Unity
// 0.029 / 0.107 (rounding normal_octahedral: 0.021 / 0.059).
uvec2 encodeNormalOctahedralTrunc(vec3 n, uint bits, float scaleAdd) {
    vec2 p = octEncode(n);
    precise float s = float((1u << bits) - 1u) + scaleAdd;
    precise vec2 u = clamp(vec2(p.x * 0.5 + 0.5, p.y * 0.5 + 0.5), vec2(0.0), vec2(1.0));
    precise vec2 q = floor(u * s);
    return min(uvec2(uint(q.x), uint(q.y)), uvec2((1u << bits) - 1u));
}

vec3 decodeNormalOctahedralTrunc(uvec2 code, uint bits) {
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

// zeux/niagara's emissive-to-albedo ratio and dithered octahedral normals.
#include "niagara_encodings.glsl"

#endif  // GBL_ENCODINGS_GLSL
