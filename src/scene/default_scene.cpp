// The built-in scene: needs no file, and covers what a G-buffer layout can get wrong —
// roughness from mirror to fully rough, dielectric vs metal, coloured F0 (metals and a
// KHR_materials_specular dielectric) and a ground with texel-scale normal detail.
#include <glm/gtc/matrix_transform.hpp>

#include "scene.h"
#include "scene_detail_normal_map.h"
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

void addGround(Scene& scene) {
    scene.textures.push_back(makeDetailNormalMap(1024));
    Material ground = makeMaterial("ground, detail normal map", glm::vec3(0.45f, 0.43f, 0.40f), 0.0f, 0.6f);
    ground.normalTexture = static_cast<int>(scene.textures.size()) - 1;
    scene.materials.push_back(ground);
    // 14 m wide: 1.4 cm per texel, so the detail is fine compared with a pixel's footprint.
    Draw draw = appendMesh(scene, makeGroundPlane(14.0f, 8));
    draw.material = static_cast<int>(scene.materials.size()) - 1;
    scene.draws.push_back(draw);
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

Scene makeDefaultScene() {
    Scene scene;
    scene.source = "built-in default scene";
    SceneParts parts{scene, appendMesh(scene, makeUvSphere(kSphereRadius, 64, 32))};
    addRoughnessMetallicGrid(parts);
    addColouredSpecularRow(parts);
    addGround(scene);
    scene.camera = makeGridCamera();
    scene.lights = {defaultSun(), bluePointLight()};
    scene.bounds = worldBounds(scene);
    return scene;
}

}  // namespace gbl
