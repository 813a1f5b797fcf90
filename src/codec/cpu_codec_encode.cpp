// Encode loops of the CPU codec: for each block of up to kBlock pixels of a row, the Surfaces are
// transposed member-major once; then each target's words start from its constant words, and field
// by field the inputs are turned into codes by the field's primitive (src/encoding/encodings.h, inline) in
// one tight loop per field, and OR-ed into place. The loops vectorise (AVX2 clone, see
// simd_clones.h); they need -fno-math-errno -fno-trapping-math (set for this file in
// CMakeLists.txt), which change no value.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "cpu_codec_kernels.h"
#include "encodings.h"
#include "encodings_fast.h"
#include "niagara_encodings.h"
#include "simd_clones.h"
#include "stream_copy.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
#endif

namespace gbl::codec {

using namespace enc;

namespace {

// The Surfaces as one array of floats (36 per pixel, static_assert in cpu_codec_plan.h): member
// `index` of pixel j is floats(px)[j * kSurfaceFloats + index]. Plain float loads: a byte-wise
// copy here made GCC assemble the gathered vectors through the stack (store-forwarding stalls).
GBL_CLONE_INLINE const float* floats(const Surface* px) { return reinterpret_cast<const float*>(px); }

// One input, one code per pixel.
template <class Fn>
GBL_CLONE_INLINE void map1(int n, const float* __restrict in, uint32_t* __restrict out, Fn fn) {
    for (int j = 0; j < n; ++j) out[j] = fn(in[j]);
}

// A vec3 per pixel (in[0..2]), 1-3 codes per pixel.
template <class Fn>
GBL_CLONE_INLINE void map3to1(int n, const float* __restrict x, const float* __restrict y,
                              const float* __restrict z, uint32_t* __restrict o0, Fn fn) {
    for (int j = 0; j < n; ++j) o0[j] = fn(vec3(x[j], y[j], z[j]));
}
template <class Fn>
GBL_CLONE_INLINE void map3to2(int n, const float* __restrict x, const float* __restrict y,
                              const float* __restrict z, uint32_t* __restrict o0, uint32_t* __restrict o1, Fn fn) {
    for (int j = 0; j < n; ++j) {
        const uvec2 c = fn(vec3(x[j], y[j], z[j]), j);
        o0[j] = c.x;
        o1[j] = c.y;
    }
}
template <class Fn>
GBL_CLONE_INLINE void map3to3(int n, const float* __restrict x, const float* __restrict y,
                              const float* __restrict z, uint32_t* __restrict o0, uint32_t* __restrict o1,
                              uint32_t* __restrict o2, Fn fn) {
    for (int j = 0; j < n; ++j) {
        const uvec3 c = fn(vec3(x[j], y[j], z[j]));
        o0[j] = c.x;
        o1[j] = c.y;
        o2[j] = c.z;
    }
}

// Mirror of the generated writeGBuffer for colour transforms: 3 unorm codes of fwd(rgb).
// Chroma is quantised by Q: quantizeChroma (the YCbCr family, midpoint code exactly neutral) or
// quantizeUnorm (YCoCg), as chromaQuantize in wiring_codegen.
template <vec3 (*Fwd)(vec3), uint (*Q)(float, uint)>
GBL_CLONE_INLINE void transformed3(int n, EncodeBlock& b, uint bits) {
    map3to3(n, b.src[0], b.src[1], b.src[2], b.code[0], b.code[1], b.code[2], [bits](vec3 v) {
        const vec3 t = Fwd(v);
        return uvec3(quantizeUnorm(t.x, bits), Q(t.y, bits), Q(t.z, bits));
    });
}

// Luma and the chroma this pixel's parity stores. chromaForPixel(ivec2(x0 + j, y), (t.y, t.z)) is
// written out with an int parity: GCC 12 does not vectorise the loop through chromaIsSecond's bool.
template <vec3 (*Fwd)(vec3), uint (*Q)(float, uint)>
GBL_CLONE_INLINE void checkerboard(int n, int x0, int y, EncodeBlock& b, uint bits) {
    map3to2(n, b.src[0], b.src[1], b.src[2], b.code[0], b.code[1], [bits, x0, y](vec3 v, int j) {
        const vec3 t = Fwd(v);
        const int second = (x0 + j + y) & 1;
        return uvec2(quantizeUnorm(t.x, bits), Q(second ? t.z : t.y, bits));
    });
}

// sRGB (or gamma 2.2: the table decides) codes of a row (n <= kBlock): encodeSrgb8Fast in three
// passes, the buckets (vectorised), their entries by scalar loads (gatherWords: a vectorised
// look-up is assembled lane by lane on the shuffle ports), the codes (vectorised, straight into
// `out`: this pass reads no table, only the row and the local entries, so the one alias check
// GCC adds in place of the `restrict` it drops in target_clones clones is all it costs).
GBL_SIMD_CLONES_AVX512 void srgb8Row(int n, const float* in, uint32_t* out, const Srgb8EncodeTable& table) {
    const Srgb8EncodeTable t = table;
    alignas(32) uint32_t buckets[kBlock], entries[kBlock];
    for (int j = 0; j < n; ++j) buckets[j] = srgb8Bucket(in[j], t);
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // GCC cannot see that it reads only the n written
#endif
    gatherWords(n, buckets, t.entries, entries);
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
    for (int j = 0; j < n; ++j) out[j] = srgb8FromEntry(in[j], entries[j], t);
}

// srgb8Row of |in|: HDRP's fast sRGB codes the magnitude (encodeSrgb8FastHdrp).
GBL_SIMD_CLONES_AVX512 void srgb8AbsRow(int n, const float* in, uint32_t* out, const Srgb8EncodeTable& table) {
    alignas(32) float magnitude[kBlock];
    for (int j = 0; j < n; ++j) magnitude[j] = std::fabs(in[j]);
    srgb8Row(n, magnitude, out, table);
}

// Prefetches of the Surfaces two blocks ahead, spread over the work of the current block: one
// slice of the lines before each field's codes (and the material words), so that misses are in
// flight all the time the block computes. Issued all at once, as the loads of loadSurfaces went
// before, they leave memory idle while the fields compute, and each burst waits for the core's
// few outstanding-miss slots. Side by side with the burst in loadSurfaces (16 KB ahead,
// prefetcht0), a first version with a slice per target (codec_bench, CPU time per image over both
// threads, loaded machine): niagara 40-56 -> 31-32 ms, compact-octahedral 38-44 -> 24-33 ms. Two blocks
// ahead and into the outer caches (prefetcht2, locality 1): the line is not needed before the
// next block but one, and 22 KB of Surfaces ahead would crowd the block's own working set out of L1.
class SurfacePrefetch {
  public:
    // From the Surface `ahead` (may lie past the image: prefetches never fault), `n` Surfaces, in
    // `steps` calls of step().
    SurfacePrefetch(const Surface* ahead, int n, int steps)
        : at_(reinterpret_cast<uintptr_t>(ahead) & ~uintptr_t(63)),
          end_(reinterpret_cast<uintptr_t>(ahead + n)),
          perStep_(((size_t(n) * sizeof(Surface) + size_t(steps) * 64 - 1) / size_t(steps) + 63) & ~size_t(63)) {}
    void step() {
        const uintptr_t to = std::min(at_ + perStep_, end_);
        for (; at_ < to; at_ += 64) __builtin_prefetch(reinterpret_cast<const void*>(at_), 0, 1);
    }

