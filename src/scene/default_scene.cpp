// The built-in scene: needs no file, and covers what a G-buffer layout can get wrong —
// roughness from mirror to fully rough, dielectric vs metal, coloured F0 (metals and a
// KHR_materials_specular dielectric) and a ground with texel-scale normal detail (the sphere
// grid, makeSphereGridScene); around it, filling the frame: textured albedo with saturated
// chroma detail, a tiled metal/dielectric panel with sharp boundaries, a large sphere with fine
// normal detail facing every axis, an emissive sign, an alpha-tested wire fence, and buildings
// from 100 m to 400 m away on a ground that reaches the horizon (depth precision). Occlusion maps
// as real assets carry them: the ground's, baked from the spheres above it (contact shadows), and
// the tiles' grooves, packed with their roughness and metallic (a layout that drops occlusion
// loses here as on real content).
#include <glm/gtc/matrix_transform.hpp>

#include "scene.h"
#include "scene_detail_normal_map.h"
#include "procedural_textures.h"
#include "scene_shapes.h"

namespace gbl {
namespace {

constexpr float kSphereRadius = 0.4f;
constexpr float kSpacing = 1.0f;
constexpr int kColumns = 6;
// Sphere rows, bottom to top: y of the centres.
constexpr float kColouredRowY = 0.5f, kDielectricRowY = 1.5f, kMetalRowY = 2.5f;

// Roughness of column c: 0.05 (near mirror, where encodings of normals hurt most) to 1.
float roughnessOfColumn(int column) { return 0.05f + 0.95f * float(column) / float(kColumns - 1); }

float xOfColumn(int column) { return (float(column) - 0.5f * float(kColumns - 1)) * kSpacing; }

struct SceneParts {
    Scene& scene;
    Draw sphere;  // geometry of the shared sphere; per draw only material and model change

