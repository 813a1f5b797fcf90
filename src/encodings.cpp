// C++ mirror of shaders/encodings.glsl, line for line, same names (see that file and
// encodings.h for the contract: ranges, bits, error bounds, sources). Compiled with
// -ffp-contract=off; float literals carry an `f` so that nothing is promoted to double.
// Edit both files together: tests/encodings_test.cpp checks the sRGB tables are identical.
#include "encodings.h"

namespace gbl::enc {

// ---------------------------------------------------------------------------------------------
// 1. Fixed point. Source: Vulkan spec, "Fixed-Point Data Conversions" (but ties round up).
// ---------------------------------------------------------------------------------------------

// quantizeUnorm: x in [0,1] (clamped) -> code in [0, 2^bits-1]; bits 1..24.
// Error: |dequantizeUnorm(code) - x| <= (0.5 + 2^(bits-24)) / (2^bits - 1): half a step, plus
// float's rounding of x * s (which can also turn a near-tie into a tie: the code may differ by
// one from rounding the exact product, e.g. x = 0.54705882f, 8 bits: 140, exact 139.4999..).
// The min() keeps 24 bits from overflowing (1.0 * 16777215 + 0.5 rounds to 2^24).
uint quantizeUnorm(float x, uint bits) {
    float s = float((1u << bits) - 1u);
    float q = floor(clamp(x, 0.0f, 1.0f) * s + 0.5f);
    return min(uint(q), (1u << bits) - 1u);
}

// dequantizeUnorm: code in [0, 2^bits-1] -> [0,1]; exact inverse at every code.
float dequantizeUnorm(uint code, uint bits) {
    float s = float((1u << bits) - 1u);
    return float(code) / s;
}

// quantizeSnorm: x in [-1,1] (clamped) -> two's complement code in the low `bits` bits,
// symmetric: -1 -> -(2^(bits-1)-1), +1 -> 2^(bits-1)-1; bits 2..24.
// Error: |dequantizeSnorm(code) - x| <= (0.5 + 2^(bits-24)) / (2^(bits-1) - 1).
uint quantizeSnorm(float x, uint bits) {
    float s = float((1u << (bits - 1u)) - 1u);
    float q = floor(clamp(x, -1.0f, 1.0f) * s + 0.5f);
    return uint(int(q)) & ((1u << bits) - 1u);
}

// dequantizeSnorm: low `bits` bits, two's complement -> [-1,1]; -2^(bits-1) decodes to -1.
float dequantizeSnorm(uint code, uint bits) {
    float s = float((1u << (bits - 1u)) - 1u);
    int c = int(code << (32u - bits)) >> (32u - bits);
    return max(float(c) / s, -1.0f);
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
// tests/encodings_test.cpp (DISABLED_PrintSrgbTables); the C++ arrays hold identical literals.
// ---------------------------------------------------------------------------------------------

const float kSrgbDecode[256] = {
    0.0f, 0.000303527f, 0.000607054f, 0.000910581f, 0.001214108f, 0.001517635f, 0.001821162f, 0.0021246888f,
    0.002428216f, 0.0027317428f, 0.00303527f, 0.0033465358f, 0.0036765074f, 0.004024717f, 0.004391442f, 0.0047769533f,
    0.0051815165f, 0.0056053917f, 0.006048833f, 0.0065120906f, 0.00699541f, 0.007499032f, 0.008023193f, 0.008568126f,
    0.009134059f, 0.009721218f, 0.010329823f, 0.010960094f, 0.011612245f, 0.012286488f, 0.0129830325f, 0.013702083f,
    0.014443844f, 0.015208514f, 0.015996294f, 0.016807375f, 0.017641954f, 0.01850022f, 0.019382361f, 0.020288562f,
    0.02121901f, 0.022173885f, 0.023153367f, 0.024157632f, 0.02518686f, 0.026241222f, 0.027320892f, 0.02842604f,
    0.029556835f, 0.030713445f, 0.031896032f, 0.033104766f, 0.034339808f, 0.035601314f, 0.03688945f, 0.038204372f,
    0.039546236f, 0.0409152f, 0.04231141f, 0.04373503f, 0.045186203f, 0.046665087f, 0.048171826f, 0.049706567f,
    0.051269457f, 0.052860647f, 0.054480277f, 0.05612849f, 0.05780543f, 0.059511237f, 0.061246052f, 0.063010015f,
    0.064803265f, 0.06662594f, 0.06847817f, 0.070360094f, 0.07227185f, 0.07421357f, 0.07618538f, 0.07818742f,
    0.08021982f, 0.08228271f, 0.08437621f, 0.08650046f, 0.08865558f, 0.09084171f, 0.093058966f, 0.09530747f,
    0.09758735f, 0.099898726f, 0.10224173f, 0.104616486f, 0.107023105f, 0.10946171f, 0.11193243f, 0.114435375f,
    0.116970666f, 0.11953843f, 0.122138776f, 0.12477182f, 0.12743768f, 0.13013647f, 0.13286832f, 0.13563333f,
    0.13843161f, 0.14126329f, 0.14412847f, 0.14702727f, 0.14995979f, 0.15292615f, 0.15592647f, 0.15896083f,
    0.16202937f, 0.1651322f, 0.1682694f, 0.17144111f, 0.1746474f, 0.17788842f, 0.18116425f, 0.18447499f,
    0.18782078f, 0.19120169f, 0.19461784f, 0.19806932f, 0.20155625f, 0.20507874f, 0.20863687f, 0.21223076f,
    0.2158605f, 0.2195262f, 0.22322796f, 0.22696587f, 0.23074006f, 0.23455058f, 0.23839757f, 0.24228112f,
    0.24620132f, 0.25015828f, 0.2541521f, 0.25818285f, 0.26225066f, 0.2663556f, 0.2704978f, 0.2746773f,
    0.27889428f, 0.28314874f, 0.28744084f, 0.29177064f, 0.29613826f, 0.30054379f, 0.3049873f, 0.30946892f,
    0.31398872f, 0.31854677f, 0.3231432f, 0.3277781f, 0.33245152f, 0.33716363f, 0.34191442f, 0.34670407f,
    0.3515326f, 0.35640013f, 0.3613068f, 0.3662526f, 0.3712377f, 0.37626213f, 0.38132602f, 0.38642943f,
    0.39157248f, 0.39675522f, 0.40197778f, 0.4072402f, 0.4125426f, 0.41788507f, 0.42326766f, 0.4286905f,
    0.43415365f, 0.43965718f, 0.4452012f, 0.4507858f, 0.45641103f, 0.462077f, 0.4677838f, 0.47353148f,
    0.47932017f, 0.48514995f, 0.49102086f, 0.49693298f, 0.5028865f, 0.50888133f, 0.5149177f, 0.52099556f,
    0.5271151f, 0.5332764f, 0.5394795f, 0.54572445f, 0.55201143f, 0.5583404f, 0.5647115f, 0.57112485f,
    0.57758045f, 0.58407843f, 0.59061885f, 0.59720176f, 0.60382736f, 0.61049557f, 0.6172066f, 0.6239604f,
    0.63075715f, 0.63759685f, 0.6444797f, 0.65140563f, 0.65837485f, 0.6653873f, 0.67244315f, 0.6795425f,
    0.6866853f, 0.69387174f, 0.7011019f, 0.70837575f, 0.7156935f, 0.7230551f, 0.73046076f, 0.7379104f,
    0.7454042f, 0.7529422f, 0.7605245f, 0.76815116f, 0.7758222f, 0.7835378f, 0.7912979f, 0.7991027f,
    0.80695224f, 0.8148466f, 0.82278574f, 0.8307699f, 0.838799f, 0.8468732f, 0.8549926f, 0.8631572f,
    0.8713671f, 0.8796224f, 0.8879231f, 0.8962694f, 0.9046612f, 0.91309863f, 0.92158186f, 0.9301109f,
    0.9386857f, 0.9473065f, 0.9559733f, 0.9646863f, 0.9734453f, 0.9822506f, 0.9911021f, 1.0f};

const float kSrgbEncodeThresholds[255] = {
    0.0001517635f, 0.0004552905f, 0.0007588175f, 0.0010623445f, 0.0013658715f, 0.0016693985f, 0.0019729256f, 0.0022764525f,
    0.0025799794f, 0.0028835065f, 0.003188301f, 0.0035092595f, 0.003848315f, 0.0042057484f, 0.004581833f, 0.0049768374f,
    0.0053910245f, 0.005824651f, 0.0062779696f, 0.0067512277f, 0.0072446684f, 0.007758531f, 0.0082930485f, 0.008848454f,
    0.009424971f, 0.0100228265f, 0.010642237f, 0.011283422f, 0.0119465925f, 0.01263196f, 0.013339732f, 0.014070112f,
    0.014823304f, 0.015599503f, 0.01639891f, 0.017221717f, 0.018068116f, 0.018938296f, 0.019832443f, 0.020750746f,
    0.021693384f, 0.022660539f, 0.023652392f, 0.024669116f, 0.025710888f, 0.026777884f, 0.027870271f, 0.028988222f,
    0.030131903f, 0.031301484f, 0.032497123f, 0.03371899f, 0.034967244f, 0.036242045f, 0.037543554f, 0.03887193f,
    0.04022732f, 0.04160989f, 0.043019786f, 0.044457164f, 0.045922175f, 0.047414966f, 0.04893569f, 0.050484486f,
    0.05206151f, 0.0536669f, 0.055300802f, 0.05696336f, 0.058654718f, 0.060375012f, 0.062124386f, 0.063902974f,
    0.06571092f, 0.06754836f, 0.06941541f, 0.07131224f, 0.07323896f, 0.07519571f, 0.07718262f, 0.07919982f,
    0.08124745f, 0.083325624f, 0.08543449f, 0.08757416f, 0.08974477f, 0.091946445f, 0.0941793f, 0.09644348f,
    0.098739095f, 0.10106628f, 0.10342514f, 0.105815805f, 0.10823841f, 0.11069305f, 0.11317987f, 0.11569897f,
    0.11825049f, 0.12083452f, 0.1234512f, 0.12610064f, 0.12878296f, 0.13149826f, 0.13424668f, 0.1370283f,
    0.13984329f, 0.14269169f, 0.14557366f, 0.14848931f, 0.15143874f, 0.15442206f, 0.1574394f, 0.16049084f,
    0.1635765f, 0.1666965f, 0.16985095f, 0.17303993f, 0.17626357f, 0.17952198f, 0.18281525f, 0.1861435f,
    0.18950684f, 0.19290535f, 0.19633916f, 0.19980836f, 0.20331305f, 0.20685335f, 0.21042934f, 0.21404114f,
    0.21768886f, 0.22137257f, 0.2250924f, 0.22884843f, 0.23264077f, 0.23646952f, 0.24033478f, 0.24423665f,
    0.24817522f, 0.2521506f, 0.25616285f, 0.26021212f, 0.2642985f, 0.26842204f, 0.2725829f, 0.2767811f,
    0.28101683f, 0.2852901f, 0.28960103f, 0.29394975f, 0.2983363f, 0.3027608f, 0.30722338f, 0.31172407f,
    0.31626296f, 0.3208402f, 0.32545584f, 0.33011f, 0.33480275f, 0.3395342f, 0.34430438f, 0.34911346f,
    0.3539615f, 0.35884857f, 0.3637748f, 0.36874023f, 0.373745f, 0.37878916f, 0.38387278f, 0.388996f,
    0.3941589f, 0.39936155f, 0.40460402f, 0.40988642f, 0.41520885f, 0.42057136f, 0.42597407f, 0.43141705f,
    0.43690038f, 0.44242412f, 0.44798842f, 0.45359334f, 0.45923892f, 0.46492532f, 0.47065255f, 0.47642073f,
    0.48222995f, 0.48808026f, 0.49397177f, 0.49990457f, 0.50587875f, 0.51189435f, 0.5179514f, 0.5240502f,
    0.5301906f, 0.5363727f, 0.54259676f, 0.5488627f, 0.55517066f, 0.5615207f, 0.56791294f, 0.5743474f,
    0.58082414f, 0.58734334f, 0.59390503f, 0.6005093f, 0.60715616f, 0.61384577f, 0.62057817f, 0.6273534f,
    0.63417166f, 0.64103293f, 0.6479373f, 0.6548849f, 0.66187567f, 0.66890985f, 0.6759874f, 0.68310845f,
    0.6902731f, 0.6974814f, 0.7047334f, 0.71202916f, 0.7193689f, 0.72675246f, 0.7341801f, 0.74165183f,
    0.74916774f, 0.7567279f, 0.7643323f, 0.7719812f, 0.7796745f, 0.78741235f, 0.7951948f, 0.8030219f,
    0.81089383f, 0.8188106f, 0.8267722f, 0.83477885f, 0.84283054f, 0.8509273f, 0.8590693f, 0.8672565f,
    0.8754891f, 0.8837671f, 0.89209056f, 0.9004596f, 0.9088742f, 0.91733456f, 0.9258407f, 0.9343926f,
    0.9429904f, 0.9516342f, 0.96032405f, 0.96906f, 0.97784215f, 0.98667055f, 0.99554527f};

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
    vec3 h = n * 0.5f + 0.5f;
    return uvec3(quantizeUnorm(h.x, bits), quantizeUnorm(h.y, bits), quantizeUnorm(h.z, bits));
}

vec3 decodeNormalXyz(uvec3 code, uint bits) {
    vec3 v = vec3(dequantizeUnorm(code.x, bits), dequantizeUnorm(code.y, bits), dequantizeUnorm(code.z, bits));
    return normalize(v * 2.0f - 1.0f);
}

// encodeNormalBestFit: CryEngine 3 best-fit normals, 3 x 8 bits. Source: Kaplanyan,
// "CryENGINE 3: Reaching the Speed of Light", SIGGRAPH 2010 Advances course. The original looks
// the best length up in a 1024x1024 texture; here the same search runs in code: a decoded
// vector is d = 2*code - 255 (odd integers in [-255,255]); for each odd value k = 255, 253, ..1
// of the largest component we round the others to the nearest odd integer along the ray
// (t = k * n / max|n|) and keep the d whose direction is closest to n, measured as
// |d/|d| - n|^2 (not cos, which float cannot resolve below ~0.02 deg); first wins ties.
// Cost: 128 candidates x (3 floor, 4 div, 1 sqrt, ~20 mul/add).
// Error: mean 0.028 deg, p99 0.11, max 0.31 (6x better mean than 8-bit xyz: 0.17 / 0.39). The max
// is structural: 0 is not an odd code, so +z is best met by (1, 1, 255). Checked optimal against a
// wider search (+-2 odd steps on every component at every k) in tests/encodings_test.cpp.
uvec3 encodeNormalBestFit(vec3 n) {
    float m = max(abs(n.x), max(abs(n.y), abs(n.z)));
    if (!(m > 0.0f)) return uvec3(128u, 128u, 255u);
    vec3 q = vec3(n.x / m, n.y / m, n.z / m);
    vec3 best = vec3(1.0f, 1.0f, 255.0f);
    float bestErr = 8.0f;
    for (int i = 0; i < 128; ++i) {
        float k = float(255 - 2 * i);
        float dx = 2.0f * floor(q.x * k * 0.5f) + 1.0f;
        float dy = 2.0f * floor(q.y * k * 0.5f) + 1.0f;
        float dz = 2.0f * floor(q.z * k * 0.5f) + 1.0f;
        float len = sqrt(dx * dx + dy * dy + dz * dz);
        float ex = dx / len - n.x;
        float ey = dy / len - n.y;
        float ez = dz / len - n.z;
        float err = ex * ex + ey * ey + ez * ez;
        if (err < bestErr) {
            bestErr = err;
            best = vec3(dx, dy, dz);
        }
    }
    return uvec3(uint(best.x + 255.0f) >> 1u, uint(best.y + 255.0f) >> 1u, uint(best.z + 255.0f) >> 1u);
}

vec3 decodeNormalBestFit(uvec3 code) {
    return normalize(vec3(code) / 255.0f * 2.0f - 1.0f);
}

// encodeNormalXyZSign: unorm x, y (bits 2..16 each) + z-sign bit (code.z: 1 when n.z < 0).
// Source: Sousa et al., "The Rendering Technologies of Crysis 3", GDC 2013 (N.xy + Zsign).
// Error: poor near the equator (z ~ 0, where z = sqrt(1 - x^2 - y^2) is ill-conditioned):
// mean / max 8 bits 0.47 / 5.8 deg, 10 bits 0.14 / 2.9, 16 bits 0.0030 / 0.35.
uvec3 encodeNormalXyZSign(vec3 n, uint bits) {
    vec2 h = vec2(n.x * 0.5f + 0.5f, n.y * 0.5f + 0.5f);
    return uvec3(quantizeUnorm(h.x, bits), quantizeUnorm(h.y, bits), n.z < 0.0f ? 1u : 0u);
}

vec3 decodeNormalXyZSign(uvec3 code, uint bits) {
    float x = dequantizeUnorm(code.x, bits) * 2.0f - 1.0f;
    float y = dequantizeUnorm(code.y, bits) * 2.0f - 1.0f;
    float z = sqrt(max(0.0f, 1.0f - x * x - y * y));
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
    vec2 e = vec2(1.0f, 0.5f);
    float lxy = sqrt(n.x * n.x + n.y * n.y);
    if (n.z >= 0.0f) {
        float f = sqrt(8.0f * n.z + 8.0f);
        e = vec2(n.x / f + 0.5f, n.y / f + 0.5f);
    } else if (lxy > 0.0f) {
        float r = sqrt((1.0f - n.z) * 0.125f);
        e = vec2(n.x / lxy * r + 0.5f, n.y / lxy * r + 0.5f);
    }
    return uvec2(quantizeUnorm(e.x, bits), quantizeUnorm(e.y, bits));
}

vec3 decodeNormalSpheremap(uvec2 code, uint bits) {
    vec2 fenc = vec2(dequantizeUnorm(code.x, bits), dequantizeUnorm(code.y, bits)) * 4.0f - 2.0f;
    float f = dot(fenc, fenc);
    float g = sqrt(max(1.0f - f / 4.0f, 0.0f));
    return normalize(vec3(fenc * g, 1.0f - f / 2.0f));
}

// encodeNormalStereographic: stereographic projection from -z, scaled by 1/1.7777 into [0,1]^2,
// 2 x unorm bits. Source: Pranckevicius 2009, method #7. NOT a full-sphere mapping: directions
// with |n.x| or |n.y| > 1.7777 * (1 + n.z) (roughly > 120 deg from +z) clamp to the square's
// edge; meant for view-space normals. Error, z >= 0: mean / max 8 bits 0.46 / 1.13 deg (the max is
// +z itself: 2^b - 1 levels have no exact centre), 16 bits 0.0018 / 0.0044; over the whole
// sphere 8 bits: mean 3.6 deg, max 57 deg (the clamped back).
uvec2 encodeNormalStereographic(vec3 n, uint bits) {
    float d = max(n.z + 1.0f, 0.000001f);
    vec2 e = vec2(n.x / d / 1.7777f * 0.5f + 0.5f, n.y / d / 1.7777f * 0.5f + 0.5f);
    return uvec2(quantizeUnorm(e.x, bits), quantizeUnorm(e.y, bits));
}

vec3 decodeNormalStereographic(uvec2 code, uint bits) {
    vec2 e = vec2(dequantizeUnorm(code.x, bits), dequantizeUnorm(code.y, bits));
    vec3 nn = vec3(e * (2.0f * 1.7777f) - 1.7777f, 1.0f);
    float g = 2.0f / dot(nn, nn);
    return normalize(vec3(vec2(nn.x, nn.y) * g, g - 1.0f));
}

// Octahedral helpers. Source: Cigolle, Donow, Evangelakos, Mara, McGuire, Meyer, "A Survey of
// Efficient Representations for Independent Unit Vectors", JCGT 3(2), 2014, listings 1-2.
vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f); }

