// The glTF loader on real files: the shared CC0 models against the numbers their READMEs give,
// and Debian's assimp test files, well-formed and broken.
#include "scene_test_support.h"

namespace gbl {
namespace {

using namespace scene_test;

// ---------------------------------------------------------------------------------------------
// Real models (numbers from ../shared/assets/README.md)

TEST(RealModels, WaterBottleMatchesReadme) {
    GBL_REQUIRE_FILE(waterBottle());
    const Scene& s = loadCached(waterBottle());
    expectRenderable(s);
    EXPECT_EQ(s.vertices.size(), 2549u);  // file has NORMAL and TANGENT: nothing is un-shared
    EXPECT_EQ(s.indices.size(), 13530u);
    ASSERT_EQ(s.draws.size(), 1u);
    ASSERT_EQ(s.materials.size(), 1u);
    const Material& m = s.materials[0];
    // One packed ORM image feeds metallic-roughness and occlusion: one linear texture, shared.
    EXPECT_NE(m.metallicRoughnessTexture, kNoTexture);
    EXPECT_EQ(m.metallicRoughnessTexture, m.occlusionTexture);
    ASSERT_EQ(s.textures.size(), 4u);  // base colour, ORM, normal, emissive
    for (const Texture& t : s.textures) {
        EXPECT_EQ(t.width, 2048);
        EXPECT_EQ(t.height, 2048);
    }
    EXPECT_TRUE(s.textures[size_t(m.baseColorTexture)].srgb);
    EXPECT_TRUE(s.textures[size_t(m.emissiveTexture)].srgb);
    EXPECT_FALSE(s.textures[size_t(m.metallicRoughnessTexture)].srgb);
    EXPECT_FALSE(s.textures[size_t(m.normalTexture)].srgb);
    EXPECT_EQ(m.emissiveFactor, glm::vec3(1.0f));
    const glm::vec3 size = s.bounds.max - s.bounds.min;
    EXPECT_NEAR(size.x, 0.109f, 0.003f);
    EXPECT_NEAR(size.y, 0.260f, 0.003f);
    EXPECT_NEAR(size.z, 0.109f, 0.003f);
    EXPECT_FALSE(s.camera.fromFile);
    expectCameraSeesBounds(s.camera, s.bounds, 1.0f);
    expectCameraSeesBounds(s.camera, s.bounds, 16.0f / 9.0f);

    // README: ~42% of ORM texels are metallic (B > 128). Catches channel-order and decode bugs.
    const Texture& orm = s.textures[size_t(m.metallicRoughnessTexture)];
    size_t metallic = 0;
    for (size_t i = 0; i < orm.rgba.size(); i += 4) metallic += orm.rgba[i + 2] > 128 ? 1 : 0;
    EXPECT_NEAR(double(metallic) / double(orm.rgba.size() / 4), 0.42, 0.05);
}

TEST(RealModels, AvocadoMatchesReadmeAndCameraScalesWithItsSize) {
    GBL_REQUIRE_FILE(avocado());
    const Scene& s = loadCached(avocado());
    expectRenderable(s);
    EXPECT_EQ(s.vertices.size(), 406u);
    EXPECT_EQ(s.indices.size(), 2046u);
    ASSERT_EQ(s.textures.size(), 3u);
    for (const Texture& t : s.textures) EXPECT_EQ(t.width * t.height, 2048 * 2048);
    const glm::vec3 size = s.bounds.max - s.bounds.min;
    EXPECT_NEAR(size.x, 0.043f, 0.002f);
    EXPECT_NEAR(size.y, 0.063f, 0.002f);
    EXPECT_NEAR(size.z, 0.028f, 0.002f);
    // A 6 cm object: a generic 0.01..100 camera would waste depth precision; ours hugs it.
    EXPECT_LT(s.camera.zNear, 0.1f);
    EXPECT_LT(s.camera.zFar, 1.0f);
    expectCameraSeesBounds(s.camera, s.bounds, 1.0f);
    expectCameraSeesBounds(s.camera, s.bounds, 16.0f / 9.0f);

    // README: roughness (G) ~220/255 almost everywhere, metallic (B) 0 everywhere. A separate
    // decode of the PNG found B = 0 on all but 33 of 4,194,304 texels (the largest is 45).
    const Texture& rm = s.textures[size_t(s.materials[0].metallicRoughnessTexture)];
    double sumG = 0.0;
    size_t nonZeroB = 0;
    for (size_t i = 0; i < rm.rgba.size(); i += 4) {
        sumG += rm.rgba[i + 1];
        nonZeroB += rm.rgba[i + 2] != 0 ? 1 : 0;
    }
    EXPECT_NEAR(sumG / double(rm.rgba.size() / 4), 220.0, 20.0);
    EXPECT_LT(nonZeroB, 100u);
}

// Generated tangents against the ones the artists' tools wrote. Measured: WaterBottle 97.3%,
// Avocado 99.0% of vertices within 25 degrees; handedness identical on 100% of both.
// Thresholds: 95% within 25 degrees, 99% same handedness.
void expectGeneratedTangentsAgree(const Scene& s) {
    std::vector<Vertex> generated = s.vertices;
    generateTangents(generated, s.indices);
    size_t sameDirection = 0, sameHandedness = 0;
    for (size_t i = 0; i < generated.size(); ++i) {
        const glm::vec3 t(generated[i].tangent);
        EXPECT_TRUE(isUnit(t));
        EXPECT_LT(std::abs(glm::dot(t, generated[i].normal)), 1e-3f);
        sameDirection += glm::dot(t, glm::vec3(s.vertices[i].tangent)) > std::cos(glm::radians(25.0f)) ? 1 : 0;
        sameHandedness += generated[i].tangent.w == s.vertices[i].tangent.w ? 1 : 0;
    }
    EXPECT_GE(double(sameDirection), 0.95 * double(generated.size()));
    EXPECT_GE(double(sameHandedness), 0.99 * double(generated.size()));
}

TEST(Tangents, GeneratedAgreeWithWaterBottleSupplied) {
    GBL_REQUIRE_FILE(waterBottle());
    expectGeneratedTangentsAgree(loadCached(waterBottle()));
}

TEST(Tangents, GeneratedAgreeWithAvocadoSupplied) {
    GBL_REQUIRE_FILE(avocado());
    expectGeneratedTangentsAgree(loadCached(avocado()));
}

// ---------------------------------------------------------------------------------------------
// assimp test models: well-formed

TEST(AssimpModels, TwoCylinderEngineLoadsAllPrimitives) {
    const fs::path path = test::assimpGltf2() / "2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
    GBL_REQUIRE_FILE(path);
    const Scene& s = loadCached(path);
    expectRenderable(s);
    // 29 meshes, 34 primitives, placed by nodes 115 times: one draw per placement, while the
    // geometry is stored once per primitive (84,657 vertices if it were copied per placement).
    EXPECT_EQ(s.draws.size(), 115u);
    EXPECT_EQ(s.vertices.size(), 55843u);
    EXPECT_EQ(s.indices.size(), 227190u);
    EXPECT_GT(s.materials.size(), 30u);
    EXPECT_TRUE(s.camera.fromFile);  // the file has a perspective camera
}

TEST(AssimpModels, BoxTexturedGltfGlbAndEmbeddedGiveIdenticalScenes) {
    const fs::path dir = test::assimpGltf2();
    const fs::path paths[] = {dir / "BoxTextured-glTF/BoxTextured.gltf", dir / "BoxTextured-glTF-Binary/BoxTextured.glb",
                              dir / "BoxTextured-glTF-Embedded/BoxTextured.gltf"};
    for (const fs::path& p : paths) GBL_REQUIRE_FILE(p);
    const Scene& reference = loadCached(paths[0]);
    expectRenderable(reference);
    EXPECT_EQ(reference.vertices.size(), 24u);
    EXPECT_EQ(reference.indices.size(), 36u);
    ASSERT_EQ(reference.textures.size(), 1u);
    EXPECT_TRUE(reference.textures[0].srgb);
    for (const fs::path& p : {paths[1], paths[2]}) {
        SCOPED_TRACE(p.string());
        const Scene& s = loadCached(p);
        ASSERT_EQ(s.vertices.size(), reference.vertices.size());
        EXPECT_EQ(0, std::memcmp(s.vertices.data(), reference.vertices.data(), s.vertices.size() * sizeof(Vertex)));
        EXPECT_EQ(s.indices, reference.indices);
        ASSERT_EQ(s.draws.size(), reference.draws.size());
        EXPECT_EQ(s.draws[0].model, reference.draws[0].model);
        ASSERT_EQ(s.textures.size(), 1u);
        EXPECT_EQ(s.textures[0].rgba, reference.textures[0].rgba);
    }
}

// ---------------------------------------------------------------------------------------------
// assimp test models: broken. Each either throws a UserError naming the file, or loads into a
// renderable scene; the expectation per file is stated (and checked) exactly.

struct BrokenFile {
    const char* path;        // under /usr/share/assimp/models/glTF2
    const char* errorText;   // nullptr: loads safely; else part of the expected UserError
    const char* why;
};

const BrokenFile kBrokenFiles[] = {
    // Wrong JSON types violate the specification; tinygltf drops or defaults them silently, so
    // they are refused, naming the JSON path (scene_gltf_json_check.h).
    {"wrongTypes/badArray.gltf", "meshes[0].primitives: must be an array, not an object", "primitives is an object"},
    {"wrongTypes/badExtension.gltf", "extensions.KHR_texture_transform: must be an object, not a string",
     "an extension that is a string"},
    {"wrongTypes/badNumber.gltf", "normalTexture.scale: must be a number, not a string", "scale \"not a number\""},
    {"wrongTypes/badObject.gltf", "materials[0].pbrMetallicRoughness: must be an object, not an array",
     "pbrMetallicRoughness as array"},
    {"wrongTypes/badString.gltf", "scenes[0].name: must be a string, not an integer", "scene name 42"},
    // -1 is an integer: what is wrong is its sign (the message said "not an integer").
    {"wrongTypes/badUint.gltf", "baseColorTexture.index: -1 is negative; an index must be >= 0", "texture index -1"},
    {"IndexOutOfRange/IndexOutOfRange.gltf", "out of range", "index 255 of 24 vertices"},
    {"IndexOutOfRange/AllIndicesOutOfRange.gltf", "out of range", "every index out of range"},
    {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "non-finite", "Inf positions"},
    {"MissingBin/BoxTextured.gltf", "BoxTextured0.bin", ".bin file absent"},
    {"TestNoRootNode/NoScene.gltf", "no scenes", "no scenes array"},
    {"TestNoRootNode/SceneWithoutNodes.gltf", "no nodes", "empty scene"},
    {"SchemaFailures/sceneWrongType.gltf", "scene: must be an index", "scene is the string \"hello\""},
    {"IncorrectVertexArrays/Cube.gltf", "whole triangles", "35 non-indexed vertices in TRIANGLES mode"},
    {"RecursiveNodes/RecursiveNodes.gltf", "cycle", "node 0 -> 1 -> 0"},
    {"draco/2CylinderEngine.gltf", "uses Draco compression, which gbufferlab does not support; re-export without Draco",
     "KHR_draco_mesh_compression required"},
    {"BoxBadNormals-glTF-Binary/BoxBadNormals.glb", nullptr, "zero/short normals are repaired"},
};

class BrokenFiles : public ::testing::TestWithParam<BrokenFile> {};

TEST_P(BrokenFiles, ThrowUserErrorNamingTheFileOrLoadSafely) {
    const BrokenFile& file = GetParam();
    const fs::path path = test::assimpGltf2() / file.path;
    GBL_REQUIRE_FILE(path);
    SCOPED_TRACE(std::string(file.path) + ": " + file.why);
    if (file.errorText == nullptr) {
        Scene s;
        ASSERT_NO_THROW(s = loadGltfScene(path.string()));
        expectRenderable(s);
        return;
    }
    const std::string message = loadError(path);
    EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
    EXPECT_NE(message.find(file.errorText), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "the error policy wants one line: " << message;
}

std::string brokenFileName(const ::testing::TestParamInfo<BrokenFile>& info) {
    std::string name = info.param.path;
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
}

INSTANTIATE_TEST_SUITE_P(Assimp, BrokenFiles, ::testing::ValuesIn(kBrokenFiles), brokenFileName);

TEST(AssimpModels, BoxBadNormalsAreReplacedByFaceNormals) {
    const fs::path path = test::assimpGltf2() / "BoxBadNormals-glTF-Binary/BoxBadNormals.glb";
    GBL_REQUIRE_FILE(path);
    const Scene s = loadGltfScene(path.string());
    // Every vertex normal must agree with the face it belongs to (the box's faces are flat).
    for (size_t i = 0; i + 2 < s.indices.size(); i += 3) {
        const Vertex& a = s.vertices[s.indices[i]];
        const glm::vec3 face = glm::normalize(glm::cross(s.vertices[s.indices[i + 1]].position - a.position,
                                                         s.vertices[s.indices[i + 2]].position - a.position));
        for (int k = 0; k < 3; ++k) EXPECT_GT(glm::dot(s.vertices[s.indices[i + size_t(k)]].normal, face), 0.99f);
    }
}


}  // namespace
}  // namespace gbl