    int addMaterial(const Material& m) {
        scene.materials.push_back(m);
        return static_cast<int>(scene.materials.size()) - 1;
    }
    void addSphere(const Material& m, float x, float y) {
        Draw draw = sphere;
        draw.material = addMaterial(m);
        draw.model = glm::translate(glm::mat4(1.0f), glm::vec3(x, y, 0.0f));
        scene.draws.push_back(draw);
    }
};

Draw appendMesh(Scene& scene, const ShapeMesh& mesh) {
    Draw draw;
    draw.firstIndex = static_cast<uint32_t>(scene.indices.size());
    draw.indexCount = static_cast<uint32_t>(mesh.indices.size());
    draw.vertexOffset = static_cast<int32_t>(scene.vertices.size());
    scene.vertices.insert(scene.vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
    scene.indices.insert(scene.indices.end(), mesh.indices.begin(), mesh.indices.end());
    return draw;
}

Material makeMaterial(const std::string& name, glm::vec3 baseColor, float metallic, float roughness) {
    Material m;
    m.name = name;
    m.baseColorFactor = glm::vec4(baseColor, 1.0f);
    m.metallicFactor = metallic;
    m.roughnessFactor = roughness;
    return m;
}

void addRoughnessMetallicGrid(SceneParts& parts) {
    // A saturated dielectric, so chroma loss shows; a neutral silver metal.
    const glm::vec3 terracotta(0.85f, 0.30f, 0.12f), silver(0.95f, 0.93f, 0.88f);
    for (int c = 0; c < kColumns; ++c) {
        const float r = roughnessOfColumn(c);
        const std::string suffix = " roughness " + std::to_string(r).substr(0, 4);
        parts.addSphere(makeMaterial("dielectric" + suffix, terracotta, 0.0f, r), xOfColumn(c), kDielectricRowY);
        parts.addSphere(makeMaterial("metal" + suffix, silver, 1.0f, r), xOfColumn(c), kMetalRowY);
    }
}

void addColouredSpecularRow(SceneParts& parts) {
    // Metals' F0 is their base colour (measured values for gold and copper).
    const glm::vec3 gold(1.0f, 0.766f, 0.336f), copper(0.955f, 0.638f, 0.538f);
    // A dielectric with a red-tinted F0 via KHR_materials_specular:
    // F0 = min(0.04 * specularColor, 1) * specular = (0.12, 0.03, 0.03) over a dark blue body.
    Material redSpecular = makeMaterial("dielectric red specular roughness 0.1", glm::vec3(0.05f, 0.08f, 0.25f), 0.0f, 0.1f);
    redSpecular.specularColorFactor = glm::vec3(3.0f, 0.75f, 0.75f);
    Material redSpecularRough = redSpecular;
    redSpecularRough.name = "dielectric red specular roughness 0.4";
    redSpecularRough.roughnessFactor = 0.4f;

    const Material row[kColumns] = {
        makeMaterial("gold roughness 0.2", gold, 1.0f, 0.2f),
        makeMaterial("copper roughness 0.2", copper, 1.0f, 0.2f),
        makeMaterial("gold roughness 0.55", gold, 1.0f, 0.55f),
        makeMaterial("copper roughness 0.55", copper, 1.0f, 0.55f),
        redSpecular,
        redSpecularRough,
    };
    for (int c = 0; c < kColumns; ++c) parts.addSphere(row[c], xOfColumn(c), kColouredRowY);
}

constexpr float kGroundSize = 14.0f;  // metres
const char* const kGroundName = "ground, detail normal map";

void addGround(Scene& scene) {
    scene.textures.push_back(makeDetailNormalMap(1024));
    Material ground = makeMaterial(kGroundName, glm::vec3(0.45f, 0.43f, 0.40f), 0.0f, 0.6f);
    ground.normalTexture = static_cast<int>(scene.textures.size()) - 1;
    scene.materials.push_back(ground);
    // 14 m wide: 1.4 cm per texel, so the detail is fine compared with a pixel's footprint.
    Draw draw = appendMesh(scene, makeGroundPlane(kGroundSize, 8));
    draw.material = static_cast<int>(scene.materials.size()) - 1;
    scene.draws.push_back(draw);
}

int addTexture(Scene& scene, Texture t) {
    scene.textures.push_back(std::move(t));
    return static_cast<int>(scene.textures.size()) - 1;
}

// A rectangle w x h centred at `centre`, facing `facing` (+Z, -X, +X or +Y), from the ground-plane
// mesh (its uv spans the rectangle once; `uvRepeat` scales it through the texture's tiling).
void addPanel(Scene& scene, const Draw& plane, int material, glm::vec3 centre, glm::vec2 size, glm::vec3 facing) {
    Draw d = plane;
    d.material = material;
    glm::mat4 m = glm::translate(glm::mat4(1.0f), centre);
    if (facing.z > 0.5f)
        m = glm::rotate(m, glm::radians(90.0f), glm::vec3(1, 0, 0));  // +Y -> +Z
    else if (facing.x < -0.5f)
        m = glm::rotate(m, glm::radians(90.0f), glm::vec3(0, 0, 1));  // +Y -> -X
    else if (facing.x > 0.5f)
        m = glm::rotate(m, glm::radians(-90.0f), glm::vec3(0, 0, 1));  // +Y -> +X
    d.model = glm::scale(m, glm::vec3(size.x, 1.0f, size.y));  // the plane mesh is 1 x 1
    scene.draws.push_back(d);
}

// Everything around the sphere grid; positions are for the grid camera (makeGridCamera), whose
// frame spans about x in [-5.8, 5.8] and y in [-0.9, 5.7] at z = 0 at 16:9.
void addSurroundings(Scene& scene, const Draw& sphere) {
    const Draw plane = appendMesh(scene, makeGroundPlane(1.0f, 1));
    auto material = [&](Material m) {
        scene.materials.push_back(std::move(m));
        return static_cast<int>(scene.materials.size()) - 1;
    };

    // Left: a mosaic wall (chroma changing every few pixels).
    Material mosaic = makeMaterial("mosaic wall", glm::vec3(1.0f), 0.0f, 0.5f);
    mosaic.baseColorTexture = addTexture(scene, makeMosaicAlbedo(128));
    addPanel(scene, plane, material(mosaic), {-4.6f, 1.9f, -0.6f}, {2.8f, 3.8f}, {0, 0, 1});

    // Right: tiles of metal (gold, copper, silver) and paint, each with its own roughness.
    Material tiles = makeMaterial("metal and paint tiles", glm::vec3(1.0f), 1.0f, 1.0f);
    tiles.baseColorTexture = addTexture(scene, makeTileBaseColor(256));
    tiles.metallicRoughnessTexture = addTexture(scene, makeTileMetalRoughness(256));
    tiles.occlusionTexture = tiles.metallicRoughnessTexture;  // packed: R occlusion, G roughness, B metallic
    addPanel(scene, plane, material(tiles), {4.6f, 1.9f, -0.6f}, {2.8f, 3.8f}, {0, 0, 1});

    // An emissive sign above the tiles, and a small glowing sphere in front of the grid.
    Material sign = makeMaterial("emissive sign", glm::vec3(0.02f), 0.0f, 0.9f);
    sign.emissiveFactor = glm::vec3(1.0f);
    sign.emissiveTexture = addTexture(scene, makeEmissiveStripes(256));
    addPanel(scene, plane, material(sign), {4.6f, 4.3f, -0.6f}, {2.8f, 0.9f}, {0, 0, 1});
    Material glow = makeMaterial("emissive sphere", glm::vec3(0.9f, 0.5f, 0.2f), 0.0f, 0.5f);
    glow.emissiveFactor = glm::vec3(1.0f, 0.55f, 0.2f);
    Draw glowDraw = sphere;
    glowDraw.material = material(glow);
    glowDraw.model = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(2.2f, 0.25f, 2.2f)), glm::vec3(0.6f));
    scene.draws.push_back(glowDraw);

