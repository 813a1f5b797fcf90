#pragma once
// A scene flattened for rendering: one vertex and one index array for all meshes, one draw per
// glTF primitive with its world matrix, materials with factors and texture indices, textures
// decoded to RGBA8, a camera and punctual lights. Loaded from glTF 2.0 or built in code.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace gbl {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec4 tangent;  // xyz tangent, w = bitangent sign (glTF convention: B = cross(N, T) * w)
    glm::vec2 uv;
    glm::vec2 uv1{0.0f};  // TEXCOORD_1, for textures whose texCoord is 1 (0 where the primitive has none)
};

struct Texture {
    std::string name;
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;  // RGBA8, rows top to bottom (glTF uv (0,0) = first row)
    bool srgb = false;          // true for base colour, emissive, specular colour (glTF: sRGB-encoded)
};

constexpr int kNoTexture = -1;

// A material's texture slots, in shaders/shared_types.h's order (GBL_SLOT_*).
enum class TextureSlot : int {
    BaseColor, MetallicRoughness, Normal, Occlusion, Emissive, Specular, SpecularColor,
    Clearcoat, ClearcoatRoughness, ClearcoatNormal, SheenColor, SheenRoughness, Anisotropy, Count
};
constexpr size_t kTextureSlotCount = size_t(TextureSlot::Count);

// The texture coordinates a slot samples: TEXCOORD_<texCoord>, through KHR_texture_transform's
// uv' = offset + rotation * (scale * uv) (its README: translation * rotation * scale; the rotation
// "counter-clockwise" in UV space, whose v axis points down, i.e. (u, v) -> (cos u + sin v,
// -sin u + cos v): the matrix of glTF issue 1563 that Babylon.js, Blender's importer, three.js and
// the TextureTransformTest sample model agree on, not the README's GLSL listing).
struct TextureTransform {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;  // radians
    glm::vec2 scale{1.0f};
    int texCoord = 0;       // 0 or 1 (the loader refuses others)
    bool transforms() const { return offset != glm::vec2(0.0f) || rotation != 0.0f || scale != glm::vec2(1.0f); }
    // The 2x2 linear part, column-major: m[0] = first column.
    glm::mat2 matrix() const;
};

// The material layers (shaders/brdf_layers.glsl GBL_LAYER_*).
constexpr int kLayerCoat = 1;
constexpr int kLayerSheen = 2;
constexpr int kLayerAnisotropy = 4;

// glTF metallic-roughness material, with the KHR_materials_* extensions the loader reads
// (specular, ior, emissive_strength, clearcoat, sheen, anisotropy) and KHR_texture_transform.
struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    float metallicFactor = 1.0f;
    float roughnessFactor = 1.0f;
    glm::vec3 emissiveFactor{0.0f};
    float normalScale = 1.0f;
    float occlusionStrength = 1.0f;
    // KHR_materials_specular: F0 of dielectrics = min(0.04 * specularColor, 1) * specular (glTF spec).
    float specularFactor = 1.0f;
    glm::vec3 specularColorFactor{1.0f};
    int baseColorTexture = kNoTexture;
    int metallicRoughnessTexture = kNoTexture;  // G = roughness, B = metallic
    int normalTexture = kNoTexture;
    int occlusionTexture = kNoTexture;          // R = occlusion
    int emissiveTexture = kNoTexture;
    int specularTexture = kNoTexture;           // A = specular
    int specularColorTexture = kNoTexture;      // RGB = specular colour (sRGB)
    // KHR_materials_ior: dielectric F0 = ((ior - 1) / (ior + 1))^2; 0 is the specular-glossiness
    // compatibility mode (F0 = 1: the Fresnel term "MUST evaluate to 1.0").
    float ior = 1.5f;
    // KHR_materials_emissive_strength: multiplies emissiveFactor (which stays in [0, 1]).
    float emissiveStrength = 1.0f;
    // KHR_materials_clearcoat: clearcoat = factor * texture.r, roughness = factor * texture.g, the
    // coat's normal from its own normal texture (none: the geometry's normal, not the base's map).
    float clearcoatFactor = 0.0f;
    int clearcoatTexture = kNoTexture;
    float clearcoatRoughnessFactor = 0.0f;
    int clearcoatRoughnessTexture = kNoTexture;
    int clearcoatNormalTexture = kNoTexture;
    float clearcoatNormalScale = 1.0f;
    // KHR_materials_sheen: colour = factor * texture.rgb (sRGB), roughness = factor * texture.a.
    glm::vec3 sheenColorFactor{0.0f};
    int sheenColorTexture = kNoTexture;
    float sheenRoughnessFactor = 0.0f;
    int sheenRoughnessTexture = kNoTexture;
    // KHR_materials_anisotropy: strength = factor * texture.b, direction = rotation applied to
    // texture.rg * 2 - 1 (or +x) in the tangent frame.
    float anisotropyStrength = 0.0f;
    float anisotropyRotation = 0.0f;  // radians, counter-clockwise from the tangent
    int anisotropyTexture = kNoTexture;
    // Per slot (TextureSlot): KHR_texture_transform and the texCoord set.
    std::array<TextureTransform, kTextureSlotCount> uvTransforms{};
    // KHR_materials_transmission / KHR_materials_volume: deferred engines draw such materials
    // forward, after the G-buffer's lighting; gbufferlab masks their pixels out of every metric and
    // counts them (`forward` names the extension).
    std::string forward;
    // alphaMode BLEND, rendered opaque here (scene_gltf_materials.cpp); the cross-check leaves its
    // pixels out, as the Sample Viewer blends them (docs/crosscheck.md).
    bool alphaBlend = false;
    // The layers the material has (kLayer* bits): a factor above 0 enables each.
    int layers() const;
    bool doubleSided = false;
    // glTF alphaMode MASK: fragments whose alpha (base colour factor x texture) is below
    // alphaCutoff are discarded (glTF 2.0, 3.9.4). OPAQUE and BLEND render opaque.
    bool alphaMask = false;
    float alphaCutoff = 0.5f;
    // Per-material values of a layout's stencil extras (layouts/README.md [depth] stencil), by
    // attribute name ("indoor", "ambient_id", ...): the G-buffer pass writes them as this material's
    // stencil reference; an extra not named here holds the layout's declared `value`.
    std::vector<std::pair<std::string, uint32_t>> stencilValues;
};

