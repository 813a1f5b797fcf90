// loadGltfScene: parse with tinygltf, reject what gbufferlab cannot render, then flatten the
// chosen scene into one vertex/index array with a draw per (node, primitive).
#include <algorithm>
#include <array>
#include <filesystem>
#include <string_view>
#include <map>
#include <tuple>

#include "file_io.h"
#include "scene.h"
#include "scene_gltf_files.h"
#include "scene_gltf_images.h"
#include "scene_gltf_json_check.h"
#include "scene_gltf_camera_lights.h"
#include "scene_gltf_context.h"
#include "scene_gltf_geometry.h"
#include "scene_gltf_materials.h"
#include "scene_gltf_nodes.h"

namespace gbl {
namespace {

// Extensions whose data this loader reads (or, for quantization, whose types it accepts; for
// transmission and volume, whose materials it masks out of the metrics as drawn forward).
// A file that *requires* any other one cannot be shown correctly, so it is refused.
constexpr std::array kSupportedRequiredExtensions = {
    "KHR_materials_specular",   "KHR_lights_punctual",        "KHR_mesh_quantization",
    "KHR_texture_transform",    "KHR_materials_clearcoat",    "KHR_materials_sheen",
    "KHR_materials_anisotropy", "KHR_materials_ior",          "KHR_materials_emissive_strength",
    "KHR_materials_transmission", "KHR_materials_volume"};

bool startsWithGlbMagic(const std::vector<unsigned char>& bytes) {
    return bytes.size() >= 4 && std::equal(bytes.begin(), bytes.begin() + 4, "glTF");
}

// Draco-compressed primitives have accessors without bufferViews, which tinygltf (built without
// Draco) rejects before we can look at extensionsRequired; a failed load of a file naming the
// extension is reported as the Draco problem it almost certainly is.
bool mentionsDraco(const std::vector<unsigned char>& bytes) {
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    return text.find("KHR_draco_mesh_compression") != std::string_view::npos;
}

// tinygltf's messages are multi-line; the error policy wants one line.
std::string oneLine(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    std::string out;
    for (char c : text) {
        if (c == '\n') out += "; ";
        else if (c != '\r') out += c;
    }
    return out;
}

// The file is read once, as a regular file (a directory or FIFO is refused, never read); its JSON
// is checked against the specification (scene_gltf_json_check.h); the files it names are read
// through GltfFileAccess (regular files inside the scene's folder).
tinygltf::Model parseFile(const std::string& path, const GltfLoadOptions& options) {
    const std::vector<unsigned char> bytes = readBinaryFile(path);
    registerInput(path);  // no output may replace it (file_io.h)
    const bool glb = startsWithGlbMagic(bytes);
    checkGltfJson(path, bytes);
    GltfFileAccess files(path, options.allowOutsideScene);
    tinygltf::TinyGLTF parser;
    parser.SetFsCallbacks(files.callbacks());
    GltfImageBudget images(path);
    images.install(parser);
    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
    try {
        // By content, not extension: .glb files renamed to .gltf still load.
        ok = glb ? parser.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), files.baseDir())
                 : parser.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                              unsigned(bytes.size()), files.baseDir());
    } catch (const std::exception& e) {  // its JSON parser may throw on malformed input
        err = e.what();
        ok = false;
    }
    // A refused URI fails the load even where tinygltf would carry on without the file (images).
    if (!files.refusal().empty()) throwUserError(files.refusal());
    if (!images.refusal().empty()) throwUserError(images.refusal());
    if (!ok && mentionsDraco(bytes))  // tinygltf fails on Draco's missing bufferViews first
        throwUserError(formatPlace(escapeText(path)) +
                       ": extensionsRequired: uses Draco compression, which gbufferlab does not support; "
                       "re-export without Draco");
    if (!ok)
        throwUserError(formatPlace(escapeText(path)) + ": not a loadable glTF 2.0 file: " +
                       escapeText(oneLine(err.empty() ? warn : err)) + "; check the file and its .bin/image files");
    return model;
}

void checkRequiredExtensions(const GltfContext& ctx) {
    for (const std::string& ext : ctx.model.extensionsRequired) {
        if (ext == "KHR_draco_mesh_compression")
            ctx.fail("extensionsRequired", "uses Draco compression, which gbufferlab does not support",
                     "re-export without Draco");
        if (std::find(kSupportedRequiredExtensions.begin(), kSupportedRequiredExtensions.end(), ext) ==
            kSupportedRequiredExtensions.end())
            ctx.fail("extensionsRequired", "requires " + ext + ", which gbufferlab does not support",
                     "re-export without " + ext);
    }
}

// One geometry per (mesh, primitive, mirrored) lives in the shared arrays; draws reference it.
struct GeometryRange {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int32_t vertexOffset = 0;
};

class SceneBuilder {
public:
    SceneBuilder(const GltfContext& ctx, Scene& scene) : ctx_(ctx), scene_(scene) {}

