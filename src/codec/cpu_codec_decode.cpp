// Decode loops of the CPU codec, a mirror of the generated readGBuffer: for each block of up to
// kBlock pixels of a row, the block's Surfaces are built member-major (one row of floats per
// Surface float, all zero to start, as readGBuffer starts from Surface(0)), then per field the
// codes are extracted and decoded by the field's primitive (src/encoding/encodings.h, inline) in one loop,
// then the material words and the fallbacks (in dependency order) fill the rest, and the block
// is written out as Surfaces. The loops vectorise (AVX2 clone, see simd_clones.h); they need
// -fno-math-errno -fno-trapping-math (set for this file in CMakeLists.txt), which change no value.
#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <stdexcept>

#include "cpu_codec_kernels.h"
#include "encodings.h"
#include "niagara_encodings.h"
#include "simd_clones.h"
#include "stream_copy.h"

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace gbl::codec {

using namespace enc;

namespace {

struct DecodeBlock {
    alignas(32) uint32_t code[4][kBlock + 2];
    alignas(32) float val[3][kBlock];
    alignas(32) float s[kSurfaceFloats][kBlock];  // the block's Surfaces, member-major
    // Checkerboard: luma and chroma of the centre row (x0 - 1 .. x0 + n), the row above, below.
    alignas(32) float luma[3][kBlock + 2];
    alignas(32) float chroma[3][kBlock + 2];
    alignas(32) float cover[3][kBlock + 2];  // gblCovered of the same pixels
    alignas(32) float pixels[kSurfaceFloats * kBlock];  // the block's Surfaces, interleaved
    alignas(32) uint32_t sel[kBlock];     // the stored shading-model id (a layout with a selector)
    alignas(32) float keep[4][kBlock];    // a conditional field's attribute before it (3: what it carries)
};

// The image border mirror of the former per-pixel codec (x = -1 reads x = 1).
GBL_CLONE_INLINE int mirror(int p, int size) {
    p = std::abs(p);
    p = (size - 1) - std::abs((size - 1) - p);
    return std::clamp(p, 0, size - 1);
}

template <int Words>
GBL_CLONE_INLINE void extractCode(const CodePlan& code, int n, const uint32_t* __restrict words,
                                  uint32_t* __restrict out) {
    if (code.pieces.empty()) std::fill(out, out + n, 0u);
    for (size_t i = 0; i < code.pieces.size(); ++i) {
        const Piece& p = code.pieces[i];
        const int w = p.word, shift = p.shift, codeShift = p.codeShift;
        const uint32_t mask = p.mask;
        if (i == 0) {  // assigned, not ORed into zeros: a memset per code cost more than the loop
            for (int j = 0; j < n; ++j) out[j] = ((words[j * Words + w] >> shift) & mask) << codeShift;
        } else {
            for (int j = 0; j < n; ++j) out[j] |= ((words[j * Words + w] >> shift) & mask) << codeShift;
        }
    }
}

GBL_CLONE_INLINE uint32_t extractOne(const CodePlan& code, const uint32_t* words) {
    uint32_t c = 0u;
    for (const Piece& p : code.pieces) c |= ((words[p.word] >> p.shift) & p.mask) << p.codeShift;
    return c;
}

template <class Fn>
GBL_CLONE_INLINE void map1(int n, const uint32_t* __restrict c, float* __restrict out, Fn fn) {
    for (int j = 0; j < n; ++j) out[j] = fn(c[j]);
}

// Up to 3 codes per pixel in, a vec3 per pixel out.
template <class Fn>
GBL_CLONE_INLINE void map3(int n, const uint32_t* __restrict c0, const uint32_t* __restrict c1,
                           const uint32_t* __restrict c2, float* __restrict x, float* __restrict y, float* __restrict z,
                           Fn fn) {
    for (int j = 0; j < n; ++j) {
        const vec3 v = fn(c0[j], c1[j], c2[j]);
        x[j] = v.x;
        y[j] = v.y;
        z[j] = v.z;
    }
}

// Linear values of a row of sRGB codes (n <= kBlock). Written to a local array first: in
// target_clones clones GCC 12 drops `restrict`, and then cannot rule out that the stores change
// kSrgbDecode (floats, like `out`), so the loop stays scalar; a local array cannot alias it.
GBL_SIMD_CLONES void srgb8Row(int n, const uint32_t* c, float* out) {
    alignas(32) float values[kBlock];
    for (int j = 0; j < n; ++j) values[j] = decodeSrgb8(c[j]);
    std::copy(values, values + n, out);
}

// Mirror of the colour decoders: the inverse transform of the 3 dequantised codes (chroma by D:
// dequantizeChroma for the YCbCr family, dequantizeUnorm for YCoCg).
template <vec3 (*Inv)(vec3), float (*D)(uint, uint)>
GBL_CLONE_INLINE void transformedRow(int n, const uint32_t* c0, const uint32_t* c1, const uint32_t* c2, float* x,
                                     float* y, float* z, uint bits) {
    map3(n, c0, c1, c2, x, y, z, [bits](uint a, uint b1, uint b2) {
        return Inv(vec3(dequantizeUnorm(a, bits), D(b1, bits), D(b2, bits)));
    });
}

// Where a decoded vec3 goes: component c into the Surface row dest + c when the attribute has it,
// else into scratch (b.val), as setMember drops the components beyond the attribute's.
struct Outputs {
    float* c[3];
};
GBL_CLONE_INLINE Outputs outputsFor(DecodeBlock& b, int dest, int components) {
    Outputs o;
    for (int c = 0; c < 3; ++c) o.c[c] = c < components ? b.s[dest + c] : b.val[c];
    return o;
}

// A scalar encoding's decode, per component (components beyond the codes are 0).
GBL_SIMD_CLONES void decodeScalarValues(const FieldPlan& f, int n, DecodeBlock& b, const Outputs& o) {
    for (size_t k = 0; k < 3; ++k) {
        float* out = o.c[k];
        if (k >= f.codes.size()) {
            std::fill(out, out + n, 0.0f);
            continue;
        }
        const uint bk = f.codes[k].bits;
        const uint32_t* c = b.code[k];
        switch (f.codec) {
            case Codec::Unorm: map1(n, c, out, [bk](uint x) { return dequantizeUnorm(x, bk); }); break;
            case Codec::Snorm: map1(n, c, out, [bk](uint x) { return dequantizeSnorm(x, bk); }); break;
            case Codec::Float16: map1(n, c, out, [](uint x) { return decodeFloat16(x); }); break;
            case Codec::Float11: map1(n, c, out, [](uint x) { return decodeFloat11(x); }); break;
            case Codec::Float10: map1(n, c, out, [](uint x) { return decodeFloat10(x); }); break;
            case Codec::Float32: map1(n, c, out, [](uint x) { return decodeFloat32(x); }); break;
            case Codec::Depth24: map1(n, c, out, [](uint x) { return dequantizeDepth24(x); }); break;
            case Codec::Gloss:
                map1(n, c, out, [bk](uint x) { return roughnessFromGloss(dequantizeUnorm(x, bk)); });
                break;
            case Codec::SmoothnessCry:
                map1(n, c, out, [bk](uint x) { return roughnessFromSmoothnessCry(dequantizeUnorm(x, bk)); });
                break;
            case Codec::CryGlossPower: map1(n, c, out, [](uint x) { return decodeCryGlossPower(x); }); break;
            case Codec::Kz2LogPower: map1(n, c, out, [](uint x) { return decodeKz2LogPower(x); }); break;
            case Codec::Reflectance:
                map1(n, c, out, [bk](uint x) { return specularFromReflectance(dequantizeUnorm(x, bk)); });
                break;
            case Codec::UnormRoundEven: map1(n, c, out, [bk](uint x) { return dequantizeUnorm(x, bk); }); break;
            case Codec::CoatRoughnessBevy:
                map1(n, c, out, [bk](uint x) { return decodeCoatRoughnessBevy(x, bk); });
                break;
            case Codec::UnormSigned: map1(n, c, out, [bk](uint x) { return dequantizeUnormSigned(x, bk); }); break;
            case Codec::UnormSqrt: map1(n, c, out, [](uint x) { return decodeUnormSqrt(x); }); break;
            case Codec::ReflectanceBevyWebgl2:
                map1(n, c, out, [bk](uint x) { return specularFromReflectanceBevyWebgl2(dequantizeUnorm(x, bk)); });
                break;
            default: break;  // Id: CpuCodec::decode throws before (plan.decodeError)
        }
    }
}

// Decoded attribute of a non-checkerboard field, from b.code into `o` (mirror of decodeFieldExpr):
// scalars per component (decodeScalarValues), vec3 encodings with code 0's bits.
GBL_SIMD_CLONES void decodeValues(const FieldPlan& f, int n, DecodeBlock& b, const Outputs& o) {
    if (isScalar(f.codec)) {
        decodeScalarValues(f, n, b, o);
        return;
    }
    const uint bits = f.codes[0].bits;
    const uint32_t *c0 = b.code[0], *c1 = b.code[1], *c2 = b.code[2];
    float *x = o.c[0], *y = o.c[1], *z = o.c[2];
    switch (f.codec) {
        case Codec::Srgb8:
            srgb8Row(n, c0, x);
            srgb8Row(n, c1, y);
            srgb8Row(n, c2, z);
            return;
        case Codec::Luma:
            map1(n, c0, x, [bits](uint c) { return dequantizeUnorm(c, bits); });
            std::copy(x, x + n, y);
            std::copy(x, x + n, z);
            return;
        case Codec::YCbCr: transformedRow<yCbCrToRgb, dequantizeChroma>(n, c0, c1, c2, x, y, z, bits); return;
        case Codec::YCbCrSqrt:
            transformedRow<yCbCrSqrtToRgb, dequantizeChroma>(n, c0, c1, c2, x, y, z, bits);
            return;
        case Codec::YCoCg: transformedRow<yCoCgToRgb, dequantizeUnorm>(n, c0, c1, c2, x, y, z, bits); return;
        case Codec::NormalXyz:
            map3(n, c0, c1, c2, x, y, z,
                 [bits](uint a, uint b1, uint b2) { return decodeNormalXyz(uvec3(a, b1, b2), bits); });
            return;
        case Codec::NormalBestFit:
            map3(n, c0, c1, c2, x, y, z,
                 [](uint a, uint b1, uint b2) { return decodeNormalBestFit(uvec3(a, b1, b2)); });
            return;
        case Codec::NormalXyZSign:
            map3(n, c0, c1, c2, x, y, z,
                 [bits](uint a, uint b1, uint b2) { return decodeNormalXyZSign(uvec3(a, b1, b2), bits); });
            return;
        case Codec::NormalSpheremap:
            map3(n, c0, c1, c1, x, y, z,
                 [bits](uint a, uint b1, uint) { return decodeNormalSpheremap(uvec2(a, b1), bits); });
            return;
        case Codec::NormalStereographic:
            map3(n, c0, c1, c1, x, y, z,
                 [bits](uint a, uint b1, uint) { return decodeNormalStereographic(uvec2(a, b1), bits); });
            return;
        case Codec::NormalOctahedral:
            map3(n, c0, c1, c1, x, y, z,
                 [bits](uint a, uint b1, uint) { return decodeNormalOctahedral(uvec2(a, b1), bits); });
            return;
        case Codec::NormalOctahedralPrecise:
            map3(n, c0, c1, c1, x, y, z,
                 [bits](uint a, uint b1, uint) { return decodeNormalOctahedralPrecise(uvec2(a, b1), bits); });
            return;
        case Codec::Gamma22:
            map1(n, c0, x, [](uint c) { return decodeGamma22(c); });
            map1(n, c1, y, [](uint c) { return decodeGamma22(c); });
            map1(n, c2, z, [](uint c) { return decodeGamma22(c); });
            return;
        case Codec::Srgb8FastHdrp:
            map1(n, c0, x, [](uint c) { return decodeSrgb8FastHdrp(c); });
            map1(n, c1, y, [](uint c) { return decodeSrgb8FastHdrp(c); });
            map1(n, c2, z, [](uint c) { return decodeSrgb8FastHdrp(c); });
            return;
        case Codec::Float111110:
            map1(n, c0, x, [](uint c) { return decodeFloat11(c); });
            map1(n, c1, y, [](uint c) { return decodeFloat11(c); });
            map1(n, c2, z, [](uint c) { return decodeFloat10(c); });
            return;
        case Codec::Rgb9e5: {
            const uint32_t* c3 = b.code[3];
            for (int j = 0; j < n; ++j) {
                const vec3 v = decodeRgb9e5(uvec4(c0[j], c1[j], c2[j], c3[j]));
                x[j] = v.x;
                y[j] = v.y;
                z[j] = v.z;
            }
            return;
        }
        case Codec::Float111110HdrpAoTag: {
            // Emissive, and the occlusion the tag holds (1 where it holds emissive), as HDRP decodes.
            float* __restrict ao = b.s[f.carried];
            for (int j = 0; j < n; ++j) {
                const uvec3 c(c0[j], c1[j], c2[j]);
                const vec3 e = decodeFloat111110HdrpAoTag(c);
                ao[j] = decodeHdrpAoTagOcclusion(c);
                x[j] = e.x;
                y[j] = e.y;
                z[j] = e.z;
            }
            return;
        }
        case Codec::AnisotropyTangentAngleHdrp: {
            // Against the decoded normal (validation puts its field before this one), and the
            // strength it carries, as HDRP's DecodeFromGBuffer (engine_encodings.h).
            const float *nx = b.s[f.reads], *ny = b.s[f.reads + 1], *nz = b.s[f.reads + 2];
            float* __restrict strength = b.s[f.carried];
            for (int j = 0; j < n; ++j) {
                const uvec3 c(c0[j], c1[j], c2[j]);
                const vec3 t = decodeAnisotropyHdrp(c, vec3(nx[j], ny[j], nz[j]));
                strength[j] = decodeAnisotropyHdrpStrength(c);
                x[j] = t.x;
                y[j] = t.y;
                z[j] = t.z;
            }
            return;
        }
        case Codec::NormalOctahedralDeltaUe: {
            // Against the decoded coat normal, as GetClearCoatBottomNormal reads the decoded
            // GBuffer.WorldNormal (ClearCoatCommon.ush:9); validation puts a field of the same
            // models storing it before this one.
            const float *tx = b.s[f.reads], *ty = b.s[f.reads + 1], *tz = b.s[f.reads + 2];
            for (int j = 0; j < n; ++j) {
                const vec3 v = decodeNormalOctahedralDeltaUe(uvec2(c0[j], c1[j]), vec3(tx[j], ty[j], tz[j]), bits);
                x[j] = v.x;
                y[j] = v.y;
                z[j] = v.z;
            }
            return;
        }
        case Codec::EmissiveAlbedoRatio: {
            // From the decoded base colour: validation puts its field before this one.
            const float *ar = b.s[f.reads], *ag = b.s[f.reads + 1], *ab = b.s[f.reads + 2];
            for (int j = 0; j < n; ++j) {
                const vec3 e = decodeEmissiveAlbedoRatio(b.code[0][j], bits, vec3(ar[j], ag[j], ab[j]));
                o.c[0][j] = e.x;
                o.c[1][j] = e.y;
                o.c[2][j] = e.z;
            }
            return;
        }
        case Codec::NormalOctahedralDithered:
        case Codec::NormalOctahedralBevy:
        case Codec::NormalOctahedralUnity:
        case Codec::NormalOctahedralHdrp:
            map3(n, c0, c1, c1, x, y, z,
                 [bits](uint a, uint b1, uint) { return decodeNormalOctahedralUnorm(uvec2(a, b1), bits); });
            return;
        case Codec::NormalXyFloat16:
            map3(n, c0, c1, c1, x, y, z, [](uint a, uint b1, uint) { return decodeNormalXyFloat16(uvec2(a, b1)); });
            return;
        default: return;  // checkerboard: decodeCheckerboard
    }
}

// Dequantised luma and chroma codes of `count` pixels of `row` from x = xFrom, mirrored at the
// image's left and right edges: the inside of the image in contiguous loops, the (at most two)
// pixels beyond its edges one by one.
template <int Words>
GBL_CLONE_INLINE void lumaChromaRow(const FieldPlan& f, const uint32_t* image, const uint8_t* covered, int width,
                                    int row, int xFrom, int count, float* __restrict luma, float* __restrict chroma,
                                    float* __restrict cover, DecodeBlock& b) {
    const uint bits = f.codes[0].bits;
    const int lo = std::max(xFrom, 0), hi = std::min(xFrom + count, width);
    const uint32_t* rowWords = image + size_t(row) * size_t(width) * Words;
    uint32_t* __restrict lumaCode = b.code[2];  // free: a checkerboard field has 2 codes
    uint32_t* __restrict chromaCode = b.code[3];
    extractCode<Words>(f.codes[0], hi - lo, rowWords + size_t(lo) * Words, lumaCode + (lo - xFrom));
    extractCode<Words>(f.codes[1], hi - lo, rowWords + size_t(lo) * Words, chromaCode + (lo - xFrom));
    // Only the pixels beyond the edges (k < lo - xFrom, k >= hi - xFrom): a loop over all `count`
    // that skipped the inside cost a compare and branch per pixel (perf: ~12 % of crysis3-thin's decode).
    const int ranges[2][2] = {{0, std::min(lo - xFrom, count)}, {std::max(hi - xFrom, 0), count}};
    for (const auto& r : ranges)
        for (int k = r[0]; k < r[1]; ++k) {
        const uint32_t* w = rowWords + size_t(mirror(xFrom + k, width)) * Words;
        lumaCode[k] = extractOne(f.codes[0], w);
        chromaCode[k] = extractOne(f.codes[1], w);
        }
    if (f.codec == Codec::YCbCrCheckerboard) {
        for (int k = 0; k < count; ++k) {
            luma[k] = dequantizeUnorm(lumaCode[k], bits);
            chroma[k] = dequantizeChroma(chromaCode[k], bits);
        }
    } else {
        for (int k = 0; k < count; ++k) {
            luma[k] = dequantizeUnorm(lumaCode[k], bits);
            chroma[k] = dequantizeUnorm(chromaCode[k], bits);
        }
    }
    // gblCovered: 1 where the pixel has geometry (all pixels when no mask is given).
    if (!covered) {
        std::fill(cover, cover + count, 1.0f);
        return;
    }
    const uint8_t* rowCovered = covered + size_t(row) * size_t(width);
    for (int k = 0; k < count; ++k) cover[k] = rowCovered[mirror(xFrom + k, width)] ? 1.0f : 0.0f;
}

// The reconstruction over a block (restrict views of the rows: centre luma / chroma l0 / k0 at
// x0 - 1 .. x0 + n, above l1 / k1 and below l2 / k2 at x0 .. x0 + n - 1).
template <vec3 (*Inv)(vec3)>
GBL_CLONE_INLINE void reconstructRow(int n, int x0, int y, const float* __restrict l0, const float* __restrict k0,
                                     const float* __restrict l1, const float* __restrict k1,
                                     const float* __restrict l2, const float* __restrict k2,
                                     const float* __restrict v0, const float* __restrict v1,
                                     const float* __restrict v2, float* __restrict x, float* __restrict yv,
                                     float* __restrict z) {
    for (int j = 0; j < n; ++j) {
        const vec2 c = vec2(l0[j + 1], k0[j + 1]);
        const vec2 n0 = vec2(l0[j + 2], k0[j + 2]);
        const vec2 n1 = vec2(l0[j], k0[j]);
        const vec2 n2 = vec2(l2[j], k2[j]);
        const vec2 n3 = vec2(l1[j], k1[j]);
        // reconstructChroma(ivec2(x0 + j, y), ...) is this call plus the swap below where
        // chromaIsSecond; written out with an int parity because GCC 12 does not vectorise the
        // loop through chromaIsSecond's bool.
        const vec2 r = reconstructChroma(c.x, c.y, vec4(n0.x, n1.x, n2.x, n3.x), vec4(n0.y, n1.y, n2.y, n3.y),
                                         vec4(v0[j + 2], v0[j], v2[j], v1[j]));
        const int second = (x0 + j + y) & 1;
        const vec2 ch = vec2(second ? r.y : r.x, second ? r.x : r.y);
        const vec3 v = Inv(vec3(c.x, ch.x, ch.y));
        x[j] = v.x;
        yv[j] = v.y;
        z[j] = v.z;
    }
}

// Checkerboard chroma (mirror of the generated readGBuffer and the former per-pixel codec): the
// centre's luma and chroma, the other chroma rebuilt from the 4 neighbours (+x, -x, +y, -y),
// mirrored at the borders, then the inverse colour transform.
template <int Words, vec3 (*Inv)(vec3)>
GBL_CLONE_INLINE void decodeCheckerboard(const FieldPlan& f, const uint32_t* image, const uint8_t* covered, int width,
                                         int height, int x0, int y, int n, DecodeBlock& b) {
    lumaChromaRow<Words>(f, image, covered, width, y, x0 - 1, n + 2, b.luma[0], b.chroma[0], b.cover[0], b);
    lumaChromaRow<Words>(f, image, covered, width, mirror(y - 1, height), x0, n, b.luma[1], b.chroma[1], b.cover[1],
                         b);
    lumaChromaRow<Words>(f, image, covered, width, mirror(y + 1, height), x0, n, b.luma[2], b.chroma[2], b.cover[2],
                         b);
    const Outputs o = outputsFor(b, f.source, f.components);
    reconstructRow<Inv>(n, x0, y, b.luma[0], b.chroma[0], b.luma[1], b.chroma[1], b.luma[2], b.chroma[2], b.cover[0],
                        b.cover[1], b.cover[2], o.c[0], o.c[1], o.c[2]);
}

template <int Words>
GBL_CLONE_INLINE void decodeTarget(const TargetPlan& t, const uint32_t* image, const uint8_t* covered, int width,
                                   int height, int x0, int y, int n, DecodeBlock& b) {
    // A target of extras only (ue4's GBufferD and E) decodes to nothing: not even prefetched,
    // its words are never read (8 of ue4's 20 bytes per pixel).
    if (t.decodeFields.empty()) return;
    const uint32_t* words = image + (size_t(y) * size_t(width) + size_t(x0)) * Words;
    prefetchAhead(words, size_t(n) * Words * sizeof(uint32_t));
    for (const FieldPlan& f : t.decodeFields) {
        if (f.codec == Codec::YCbCrCheckerboard) {
            decodeCheckerboard<Words, yCbCrToRgb>(f, image, covered, width, height, x0, y, n, b);
        } else if (f.codec == Codec::YCoCgCheckerboard) {
            decodeCheckerboard<Words, yCoCgToRgb>(f, image, covered, width, height, x0, y, n, b);
        } else if (f.ids) {
            // Conditional (layouts/README.md, "Shading models"): decoded where the stored id is one of
            // its models', else the attribute keeps what it held (0, a field of another model, or
            // later its fallback), as the generated readGBuffer's `if`. A block with no such pixel
            // (a scene without the field's layer) keeps everything: nothing to decode; one whose
            // every pixel is of its models decodes straight, as an unconditional field.
            int count = 0;
            for (int j = 0; j < n; ++j) count += int((f.ids >> b.sel[j]) & 1u);
            if (count == 0) continue;
            if (count == n) {
                for (size_t k = 0; k < f.codes.size(); ++k) extractCode<Words>(f.codes[k], n, words, b.code[k]);
                decodeValues(f, n, b, outputsFor(b, f.source, f.components));
                continue;
            }
            for (int c = 0; c < f.components; ++c) std::copy(b.s[f.source + c], b.s[f.source + c] + n, b.keep[c]);
            if (f.carried >= 0) std::copy(b.s[f.carried], b.s[f.carried] + n, b.keep[3]);
            for (size_t k = 0; k < f.codes.size(); ++k) extractCode<Words>(f.codes[k], n, words, b.code[k]);
            decodeValues(f, n, b, outputsFor(b, f.source, f.components));
            const uint32_t ids = f.ids;
            const uint32_t* __restrict sel = b.sel;
            for (int c = 0; c < f.components; ++c) {
                float* __restrict row = b.s[f.source + c];
                const float* __restrict kept = b.keep[c];
                for (int j = 0; j < n; ++j) row[j] = ((ids >> sel[j]) & 1u) ? row[j] : kept[j];
            }
            if (f.carried >= 0) {
                float* __restrict row = b.s[f.carried];
                const float* __restrict kept = b.keep[3];
                for (int j = 0; j < n; ++j) row[j] = ((ids >> sel[j]) & 1u) ? row[j] : kept[j];
            }
        } else {
            for (size_t k = 0; k < f.codes.size(); ++k) extractCode<Words>(f.codes[k], n, words, b.code[k]);
            decodeValues(f, n, b, outputsFor(b, f.source, f.components));
        }
    }
}

// The stored shading-model id of the block's pixels, before any field: conditional fields and
// fallbacks test it; Surface::shadingModel holds it (as a float, as readGBuffer's float(gblSel)).
template <int Words>
GBL_CLONE_INLINE void decodeSelector(const CodecPlan& plan, const uint32_t* image, int width, int x0, int y, int n,
                                     DecodeBlock& b) {
    const uint32_t* words = image + (size_t(y) * size_t(width) + size_t(x0)) * Words;
    extractCode<Words>(plan.selectorCode, n, words, b.sel);
    float* __restrict out = b.s[surfaceOffset(Attribute::ShadingModel)];
    for (int j = 0; j < n; ++j) out[j] = float(b.sel[j]);
}

GBL_SIMD_CLONES void decodeSelectorBlock(const CodecPlan& plan, const ConstWordViews& in, int width, int x0, int y,
                                         int n, DecodeBlock& b) {
    const uint32_t* image = in.targets[plan.selectorTarget];
    switch (plan.selectorWords) {
        case 1: decodeSelector<1>(plan, image, width, x0, y, n, b); return;
        case 2: decodeSelector<2>(plan, image, width, x0, y, n, b); return;
        default: decodeSelector<4>(plan, image, width, x0, y, n, b); return;
    }
}

GBL_SIMD_CLONES void decodeTargetBlock(const TargetPlan& t, const uint32_t* image, const uint8_t* covered, int width,
                                       int height, int x0, int y, int n, DecodeBlock& b) {
    switch (t.words) {
        case 1: decodeTarget<1>(t, image, covered, width, height, x0, y, n, b); return;
        case 2: decodeTarget<2>(t, image, covered, width, height, x0, y, n, b); return;
        default: decodeTarget<4>(t, image, covered, width, height, x0, y, n, b); return;
    }
}

// The material words of the block's pixels into their Surface floats (0 beyond the slot's): per
// material target, 4 pixels' words at a time transposed into the 4 channels' Surface rows (bit
// moves; an unused channel goes to scratch, b.val[0]).
GBL_SIMD_CLONES void decodeMaterial(const CodecPlan& plan, const uint32_t* const* material, size_t first, int n,
                                    DecodeBlock& b) {
    for (int m = 0; m < plan.materialTargets; ++m) prefetchAhead(material[m] + first * 4, size_t(n) * 16);
    for (int m = 0; m < plan.materialTargets; ++m) {
        float* rows[4];
        for (int ch = 0; ch < 4; ++ch) {
            const int dest = plan.materialSource[size_t(m * 4 + ch)];
            rows[ch] = dest < 0 ? b.val[0] : b.s[dest];
        }
        const float* words = reinterpret_cast<const float*>(material[m] + first * 4);
        int j = 0;
#if defined(__SSE2__)
        for (; j + 4 <= n; j += 4) {
            __m128 r0 = _mm_loadu_ps(words + (j + 0) * 4), r1 = _mm_loadu_ps(words + (j + 1) * 4);
            __m128 r2 = _mm_loadu_ps(words + (j + 2) * 4), r3 = _mm_loadu_ps(words + (j + 3) * 4);
            _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
            _mm_store_ps(rows[0] + j, r0);
            _mm_store_ps(rows[1] + j, r1);
            _mm_store_ps(rows[2] + j, r2);
            _mm_store_ps(rows[3] + j, r3);
        }
#endif
        const uint32_t* w = material[m] + first * 4;
        for (; j < n; ++j)
            for (int ch = 0; ch < 4; ++ch) rows[ch][j] = uintBitsToFloat(w[size_t(j) * 4 + size_t(ch)]);
    }
    for (const MaterialSlotPlan& slot : plan.materialSlots)
        for (int c = slot.slotComponents; c < slot.components; ++c)
            std::fill(b.s[slot.dest + c], b.s[slot.dest + c] + n, 0.0f);
}

// Mirror of applyFallback in the former per-pixel codec (the same vec3 expressions per pixel).
GBL_SIMD_CLONES void applyFallbacks(const CodecPlan& plan, int n, DecodeBlock& b) {
    const int base = surfaceOffset(Attribute::BaseColor), met = surfaceOffset(Attribute::Metallic);
    const int spec = surfaceOffset(Attribute::Specular), specColor = surfaceOffset(Attribute::SpecularColor);
    const int diffuse = surfaceOffset(Attribute::DiffuseColor), rough = surfaceOffset(Attribute::Roughness);
    auto at = [&](int first, int j) { return vec3(b.s[first][j], b.s[first + 1][j], b.s[first + 2][j]); };
    for (const FallbackPlan& fb : plan.fallbacks) {
        if (fb.kind == FallbackKind::MaterialPass) continue;  // decodeMaterial
        // Straight into the attribute's rows: no fallback reads the attribute it sets.
        const Outputs o = outputsFor(b, fb.dest, fb.components);
        float* __restrict x = o.c[0];
        float* __restrict y = o.c[1];
        float* __restrict z = o.c[2];
        const uint32_t storedIds = fb.storedIds;
        const uint32_t* __restrict sel = b.sel;
        auto each = [&](auto fn) {
            int stored = 0;  // pixels whose model stores the attribute: all (skip), none (every pixel), some
            for (int j = 0; storedIds && j < n; ++j) stored += int((storedIds >> sel[j]) & 1u);
            if (storedIds && stored == n) return;
            if (stored > 0) {  // stored under some models: the fallback where the pixel's model does not store it
                for (int j = 0; j < n; ++j) {
                    if ((storedIds >> sel[j]) & 1u) continue;
                    const vec3 v = fn(j);
                    x[j] = v.x;
                    y[j] = v.y;
                    z[j] = v.z;
                }
                return;
            }
            for (int j = 0; j < n; ++j) {
                const vec3 v = fn(j);
                x[j] = v.x;
                y[j] = v.y;
                z[j] = v.z;
            }
        };
        switch (fb.kind) {
            case FallbackKind::Constant:
                each([&](int) { return vec3(fb.value[0], fb.value[1], fb.value[2]); });
                break;
            case FallbackKind::FromMetallic:
                each([&](int j) { return vec3(0.04f) * (1.0f - b.s[met][j]) + at(base, j) * b.s[met][j]; });
                break;
            case FallbackKind::Ue4:
                each([&](int j) { return specularColorUE4(at(base, j), b.s[met][j], b.s[spec][j]); });
                break;
            case FallbackKind::FromBaseColor: each([&](int j) { return at(base, j) * (1.0f - b.s[met][j]); }); break;
            case FallbackKind::FromDiffuseSpecular:
                each([&](int j) { return at(diffuse, j) + b.s[met][j] * at(specColor, j); });
                break;
            case FallbackKind::FromSpecularColor:
                each([&](int j) {
                    const vec3 f0 = at(specColor, j);
                    return vec3(clamp((max(f0.x, max(f0.y, f0.z)) - 0.04f) / 0.96f, 0.0f, 1.0f));
                });
                break;
            case FallbackKind::FromRoughness: each([&](int j) { return vec3(b.s[rough][j]); }); break;
            default: each([](int) { return vec3(0.0f); }); break;  // Forward: emissive reads back 0
        }
    }
}

// The block's member-major floats out as n Surfaces. A Surface is 9 groups of 4 floats (144
// bytes), so where the block's first Surface is 16-byte aligned (a std::vector's image) every one
// is: 4 Surfaces at a time are 4 x 4 transposes per group, streamed straight to the image.
// Otherwise they are interleaved into b.pixels and copied by streamCopy (that copy was ~40 % of
// this function's time).
GBL_SIMD_CLONES void writeSurfaces(DecodeBlock& b, int n, Surface* out) {
    int j = 0;
#if defined(__SSE2__)
    static_assert(kSurfaceFloats == 36 && sizeof(Surface) == 144, "9 groups of 4 members");
    const bool aligned = reinterpret_cast<uintptr_t>(out) % 16 == 0;
    float* __restrict dst = aligned ? reinterpret_cast<float*>(out) : b.pixels;
    for (; j + 4 <= n; j += 4) {
        float* o = dst + size_t(j) * kSurfaceFloats;
        for (int k = 0; k < kSurfaceFloats; k += 4) {
            __m128 r0 = _mm_load_ps(&b.s[k][j]), r1 = _mm_load_ps(&b.s[k + 1][j]);
            __m128 r2 = _mm_load_ps(&b.s[k + 2][j]), r3 = _mm_load_ps(&b.s[k + 3][j]);
            _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
            if (aligned) {
                _mm_stream_ps(o + 0 * kSurfaceFloats + k, r0);
                _mm_stream_ps(o + 1 * kSurfaceFloats + k, r1);
                _mm_stream_ps(o + 2 * kSurfaceFloats + k, r2);
                _mm_stream_ps(o + 3 * kSurfaceFloats + k, r3);
            } else {
                _mm_storeu_ps(o + 0 * kSurfaceFloats + k, r0);
                _mm_storeu_ps(o + 1 * kSurfaceFloats + k, r1);
                _mm_storeu_ps(o + 2 * kSurfaceFloats + k, r2);
                _mm_storeu_ps(o + 3 * kSurfaceFloats + k, r3);
            }
        }
    }
    if (!aligned) streamCopy(out, b.pixels, size_t(j) * sizeof(Surface));
#endif
    // The rest (n not a multiple of 4, or no SSE2): interleaved, then copied.
    float* __restrict o = b.pixels;
    for (int p = j; p < n; ++p)
        for (int k = 0; k < kSurfaceFloats; ++k) o[(p - j) * kSurfaceFloats + k] = b.s[k][p];
    if (j < n) streamCopy(out + j, o, size_t(n - j) * sizeof(Surface));
}

}  // namespace

void decodeRows(const CodecPlan& plan, const ConstWordViews& in, int width, int height, int y0, int y1,
                Surface* out) {
    if (plan.decodeError) throw std::logic_error(plan.decodeError);
    DecodeBlock b;
    for (int y = y0; y < y1; ++y)
        for (int x0 = 0; x0 < width; x0 += kBlock) {
            const int n = std::min(kBlock, width - x0);
            const size_t first = size_t(y) * size_t(width) + size_t(x0);
            // Surface(0), readGBuffer's start: only the floats nothing below sets need it.
            for (const int k : plan.unwritten) std::fill(b.s[k], b.s[k] + kBlock, 0.0f);
            if (plan.selectorTarget >= 0) decodeSelectorBlock(plan, in, width, x0, y, n, b);
            for (size_t t = 0; t < plan.targets.size(); ++t)
                decodeTargetBlock(plan.targets[t], in.targets[t], in.covered, width, height, x0, y, n, b);
            decodeMaterial(plan, in.material, first, n, b);
            applyFallbacks(plan, n, b);
            writeSurfaces(b, n, out + (first - size_t(y0) * size_t(width)));
        }
    streamFence();
}

}  // namespace gbl::codec