  private:
    uintptr_t at_, end_;
    size_t perStep_;
};

// The block's Surfaces member-major (b.s[k][j] = float k of pixel j): 4 x 4 transposes (4 pixels
// by 4 members at a time: the Surface is 9 groups of 4), cheaper than gathering each field's
// members with strided loads. Its lines were prefetched while the blocks before computed
// (SurfacePrefetch). Only the groups of 4
// members the layout reads (plan.encodeGroups) are transposed: 4 of the 6 for crysis3-thin and
// compact-octahedral (the memory traffic is the same: every line is touched either way).
GBL_SIMD_CLONES_AVX512 void loadSurfaces(const Surface* px, int n, uint32_t groups, EncodeBlock& b) {
    const float* __restrict in = floats(px);
    int j = 0;
#if defined(__SSE2__)
    static_assert(kSurfaceFloats == 36, "9 groups of 4 members");
    for (; j + 4 <= n; j += 4) {
        for (int k = 0; k < kSurfaceFloats; k += 4) {
            if (!(groups & (1u << (k / 4)))) continue;  // no field reads these members
            __m128 r0 = _mm_loadu_ps(in + (j + 0) * kSurfaceFloats + k);
            __m128 r1 = _mm_loadu_ps(in + (j + 1) * kSurfaceFloats + k);
            __m128 r2 = _mm_loadu_ps(in + (j + 2) * kSurfaceFloats + k);
            __m128 r3 = _mm_loadu_ps(in + (j + 3) * kSurfaceFloats + k);
            _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
            _mm_store_ps(&b.s[k][j], r0);
            _mm_store_ps(&b.s[k + 1][j], r1);
            _mm_store_ps(&b.s[k + 2][j], r2);
            _mm_store_ps(&b.s[k + 3][j], r3);
        }
    }
#endif
    for (; j < n; ++j)
        for (int k = 0; k < kSurfaceFloats; ++k) b.s[k][j] = in[j * kSurfaceFloats + k];
}

// The field's input components for the block: rows of its Surface members, or its constant.
GBL_CLONE_INLINE void gatherInputs(const FieldPlan& f, int n, EncodeBlock& b) {
    for (int c = 0; c < f.inputs; ++c) {
        if (f.source < 0) {
            std::fill(b.in[c], b.in[c] + n, f.constant[c]);
            b.src[c] = b.in[c];
        } else {
            b.src[c] = b.s[f.source + c];
        }
    }
}

// ORs a code's pieces into the block's words, kept word-major (words[w][j]) so that each piece
// is one contiguous, vectorised loop.
GBL_CLONE_INLINE void placeCode(const CodePlan& code, int n, const uint32_t* __restrict c,
                                uint32_t (*__restrict words)[kBlock]) {
    for (const Piece& p : code.pieces) {
        uint32_t* __restrict w = words[p.word];
        const int shift = p.shift, codeShift = p.codeShift;
        const uint32_t mask = p.mask;
        for (int j = 0; j < n; ++j) w[j] |= ((c[j] >> codeShift) & mask) << shift;
    }
}

// The pixel's shading model by the encoder's rule (src/layout/shading_models.cpp, as the generated
// writeGBuffer's gblModel): the tests in reverse order of preference, so that the first that holds
// is the last written; Default (0) where none does.
GBL_CLONE_INLINE void pickModels(const CodecPlan& plan, int n, EncodeBlock& b) {
    uint32_t* __restrict model = b.model;
    std::fill(model, model + n, 0u);
    for (auto it = plan.modelTests.rbegin(); it != plan.modelTests.rend(); ++it) {
        const uint32_t m = it->model;
        for (int c = 0; c < it->components; ++c) {
            const float* __restrict x = b.s[it->first + c];
            for (int j = 0; j < n; ++j) model[j] = x[j] > 0.0f ? m : model[j];
        }
    }
}

// Codes of a field that depend on the pixel's model: the selector's id, and a conditional field's
// codes kept on the pixels of its models only (0 elsewhere: its bits are left to the fields of the
// pixel's own model).
GBL_CLONE_INLINE void modelCodes(const FieldPlan& f, int n, EncodeBlock& b) {
    const uint32_t* __restrict model = b.model;
    if (f.selector) {
        uint32_t* __restrict c = b.code[0];
        for (int j = 0; j < n; ++j) c[j] = f.modelIds[model[j] & 3u];
        return;
    }
    if (f.codec == Codec::Id)  // a conditional integer extra: its declared value is the code
        for (size_t k = 0; k < f.codes.size(); ++k) std::fill(b.code[k], b.code[k] + n, f.idValue[k]);
    const uint32_t models = f.models;
    for (size_t k = 0; k < f.codes.size(); ++k) {
        uint32_t* __restrict c = b.code[k];
        for (int j = 0; j < n; ++j) c[j] = ((models >> model[j]) & 1u) ? c[j] : 0u;
    }
}

// Whether some pixel of the block is of one of `models`: a conditional field's codes are 0 on
// every other pixel, so a block without one (a scene without the field's layer) skips the field.
GBL_CLONE_INLINE bool anyOfModels(uint32_t models, const uint32_t* __restrict model, int n) {
    uint32_t any = 0;
    for (int j = 0; j < n; ++j) any |= (models >> model[j]) & 1u;
    return any != 0;
}

// Every pixel starts from the target's constant words, then the fields are ORed in; the block's
// words are then interleaved into the image (Words per pixel).
template <int Words>
GBL_CLONE_INLINE void encodeTarget(const TargetPlan& t, int n, int x0, int y, EncodeBlock& b,
                                   uint32_t* __restrict out, SurfacePrefetch& ahead) {
    for (int k = 0; k < Words; ++k) std::fill(b.words[k], b.words[k] + kBlock, t.constantWords[k]);
    for (const FieldPlan& f : t.encodeFields) {
        ahead.step();
        if (f.models && !f.selector && !anyOfModels(f.models, b.model, n)) continue;
        if (!f.selector) {
            gatherInputs(f, n, b);
            encodeCodes(f, n, x0, y, b);
        }
        if (f.selector || f.models) modelCodes(f, n, b);
        for (size_t k = 0; k < f.codes.size(); ++k) placeCode(f.codes[k], n, b.code[k], b.words);
    }
    int j = 0;
#if defined(__SSE2__)
    // 4 pixels' words at a time interleaved in registers (Words 2: unpacks, 4: a 4 x 4 transpose)
    // and streamed straight to the image when it is 16-byte aligned there (a std::vector's image
    // is, at every block of a row whose pixel index times Words is a multiple of 4), instead of
    // through b.pixels and a copy.
    if (reinterpret_cast<uintptr_t>(out) % 16 == 0) {
        __m128i* dst = reinterpret_cast<__m128i*>(out);
        for (; j + 4 <= n; j += 4) {
            const __m128i w0 = _mm_load_si128(reinterpret_cast<const __m128i*>(b.words[0] + j));
            if constexpr (Words == 1) {
                _mm_stream_si128(dst + j / 4, w0);
            } else if constexpr (Words == 2) {
                const __m128i w1 = _mm_load_si128(reinterpret_cast<const __m128i*>(b.words[1] + j));
                _mm_stream_si128(dst + j / 2, _mm_unpacklo_epi32(w0, w1));
                _mm_stream_si128(dst + j / 2 + 1, _mm_unpackhi_epi32(w0, w1));
            } else {
                __m128 r0 = _mm_castsi128_ps(w0), r1 = _mm_load_ps(reinterpret_cast<const float*>(b.words[1] + j));
                __m128 r2 = _mm_load_ps(reinterpret_cast<const float*>(b.words[2] + j));
                __m128 r3 = _mm_load_ps(reinterpret_cast<const float*>(b.words[3] + j));
                _MM_TRANSPOSE4_PS(r0, r1, r2, r3);  // bit moves only
                _mm_stream_si128(dst + j, _mm_castps_si128(r0));
                _mm_stream_si128(dst + j + 1, _mm_castps_si128(r1));
                _mm_stream_si128(dst + j + 2, _mm_castps_si128(r2));
                _mm_stream_si128(dst + j + 3, _mm_castps_si128(r3));
            }
        }
    }
#endif
    uint32_t* __restrict pixels = b.pixels;
    for (int p = j; p < n; ++p)
        for (int k = 0; k < Words; ++k) pixels[(p - j) * Words + k] = b.words[k][p];
    if (j < n) streamCopy(out + size_t(j) * Words, pixels, size_t(n - j) * Words * sizeof(uint32_t));
}

GBL_SIMD_CLONES_AVX512 void encodeBlock(const TargetPlan& t, int n, int x0, int y, EncodeBlock& b, uint32_t* words,
                                        SurfacePrefetch& ahead) {
    switch (t.words) {
        case 1: encodeTarget<1>(t, n, x0, y, b, words, ahead); return;
        case 2: encodeTarget<2>(t, n, x0, y, b, words, ahead); return;
        default: encodeTarget<4>(t, n, x0, y, b, words, ahead); return;
    }
}

// Material pass words: the float32 bits of the slots' attributes, 0 in unused channels. The 4
// channels of a material target are 4 rows of the block's member-major Surfaces (a row of zeros
// for an unused channel), interleaved by 4 x 4 transposes (bit moves: every word is the float's
// bits) and streamed to the image, straight from the registers when the image is 16-byte
// aligned (a std::vector's memory is), else through b.pixels.
GBL_SIMD_CLONES_AVX512 void encodeMaterial(const CodecPlan& plan, int n, size_t first, uint32_t* const* material,
                                           EncodeBlock& b, SurfacePrefetch& ahead) {
    alignas(32) static const float zeros[kBlock] = {};
    for (int m = 0; m < plan.materialTargets; ++m) {
        ahead.step();
        const float* rows[4];
        for (int ch = 0; ch < 4; ++ch) {
            const int src = plan.materialSource[size_t(m * 4 + ch)];
            rows[ch] = src < 0 ? zeros : b.s[src];
        }
        uint32_t* dst = material[m] + first * 4;
        int j = 0;
#if defined(__SSE2__)
        if (reinterpret_cast<uintptr_t>(dst) % 16 == 0) {
            float* out = reinterpret_cast<float*>(dst);
            for (; j + 4 <= n; j += 4) {
                __m128 r0 = _mm_load_ps(rows[0] + j), r1 = _mm_load_ps(rows[1] + j);
                __m128 r2 = _mm_load_ps(rows[2] + j), r3 = _mm_load_ps(rows[3] + j);
                _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
                _mm_stream_ps(out + (j + 0) * 4, r0);
                _mm_stream_ps(out + (j + 1) * 4, r1);
                _mm_stream_ps(out + (j + 2) * 4, r2);
                _mm_stream_ps(out + (j + 3) * 4, r3);
            }
        }
#endif
        uint32_t* __restrict words = b.pixels;
        for (int k = j; k < n; ++k)
            for (int ch = 0; ch < 4; ++ch) words[(k - j) * 4 + ch] = floatBitsToUint(rows[ch][k]);
        if (j < n) streamCopy(dst + size_t(j) * 4, words, size_t(n - j) * 4 * sizeof(uint32_t));
    }
}


// A scalar encoding's codes, per component with each code's bits.
GBL_SIMD_CLONES_AVX512 void encodeScalarCodes(const FieldPlan& f, int n, EncodeBlock& b) {
    for (size_t k = 0; k < f.codes.size(); ++k) {
        const uint bk = f.codes[k].bits;
        const float* in = b.src[k];
        uint32_t* out = b.code[k];
        switch (f.codec) {
            case Codec::Unorm: map1(n, in, out, [bk](float x) { return quantizeUnorm(x, bk); }); break;
            case Codec::Snorm: map1(n, in, out, [bk](float x) { return quantizeSnorm(x, bk); }); break;
            case Codec::Float16: encodeFloat16Row(n, in, out); break;  // F16C where the CPU has it
            case Codec::Float11: map1(n, in, out, [](float x) { return encodeFloat11Fast(x); }); break;
            case Codec::Float10: map1(n, in, out, [](float x) { return encodeFloat10Fast(x); }); break;
            case Codec::Float32: map1(n, in, out, [](float x) { return encodeFloat32(x); }); break;
            case Codec::Depth24: map1(n, in, out, [](float x) { return quantizeDepth24(x); }); break;
            case Codec::Gloss:
                map1(n, in, out, [bk](float x) { return quantizeUnorm(glossFromRoughness(x), bk); });
                break;
            case Codec::SmoothnessCry:
                map1(n, in, out, [bk](float x) { return quantizeUnorm(smoothnessFromRoughnessCry(x), bk); });
                break;
            case Codec::CryGlossPower: map1(n, in, out, [](float x) { return encodeCryGlossPower(x); }); break;
            case Codec::Kz2LogPower: map1(n, in, out, [](float x) { return encodeKz2LogPower(x); }); break;
            case Codec::UnormRoundEven:
                map1(n, in, out, [bk](float x) { return quantizeUnormRoundEven(x, bk); });
                break;
            case Codec::CoatRoughnessBevy:
                map1(n, in, out, [bk](float x) { return encodeCoatRoughnessBevy(x, bk); });
                break;
            case Codec::UnormSigned:
                map1(n, in, out, [bk](float x) { return quantizeUnormSigned(x, bk); });
                break;
            case Codec::UnormSqrt: srgb8Row(n, in, out, unormSqrtEncodeTable()); break;  // by the table form
            case Codec::Reflectance:
            case Codec::ReflectanceBevyWebgl2:  // the bias is the read's alone
                map1(n, in, out, [bk](float x) { return quantizeUnorm(reflectanceFromSpecular(x), bk); });
                break;
            default: break;  // Id: folded into the target's constant words by compilePlan
        }
    }
}

}  // namespace

// Mirror of encodeField in the former per-pixel codec (and of emitEncodeField in wiring_codegen):
// scalars per component with each code's bits (encodeScalarCodes), vec3 encodings with the first
// code's bits.
GBL_SIMD_CLONES_AVX512 void encodeCodes(const FieldPlan& f, int n, int x0, int y, EncodeBlock& b) {
    const uint bits = f.codes[0].bits;
    if (isScalar(f.codec)) {
        encodeScalarCodes(f, n, b);
        return;
    }
    const float *x = b.src[0], *yv = b.src[1], *z = b.src[2];
    uint32_t *c0 = b.code[0], *c1 = b.code[1], *c2 = b.code[2];
    switch (f.codec) {
        case Codec::Srgb8:
            srgb8Row(n, x, c0, srgb8EncodeTable());
            srgb8Row(n, yv, c1, srgb8EncodeTable());
            srgb8Row(n, z, c2, srgb8EncodeTable());
            return;
        case Codec::Luma:
            map3to1(n, x, yv, z, c0, [bits](vec3 v) { return quantizeUnorm(lumaBt601(v), bits); });
            return;
        case Codec::YCbCr: transformed3<rgbToYCbCr, quantizeChroma>(n, b, bits); return;
        case Codec::YCbCrSqrt: transformed3<rgbToYCbCrSqrt, quantizeChroma>(n, b, bits); return;
        case Codec::YCoCg: transformed3<rgbToYCoCg, quantizeUnorm>(n, b, bits); return;
        case Codec::YCbCrCheckerboard: checkerboard<rgbToYCbCr, quantizeChroma>(n, x0, y, b, bits); return;
        case Codec::YCoCgCheckerboard: checkerboard<rgbToYCoCg, quantizeUnorm>(n, x0, y, b, bits); return;
        case Codec::NormalXyz:
            map3to3(n, x, yv, z, c0, c1, c2, [bits](vec3 v) { return encodeNormalXyz(v, bits); });
            return;
        case Codec::NormalBestFit:  // a look-up, as on the GPU; in passes (encodings_fast.h)
            encodeNormalBestFitRow(n, x, yv, z, bestFitNormalTable().data(), c0, c1, c2);
            return;
        case Codec::NormalXyZSign:
            map3to3(n, x, yv, z, c0, c1, c2, [bits](vec3 v) { return encodeNormalXyZSign(v, bits); });
            return;
        case Codec::NormalSpheremap:
            map3to2(n, x, yv, z, c0, c1, [bits](vec3 v, int) { return encodeNormalSpheremap(v, bits); });
            return;
        case Codec::NormalStereographic:
            map3to2(n, x, yv, z, c0, c1, [bits](vec3 v, int) { return encodeNormalStereographic(v, bits); });
            return;
        case Codec::NormalOctahedral:
            map3to2(n, x, yv, z, c0, c1, [bits](vec3 v, int) { return encodeNormalOctahedral(v, bits); });
            return;
        case Codec::NormalOctahedralPrecise:
            map3to2(n, x, yv, z, c0, c1, [bits](vec3 v, int) { return encodeNormalOctahedralPrecise(v, bits); });
            return;
        case Codec::Gamma22:  // encodeGamma22's codes by one look-up each, as sRGB (encodings_fast.h)
            srgb8Row(n, x, c0, gamma22EncodeTable());
            srgb8Row(n, yv, c1, gamma22EncodeTable());
            srgb8Row(n, z, c2, gamma22EncodeTable());
            return;
        case Codec::Srgb8FastHdrp:  // |x| by the table form (encodings_fast.h): 8 dependent steps saved
            srgb8AbsRow(n, x, c0, srgbFastHdrpEncodeTable());
            srgb8AbsRow(n, yv, c1, srgbFastHdrpEncodeTable());
            srgb8AbsRow(n, z, c2, srgbFastHdrpEncodeTable());
            return;
        case Codec::Float111110:
            map1(n, x, c0, [](float v) { return encodeFloat11Fast(v); });
            map1(n, yv, c1, [](float v) { return encodeFloat11Fast(v); });
            map1(n, z, c2, [](float v) { return encodeFloat10Fast(v); });
            return;
        case Codec::Rgb9e5: {
            uint32_t* c3 = b.code[3];
            for (int j = 0; j < n; ++j) {
                const uvec4 c = encodeRgb9e5(vec3(x[j], yv[j], z[j]));
                c0[j] = c.x;
                c1[j] = c.y;
                c2[j] = c.z;
                c3[j] = c.w;
            }
            return;
        }
        case Codec::NormalOctahedralBevy:
            map3to2(n, x, yv, z, c0, c1, [bits](vec3 v, int) { return encodeNormalOctahedralBevy(v, bits); });
            return;
        case Codec::NormalOctahedralUnity:
            map3to2(n, x, yv, z, c0, c1, [bits](vec3 v, int) { return encodeNormalOctahedralUnity(v, bits); });
            return;
        case Codec::NormalOctahedralHdrp:
            map3to2(n, x, yv, z, c0, c1, [bits](vec3 v, int) { return encodeNormalOctahedralHdrp(v, bits); });
            return;
        case Codec::NormalXyFloat16:
            map3to2(n, x, yv, z, c0, c1, [](vec3 v, int) { return encodeNormalXyFloat16(v); });
            return;
        case Codec::Float111110HdrpAoTag: {
            // The unquantised occlusion of the pixel, as HDRP writes surfaceData.ambientOcclusion.
            const float* ao = b.s[f.carried];
            for (int j = 0; j < n; ++j) {
                const uvec3 c = encodeFloat111110HdrpAoTag(vec3(x[j], yv[j], z[j]), ao[j]);
                c0[j] = c.x;
                c1[j] = c.y;
                c2[j] = c.z;
            }
            return;
        }
        case Codec::AnisotropyTangentAngleHdrp: {
            // The unquantised normal and anisotropy, as HDRP reads surfaceData.normalWS and .anisotropy.
            const float *nx = b.s[f.reads], *ny = b.s[f.reads + 1], *nz = b.s[f.reads + 2];
            const float* a = b.s[f.carried];
            for (int j = 0; j < n; ++j) {
                const uvec3 c = encodeAnisotropyHdrp(vec3(x[j], yv[j], z[j]), a[j], vec3(nx[j], ny[j], nz[j]));
                c0[j] = c.x;
                c1[j] = c.y;
                c2[j] = c.z;
            }
            return;
        }
        case Codec::NormalOctahedralDeltaUe: {
            // Against the unquantised coat normal, as UE's oct2 reads GBuffer.WorldNormal before
            // it is encoded (ShadingModelsMaterial.ush:98); on pixels of other models the codes
            // are dropped (modelCodes).
            const float *tx = b.s[f.reads], *ty = b.s[f.reads + 1], *tz = b.s[f.reads + 2];
            for (int j = 0; j < n; ++j) {
                const uvec2 c = encodeNormalOctahedralDeltaUe(vec3(x[j], yv[j], z[j]), vec3(tx[j], ty[j], tz[j]), bits);
                c0[j] = c.x;
                c1[j] = c.y;
            }
            return;
        }
        case Codec::EmissiveAlbedoRatio: {
            // The unquantised base colour of the pixel, as niagara's mesh.frag.glsl divides by albedo.
            const float *ar = b.s[f.reads], *ag = b.s[f.reads + 1], *ab = b.s[f.reads + 2];
            for (int j = 0; j < n; ++j)
                c0[j] = encodeEmissiveAlbedoRatio(vec3(x[j], yv[j], z[j]), vec3(ar[j], ag[j], ab[j]), bits);
            return;
        }
        case Codec::NormalOctahedralDithered:
            if (f.ditherPerFrame) {
                const uint32_t frame = f.frameIndex;
                map3to2(n, x, yv, z, c0, c1, [bits, x0, y, frame](vec3 v, int j) {
                    return encodeNormalOctahedralDitheredAtFrame(v, bits, ivec2(x0 + j, y), frame);
                });
                return;
            }
            map3to2(n, x, yv, z, c0, c1,
                    [bits, x0, y](vec3 v, int j) { return encodeNormalOctahedralDithered(v, bits, ivec2(x0 + j, y)); });
            return;
        default: return;  // scalars: above
    }
}

void encodeRows(const CodecPlan& plan, const Surface* surfaces, int width, int y0, int y1, const WordViews& out) {
    EncodeBlock b;
    int steps = plan.materialTargets + 1;  // a slice per field, per material target, and one to start
    for (const TargetPlan& t : plan.targets) steps += int(t.encodeFields.size());
    for (int y = y0; y < y1; ++y)
        for (int x0 = 0; x0 < width; x0 += kBlock) {
            const int n = std::min(kBlock, width - x0);
            const size_t first = size_t(y) * size_t(width) + size_t(x0);
            const Surface* px = surfaces + first;
            SurfacePrefetch ahead(px + 2 * kBlock, kBlock, steps);
            ahead.step();
            loadSurfaces(px, n, plan.encodeGroups, b);
            if (plan.selectorTarget >= 0) pickModels(plan, n, b);
            for (size_t t = 0; t < plan.targets.size(); ++t) {
                const TargetPlan& tp = plan.targets[t];
                encodeBlock(tp, n, x0, y, b, out.targets[t] + first * size_t(tp.words), ahead);
            }
            if (plan.materialTargets > 0) encodeMaterial(plan, n, first, out.material, b, ahead);
        }
    streamFence();
}

}  // namespace gbl::codec