    // Front left: a large sphere with the ground's fine normal detail, facing every axis.
    Material detailed = makeMaterial("detail-normal sphere", glm::vec3(0.55f, 0.6f, 0.62f), 0.0f, 0.35f);
    for (const Material& m : scene.materials)  // the ground's detail normal map (addGround)
        if (m.normalTexture != kNoTexture) detailed.normalTexture = m.normalTexture;
    Draw big = sphere;
    big.material = material(detailed);
    big.model = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-2.6f, 0.8f, 2.0f)), glm::vec3(2.0f));
    scene.draws.push_back(big);

    // An alpha-tested wire fence in front of the mosaic wall.
    Material fence = makeMaterial("wire fence (alpha mask)", glm::vec3(1.0f), 1.0f, 0.45f);
    fence.baseColorTexture = addTexture(scene, makeFenceAlbedo(256));
    fence.alphaMask = true;
    fence.alphaCutoff = 0.5f;
    fence.doubleSided = true;
    addPanel(scene, plane, material(fence), {-4.6f, 0.75f, 0.6f}, {2.8f, 1.5f}, {0, 0, 1});

    // Far away: a ground to the horizon just under the near one, and buildings at 100-400 m,
    // each a front, a side and a roof.
    Material far = makeMaterial("far ground", glm::vec3(0.3f, 0.32f, 0.28f), 0.0f, 0.8f);
    addPanel(scene, plane, material(far), {0.0f, -0.02f, -900.0f}, {4000.0f, 1800.0f}, {0, 1, 0});
    Material concrete = makeMaterial("far buildings", glm::vec3(0.6f, 0.58f, 0.55f), 0.0f, 0.7f);
    Material glass = makeMaterial("far buildings, metal cladding", glm::vec3(0.7f, 0.75f, 0.8f), 1.0f, 0.25f);
    const int concreteId = material(concrete), glassId = material(glass);
    struct Building { float x, z, width, height; };
    const Building buildings[] = {{-60.0f, -110.0f, 30.0f, 45.0f}, {-15.0f, -160.0f, 25.0f, 70.0f},
                                  {25.0f, -120.0f, 20.0f, 55.0f},  {70.0f, -250.0f, 40.0f, 110.0f},
                                  {-120.0f, -400.0f, 60.0f, 160.0f}, {150.0f, -380.0f, 50.0f, 130.0f}};
    int i = 0;
    for (const Building& b : buildings) {
        const int id = (i++ % 2) ? glassId : concreteId;
        addPanel(scene, plane, id, {b.x, b.height * 0.5f, b.z + b.width * 0.5f}, {b.width, b.height}, {0, 0, 1});
        addPanel(scene, plane, id, {b.x + (b.x < 0 ? 0.5f : -0.5f) * b.width, b.height * 0.5f, b.z},
                 {b.width, b.height}, {b.x < 0 ? 1.0f : -1.0f, 0, 0});
        addPanel(scene, plane, id, {b.x, b.height, b.z}, {b.width, b.width}, {0, 1, 0});
    }
}

