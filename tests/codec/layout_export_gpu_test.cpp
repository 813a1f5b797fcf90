// `gbufferlab layouts export` on lavapipe, for every shipped layout, in GLSL and in HLSL (glslang's
// HLSL front end), in one Vulkan instance:
//  1. raster: a full-screen pass whose fragment shader calls the exported encode writes render
//     targets of the layout's REAL formats (UNORM, sRGB, A2B10G10R10, B10G11R11 UFLOAT, RGBA16F,
//     SNORM, UINT ...); the bytes read back must equal the CPU mirror's words bit for bit;
//  2. decode: a compute shader reads those images (with the 4 neighbours and a coverage pattern)
//     through the exported decode; the surfaces must equal the CPU decode's within 4 ulp;
//  3. --kernel: the export's own compute entry point; the values it hands each target must be
//     the ones the format stores exactly (UNORM / SNORM: f * (2^b - 1) within [code, code + 0.25),
//     so rounding and truncation agree; sRGB: the code's exact linear value; small floats
//     representable), their codes the CPU mirror's, and its decode the CPU decode's.
// Visibility layouts (ids, not a surface) run the kernel against the packing written out here.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <set>
#include <cstdlib>

#include "best_fit_normals.h"
#include "cpu_codec.h"
#include "encodings.h"
#include "export_glsl_library.h"
#include "export_header.h"
#include "layout_export.h"
#include "layout_files.h"
#include "renderer_passes.h"
#include "shader_compiler.h"
#include "surface_support.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"
#include "wiring_field_codegen.h"
#include "wiring_plan.h"

