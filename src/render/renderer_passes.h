#pragma once
// The two passes of a deferred renderer, as plain structs built for one wiring and one size.
#include "gbuffer_wiring.h"
#include "gpu_scene.h"
#include "ibl_precompute.h"
#include "pipeline_memo.h"
#include "shader_compiler.h"
#include "shared_types.h"
#include "vk_pipeline.h"
#include "vk_resources.h"

namespace gbl {

// What the passes that read a G-buffer compile against when it is a visibility buffer: its
// resolve's texture array (set 1, binding 5) has the scene's texture count, and is indexed per
// pixel only where the device allows it. All zero/false for a G-buffer layout, so its pipelines
// do not depend on the scene.
struct TargetReadScene {
    bool visibility = false;
    uint32_t textureCount = 0;
    bool nonUniformIndexing = false;
    MaterialTextureSlots texturesBySlot;  // the resolve's candidates per slot (without non-uniform indexing)
    bool clusters = false;  // [ids] cluster_triangles: the cluster table at set 1, binding 6
    // The scene's shader features (gpu_scene.h sceneShaderFeatures), for every layout: the lighting
    // pass compiles the layers' shading (GBL_LAYERS), a resolve the material's (and its uv transforms).
    int layers = 0;
    bool uvTransforms = false;
};

struct GBufferPass {
    std::vector<GpuImage> targets;
    GpuImage depth;
    GpuImage emissive;  // emissive = forward: RGBA32F scene colour written by the G-buffer pass (else empty)
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    float clearDepth = 1.0f;
    // A band of rows (RenderSettings::bandFirstRow): render area and scissor are rows
    // renderFirstRow.. (renderRows of them) of the frame-sized images, with the frame's viewport,
    // so every pixel is rasterised and shaded as in the whole frame's pass. 0 rows: the frame.
    uint32_t renderFirstRow = 0;
    uint32_t renderRows = 0;
    // The best-fit normal table (src/encoding/best_fit_normals.h) that encodeNormalBestFit reads:
    // set 0, binding kBestFitTableBinding of every pipeline that writes a G-buffer.
    Buffer bestFitTable;
    // The encodings' 8-bit tables (src/encoding/codec_tables.h): the G-buffer pass's encoders read
    // them at set 0, and the passes reading this G-buffer (lighting, decode) at set 1, binding
    // enc::kCodecTablesBinding (writeTargetReadSet). Lent by createGBufferPass's caller, empty in
    // passes put together by hand.
    Buffer codecTables;
    // bestFitTable and codecTables belong to someone else (createGBufferPass: the Renderer's,
    // uploaded once): destroyGBufferPass leaves them. Passes put together by hand own theirs.
    bool tablesBorrowed = false;
    std::vector<std::array<uint32_t, 4>> clearWords;  // per target (GBufferWiring::targetClearWords)
    // The layout declares stencil extras: the pipeline writes the stencil with op REPLACE and a
    // dynamic reference, set per draw to stencilReference(wiring, material's values).
    bool writesStencil = false;
    GBufferWiring wiring;  // for the stencil references (only its stencil fields are read)
    // A visibility buffer (GBufferWiring::visibilityBuffer): the one target holds ids, and the
    // passes that read it resolve Surfaces from this scene's geometry, materials and textures.
    const GpuScene* visibilityScene = nullptr;
    int sceneLayers = 0;              // GpuScene::layers of the scene drawn
    bool sceneUvTransforms = false;   // GpuScene::uvTransforms
    // ... and whether its resolve may index the textures per pixel (VulkanContext::
    // nonUniformSampledImageIndexing; without it, visibility_resolve.glsl loops over them).
    bool nonUniformTextureIndexing = false;
    // ... and with clusters ([ids] cluster_triangles): each draw's id, pushed as its
    // DrawConstants::material.y (its first cluster), and the cluster table the resolve reads
    // (visibilityFirstIds, visibilityClusterTable: visibility_wiring.h). Owned by the pass.
    std::vector<uint32_t> drawFirstIds;
    Buffer clusterTable;
    // Built by createGBufferPass: a PipelineMemo owns setLayout, pipelineLayout and pipeline
    // (destroy leaves them). Passes put together by hand (the bit tests) own theirs.
    bool pipelineFromMemo = false;
    // This pass is the pipeline's first user (PipelineMemo::firstUse): the renderer warms it up.
    bool needsWarmUp = true;
};

// The layout's [space] as defines for shaders/normal_space.glsl (GBL_NORMAL_SPACE,
// GBL_POSITION_SPACE) and, where it stores position or a window depth, GBL_STORES_POSITION or
// GBL_STORES_DEPTH.
inline void addSpaceDefines(ShaderSource& s, const GBufferWiring& w) {
    s.defines.push_back({"GBL_NORMAL_SPACE", std::to_string(w.normalSpace)});
    s.defines.push_back({"GBL_POSITION_SPACE", std::to_string(w.positionSpace)});
    if (w.storesPosition) s.defines.push_back({"GBL_STORES_POSITION", "1"});
    if (w.storesDepth) s.defines.push_back({"GBL_STORES_DEPTH", "1"});
}

// Uploads bestFitNormalTable() as a storage buffer (for GBufferPass::bestFitTable).
Buffer createBestFitTableBuffer(const VulkanContext& ctx);
// Uploads enc::codecTableFloats() as a storage buffer (for GBufferPass::codecTables).
Buffer createCodecTablesBuffer(const VulkanContext& ctx);

// Both constant tables, uploaded once (the Renderer's) and lent to every createGBufferPass.
struct CodecTableBuffers {
    Buffer bestFitTable;
    Buffer codecTables;
};
void destroyCodecTableBuffers(const VulkanContext& ctx, CodecTableBuffers& tables);

// Throws UserError (one line naming the layout, the count and the fix) when the scene has more
// draws or triangles than a visibility buffer's ids hold, or the device lacks gl_PrimitiveID in
// fragment shaders. Renderer::render calls it before it allocates anything.
void checkVisibilityBufferSupport(const VulkanContext& ctx, const GBufferWiring& wiring, const GpuScene& scene);


// The pipeline (and its layouts) is taken from `memo` when this wiring's was built before, else
// built into it (gbufferPassPipeline).
// `tables` are lent (GBufferPass::tablesBorrowed): they must outlive the pass.
GBufferPass createGBufferPass(const VulkanContext& ctx, const GBufferWiring& wiring, const GpuScene& scene,
                              const Buffer& frameConstants, uint32_t width, uint32_t height, PipelineMemo& memo,
                              const CodecTableBuffers& tables);
// The pipelines of a wiring's passes alone (no images, no submission), from `memo` or built into
// it: what createGBufferPass and createLightingPass use, callable from several threads at once
// (Renderer::preparePipelines). The G-buffer pass compiles against the scene's texture count and
// what each material slot samples (GpuScene::texturesBySlot; material.glsl).
PassPipeline gbufferPassPipeline(const VulkanContext& ctx, const GBufferWiring& wiring, const GpuScene& scene,
                                 PipelineMemo& memo);
// What a lighting pipeline is built for besides its wiring. Specialised: the specular IBL mode
// and the direct lights' Fresnel compiled in as defines (GBL_IBL_MODE, GBL_FRESNEL_MODE), so the
// driver compiles only the code they take; else one pipeline reads both from the frame constants
// and serves every mode. On llvmpipe (JIT-compiles every branch) a specialised lighting pipeline
// cost 0.55-0.63 s of JIT against 0.79-1.0 s for the generic one (96x54, 4 layouts + reference,
// loaded machine): worth it for a run of one mode, not for a run of several (k specialised
// pipelines against one generic). Same pixels either way (pipeline_reuse_test).
struct LightingVariant {
    IblMode ibl = IblMode::SplitSum;
    int fresnelMode = 1;  // brdf.glsl FRESNEL_* (RenderSettings::fresnelMode)
    int brdf = 0;         // brdf.glsl BRDF_* (RenderSettings::brdf)
    bool specialised = true;
};
PassPipeline lightingPassPipeline(const VulkanContext& ctx, const GBufferWiring& wiring, const TargetReadScene& scene,
                                  const LightingVariant& variant, PipelineMemo& memo);
// Records the pass; leaves targets and depth in SHADER_READ_ONLY_OPTIMAL.
void recordGBufferPass(VkCommandBuffer cmd, const GBufferPass& pass, const GpuScene& scene);
// The pass's first draw only, clipped to one pixel: makes a driver that compiles shaders at their
// first use (llvmpipe JIT-compiles its shader variants at the first draw) compile them here, so the
// compile is timed as such and not as rendering. The targets are left as recordGBufferPass leaves
// them; the frame's own pass clears them again.
void recordGBufferWarmUp(VkCommandBuffer cmd, const GBufferPass& pass, const GpuScene& scene);
void destroyGBufferPass(const VulkanContext& ctx, GBufferPass& pass);

// The parts createGBufferPass is made of, for a G-buffer filled by other shaders (the GPU/CPU bit
// test draws ready-made Surfaces from a buffer) through the same targets, pipeline state,
// clears and transitions as the renderer's:
//   the colour targets (one per wiring.targetFormats) and depth, in `pass`;
void createGBufferImages(const VulkanContext& ctx, const GBufferWiring& wiring, uint32_t width, uint32_t height,
                         GBufferPass& pass);
//   the pipeline, compiling `fragment` with the wiring's GLSL as "gbuffer_wiring.glsl"; with
//   sceneVertices, the vertex input is the GpuScene's Vertex, else none;
// The layout declares stencil extras and its depth format has stencil.
bool writesStencil(const GBufferWiring& wiring);
VkPipeline createGBufferPipeline(const VulkanContext& ctx, const GBufferWiring& wiring, VkPipelineLayout layout,
                                 const ShaderSource& vertex, ShaderSource fragment, bool sceneVertices);
// The same from compiled SPIR-V (entry points "main"): a fragment shader of another language
// (the HLSL of `layouts export`, tests/codec/layout_export_gpu_test.cpp).
VkPipeline createGBufferPipelineSpirv(const VulkanContext& ctx, const GBufferWiring& wiring, VkPipelineLayout layout,
                                      const std::vector<uint32_t>& vertexSpirv, const std::vector<uint32_t>& fragmentSpirv,
                                      bool sceneVertices);
//   begin: targets and depth cleared, viewport and scissor set, pass.pipeline and pass.set bound;
//   end: targets left in SHADER_READ_ONLY_OPTIMAL, depth in DEPTH_STENCIL_READ_ONLY_OPTIMAL.
void beginGBufferPass(VkCommandBuffer cmd, const GBufferPass& pass);
void endGBufferPass(VkCommandBuffer cmd, const GBufferPass& pass);

// Deferred lighting's material pass: a second geometry pass through the same generated GLSL,
// compiled with MATERIAL_PASS_WRITE, into the wiring's material targets.
GBufferWiring materialPassWiring(const GBufferWiring& wiring);

struct LightingPass {
    GpuImage hdr;  // RGBA32F storage image, left in GENERAL
    // Ground truth's running batch statistics (binding 9, RGBA32F, GENERAL): rgb mean radiance,
    // a = M2 of the batch luminances. Full size with LightingInputs::accumulate, else 1 x 1.
    GpuImage accumulation;
    // Set 0: frame, lights, depth, environment, output, IBL; set 1: the G-buffer targets;
    // set 2 (deferred lighting only): the material pass's targets.
    VkDescriptorSetLayout setLayouts[3] = {VK_NULL_HANDLE, VK_NULL_HANDLE, VK_NULL_HANDLE};
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet sets[3] = {VK_NULL_HANDLE, VK_NULL_HANDLE, VK_NULL_HANDLE};
    uint32_t setCount = 2;
    uint32_t width = 0, height = 0;
    bool needsWarmUp = true;  // as GBufferPass's (the memo owns the pipeline and its layouts)
};

struct LightingInputs {
    const Buffer* frameConstants;
    const Buffer* lights;
    const GBufferPass* gbuffer;
    const GpuImage* environment;
    VkSampler environmentSampler;
    VkSampler nearestSampler;
    const IblGpu* ibl;  // environment cube, pre-filtered cube, BRDF LUT (bindings 5, 6, 7)
    const GpuImage* sheenAlbedo;  // R32F E(NoV, sheen roughness) (binding 12; Renderer::sheenAlbedo_)
    const GBufferPass* materialPass = nullptr;  // deferred lighting's second geometry pass (set 2)
    const Buffer* lightBufferWords = nullptr;  // deferred lighting's light buffers (set 0, binding 9)
    bool accumulate = false;  // ground truth: batches accumulate into LightingPass::accumulation
    LightingVariant variant;  // when specialised, must match the frame constants' IBL mode and Fresnel
};

// The bindings of a set of G-buffer-like targets read with usampler2D (sets 1 and 2), and the
// encodings' tables (binding enc::kCodecTablesBinding, a storage buffer: codec_tables.glsl); for a
// visibility buffer, also what its resolve reads (shaders/visibility_buffer.glsl, GBUFFER_READ):
// binding 1 vertices, 2 indices, 3 draws, 4 materials (storage buffers), 5 the textures.
std::vector<Binding> targetReadBindings(const GBufferPass& pass);
std::vector<Binding> targetReadBindings(size_t targetCount, const TargetReadScene& scene);
// A pass's TargetReadScene: visibility from its visibilityScene, else none.
TargetReadScene targetReadScene(const GBufferPass& pass);
// The TargetReadScene createGBufferPass's pass will have for this wiring and scene (for building
// pipelines before the pass exists: Renderer::preparePipelines).
TargetReadScene targetReadScene(const VulkanContext& ctx, const GBufferWiring& wiring, const GpuScene& scene);
// Writes those bindings of `set` (targets through `nearestSampler`, the pass's codecTables).
void writeTargetReadSet(DescriptorWriter& writer, VkDescriptorSet set, const GBufferPass& pass, VkSampler nearestSampler);
// What a pass reading a G-buffer compiles with: GBL_CODEC_TABLES_SET / _BINDING (the tables from
// the storage buffer of targetReadBindings); for a visibility buffer also TEXTURE_COUNT for its
// resolve, and GBL_NONUNIFORM_TEXTURE_INDEXING where the device has it, else the candidate
// textures of each material slot (GBL_RESOLVE_SLOT_<name>: the scene's texturesBySlot).
void addTargetReadDefines(ShaderSource& s, const TargetReadScene& scene);
// GBL_LAYERS and GBL_UV_TRANSFORMS for a scene that has them (material_eval.glsl, lighting_pass.comp.glsl).
void addSceneFeatureDefines(ShaderSource& s, int layers, bool uvTransforms);

// in.gbuffer and in.materialPass must be the wiring's (their target counts are the set layouts').
LightingPass createLightingPass(const VulkanContext& ctx, const GBufferWiring& wiring, const LightingInputs& in,
                                uint32_t width, uint32_t height, PipelineMemo& memo);
// Records one dispatch; `batch` is the ground truth's batch index (push constant): batch 0
// starts the accumulation afresh, later ones add to it.
void recordLightingPass(VkCommandBuffer cmd, const LightingPass& pass, uint32_t batch = 0);
// One workgroup of batch 0 (see recordGBufferWarmUp); the frame's dispatch overwrites its pixels.
void recordLightingWarmUp(VkCommandBuffer cmd, const LightingPass& pass);
void destroyLightingPass(const VulkanContext& ctx, LightingPass& pass);

}  // namespace gbl