// The ground's occlusion map, baked from every sphere drawn above it (the grid, the glowing one,
// the large one that touches it): each draw of the shared sphere mesh, its centre and radius from
// its model matrix (a translation and a uniform scale).
void addGroundOcclusion(Scene& scene, const Draw& sphere) {
    std::vector<OccludingSphere> spheres;
    for (const Draw& d : scene.draws)
        if (d.firstIndex == sphere.firstIndex && d.vertexOffset == sphere.vertexOffset)
            spheres.push_back({glm::vec3(d.model[3]), kSphereRadius * glm::length(glm::vec3(d.model[0]))});
    // 512 texels over 14 m: 2.7 cm each, finer than the contact shadows' falloff (tens of cm).
    const int texture = addTexture(scene, makeGroundOcclusion(512, kGroundSize, spheres));
    for (Material& m : scene.materials)
        if (m.name == kGroundName) m.occlusionTexture = texture;
}

Camera makeGridCamera() {
    Camera camera;
    // In front of the grid and a little above it, looking slightly down at its middle; the
    // whole grid fits at any aspect ratio from 1:1 to wide screen.
    camera.position = glm::vec3(0.0f, 2.4f, 9.0f);
    camera.target = glm::vec3(0.0f, 1.3f, 0.0f);
    camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    camera.yFovRadians = 0.7f;
    camera.zNear = 0.1f;
    camera.zFar = 60.0f;
    return camera;
}

Light bluePointLight() {
    Light light;
    light.type = LightType::Point;
    light.position = glm::vec3(-2.5f, 3.0f, 2.5f);
    light.color = glm::vec3(0.5f, 0.7f, 1.0f);  // cool, against the warm sun
    light.intensity = 15.0f;                      // candela: ~1.3 lux at the grid's centre
    return light;
}

}  // namespace

Scene makeSphereGridScene() {
    Scene scene;
    scene.source = "built-in sphere grid";
    SceneParts parts{scene, appendMesh(scene, makeUvSphere(kSphereRadius, 64, 32))};
    addRoughnessMetallicGrid(parts);
    addColouredSpecularRow(parts);
    addGround(scene);
    scene.camera = makeGridCamera();
    scene.lights = {defaultSun(), bluePointLight()};
    scene.bounds = worldBounds(scene);
    return scene;
}

Scene makeDefaultScene() {
    Scene scene = makeSphereGridScene();
    scene.source = "built-in default scene";
    const Draw sphere = scene.draws.front();  // the grid's shared sphere mesh
    addSurroundings(scene, sphere);
    addGroundOcclusion(scene, sphere);
    scene.camera.zFar = 2000.0f;  // the far ground and buildings (100-400 m) stay inside
    scene.bounds = worldBounds(scene);
    return scene;
}

}  // namespace gbl