    void addNode(const NodeInstance& instance) {
        const int meshIndex = ctx_.model.nodes[instance.node].mesh;
        if (meshIndex < 0) return;
        if (static_cast<size_t>(meshIndex) >= ctx_.model.meshes.size())
            ctx_.fail(describeItem("node", instance.node, ctx_.model.nodes[instance.node].name),
                      "refers to mesh " + std::to_string(meshIndex) + ", but the file has " +
                          std::to_string(ctx_.model.meshes.size()),
                      "the file is corrupt; re-export it");
        const auto& mesh = ctx_.model.meshes[static_cast<size_t>(meshIndex)];
        // A mirroring matrix turns counter-clockwise triangles clockwise and flips the tangent
        // frame's handedness; such instances get their own copy with both undone.
        const bool mirrored = glm::determinant(glm::mat3(instance.world)) < 0.0f;
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            const auto range = geometry(static_cast<size_t>(meshIndex), p, mirrored);
            if (!range) {
                ++skippedPrimitives_;
                continue;
            }
            Draw draw;
            draw.firstIndex = range->firstIndex;
            draw.indexCount = range->indexCount;
            draw.vertexOffset = range->vertexOffset;
            draw.material = materialFor(static_cast<size_t>(meshIndex), p);
            draw.model = instance.world;
            scene_.draws.push_back(draw);
        }
    }

    size_t skippedPrimitives() const { return skippedPrimitives_; }

private:
    std::optional<GeometryRange> geometry(size_t mesh, size_t primitive, bool mirrored) {
        const auto key = std::make_tuple(mesh, primitive, mirrored);
        if (const auto it = cache_.find(key); it != cache_.end()) return it->second;
        std::optional<PrimitiveGeometry> loaded = loadTrianglePrimitive(ctx_, mesh, primitive);
        std::optional<GeometryRange> range;
        if (loaded) {
            if (mirrored) {
                for (size_t i = 0; i + 2 < loaded->indices.size(); i += 3)
                    std::swap(loaded->indices[i + 1], loaded->indices[i + 2]);
                for (Vertex& v : loaded->vertices) v.tangent.w = -v.tangent.w;
            }
            range = append(*loaded, mesh, primitive);
        }
        cache_.emplace(key, range);
        return range;
    }

    GeometryRange append(const PrimitiveGeometry& g, size_t mesh, size_t primitive) {
        // Draw::vertexOffset is an int32 and indices are uint32.
        constexpr size_t kLimit = size_t(INT32_MAX);
        if (scene_.vertices.size() + g.vertices.size() > kLimit || scene_.indices.size() + g.indices.size() > kLimit)
            ctx_.fail(describeItem("mesh", mesh, ctx_.model.meshes[mesh].name) + " primitive " + std::to_string(primitive),
                      "the scene exceeds 2^31 vertices or indices", "split or decimate the model");
        GeometryRange range;
        range.firstIndex = static_cast<uint32_t>(scene_.indices.size());
        range.indexCount = static_cast<uint32_t>(g.indices.size());
        range.vertexOffset = static_cast<int32_t>(scene_.vertices.size());
        scene_.vertices.insert(scene_.vertices.end(), g.vertices.begin(), g.vertices.end());
        scene_.indices.insert(scene_.indices.end(), g.indices.begin(), g.indices.end());
        return range;
    }

    int materialFor(size_t mesh, size_t primitive) {
        const int material = ctx_.model.meshes[mesh].primitives[primitive].material;
        if (material >= 0) {
            if (static_cast<size_t>(material) >= ctx_.model.materials.size())
                ctx_.fail(describeItem("mesh", mesh, ctx_.model.meshes[mesh].name) + " primitive " +
                              std::to_string(primitive),
                          "refers to material " + std::to_string(material) + ", but the file has " +
                              std::to_string(ctx_.model.materials.size()),
                          "the file is corrupt; re-export it");
            return material;
        }
        if (defaultMaterial_ < 0) {  // appended after the file's own, only when needed
            scene_.materials.push_back(defaultGltfMaterial());
            defaultMaterial_ = static_cast<int>(scene_.materials.size()) - 1;
        }
        return defaultMaterial_;
    }

    const GltfContext& ctx_;
    Scene& scene_;
    std::map<std::tuple<size_t, size_t, bool>, std::optional<GeometryRange>> cache_;
    int defaultMaterial_ = -1;
    size_t skippedPrimitives_ = 0;
};

}  // namespace

Scene loadGltfScene(const std::string& path, const GltfLoadOptions& options) {
    const tinygltf::Model model = parseFile(path, options);
    const GltfContext ctx{path, model};
    checkRequiredExtensions(ctx);

    Scene scene;
    scene.source = path;
    const size_t sceneIndex = chooseScene(ctx);
    const std::vector<NodeInstance> nodes = flattenScene(ctx, sceneIndex);
    loadMaterials(ctx, scene);

    SceneBuilder builder(ctx, scene);
    for (const NodeInstance& node : nodes) builder.addNode(node);
    if (scene.draws.empty())
        ctx.fail(describeItem("scene", sceneIndex, model.scenes[sceneIndex].name),
                 "has no triangles to draw (" + std::to_string(builder.skippedPrimitives()) +
                     " primitive(s) skipped: only mode 4 TRIANGLES with POSITION is rendered)",
                 "export the meshes as triangles");

    scene.bounds = worldBounds(scene);
    scene.camera = cameraFromNodes(ctx, nodes, scene.bounds).value_or(frameBounds(scene.bounds, 1.0f));
    scene.lights = lightsFromNodes(ctx, nodes);
    if (scene.lights.empty()) scene.lights.push_back(defaultSun());
    return scene;
}

}  // namespace gbl