namespace gbl {
namespace {

constexpr uint32_t kSize = 16;
constexpr size_t kPixels = size_t(kSize) * kSize;

std::string lang(ExportLanguage l) { return l == ExportLanguage::Hlsl ? "HLSL" : "GLSL"; }

// GBL_EXPORT_TEST_TABLES=arrays runs the check on `--tables arrays` exports (minutes per layout with
// tables on lavapipe, which is why the default is the select trees: docs/export.md).
std::string exportText(const Layout& layout, ExportLanguage l) {
    ExportOptions o;
    o.language = l;
    o.kernel = true;
    if (const char* t = std::getenv("GBL_EXPORT_TEST_TABLES"); t && std::string(t) == "arrays")
        o.tables = exporting::ExportTables::Arrays;
    return exportLayout(layout, o, [](const std::string& n) { return resolveShaderInclude(n, {}); });
}

std::vector<uint32_t> compileFor(ExportLanguage l, const std::string& name, const std::string& text,
                                 VkShaderStageFlagBits stage) {
    ShaderSource s{name, text, stage, {{"GBL_KERNEL_WIDTH", std::to_string(kSize)}, {"GBL_KERNEL_HEIGHT", std::to_string(kSize)}}, {}};
    return l == ExportLanguage::Hlsl ? compileHlslUncached(s, "main") : compileGlslUncached(s);
}

std::vector<Surface> randomSurfaces(uint32_t seed) {
    std::vector<Surface> v = test::randomSurfaces(kPixels, seed);
    test::assignLayerPatterns(v);  // every shading model of a selector's rule, and their ties
    // Edge values: 0 and 1 everywhere in one pixel, an axis normal in another.
    v[1] = Surface{};
    v[1].baseColor = v[1].specularColor = v[1].diffuseColor = glm::vec3(1.0f);
    v[1].metallic = v[1].roughness = v[1].specular = v[1].occlusion = 1.0f;
    v[2].normal = {0.0f, 0.0f, -1.0f};
    return v;
}

// The kernel's input: each member (extras: the layout's value), then covered.
std::vector<float> kernelInput(const Layout& layout, const std::vector<Surface>& surfaces) {
    const std::vector<ExportMember> members = exportSurfaceMembers(layout);
    const int n = exportKernelInputFloats(layout);
    std::vector<float> f(kPixels * size_t(n), 0.0f);
    for (size_t i = 0; i < kPixels; ++i) {
        float* p = &f[i * size_t(n)];
        for (const ExportMember& m : members)
            for (int c = 0; c < m.components; ++c) {
                if (const float* v = test::memberOf(surfaces[i], m.attribute); v && !m.isUint && m.defaultValue.empty()) {
                    p[m.firstFloat + c] = v[c];
                    continue;
                }
                const double d = m.defaultValue.empty() ? 0.0 : m.defaultValue[std::min<size_t>(size_t(c), m.defaultValue.size() - 1)];
                if (m.isUint) {
                    const uint32_t u = uint32_t(d);
                    std::memcpy(&p[m.firstFloat + c], &u, 4);
                } else {
                    p[m.firstFloat + c] = float(d);
                }
            }
        p[n - 1] = test::coveredAt(uint32_t(i % kSize), uint32_t(i / kSize)) ? 1.0f : 0.0f;
    }
    return f;
}

// Decoded members (words [0, floats) of each output record) against the CPU decode; extras
// against the layout's integers. Returns the mismatches.
size_t compareDecoded(const Layout& layout, const uint32_t* out, size_t stride, const std::vector<Surface>& cpu,
                      const std::string& what) {
    size_t bad = 0;
    for (size_t i = 0; i < kPixels; ++i)
        for (const ExportMember& m : exportSurfaceMembers(layout))
            for (int c = 0; c < m.components; ++c) {
                const uint32_t w = out[i * stride + size_t(m.firstFloat + c)];
                if (m.isUint) {
                    // the selector's member: the id decode read, as the CPU decode's shadingModel
                    const uint32_t want = m.attribute == Attribute::ShadingModel ? uint32_t(cpu[i].shadingModel)
                        : uint32_t(m.defaultValue.empty() ? 0.0 : m.defaultValue[std::min<size_t>(size_t(c), m.defaultValue.size() - 1)]);
                    if (w != want && bad++ < 5) ADD_FAILURE() << what << " pixel " << i << " " << m.name << ": " << w << " != " << want;
                    continue;
                }
                const float* v = test::memberOf(cpu[i], m.attribute);
                if (!v) continue;  // float extras: held by the words' check
                float g;
                std::memcpy(&g, &w, 4);
                if (!test::within4Ulp(g, v[c]) && bad++ < 5)
                    ADD_FAILURE() << what << " pixel " << i << " " << m.name << "[" << c << "]: " << g << ", CPU " << v[c];
            }
    return bad;
}

// The code a channel's value becomes under Vulkan's conversion for its format, asserting that
// the value leaves the conversion no choice (see the file comment); ok = false when it does not.
uint32_t codeOfValue(RealKind k, uint32_t bits, uint32_t word, int channelBits, bool& ok) {
    float f;
    std::memcpy(&f, &word, 4);
    // A small float or sRGB code: the value must be the code's exact value.
    auto exactly = [&](uint32_t (*encode)(float), float (*decode)(uint32_t)) {
        const uint32_t c = encode(f);
        ok = ok && decode(c) == f;
        return c;
    };
    switch (k) {
        case RealKind::Uint: return word;
        case RealKind::Float32: return word;
        case RealKind::Unorm:
        case RealKind::Snorm: {
            const bool s = k == RealKind::Snorm;
            const double m = s ? std::ldexp(1.0, channelBits - 1) - 1.0 : std::ldexp(1.0, channelBits) - 1.0;
            const double r = std::clamp(double(f), s ? -1.0 : 0.0, 1.0) * m;
            const double code = std::nearbyint(r);
            ok = ok && std::abs(r) - std::abs(code) >= 0.0 && std::abs(r) - std::abs(code) < 0.25 && std::trunc(r) == code;
            return uint32_t(int32_t(code)) & (channelBits >= 32 ? 0xffffffffu : (1u << channelBits) - 1u);
        }
        case RealKind::Srgb: return exactly(enc::encodeSrgb8, enc::decodeSrgb8);
        case RealKind::Float16: return exactly(enc::encodeFloat16, enc::decodeFloat16);
        case RealKind::Float11: return exactly(enc::encodeFloat11, enc::decodeFloat11);
        case RealKind::Float10: return exactly(enc::encodeFloat10, enc::decodeFloat10);
    }
    (void)bits;
    return 0;
}

// Set 0 as the export declares it: 0 kernel input, 1 kernel output, 2 best-fit table (storage
// buffers), then 3.. the targets as sampled images (decode pass only).
std::vector<std::vector<test::Resource>> set0(const Buffer& in, const Buffer& out, const Buffer& table,
                                              const std::vector<GpuImage>& images = {}) {
    std::vector<test::Resource> set = {test::storage(in), test::storage(out), test::storage(table)};
    for (const GpuImage& image : images) set.push_back(test::sampledImage(image));
    return {set};
}

// The exported kernel file (GLSL: after its #version line) with `lines` in front.
std::string withLines(const std::string& exported, ExportLanguage l, const std::string& lines) {
    if (l == ExportLanguage::Hlsl) return lines + exported;
    const size_t eol = exported.find('\n') + 1;
    return exported.substr(0, eol) + lines + exported.substr(eol);
}

// The wrappers the tests put around the exported file (the engine's part): GLSL-syntax bodies,
// translated for HLSL by the export's own translator, around language-specific declarations.
std::string fragmentWrapper(const Layout& layout, ExportLanguage l, const std::string& exported) {
    const std::string p = exportPrefix(layout);
    if (l == ExportLanguage::Hlsl)
        return withLines(exported, l, "#define GBL_KERNEL_NO_MAIN\n") + p +
               "_Targets main(float4 pos : SV_Position) { return " + p + "_kernelEncode(int2(pos.xy)); }\n";
    std::string s = withLines(exported, l, "#define GBL_KERNEL_NO_MAIN\n");
    std::string body;
    for (size_t t = 0; t < layout.targets.size(); ++t) {
        const Target& tg = layout.targets[t];
        const bool u = realKind(tg, tg.channels[0]) == RealKind::Uint;
        const size_t n = tg.channels.size();
        const std::string type = !u ? "vec4" : n == 1 ? "uint" : n == 2 ? "uvec2" : "uvec4";
        const std::string member = "rt" + std::to_string(t) + "_" + exportIdentifier(tg.name);
        s += "layout(location = " + std::to_string(t) + ") out " + type + " gblTestOut" + std::to_string(t) + ";\n";
        body += "    gblTestOut" + std::to_string(t) + " = t." + member + ";\n";
    }
    return s + "void main() {\n    " + p + "_Targets t = " + p + "_kernelEncode(ivec2(gl_FragCoord.xy));\n" + body + "}\n";
}

std::string decodeWrapper(const Layout& layout, ExportLanguage l, const std::string& exported) {
    const std::string p = exportPrefix(layout);
    const bool hlsl = l == ExportLanguage::Hlsl;
    std::string decl, fetch = p + "_Targets gblTestFetch(ivec2 q) {\n    " + p + "_Targets t;\n";
    for (size_t t = 0; t < layout.targets.size(); ++t) {
        const Target& tg = layout.targets[t];
        const bool u = realKind(tg, tg.channels[0]) == RealKind::Uint;
        const size_t n = tg.channels.size();
        const std::string ts = std::to_string(t), member = "rt" + ts + "_" + exportIdentifier(tg.name);
        const std::string swz = !u ? "" : n == 1 ? ".x" : n == 2 ? ".xy" : "";
        if (hlsl) {
            decl += std::string(u ? "Texture2D<uint4>" : "Texture2D<float4>") + " gblTestRt" + ts + " : register(t" +
                    std::to_string(3 + t) + ");\n";
            fetch += "    t." + member + " = gblTestRt" + ts + ".Load(int3(q, 0))" + swz + ";\n";
        } else {
            decl += "layout(set = 0, binding = " + std::to_string(3 + t) + ") uniform " + (u ? "utexture2D" : "texture2D") +
                    " gblTestRt" + ts + ";\n";
            fetch += "    t." + member + " = texelFetch(gblTestRt" + ts + ", q, 0)" + swz + ";\n";
        }
    }
    fetch += "    return t;\n}\n";
    std::string body = "float gblTestCovered(ivec2 q) { return ((q.x * 7 + q.y * 3) % 5) != 0 ? 1.0 : 0.0; }\n";
    body += "void gblTestDecode(ivec2 p) {\n";
    if (exportDecodeReconstructs(layout)) {
        const char* off[4] = {"ivec2(1, 0)", "ivec2(-1, 0)", "ivec2(0, 1)", "ivec2(0, -1)"};
        for (int k = 0; k < 4; ++k)
            body += "    ivec2 q" + std::to_string(k) + " = " + p + "_kernelMirror(p + " + off[k] + ");\n";
        body += "    " + p + "_Surface d = " + p + "_decode(gblTestFetch(p), gblTestFetch(q0), gblTestFetch(q1), "
                "gblTestFetch(q2), gblTestFetch(q3), vec4(gblTestCovered(q0), gblTestCovered(q1), gblTestCovered(q2), "
                "gblTestCovered(q3)), p);\n";
    } else {
        body += "    " + p + "_Surface d = " + p + "_decode(gblTestFetch(p));\n";
    }
    body += "    int o = (p.y * " + std::to_string(kSize) + " + p.x) * " + std::to_string(exportKernelOutputWords(layout)) + ";\n";
    for (const ExportMember& m : exportSurfaceMembers(layout))
        for (int c = 0; c < m.components; ++c) {
            const std::string x = "d." + m.name + (m.components > 1 ? "." + std::string(wiring::kComp[c]) : "");
            body += "    " + p + "_kernelOut[o + " + std::to_string(m.firstFloat + c) + "] = " +
                    (m.isUint ? x : "floatBitsToUint(" + x + ")") + ";\n";
        }
    body += "}\n";
    if (hlsl)
        return withLines(exported, l, "#define GBL_KERNEL_NO_MAIN\n") + decl + exporting::translateGlslToHlsl(fetch + body) +
               "[numthreads(8, 8, 1)]\nvoid main(uint3 id : SV_DispatchThreadID) { gblTestDecode(int2(id.xy)); }\n";
    return withLines(exported, l, "#extension GL_EXT_samplerless_texture_functions : require\n#define GBL_KERNEL_NO_MAIN\n") +
           decl + fetch + body +
           "layout(local_size_x = 8, local_size_y = 8) in;\nvoid main() { gblTestDecode(ivec2(gl_GlobalInvocationID.xy)); }\n";
}

class LayoutExportGpu : public test::VulkanTest {};

void checkLayout(VulkanContext& c, const Layout& layout, uint32_t seed, const Buffer& table) {
    const std::vector<Surface> surfaces = randomSurfaces(seed);
    CpuGBuffer cpu = encodeGBuffer(layout, surfaces, int(kSize), int(kSize));
    cpu.covered = test::coverageMask(kSize, kSize);
    const std::vector<Surface> cpuDecoded = decodeGBuffer(layout, cpu);
    const std::vector<float> input = kernelInput(layout, surfaces);
    const size_t outWords = size_t(exportKernelOutputWords(layout));
    const test::TestBuffer in = test::TestBuffer::holding(c, input);
    const test::TestBuffer out(c, kPixels * outWords * 4);
    const std::vector<uint32_t> vs =
        compileGlslUncached({"export.vert (test)", test::kFullScreenTriangleVertex, VK_SHADER_STAGE_VERTEX_BIT, {}, {}});

    GBufferWiring w = generateWiring(layout, WiringOptions{true});
    for (size_t t = 0; t < layout.targets.size(); ++t) w.targetFormats[t] = vkFormatFromName(layout.targets[t].format);
    w.targetClearWords.assign(layout.targets.size(), std::array<uint32_t, 4>{0, 0, 0, 0});
    w.emissiveForward = false;
    w.materialPass = false;

    for (ExportLanguage l : {ExportLanguage::Glsl, ExportLanguage::Hlsl}) {
        SCOPED_TRACE(lang(l));
        const auto start = std::chrono::steady_clock::now();
        const std::string exported = exportText(layout, l);
        // 1. raster into the real formats
        GBufferPass pass;
        createGBufferImages(c, w, kSize, kSize, pass);
        const test::DescriptorSets s(c, VK_SHADER_STAGE_FRAGMENT_BIT, set0(in, out, table));
        pass.setLayout = s.setLayouts[0];
        pass.pipelineLayout = s.pipelineLayout;
        pass.pool = s.pool;
        pass.set = s.sets[0];
        const std::vector<uint32_t> fs =
            compileFor(l, "export.frag (" + layout.name + ")", fragmentWrapper(layout, l, exported), VK_SHADER_STAGE_FRAGMENT_BIT);
        pass.pipeline = createGBufferPipelineSpirv(c, w, pass.pipelineLayout, vs, fs, false);
        c.submitAndWait([&](VkCommandBuffer cmd) {
            beginGBufferPass(cmd, pass);
            vkCmdDraw(cmd, 3, 1, 0, 0);
            endGBufferPass(cmd, pass);
        });
        size_t wordMismatches = 0, words = 0;
        for (size_t t = 0; t < pass.targets.size(); ++t) {
            const std::vector<uint32_t> gpu = test::targetWords(c, pass.targets[t], kPixels);
            ASSERT_EQ(gpu.size(), cpu.targetWords[t].size());
            for (size_t i = 0; i < gpu.size(); ++i, ++words)
                if (gpu[i] != cpu.targetWords[t][i] && wordMismatches++ < 5)
                    ADD_FAILURE() << "raster " << layout.targets[t].format << " word " << i << ": gpu 0x" << std::hex
                                  << gpu[i] << " cpu 0x" << cpu.targetWords[t][i] << std::dec;
        }
        EXPECT_EQ(wordMismatches, 0u);

        // 2. decode from the real-format images
        std::memset(out.mapped<void>(), 0xff, kPixels * outWords * 4);
        const std::string decode = decodeWrapper(layout, l, exported);
        test::ComputeKernel(c, compileFor(l, "export decode (" + layout.name + ")", decode, VK_SHADER_STAGE_COMPUTE_BIT),
                            set0(in, out, table, pass.targets))
            .dispatch(kSize / 8, kSize / 8);
        const size_t decodeMismatches =
            compareDecoded(layout, out.mapped<const uint32_t>(), outWords, cpuDecoded, "image decode");
        EXPECT_EQ(decodeMismatches, 0u);

        // 3. the export's own kernel
        std::memset(out.mapped<void>(), 0xff, kPixels * outWords * 4);
        test::ComputeKernel(c, compileFor(l, "export kernel (" + layout.name + ")", exported, VK_SHADER_STAGE_COMPUTE_BIT),
                            set0(in, out, table))
            .dispatch(kSize / 8, kSize / 8);
        const uint32_t* o = out.mapped<const uint32_t>();
        const size_t kernelDecode = compareDecoded(layout, o, outWords, cpuDecoded, "kernel decode");
        EXPECT_EQ(kernelDecode, 0u);
        size_t valueMismatches = 0, roomy = 0;
        const size_t base = size_t(exportKernelInputFloats(layout) - 1);
        for (size_t t = 0; t < layout.targets.size(); ++t) {
            const Target& tg = layout.targets[t];
            const size_t wpp = size_t(wordsPerPixel(tg));
            for (size_t i = 0; i < kPixels; ++i) {
                uint32_t wordsOut[4] = {0, 0, 0, 0};
                bool ok = true;
                for (const Channel& ch : tg.channels) {
                    const uint32_t v = o[i * outWords + base + 4 * t + size_t(wiring::channelComponent(ch))];
                    const uint32_t code = codeOfValue(realKind(tg, ch), 0, v, ch.bits, ok);
                    wordsOut[ch.offset / 32] |= code << (ch.offset % 32);
                }
                roomy += !ok;
                for (size_t k2 = 0; k2 < wpp; ++k2)
                    if (wordsOut[k2] != cpu.targetWords[t][i * wpp + k2] && valueMismatches++ < 5)
                        ADD_FAILURE() << "kernel " << tg.format << " pixel " << i << " word " << k2 << ": 0x" << std::hex
                                      << wordsOut[k2] << " cpu 0x" << cpu.targetWords[t][i * wpp + k2] << std::dec;
            }
        }
        EXPECT_EQ(valueMismatches, 0u);
        EXPECT_EQ(roomy, 0u) << "values that leave the format's conversion a choice";
        std::printf("[ export   ] %-22s %s: %zu words bit-exact in the real formats (%zu off), decode %zu off, "
                    "kernel values %zu off, %zu inexact (%.1f s)\n",
                    layout.name.c_str(), lang(l).c_str(), words, wordMismatches, decodeMismatches, valueMismatches, roomy,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        pass.setLayout = VK_NULL_HANDLE;
        pass.pipelineLayout = VK_NULL_HANDLE;
        pass.pool = VK_NULL_HANDLE;
        destroyGBufferPass(c, pass);  // the set is s's
    }
}

// Ids packed as [ids] says, written out here: triangle from bit 0, draw above it, the top bit.
void checkVisibility(VulkanContext& c, const Layout& layout, const Buffer& table) {
    const VisibilityIds& ids = layout.ids;
    std::mt19937 rng(31);
    std::vector<uint32_t> in(kPixels * 4);
    for (size_t i = 0; i < kPixels; ++i) {
        in[i * 4] = rng();
        in[i * 4 + 1] = rng();
        in[i * 4 + 2] = i % 2;
    }
    const test::TestBuffer inBuf = test::TestBuffer::holding(c, in);
    const test::TestBuffer out(c, kPixels * 5 * 4);
    auto mask = [](int b) { return b >= 64 ? ~0ull : (1ull << b) - 1; };
    for (ExportLanguage l : {ExportLanguage::Glsl, ExportLanguage::Hlsl}) {
        SCOPED_TRACE(lang(l));
        const std::string kernel = exportText(layout, l);
        test::ComputeKernel(c, compileFor(l, "export kernel (" + layout.name + ")", kernel, VK_SHADER_STAGE_COMPUTE_BIT),
                            set0(inBuf, out, table))
            .dispatch(kSize / 8, kSize / 8);
        const uint32_t* o = out.mapped<const uint32_t>();
        size_t bad = 0;
        for (size_t i = 0; i < kPixels; ++i) {
            const uint64_t tri = in[i * 4] & mask(ids.triangleBits), draw = in[i * 4 + 1] & mask(ids.drawBits);
            const uint64_t alpha = ids.alphaMaskBit ? in[i * 4 + 2] : 0;
            const uint64_t packed = tri | (draw << ids.triangleBits) | (alpha << (ids.bits - 1));
            const bool ok = o[i * 5] == tri && o[i * 5 + 1] == draw && o[i * 5 + 2] == alpha &&
                            o[i * 5 + 3] == uint32_t(packed) && o[i * 5 + 4] == uint32_t(ids.bits == 64 ? packed >> 32 : 0);
            if (!ok && bad++ < 5) ADD_FAILURE() << layout.name << " id " << i;
        }
        EXPECT_EQ(bad, 0u);
        std::printf("[ export   ] %-22s %s: %zu ids packed and unpacked as [ids] says, %zu off\n", layout.name.c_str(),
                    lang(l).c_str(), kPixels, bad);
    }
}

TEST_F(LayoutExportGpu, EveryLayoutEncodesTheMirrorsWordsInItsRealFormats) {
    VulkanContext& c = ctx();
    const test::TestBuffer table = test::TestBuffer::holding(c, enc::bestFitNormalTable());
    const uint32_t seed = 3100;
    // Every shipped layout, the reference included. Two ctest entries run half each
    // (GBL_EXPORT_TEST_SHARD=i/n: the layouts at positions i, i + n, ... of the sorted list), so
    // that ctest -j2 runs them side by side; GBL_EXPORT_TEST_LAYOUTS=a,b,... runs those layouts only
    // (all: every layout in this process; docs/export.md). The 8-bit tables compile fast only as the export writes them now (select
    // trees, src/codec/export_tables.h): as const arrays one layout took lavapipe minutes.
    std::set<std::string> subset;
    if (const char* pick = std::getenv("GBL_EXPORT_TEST_LAYOUTS"); pick && *pick) {
        std::string list = pick;
        for (size_t at = 0; list != "all" && at <= list.size();) {
            const size_t comma = std::min(list.find(',', at), list.size());
            subset.insert(list.substr(at, comma - at));
            at = comma + 1;
        }
    }
    unsigned shard = 0, shards = 1;
    if (const char* sh = std::getenv("GBL_EXPORT_TEST_SHARD"); sh && *sh) {
        ASSERT_EQ(std::sscanf(sh, "%u/%u", &shard, &shards), 2) << "GBL_EXPORT_TEST_SHARD=i/n, not " << sh;
    }
    ASSERT_LT(shard, shards);
    size_t position = 0, ran = 0;
    for (const Layout& layout : test::shippedLayouts()) {
        const size_t at = position++;
        if (!subset.empty() ? !subset.count(layout.name) : at % shards != shard) continue;
        SCOPED_TRACE(layout.name);
        ++ran;
        if (layout.pipeline == Pipeline::VisibilityBuffer) checkVisibility(c, layout, table);
        else checkLayout(c, layout, seed + uint32_t(at), table);
    }
    EXPECT_GT(ran, 0u) << "no layout ran";
}

// A layout with a shading-model selector (tests/layout/data/shading-models.toml): the export picks
// each pixel's model by the renderer's rule, places the conditional fields of that model only, and
// decodes them where the stored id says; the Surfaces carry every combination of layers.
TEST_F(LayoutExportGpu, ASelectorLayoutEncodesTheMirrorsWords) {
    VulkanContext& c = ctx();
    const test::TestBuffer table = test::TestBuffer::holding(c, enc::bestFitNormalTable());
    checkLayout(c, test::testLayout("shading-models"), 3900, table);
    checkLayout(c, test::selectorLayoutDerivingEachOther(), 3901, table);  // fallbacks deriving each other per model
}

}  // namespace
}  // namespace gbl
