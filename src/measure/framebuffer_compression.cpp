#include "framebuffer_compression.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "simd_clones.h"

namespace gbl {

namespace {

int wordsFor(int bytesPerPixel) { return bytesPerPixel <= 4 ? 1 : bytesPerPixel / 4; }

// Equal-width 8- or 10-bit colour channels r, g, b (RGBA8 UNORM / SRGB / SNORM, BGRA8, RGB10A2):
// the formats whose RGB a lossless colour transform serves (AFBC's YTR is "for RGB buffers",
// Linux Documentation/gpu/afbc.rst, "Components and Ordering"; Mesa pan_afbc.h pan_afbc_can_ytr:
// 3 or 4 channels, RGB colour space).
bool rgbTransformApplies(const std::vector<Channel>& channels) {
    if (channels.size() < 3) return false;
    int found = 0, width = 0;
    for (const Channel& c : channels) {
        if (c.name != "r" && c.name != "g" && c.name != "b") continue;
        if (c.type == ChannelType::Sfloat || c.type == ChannelType::Ufloat || c.type == ChannelType::Uint) return false;
        if (width == 0) width = c.bits;
        if (c.bits != width) return false;
        ++found;
    }
    return found == 3 && (width == 8 || width == 10);
}

}  // namespace

TexelLayout texelLayoutOf(const Target& target) {
    TexelLayout l;
    l.bytesPerPixel = target.bytes();
    l.wordsPerPixel = wordsFor(l.bytesPerPixel);
    // RGB first, in r, g, b order, so that the transform finds them in channels 0-2.
    std::vector<Channel> ordered;
    for (const char* n : {"r", "g", "b"})
        for (const Channel& c : target.channels)
            if (c.name == n) ordered.push_back(c);
    for (const Channel& c : target.channels)
        if (c.name != "r" && c.name != "g" && c.name != "b") ordered.push_back(c);
    for (const Channel& c : ordered) {
        if (l.channels == 4 || c.bits <= 0 || c.bits > 32) continue;
        l.bits[l.channels] = c.bits;
        l.offset[l.channels] = c.offset;
        ++l.channels;
    }
    l.ytr = rgbTransformApplies(target.channels);
    return l;
}

TexelLayout texelLayoutOfIds(const VisibilityIds& ids) {
    TexelLayout l;
    l.bytesPerPixel = ids.bytes();
    l.wordsPerPixel = wordsFor(l.bytesPerPixel);
    l.channels = std::max(1, ids.bits / 32);
    for (int c = 0; c < l.channels; ++c) {
        l.bits[c] = 32;
        l.offset[c] = 32 * c;
    }
    return l;
}

namespace {

constexpr int kMaxBlockPixels = 256;  // DCC's 16x16 block of 1-byte texels

inline int parameterCodeBits(int bits) {
    int kb = 0;
    while ((1 << kb) < bits + 2) ++kb;
    return kb;
}

int codedChannelBits(const TexelLayout& layout, int c) { return layout.bits[c] + (layout.ytr && (c == 1 || c == 2) ? 1 : 0); }

// One channel of one block: the W x H window at v (row stride 16; the region's planes), `bits`
// wide (T: int32_t when bits <= 30, else int64_t). Coded as:
// - a parameter code of ceil(log2(bits + 2)) bits (k in 0..bits, or "constant"),
// - the first value in `bits` bits,
// - unless every value is the first, each other value's residual against a prediction, in raster
//   order inside the block: the first row from the left neighbour, the first column from the one
//   above, the rest by the JPEG-LS / LOCO-I median edge detector (ITU-T T.87 A.4.1; Weinberger,
//   Seroussi, Sapiro, IEEE Trans. Image Processing 9(8), 2000): a = left, b = above, c = above-left;
//   taken modulo 2^bits into [-2^(bits-1), 2^(bits-1)), zigzagged (u = 2r or -2r - 1), and
//   Rice-coded with k = min{k : n 2^k >= A} (A = the sum of |r| over the n residuals coded: the
//   JPEG-LS rule, T.87 A.5.1): a code of (u >> k) ones, a zero and k bits; a quotient of 2 x bits
//   or more is escaped, 2 x bits ones and u in `bits` bits (JPEG-LS's limited code, T.87 A.5.3,
//   LIMIT = 2 x bits). With ResidualCode::ZeroFlagRice every residual is first a 1-bit flag
//   (zero or not), and only the nonzero ones are Rice-coded, as u - 1 (n counts those).
template <int W, int H, typename T>
GBL_CLONE_INLINE int blockChannelBits(const T* v, int bits, ResidualCode code) {
    constexpr int M = W * H - 1;
    using U = std::make_unsigned_t<T>;
    constexpr int width = int(sizeof(T) * 8);
    const int shift = width - bits;
    T r[M];
    int m = 0;
    for (int x = 1; x < W; ++x) r[m++] = T(v[x] - v[x - 1]);
    for (int y = 1; y < H; ++y) {
        const T* row = v + y * 16;
        const T* up = row - 16;
        r[m++] = T(row[0] - up[0]);
        for (int x = 1; x < W; ++x) {
            const T a = row[x - 1], b = up[x], c = up[x - 1];
            const T mx = a > b ? a : b, mn = a > b ? b : a;
            const T p = c >= mx ? mn : c <= mn ? mx : T(a + b - c);
            r[m++] = T(row[x] - p);
        }
    }
    uint64_t sumAbs = 0;
    U u[M];
    for (int i = 0; i < M; ++i) {
        const T wrapped = T(T(U(r[i]) << shift) >> shift);  // modulo 2^bits, signed
        u[i] = U(U(wrapped) << 1) ^ U(wrapped >> (width - 1));
        sumAbs += uint64_t(wrapped < 0 ? -int64_t(wrapped) : int64_t(wrapped));
    }
    const int kb = parameterCodeBits(bits);
    if (sumAbs == 0) return kb + bits;  // every residual 0: the block is one value
    // n: the residuals the Rice code codes (with zero flags, the nonzero ones).
    uint64_t n = M;
    if (code == ResidualCode::ZeroFlagRice) {
        n = 0;
        for (int i = 0; i < M; ++i) n += u[i] != 0;
    }
    int k = 0;
    while ((n << k) < sumAbs && k < bits) ++k;
    const U limit = U(2 * bits);
    const int escape = 2 * bits + bits;
    int total = 0;
    if (code == ResidualCode::ZeroFlagRice) {
        for (int i = 0; i < M; ++i) {
            const U q = U(u[i] - (u[i] != 0)) >> k;
            total += u[i] == 0 ? 1 : 1 + (q >= limit ? escape : int(q) + 1 + k);
        }
    } else {
        for (int i = 0; i < M; ++i) {
            const U q = u[i] >> k;
            total += q >= limit ? escape : int(q) + 1 + k;
        }
    }
    return kb + bits + total;
}

// A 16x16 region's channel planes after the colour transform, row stride 16.
template <typename T>
struct Planes {
    T v[4][kMaxBlockPixels];
};

template <typename T>
GBL_CLONE_INLINE void extract(const TexelLayout& layout, const uint32_t* words, size_t strideWords, Planes<T>& p) {
    const int wpp = layout.wordsPerPixel;
    for (int c = 0; c < layout.channels; ++c) {
        const int word = layout.offset[c] / 32, shift = layout.offset[c] % 32;
        const uint32_t mask = layout.bits[c] == 32 ? 0xFFFFFFFFu : (uint32_t(1) << layout.bits[c]) - 1;
        for (int y = 0; y < 16; ++y) {
            const uint32_t* row = words + size_t(y) * strideWords + word;
            for (int x = 0; x < 16; ++x) p.v[c][y * 16 + x] = T((row[size_t(x) * wpp] >> shift) & mask);
        }
    }
    if (layout.ytr)  // YCoCg-R (Malvar, Sullivan, Srinivasan, SPIE 7073, 2008): exactly reversible
        for (int i = 0; i < 256; ++i) {
            const T r = p.v[0][i], g = p.v[1][i], b = p.v[2][i];
            const T co = T(r - b), t = T(b + (co >> 1)), cg = T(g - t);
            p.v[0][i] = T(t + (cg >> 1));
            p.v[1][i] = co;
            p.v[2][i] = cg;
        }
}

template <int W, int H, typename T>
GBL_CLONE_INLINE int blockBits(const TexelLayout& layout, const Planes<T>& p, int x0, int y0, ResidualCode code) {
    int total = 0;
    for (int c = 0; c < layout.channels; ++c)
        total += blockChannelBits<W, H, T>(p.v[c] + y0 * 16 + x0, codedChannelBits(layout, c), code);
    return total;
}

// Bits of the w x h block at (x0, y0) of the region (w x h one of the containers' blocks).
template <typename T>
GBL_CLONE_INLINE int regionBlockBits(const TexelLayout& layout, const Planes<T>& p, int x0, int y0, int w, int h,
                                     ResidualCode code) {
    if (w == 4 && h == 4) return blockBits<4, 4, T>(layout, p, x0, y0, code);
    if (w == 8 && h == 8) return blockBits<8, 8, T>(layout, p, x0, y0, code);
    if (w == 8 && h == 4) return blockBits<8, 4, T>(layout, p, x0, y0, code);
    if (w == 16 && h == 8) return blockBits<16, 8, T>(layout, p, x0, y0, code);
    if (w == 16 && h == 16) return blockBits<16, 16, T>(layout, p, x0, y0, code);
    throw std::logic_error("framebuffer compression: no block of that size");
}

bool needsWideValues(const TexelLayout& layout) {
    for (int c = 0; c < layout.channels; ++c)
        if (codedChannelBits(layout, c) > 30) return true;  // a + b - c must not overflow
    return false;
}

// The DCC block of a texel size: 256 bytes (8x8 texels of 4 bytes, 8x4 of 8, 4x4 of 16).
void dccBlockOf(int texelBytes, int& w, int& h) {
    w = texelBytes <= 2 ? 16 : texelBytes <= 8 ? 8 : 4;
    h = kDccBlockBytes / std::max(1, texelBytes) / w;
}

// One 16x16 region (not of one colour): the AFBC subblocks' and the DCC blocks' payloads.
struct RegionSizes {
    int afbcSubblockBytes[16];
    int dccBlockBits[16];  // up to 16 DCC blocks in a region (8x4 blocks of 8-byte texels)
    int dccBlocks = 0;
};

template <typename T>
GBL_SIMD_CLONES void regionSizes(const TexelLayout& layout, const uint32_t* words, size_t strideWords, bool afbc,
                                 RegionSizes& out) {
    Planes<T> p;
    extract<T>(layout, words, strideWords, p);
    if (afbc)
        for (int s = 0; s < 16; ++s)
            out.afbcSubblockBytes[s] = (blockBits<4, 4, T>(layout, p, (s % 4) * 4, (s / 4) * 4, ResidualCode::Rice) + 7) / 8;
    int w = 0, h = 0;
    dccBlockOf(layout.bytesPerPixel, w, h);
    out.dccBlocks = 0;
    for (int y = 0; y < 16; y += h)
        for (int x = 0; x < 16; x += w)
            out.dccBlockBits[out.dccBlocks++] = regionBlockBits<T>(layout, p, x, y, w, h, ResidualCode::ZeroFlagRice);
}

}  // namespace

int payloadBits(const TexelLayout& layout, const uint32_t* words, int strideWords, int w, int h, ResidualCode code) {
    if (w > 16 || h > 16 || layout.channels == 0) throw std::logic_error("payloadBits: bad block");
    // The block into a 16x16 region (its texels repeated past its edge, unused).
    std::vector<uint32_t> region(size_t(256) * layout.wordsPerPixel);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            std::memcpy(&region[size_t(y * 16 + x) * layout.wordsPerPixel],
                        words + size_t(std::min(y, h - 1)) * size_t(strideWords) + size_t(std::min(x, w - 1)) * layout.wordsPerPixel,
                        size_t(layout.wordsPerPixel) * 4);
    const size_t stride = size_t(16) * layout.wordsPerPixel;
    if (needsWideValues(layout)) {
        Planes<int64_t> p;
        extract<int64_t>(layout, region.data(), stride, p);
        return regionBlockBits<int64_t>(layout, p, 0, 0, w, h, code);
    }
    Planes<int32_t> p;
    extract<int32_t>(layout, region.data(), stride, p);
    return regionBlockBits<int32_t>(layout, p, 0, 0, w, h, code);
}

double TargetCompression::afbcBytesPerPixel() const {
    return pixels ? (afbc.compressed ? afbc.readBytes : nominalBytes()) / double(pixels) : 0.0;
}

double TargetCompression::dccBytesPerPixel() const { return pixels ? dcc.bytes / double(pixels) : 0.0; }

TargetCompressor::TargetCompressor(std::string name, std::string format, const TexelLayout& layout, uint32_t width,
                                   uint32_t height)
    : layout_(layout), width_(width), height_(height) {
    result_.name = std::move(name);
    result_.format = std::move(format);
    result_.bytesPerPixel = layout.bytesPerPixel;
    result_.pixels = uint64_t(width) * height;
    // AFBC compresses texels of at most 32 bits: Mesa src/panfrost/lib/pan_afbc.h pan_afbc_format
    // (R8 .. R8G8B8A8, R10G10B10A2, R11G11B10, Z24S8: no 64- or 128-bit mode); the Mali-G57
    // compressed RGBA8 and RG16F and "only 32bit formats" (azhirnov/as-en
    // AE/docs/papers/GPU_Benchmarks.md:553, commit 2182035b).
    result_.afbc.compressed = layout.bytesPerPixel <= 4;
}

void TargetCompressor::addRows(const uint32_t* words, uint32_t rows) {
    const size_t rowWords = size_t(width_) * size_t(layout_.wordsPerPixel);
    rowsSeen_ += rows;
    if (rowsSeen_ > height_) throw std::logic_error("TargetCompressor: more rows than the frame has");
    while (rows > 0) {
        if (pendingRows_ == 0 && rows >= 16) {
            const uint32_t whole = rows / 16 * 16;
            processRows(words, whole);
            words += rowWords * whole;
            rows -= whole;
            continue;
        }
        const uint32_t take = std::min(rows, 16 - pendingRows_);
        pending_.insert(pending_.end(), words, words + rowWords * take);
        pendingRows_ += take;
        words += rowWords * take;
        rows -= take;
        if (pendingRows_ == 16) {
            processRows(pending_.data(), 16);
            pending_.clear();
            pendingRows_ = 0;
        }
    }
}

TargetCompression TargetCompressor::finish() {
    if (pendingRows_ > 0) processRows(pending_.data(), pendingRows_);
    pending_.clear();
    pendingRows_ = 0;
    return result_;
}

void TargetCompressor::processRows(const uint32_t* words, uint32_t rows) {
    const int wpp = layout_.wordsPerPixel;
    const uint32_t paddedWidth = (width_ + 15) / 16 * 16;
    // Partial rows or columns: a padded copy, the edge texels repeated.
    std::vector<uint32_t> padded;
    uint32_t chunkRows = rows;
    const uint32_t* src = words;
    size_t stride = size_t(width_) * wpp;
    if (rows % 16 != 0 || paddedWidth != width_) {
        chunkRows = (rows + 15) / 16 * 16;
        stride = size_t(paddedWidth) * wpp;
        padded.resize(stride * chunkRows);
        for (uint32_t y = 0; y < chunkRows; ++y) {
            const uint32_t* in = words + size_t(std::min(y, rows - 1)) * size_t(width_) * wpp;
            uint32_t* out = padded.data() + size_t(y) * stride;
            std::memcpy(out, in, size_t(width_) * wpp * 4);
            for (uint32_t x = width_; x < paddedWidth; ++x)
                std::memcpy(out + size_t(x) * wpp, in + size_t(width_ - 1) * wpp, size_t(wpp) * 4);
        }
        src = padded.data();
    }
    const int texelBytes = layout_.bytesPerPixel;
    // AFBC: Mesa src/panfrost/lib/pan_afbc.h (AFBC_HEADER_BYTES_PER_TILE 16; 16x16 superblocks;
    // 4x4 subblocks, pan_afbc_subblock_size); the header's 32-bit body offset and sixteen 6-bit
    // subblock sizes, size 1 = stored uncompressed (4 x 4 x bytes per texel), a first size of 0 =
    // the whole superblock one colour kept in the header (arch >= 7): Mesa
    // src/gallium/drivers/panfrost/pan_afbc_cso.c get_superblock_size (upcliujie/mesa 0984686).
    AfbcStats& a = result_.afbc;
    DccStats& d = result_.dcc;
    const int uncompressedSubblock = 16 * texelBytes;
    // DCC: 256-byte blocks (MAX_UNCOMPRESSED_BLOCK_SIZE 256B), stored in 32-byte sectors
    // (MIN_COMPRESSED_BLOCK_SIZE 32B on dGPUs, 64B on APUs): Mesa src/amd/vulkan/radv_image.c /
    // radv_device.c radv_init_dcc_control_reg and get_dcc_min_compressed_block_size.
    int dccW = 0, dccH = 0;
    dccBlockOf(texelBytes, dccW, dccH);
    const int dccBlocksPerRegion = 256 / (dccW * dccH);
    const bool wide = needsWideValues(layout_);
    RegionSizes sizes;
    for (uint32_t y0 = 0; y0 < chunkRows; y0 += 16) {
        const uint32_t* rowBase = src + size_t(y0) * stride;
        for (uint32_t x0 = 0; x0 < paddedWidth; x0 += 16) {
            const uint32_t* sb = rowBase + size_t(x0) * wpp;
            bool solid = true;
            for (int y = 0; y < 16 && solid; ++y)
                solid = std::memcmp(sb + size_t(y) * stride, sb, size_t(wpp) * 4) == 0 &&
                        std::memcmp(sb + size_t(y) * stride + wpp, sb + size_t(y) * stride, size_t(15 * wpp) * 4) == 0;
            if (a.compressed) {
                ++a.superblocks;
                a.headerBytes += kAfbcHeaderBytes;
                a.readBytes += kAfbcHeaderReadBytes;
            }
            if (solid) {  // one colour: AFBC's header alone; every DCC block one sector
                if (a.compressed) ++a.solidSuperblocks;
                d.blocks += uint64_t(dccBlocksPerRegion);
                d.minimumBlocks += uint64_t(dccBlocksPerRegion);
                d.bytes += double(dccBlocksPerRegion) * kDccSectorBytes;
                continue;
            }
            if (wide) regionSizes<int64_t>(layout_, sb, stride, a.compressed, sizes);
            else regionSizes<int32_t>(layout_, sb, stride, a.compressed, sizes);
            if (a.compressed)
                for (int s = 0; s < 16; ++s) {
                    const int bytes = sizes.afbcSubblockBytes[s];
                    ++a.subblocks;
                    int stored = bytes;
                    if (bytes > 63 || bytes >= uncompressedSubblock) {
                        stored = uncompressedSubblock;
                        ++a.uncompressedSubblocks;
                    }
                    a.bodyBytes += stored;
                    a.readBytes += stored;
                }
            for (int b = 0; b < sizes.dccBlocks; ++b) {
                int bytes = (sizes.dccBlockBits[b] + 7) / 8;
                bytes = (bytes + kDccSectorBytes - 1) / kDccSectorBytes * kDccSectorBytes;
                ++d.blocks;
                if (bytes >= kDccBlockBytes) {
                    bytes = kDccBlockBytes;
                    ++d.uncompressedBlocks;
                }
                if (bytes == kDccSectorBytes) ++d.minimumBlocks;
                d.bytes += bytes;
            }
        }
    }
}

double FrameCompression::nominalTargetBytesPerPixel() const {
    double s = 0;
    for (const TargetCompression& t : targets) s += t.bytesPerPixel;
    return s;
}

double FrameCompression::afbcTargetBytesPerPixel() const {
    double s = 0;
    for (const TargetCompression& t : targets) s += t.afbcBytesPerPixel();
    return s;
}

double FrameCompression::dccTargetBytesPerPixel() const {
    double s = 0;
    for (const TargetCompression& t : targets) s += t.dccBytesPerPixel();
    return s;
}

FrameCompression compressFrame(const Layout& layout, const std::vector<std::vector<uint32_t>>& targetWords,
                               uint32_t width, uint32_t height) {
    FrameCompression f;
    f.width = width;
    f.height = height;
    std::vector<std::pair<std::string, std::pair<std::string, TexelLayout>>> targets;
    if (layout.pipeline == Pipeline::VisibilityBuffer)
        targets.push_back({"ids", {layout.ids.format, texelLayoutOfIds(layout.ids)}});
    else
        for (const Target& t : layout.targets) targets.push_back({t.name, {t.format, texelLayoutOf(t)}});
    if (targetWords.size() < targets.size()) throw std::logic_error("compressFrame: fewer target words than targets");
    for (size_t i = 0; i < targets.size(); ++i) {
        const TexelLayout& tl = targets[i].second.second;
        if (targetWords[i].size() != size_t(width) * height * tl.wordsPerPixel)
            throw std::logic_error("compressFrame: target words of unexpected size");
        TargetCompressor c(targets[i].first, targets[i].second.first, tl, width, height);
        c.addRows(targetWords[i].data(), height);
        f.targets.push_back(c.finish());
    }
    return f;
}

FrameCompression poolCompression(const std::vector<FrameCompression>& frames) {
    if (frames.empty()) return {};
    FrameCompression m = frames.front();
    for (size_t t = 0; t < m.targets.size(); ++t) {
        TargetCompression& p = m.targets[t];
        for (size_t f = 1; f < frames.size(); ++f) {
            const TargetCompression& o = frames[f].targets.at(t);
            p.pixels += o.pixels;
            p.afbc.superblocks += o.afbc.superblocks;
            p.afbc.solidSuperblocks += o.afbc.solidSuperblocks;
            p.afbc.subblocks += o.afbc.subblocks;
            p.afbc.uncompressedSubblocks += o.afbc.uncompressedSubblocks;
            p.afbc.headerBytes += o.afbc.headerBytes;
            p.afbc.bodyBytes += o.afbc.bodyBytes;
            p.afbc.readBytes += o.afbc.readBytes;
            p.dcc.blocks += o.dcc.blocks;
            p.dcc.uncompressedBlocks += o.dcc.uncompressedBlocks;
            p.dcc.minimumBlocks += o.dcc.minimumBlocks;
            p.dcc.bytes += o.dcc.bytes;
        }
    }
    return m;
}

}  // namespace gbl