// octEncode: unit n -> [-1,1]^2 (lower hemisphere folded over the diagonals).
vec2 octEncode(vec3 n) {
    float l1 = abs(n.x) + abs(n.y) + abs(n.z);
    vec2 p = vec2(n.x / l1, n.y / l1);
    vec2 folded = vec2(1.0f - abs(p.y), 1.0f - abs(p.x)) * signNotZero(p);
    return n.z <= 0.0f ? folded : p;
}

// octDecode: [-1,1]^2 -> direction (not normalised).
vec3 octDecode(vec2 e) {
    vec3 v = vec3(e.x, e.y, 1.0f - abs(e.x) - abs(e.y));
    vec2 folded = vec2(1.0f - abs(v.y), 1.0f - abs(v.x)) * signNotZero(vec2(v.x, v.y));
    return v.z < 0.0f ? vec3(folded, v.z) : v;
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
    float s = float((1u << (bits - 1u)) - 1u);
    int top = int((1u << (bits - 1u)) - 1u);
    int bx = int(floor(clamp(p.x, -1.0f, 1.0f) * s));
    int by = int(floor(clamp(p.y, -1.0f, 1.0f) * s));
    ivec2 best = ivec2(bx, by);
    float bestErr = 8.0f;
    for (int i = 0; i < 4; ++i) {
        ivec2 c = ivec2(min(bx + (i & 1), top), min(by + (i >> 1), top));
        vec3 v = octDecode(vec2(float(c.x) / s, float(c.y) / s));
        float len = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
        float ex = v.x / len - n.x;
        float ey = v.y / len - n.y;
        float ez = v.z / len - n.z;
        float err = ex * ex + ey * ey + ez * ez;
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
// 5. Colour transforms (float -> float; quantise the results with quantizeUnorm).
// ---------------------------------------------------------------------------------------------

// rgbToYCbCr: ITU-R BT.601 full range (JPEG/JFIF), rgb in [0,1]^3 -> (Y, Cb+0.5, Cr+0.5) in
// [0,1]^3. Cb = (B - Y) / 1.772, Cr = (R - Y) / 1.402. Used by Crysis 3 for albedo and specular
// (Sousa et al., "The Rendering Technologies of Crysis 3", GDC 2013).
// Error: the pair is exact up to float rounding (max 2.6e-7); 8 bits per code: max abs 0.0054,
// CIEDE2000 mean 0.17, max 6.3 (darks; ycbcr_sqrt: max 1.3).
vec3 rgbToYCbCr(vec3 c) {
    float y = 0.299f * c.r + 0.587f * c.g + 0.114f * c.b;
    float cb = (c.b - y) * 0.5643341f + 0.5f;
    float cr = (c.r - y) * 0.7132668f + 0.5f;
    return vec3(y, cb, cr);
}

vec3 yCbCrToRgb(vec3 c) {
    float r = c.x + (c.z - 0.5f) * 1.402f;
    float b = c.x + (c.y - 0.5f) * 1.772f;
    float g = (c.x - 0.299f * r - 0.114f * b) / 0.587f;
    return vec3(r, g, b);
}

// lumaBt601: the Y of rgbToYCbCr (Crysis 3 stores only the specular colour's luminance).
float lumaBt601(vec3 c) {
    float y = 0.299f * c.r + 0.587f * c.g + 0.114f * c.b;
    return y;
}

// rgbToYCbCrSqrt: YCbCr of sqrt(rgb) (a gamma-2 pre-transform that spends codes on darks);
// yCbCrSqrtToRgb squares after the inverse matrix. Source: Sousa et al., Crysis 3, GDC 2013;
// Schulz, "Moving to the Next Generation - The Rendering Technology of Ryse", GDC 2014.
// Error, 8 bits per code: max abs 0.011 (brights), but darks (< 0.05) 0.0024 vs YCbCr's 0.0054;
// CIEDE2000 mean 0.20, max 1.3.
vec3 rgbToYCbCrSqrt(vec3 c) {
    vec3 s = vec3(sqrt(max(c.r, 0.0f)), sqrt(max(c.g, 0.0f)), sqrt(max(c.b, 0.0f)));
    return rgbToYCbCr(s);
}

vec3 yCbCrSqrtToRgb(vec3 c) {
    vec3 s = max(yCbCrToRgb(c), vec3(0.0f));
    return s * s;
}

// rgbToYCoCg: YCoCg with Co, Cg offset by 0.5, all in [0,1] for rgb in [0,1]^3.
// Source: Malvar & Sullivan, JVT-I014 (2003); Mavridis & Papaioannou, "The Compact YCoCg Frame
// Buffer", JCGT 1(1), 2012. Exact inverse in real arithmetic (float: max 1.5e-7); 8 bits per
// code: max abs 0.0058, CIEDE2000 mean 0.17, max 5.3.
vec3 rgbToYCoCg(vec3 c) {
    float y = 0.25f * c.r + 0.5f * c.g + 0.25f * c.b;
    float co = 0.5f * c.r - 0.5f * c.b + 0.5f;
    float cg = -0.25f * c.r + 0.5f * c.g - 0.25f * c.b + 0.5f;
    return vec3(y, co, cg);
}

vec3 yCoCgToRgb(vec3 c) {
    float co = c.y - 0.5f;
    float cg = c.z - 0.5f;
    float t = c.x - cg;
    return vec3(t + co, c.x + cg, t - co);
}

// ---------------------------------------------------------------------------------------------
// 6. Chroma checkerboard. Source: Mavridis & Papaioannou, "The Compact YCoCg Frame Buffer",
// JCGT 1(1), 2012, section 3 and listing 1. Each pixel stores Y and one chroma: the first
// (Cb / Co) where (x+y) is even, the second (Cr / Cg) where it is odd.
// ---------------------------------------------------------------------------------------------

bool chromaIsSecond(ivec2 pixel) { return ((pixel.x + pixel.y) & 1) != 0; }

// chromaForPixel: the chroma this pixel stores, from (first, second) = (Cb, Cr) or (Co, Cg).
float chromaForPixel(ivec2 pixel, vec2 chroma) { return chromaIsSecond(pixel) ? chroma.y : chroma.x; }

// reconstructChroma: the paper's edge-directed filter. The 4 direct neighbours (order: +x, -x,
// +y, -y) hold the other chroma; each gets weight 1 - step(30/255, |Yn - Yc|) (1 when its luma
// is within the threshold). Their weighted mean is the missing chroma; when all 4 weights are 0
// the first neighbour (+x) is used alone, as in the paper's listing. Returns (centre's own
// chroma, reconstructed other chroma). At image borders fetch the missing neighbour mirrored
// (x = -1 reads x = 1): a replicated (clamped) fetch would read the centre's own chroma kind.
vec2 reconstructChroma(float lumaCentre, float chromaCentre, vec4 lumaNeighbours, vec4 chromaNeighbours) {
    vec4 w = vec4(1.0f) - step(vec4(kChromaEdgeThreshold), abs(lumaNeighbours - vec4(lumaCentre)));
    float total = w.x + w.y + w.z + w.w;
    if (total == 0.0f) {
        w.x = 1.0f;
        total = 1.0f;
    }
    float other = (w.x * chromaNeighbours.x + w.y * chromaNeighbours.y + w.z * chromaNeighbours.z +
                   w.w * chromaNeighbours.w) / total;
    return vec2(chromaCentre, other);
}

// reconstructChroma with the pixel: returns (first, second) = (Cb, Cr) or (Co, Cg).
// Error, 8 bits per code, on a synthetic image of 16x16 random flat blocks (3:1 with a ramp):
// CIEDE2000 mean 0.6, p99 9, max 42 (block corners, where no neighbour shares the centre's hue).
vec2 reconstructChroma(ivec2 pixel, float lumaCentre, float chromaCentre, vec4 lumaNeighbours,
                       vec4 chromaNeighbours) {
    vec2 c = reconstructChroma(lumaCentre, chromaCentre, lumaNeighbours, chromaNeighbours);
    return chromaIsSecond(pixel) ? vec2(c.y, c.x) : c;
}

// ---------------------------------------------------------------------------------------------
// 7. Roughness maps (scalar transforms, quantise with quantizeUnorm).
// ---------------------------------------------------------------------------------------------

// glossFromRoughness / roughnessFromGloss: gloss = 1 - roughness (CryEngine glossiness).
float glossFromRoughness(float r) {
    float g = 1.0f - r;
    return g;
}
float roughnessFromGloss(float g) { return 1.0f - g; }

// smoothnessFromRoughnessCry: s = 1 - sqrt(r); roughnessFromSmoothnessCry: r = (1 - s)^2.
// Source: Schulz, "Moving to the Next Generation - The Rendering Technology of Ryse", GDC 2014.
// With 8-bit unorm s: max roughness error 0.0039 (near r = 1), 0.5/255^2 near r = 0.
float smoothnessFromRoughnessCry(float r) {
    float s = 1.0f - sqrt(max(r, 0.0f));
    return s;
}
float roughnessFromSmoothnessCry(float s) { return (1.0f - s) * (1.0f - s); }

// ---------------------------------------------------------------------------------------------
// 8. UE4 specular colour and depth.
// ---------------------------------------------------------------------------------------------

// specularColorUE4: F0 = mix(0.08 * specular, baseColor, metallic), written out as
// a * (1 - t) + b * t. Source: Epic Games, UE4 DeferredShadingCommon.ush, ComputeF0
// (Karis, "Real Shading in Unreal Engine 4", SIGGRAPH 2013).
vec3 specularColorUE4(vec3 baseColor, float metallic, float specular) {
    vec3 f0 = vec3(0.08f * specular) * (1.0f - metallic) + baseColor * metallic;
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
    float c = clamp(d, 0.0f, 1.0f);
    float h = c * 16777216.0f;
    float hi = floor(h);
    float r = (h - hi) - c;
    float up = floor(r + 0.5f);
    return uint(int(hi) + int(up));
}
float dequantizeDepth24(uint code) { return dequantizeUnorm(code & 0xffffffu, 24u); }

// positionFromDepth: uv in [0,1]^2 (texel centres, (0,0) = first row), depth in [0,1]
// (Vulkan clip z), ndc = (uv * 2 - 1, depth); returns the world position for the inverse of the
// same view-projection matrix used to render (its y convention decides which row is uv.y = 0).
vec3 positionFromDepth(vec2 uv, float depth, mat4 invViewProj) {
    vec4 ndc = vec4(uv.x * 2.0f - 1.0f, uv.y * 2.0f - 1.0f, depth, 1.0f);
    vec4 p = invViewProj * ndc;
    return vec3(p.x / p.w, p.y / p.w, p.z / p.w);
}

}  // namespace gbl::enc