struct Draw {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int32_t vertexOffset = 0;
    int material = 0;
    glm::mat4 model{1.0f};
};

struct Camera {
    glm::vec3 position{0.0f, 0.0f, 3.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float yFovRadians = 0.7f;
    float zNear = 0.01f;
    float zFar = 100.0f;  // finite; the renderer may use reversed or infinite Z
    bool fromFile = false;
    // Placed by frameScene (a glTF without a camera): the view is fitted to the drawn vertices,
    // and compare's other views (compare_views.h) are fitted the same way from their directions.
    bool framed = false;
};

enum class LightType : int { Directional = 0, Point = 1, Spot = 2 };

struct Light {
    LightType type = LightType::Directional;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;       // directional: lux; point/spot: candela (glTF units)
    glm::vec3 position{0.0f};     // world space (point, spot)
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // world space, direction the light travels
    float range = 0.0f;           // 0 = infinite
    float innerConeAngle = 0.0f;           // spot only, radians from the axis (glTF default)
    float outerConeAngle = 0.7853982f;     // spot only, radians from the axis (glTF default pi/4)
};

struct Bounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
};

struct Scene {
    std::string source;  // file path, or "built-in default scene"
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    std::vector<Draw> draws;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Light> lights;
    Camera camera;
    Bounds bounds;  // world-space bounds of all draws
    // Sample every material texture at its base level only (bilinear, no mips): what a glTF
    // sampler with minFilter LINEAR asks for. render --texture-base-level sets it, so that a
    // cross-check against another renderer (docs/crosscheck.md) sees no mip or filter footprint
    // difference; off, textures are trilinear (gpu_scene.cpp).
    bool textureBaseLevelOnly = false;
    // With textureBaseLevelOnly: the texel nearest the sample point, no bilinear weights (glTF's
    // magFilter/minFilter NEAREST). render --texture-nearest sets it, so that a cross-check sees
    // the stored texel values only: two renderers' bilinear weights differ in their last bits
    // (8-bit sub-texel precision is what D3D11 asks of a GPU), which a very sharp lobe amplifies.
    bool textureNearest = false;
};

// Loads a .gltf (external or embedded buffers) or .glb file. Throws UserError naming the file
// and the problem for anything malformed or unsupported (e.g. Draco). Generates tangents when a
// primitive has a normal map but no TANGENT. Non-indexed primitives get sequential indices.
// Adds a default sun when the file has no KHR_lights_punctual lights, and a camera that frames
// the bounds when it has none.
// Buffer and image URIs must resolve to regular files inside the scene's folder unless
// `allowOutsideScene` (the --allow-outside-scene flag).
struct GltfLoadOptions {
    bool allowOutsideScene = false;
};
Scene loadGltfScene(const std::string& path, const GltfLoadOptions& options = {});

// The built-in scene: a sphere grid over roughness x metallic, coloured-specular spheres
// (gold, copper, a coloured dielectric) and a normal-mapped ground plane with fine detail.
Scene makeDefaultScene();
// The default scene's sphere grid alone (metals and dielectrics across roughness, coloured F0,
// a ground with detail normals): the material balls of the IBL comparison.
Scene makeSphereGridScene();

// The closest camera looking along -towardCamera (up as given, then made orthogonal) whose
// frame, shrunk by 5% on each axis, holds every point's projection: the points' projected
// extent touches that margin on both sides of one axis and is centred on the other. Near and far hug the
// points. The default field of view unless given.
Camera fitPointsInView(const std::vector<glm::vec3>& points, glm::vec3 towardCamera, glm::vec3 up, float aspect,
                       float yFovRadians);
// A camera from the front (+Z), a little above, fitted to the bounds' eight corners.
Camera frameBounds(const Bounds& bounds, float aspect);
// Every drawn vertex in world space (through the indices and each draw's model matrix).
std::vector<glm::vec3> drawnPoints(const Scene& scene);
// A glTF without a camera: the view from the front, fitted to the drawn vertices (tighter than
// the bounds when the object is not box-shaped).
Camera frameScene(const Scene& scene, float aspect);

// A light used when the scene has none: a warm sun from the upper left front.
Light defaultSun();

// World-space bounds of every draw's vertices (exact: each vertex goes through its draw's model
// matrix). Empty scene: zero bounds.
Bounds worldBounds(const Scene& scene);

}  // namespace gbl
