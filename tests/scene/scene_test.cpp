// Tests of the glTF loader and its geometry helpers: real models against the numbers their
// READMEs give, the assimp test files (well-formed and broken), and small generated glTF files
// that pin down one rule each (types, bounds, transforms, materials, cameras, lights).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "error.h"
#include "scene.h"
#include "scene_gltf_textures.h"
#include "scene_normals.h"
#include "scene_shapes.h"
#include "tangents.h"
#include "test_paths.h"

namespace gbl {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// ---------------------------------------------------------------------------------------------
// Helpers

// Loading a 2048^2-textured model costs ~0.2 s (much more under ASan); load each file once.
const Scene& loadCached(const fs::path& path) {
    static std::map<std::string, Scene> cache;
    const auto it = cache.find(path.string());
    if (it != cache.end()) return it->second;
    const auto start = std::chrono::steady_clock::now();
    Scene scene = loadGltfScene(path.string());
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::cout << "[ load     ] " << path.filename().string() << ": " << ms << " ms, " << scene.vertices.size()
              << " vertices, " << scene.draws.size() << " draws, " << scene.textures.size() << " textures\n";
    return cache.emplace(path.string(), std::move(scene)).first->second;
}

// The UserError message loading `path` gives; an empty string (and a failure) if none.
std::string loadError(const fs::path& path) {
    try {
        loadGltfScene(path.string());
    } catch (const UserError& e) {
        return e.what();
    }
    ADD_FAILURE() << path << " loaded, but a UserError was expected";
    return {};
}

bool isUnit(const glm::vec3& v, float tolerance = 1e-3f) { return std::abs(glm::length(v) - 1.0f) < tolerance; }

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// What the renderer relies on, for any scene the loader returns.
void expectRenderable(const Scene& s) {
    ASSERT_FALSE(s.draws.empty());
    for (const Draw& d : s.draws) {
        ASSERT_LE(size_t(d.firstIndex) + d.indexCount, s.indices.size());
        EXPECT_EQ(d.indexCount % 3, 0u);
        ASSERT_GE(d.material, 0);
        ASSERT_LT(size_t(d.material), s.materials.size());
        ASSERT_GE(d.vertexOffset, 0);
        for (uint32_t i = 0; i < d.indexCount; ++i)
            ASSERT_LT(size_t(s.indices[d.firstIndex + i]) + size_t(d.vertexOffset), s.vertices.size());
        for (int c = 0; c < 4; ++c) EXPECT_TRUE(isFinite(glm::vec3(d.model[c])));
    }
    for (const Material& m : s.materials) {
        for (int t : {m.baseColorTexture, m.metallicRoughnessTexture, m.normalTexture, m.occlusionTexture,
                      m.emissiveTexture, m.specularTexture, m.specularColorTexture}) {
            EXPECT_GE(t, kNoTexture);
            EXPECT_LT(t, int(s.textures.size()));
        }
    }
    for (const Texture& t : s.textures) {
        EXPECT_GT(t.width, 0);
        EXPECT_EQ(t.rgba.size(), size_t(t.width) * size_t(t.height) * 4);
    }
    size_t bad = 0;
    for (const Vertex& v : s.vertices) {
        const glm::vec3 t(v.tangent);
        const bool ok = isFinite(v.position) && isUnit(v.normal) && isUnit(t) &&
                        std::abs(glm::dot(v.normal, t)) < 1e-3f && std::abs(v.tangent.w) == 1.0f &&
                        std::isfinite(v.uv.x) && std::isfinite(v.uv.y);
        bad += ok ? 0 : 1;
    }
    EXPECT_EQ(bad, 0u) << "vertices with non-unit or non-orthogonal normal/tangent, or non-finite data";
    EXPECT_TRUE(isFinite(s.bounds.min) && isFinite(s.bounds.max));
    EXPECT_TRUE(glm::all(glm::lessThanEqual(s.bounds.min, s.bounds.max)));
    EXPECT_GT(s.camera.zNear, 0.0f);
    EXPECT_GT(s.camera.zFar, s.camera.zNear);
    EXPECT_TRUE(std::isfinite(s.camera.zFar));
    EXPECT_GT(s.camera.yFovRadians, 0.0f);
    ASSERT_FALSE(s.lights.empty());
    for (const Light& l : s.lights) EXPECT_TRUE(isUnit(l.direction));
}

glm::vec4 toClip(const Camera& c, float aspect, const glm::vec3& p) {
    const glm::mat4 proj = glm::perspective(c.yFovRadians, aspect, c.zNear, c.zFar);
    return proj * glm::lookAt(c.position, c.target, c.up) * glm::vec4(p, 1.0f);
}

// Inside the view frustum, depth range [0, 1] (GLM_FORCE_DEPTH_ZERO_TO_ONE).
bool insideFrustum(const glm::vec4& clip) {
    return clip.w > 0.0f && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w && clip.z >= 0.0f &&
           clip.z <= clip.w;
}

void expectCameraSeesBounds(const Camera& camera, const Bounds& b, float aspect) {
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
        EXPECT_TRUE(insideFrustum(toClip(camera, aspect, corner))) << "corner " << i << " aspect " << aspect;
    }
}

fs::path waterBottle() { return test::sharedAssets() / "models/WaterBottle/WaterBottle.gltf"; }
fs::path avocado() { return test::sharedAssets() / "models/Avocado/Avocado.gltf"; }

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
    {"wrongTypes/badUint.gltf", "baseColorTexture.index: must be an index (a whole number >= 0), not an integer",
     "texture index -1"},
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

// ---------------------------------------------------------------------------------------------
// Generated glTF files: one rule each

std::string base64(const std::vector<uint8_t>& data) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < data.size(); i += 3) {
        const uint32_t n = uint32_t(data[i]) << 16 | (i + 1 < data.size() ? uint32_t(data[i + 1]) << 8 : 0) |
                           (i + 2 < data.size() ? data[i + 2] : 0);
        out += digits[n >> 18 & 63];
        out += digits[n >> 12 & 63];
        out += i + 1 < data.size() ? digits[n >> 6 & 63] : '=';
        out += i + 2 < data.size() ? digits[n & 63] : '=';
    }
    return out;
}

fs::path scratchDir() {
    const fs::path dir = fs::path(::testing::TempDir()) / ("gbl_scene_test_" + std::to_string(getpid()));
    fs::create_directories(dir);
    return dir;
}

// A glTF document with one embedded buffer, built one bufferView/accessor at a time.
struct GltfBuilder {
    json doc;
    std::vector<uint8_t> bin;

    GltfBuilder() {
        doc["asset"]["version"] = "2.0";
        doc["scene"] = 0;
        doc["scenes"] = json::array({{{"nodes", {0}}}});
        doc["nodes"] = json::array({{{"mesh", 0}}});
        doc["bufferViews"] = json::array();
        doc["accessors"] = json::array();
    }

    template <typename T>
    int view(const std::vector<T>& data, size_t stride = 0) {
        while (bin.size() % 4) bin.push_back(0);
        json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", data.size() * sizeof(T)}};
        if (stride) v["byteStride"] = stride;
        const auto* bytes = reinterpret_cast<const uint8_t*>(data.data());
        bin.insert(bin.end(), bytes, bytes + data.size() * sizeof(T));
        doc["bufferViews"].push_back(v);
        return int(doc["bufferViews"].size()) - 1;
    }

    int accessor(int bufferView, int componentType, size_t count, const char* type, size_t byteOffset = 0,
                 bool normalized = false) {
        json a = {{"bufferView", bufferView}, {"componentType", componentType}, {"count", count}, {"type", type}};
        if (byteOffset) a["byteOffset"] = byteOffset;
        if (normalized) a["normalized"] = true;
        doc["accessors"].push_back(a);
        return int(doc["accessors"].size()) - 1;
    }

    json& primitive(size_t mesh = 0, size_t prim = 0) { return doc["meshes"][mesh]["primitives"][prim]; }

    fs::path write(const std::string& name) {
        doc["buffers"] = json::array(
            {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
        const fs::path path = scratchDir() / name;
        std::ofstream(path) << doc.dump(1);
        return path;
    }
};

constexpr int kFloat = 5126, kUShort = 5123, kUByte = 5121, kShort = 5122;

// A unit quad in the XY plane facing +Z, indexed, uv with v = 0 at the top (glTF).
GltfBuilder quad() {
    GltfBuilder b;
    const int pos = b.accessor(b.view<float>({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}), kFloat, 4, "VEC3");
    const int nrm = b.accessor(b.view<float>({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}), kFloat, 4, "VEC3");
    const int uv = b.accessor(b.view<float>({0, 1, 1, 1, 1, 0, 0, 0}), kFloat, 4, "VEC2");
    const int idx = b.accessor(b.view<uint16_t>({0, 1, 2, 0, 2, 3}), kUShort, 6, "SCALAR");
    b.doc["meshes"] = json::array(
        {{{"primitives", json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}},
                                       {"indices", idx}}})}}});
    return b;
}

void expectErrorNames(const fs::path& path, std::initializer_list<const char*> parts) {
    const std::string message = loadError(path);
    EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
    for (const char* part : parts) EXPECT_NE(message.find(part), std::string::npos) << "want '" << part << "' in: " << message;
}

// Spec violations tinygltf accepts (issue 13): each is refused with the JSON path and a fix.
TEST(GltfSpec, ViolationsTinygltfAcceptsAreRefused) {
    struct Case {
        const char* name;
        std::function<void(GltfBuilder&)> breakIt;
        const char* expected;
    };
    const std::vector<Case> cases = {
        {"texcoord1.gltf",
         [](GltfBuilder& b) {
             b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", 1}}}}}}});
             b.doc["textures"] = json::array({{{"source", 0}}});
             b.doc["images"] = json::array({{{"uri", "missing.png"}}});
             b.primitive()["material"] = 0;
         },
         "materials[0].pbrMetallicRoughness.baseColorTexture.texCoord: 1 names TEXCOORD_1, which meshes[0].primitives[0]"},
        {"metallic15.gltf",
         [](GltfBuilder& b) { b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"metallicFactor", 1.5}}}}}); },
         "materials[0].pbrMetallicRoughness.metallicFactor: 1.5 is outside [0, 1]"},
        {"basecolor.gltf",
         [](GltfBuilder& b) {
             b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {1, -0.5, 1, 1}}}}}});
         },
         "baseColorFactor[1]: -0.5 is outside [0, 1]"},
        {"emissive.gltf", [](GltfBuilder& b) { b.doc["materials"] = json::array({{{"emissiveFactor", {2, 0, 0}}}}); },
         "materials[0].emissiveFactor[0]: 2 is outside [0, 1]"},
        {"zero_quat.gltf", [](GltfBuilder& b) { b.doc["nodes"][0]["rotation"] = {0, 0, 0, 0}; },
         "nodes[0].rotation: is a zero quaternion"},
        {"ortho0.gltf",
         [](GltfBuilder& b) {
             b.doc["cameras"] = json::array(
                 {{{"type", "orthographic"}, {"orthographic", {{"xmag", 0}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}}});
             b.doc["nodes"][0]["camera"] = 0;
         },
         "cameras[0].orthographic.xmag: is 0"},
        {"version1.gltf", [](GltfBuilder& b) { b.doc["asset"]["version"] = "1.0"; },
         "asset.version: '1.0': gbufferlab reads glTF 2.x only"},
        {"matrix15.gltf", [](GltfBuilder& b) { b.doc["nodes"][0]["matrix"] = std::vector<double>(15, 1.0); },
         "nodes[0].matrix: has 15 elements, the specification says 16"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        GltfBuilder b = quad();
        c.breakIt(b);
        const std::string message = loadError(b.write(c.name));
        EXPECT_NE(message.find(c.name), std::string::npos) << message;
        EXPECT_NE(message.find(c.expected), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    // The edges of the ranges are legal.
    GltfBuilder edge = quad();
    edge.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"metallicFactor", 1.0}, {"roughnessFactor", 0.0}}}}});
    edge.primitive()["material"] = 0;
    EXPECT_NO_THROW(loadGltfScene(edge.write("edges.gltf").string()));
}

TEST(GltfSpec, BrokenJsonIsRephrasedWithLineAndColumn) {
    const fs::path path = scratchDir() / "broken.gltf";
    std::ofstream(path) << "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"scenes\": [ oops ]\n}\n";
    const std::string message = loadError(path);
    EXPECT_EQ(message.rfind(path.string() + ":3:", 0), 0u) << message;
    EXPECT_NE(message.find("not valid JSON"), std::string::npos) << message;
    EXPECT_EQ(message.find("json.exception"), std::string::npos) << message;
}

// nlohmann-json throws out_of_range (not parse_error) for a number beyond a double; "9e390" (5 bytes)
// is the input scripts/fuzz.sh found and minimised: it escaped the loader and ended the process.
TEST(GltfSpec, NumberBeyondADoubleIsRefusedWithItsPlace) {
    struct Case {
        std::string text, place;
    };
    const std::vector<Case> cases = {
        {"9e390", ":1:1:"},
        {"{\n  \"asset\": {\"version\": \"2.0\", \"x\": \"-0.9e390\"},\n  \"scenes\": [ -0.9e390 ]\n}\n", ":3:15:"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.text);
        const fs::path path = scratchDir() / "overflow.gltf";
        std::ofstream(path) << c.text;
        const std::string message = loadError(path);
        EXPECT_EQ(message.rfind(path.string() + c.place, 0), 0u) << message;
        EXPECT_NE(message.find("not valid JSON: number overflow"), std::string::npos) << message;
        EXPECT_EQ(message.find("json.exception"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

// Buffer and image URIs: only regular files, only inside the scene's folder unless allowed.
TEST(GltfFiles, UrisOutsideTheSceneFolderAreRefusedUnlessAllowed) {
    const fs::path root = scratchDir() / "confined";
    fs::create_directories(root / "scene");
    GltfBuilder b = quad();
    const fs::path inside = b.write("unused.gltf");  // fills b.bin and the buffer entry
    std::ofstream(root / "outside.bin", std::ios::binary).write(reinterpret_cast<const char*>(b.bin.data()),
                                                                  std::streamsize(b.bin.size()));
    std::ofstream(root / "scene" / "inside.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(b.bin.data()), std::streamsize(b.bin.size()));
    auto sceneWithUri = [&](const std::string& name, const std::string& uri) {
        json doc = b.doc;
        doc["buffers"][0]["uri"] = uri;
        const fs::path path = root / "scene" / name;
        std::ofstream(path) << doc.dump(1);
        return path.string();
    };
    EXPECT_NO_THROW(loadGltfScene(sceneWithUri("inside.gltf", "inside.bin")));
    for (const std::string& uri : {std::string("../outside.bin"), (root / "outside.bin").string(),
                                   std::string("./../scene/../outside.bin")}) {
        SCOPED_TRACE(uri);
        const std::string path = sceneWithUri("outside.gltf", uri);
        std::string message;
        try {
            loadGltfScene(path);
        } catch (const UserError& e) {
            message = e.what();
        }
        EXPECT_NE(message.find("outside the scene's folder"), std::string::npos) << message;
        EXPECT_NE(message.find("--allow-outside-scene"), std::string::npos) << message;
        const Scene s = loadGltfScene(path, GltfLoadOptions{true});
        EXPECT_EQ(s.vertices.size(), 4u);
    }
    // A FIFO as the buffer: refused without reading (a read would block forever).
    ASSERT_EQ(::mkfifo((root / "scene" / "fifo.bin").c_str(), 0600), 0);
    const std::string fifo = sceneWithUri("fifo.gltf", "fifo.bin");
    std::string message;
    try {
        loadGltfScene(fifo);
    } catch (const UserError& e) {
        message = e.what();
    }
    EXPECT_NE(message.find("is not a regular file"), std::string::npos) << message;
    fs::remove_all(root);
}

TEST(GltfValidation, QuadLoadsWithExpectedData) {
    GltfBuilder b = quad();
    const Scene s = loadGltfScene(b.write("quad.gltf").string());
    expectRenderable(s);
    ASSERT_EQ(s.vertices.size(), 4u);
    EXPECT_EQ(s.vertices[2].position, glm::vec3(1, 1, 0));
    EXPECT_EQ(s.vertices[2].uv, glm::vec2(1, 0));
    EXPECT_EQ(s.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    ASSERT_EQ(s.materials.size(), 1u);  // glTF's default material, added for the primitive
    EXPECT_EQ(s.materials[0].metallicFactor, 1.0f);
    EXPECT_EQ(s.materials[0].roughnessFactor, 1.0f);
    ASSERT_EQ(s.lights.size(), 1u);  // defaultSun
    EXPECT_EQ(s.lights[0].type, LightType::Directional);
}

TEST(GltfValidation, PositionOfWrongTypeNamesMeshPrimitiveAndAccessor) {
    GltfBuilder b = quad();
    b.primitive()["attributes"]["POSITION"] = b.accessor(0, kFloat, 4, "VEC2");
    expectErrorNames(b.write("position_vec2.gltf"), {"mesh 0", "primitive 0", "POSITION accessor 4", "VEC2", "VEC3"});
}

TEST(GltfValidation, AccessorPastTheEndOfItsBufferViewIsRejected) {
    GltfBuilder b = quad();
    b.doc["accessors"][0]["count"] = 5;  // 60 bytes of positions in a 48-byte view
    b.doc["accessors"][1]["count"] = 5;
    b.doc["accessors"][2]["count"] = 5;
    expectErrorNames(b.write("accessor_past_end.gltf"), {"mesh 0", "primitive 0", "POSITION accessor 0", "past the end"});
}

TEST(GltfValidation, BufferViewPastTheEndOfTheBufferIsRejected) {
    GltfBuilder b = quad();
    b.doc["bufferViews"][3]["byteLength"] = 4000;
    const std::string message = loadError(b.write("view_past_end.gltf"));
    EXPECT_NE(message.find("view_past_end.gltf"), std::string::npos) << message;
}

TEST(GltfValidation, IndexOutOfRangeNamesTheIndicesAccessor) {
    GltfBuilder b = quad();
    b.doc["accessors"][3]["bufferView"] = b.view<uint16_t>({0, 1, 2, 0, 2, 4});
    expectErrorNames(b.write("index_4_of_4.gltf"), {"mesh 0", "primitive 0", "indices accessor 3", "out of range"});
}

TEST(GltfValidation, NanPositionIsAnError) {
    GltfBuilder b = quad();
    b.doc["accessors"][0]["bufferView"] = b.view<float>({0, 0, 0, 1, 0, 0, 1, NAN, 0, 0, 1, 0});
    expectErrorNames(b.write("nan_position.gltf"), {"POSITION accessor 0", "vertex 2", "NaN"});
}

TEST(GltfValidation, IntegerPositionsNeedKhrMeshQuantization) {
    GltfBuilder b = quad();
    b.primitive()["attributes"]["POSITION"] = b.accessor(b.view<int16_t>({0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0}), kShort, 4, "VEC3");
    expectErrorNames(b.write("short_positions.gltf"), {"POSITION accessor", "short", "KHR_mesh_quantization"});
    b.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
    const Scene s = loadGltfScene(b.write("short_positions_quantized.gltf").string());
    EXPECT_EQ(s.vertices[2].position, glm::vec3(2, 2, 0));  // not normalized: integer values as-is
}

TEST(GltfValidation, UnsupportedRequiredExtensionIsRefused) {
    GltfBuilder b = quad();
    b.doc["extensionsRequired"] = {"KHR_texture_basisu"};
    b.doc["extensionsUsed"] = {"KHR_texture_basisu"};
    expectErrorNames(b.write("basisu.gltf"), {"KHR_texture_basisu", "not support"});
}

TEST(GltfValidation, MissingOrGarbageFileIsAUserError) {
    expectErrorNames(scratchDir() / "does_not_exist.gltf", {"not found"});
    const fs::path garbage = scratchDir() / "garbage.gltf";
    std::ofstream(garbage) << "{ this is not json";
    expectErrorNames(garbage, {});
    const fs::path badGlb = scratchDir() / "truncated.glb";
    std::ofstream(badGlb, std::ios::binary) << "glTF\x02";
    expectErrorNames(badGlb, {});
}

TEST(GltfGeometry, InterleavedStridedNormalizedAttributesAreDecoded) {
    // Per vertex: float position[3], normalized unsigned byte uv[2], 2 bytes padding: stride 16.
    struct Packed {
        float p[3];
        uint8_t uv[2], pad[2];
    };
    const std::vector<Packed> data = {
        {{0, 0, 0}, {0, 255}, {}}, {{1, 0, 0}, {255, 255}, {}}, {{1, 1, 0}, {255, 0}, {}}, {{0, 1, 0}, {51, 0}, {}}};
    GltfBuilder b;
    const int v = b.view(data, sizeof(Packed));
    const int pos = b.accessor(v, kFloat, 4, "VEC3");
    const int uv = b.accessor(v, kUByte, 4, "VEC2", 12, true);
    const int idx = b.accessor(b.view<uint8_t>({0, 1, 2, 0, 2, 3}), kUByte, 6, "SCALAR");
    b.doc["meshes"] = json::array(
        {{{"primitives", json::array({{{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}, {"indices", idx}}})}}});
    const Scene s = loadGltfScene(b.write("interleaved.gltf").string());
    expectRenderable(s);
    // No NORMAL: flat shading needs one vertex per triangle corner, so 6 (0 1 2, 0 2 3).
    ASSERT_EQ(s.vertices.size(), 6u);
    EXPECT_EQ(s.vertices[4].position, glm::vec3(1, 1, 0));
    EXPECT_EQ(s.vertices[5].position, glm::vec3(0, 1, 0));
    EXPECT_EQ(s.vertices[1].uv, glm::vec2(1, 1));
    EXPECT_FLOAT_EQ(s.vertices[5].uv.x, 0.2f);  // 51 / 255
    EXPECT_EQ(s.vertices[5].uv.y, 0.0f);
    for (const Vertex& vertex : s.vertices) EXPECT_EQ(vertex.normal, glm::vec3(0, 0, 1));
}

TEST(GltfGeometry, NonIndexedWithoutNormalsGetsFlatFaceNormals) {
    // Two triangles folded 90 degrees along their shared edge (x = 0): faces +Z and +X.
    GltfBuilder b;
    const int pos = b.accessor(b.view<float>({0, 0, 0, 0, 1, 0, -1, 0, 0,   // in the z = 0 plane, facing +Z
                                              0, 0, 0, 0, 0, -1, 0, 1, 0}),  // in the x = 0 plane, facing +X
                               kFloat, 6, "VEC3");
    b.doc["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}}})}}});
    const Scene s = loadGltfScene(b.write("folded.gltf").string());
    expectRenderable(s);
    ASSERT_EQ(s.vertices.size(), 6u);
    EXPECT_EQ(s.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(glm::dot(s.vertices[size_t(i)].normal, glm::vec3(0, 0, 1)), 1.0f, 1e-6f);
    for (int i = 3; i < 6; ++i) EXPECT_NEAR(glm::dot(s.vertices[size_t(i)].normal, glm::vec3(1, 0, 0)), 1.0f, 1e-6f);
}

TEST(GltfGeometry, SparseAccessorSubstitutesValues) {
    GltfBuilder b = quad();
    // Move vertex 2 from (1, 1, 0) to (3, 4, 0) through a sparse substitution.
    b.doc["accessors"][0]["sparse"] = {{"count", 1},
                                       {"indices", {{"bufferView", b.view<uint16_t>({2, 0})}, {"componentType", kUShort}}},
                                       {"values", {{"bufferView", b.view<float>({3, 4, 0})}}}};
    const Scene s = loadGltfScene(b.write("sparse.gltf").string());
    EXPECT_EQ(s.vertices[2].position, glm::vec3(3, 4, 0));
    EXPECT_EQ(s.vertices[1].position, glm::vec3(1, 0, 0));
    EXPECT_FLOAT_EQ(s.bounds.max.x, 3.0f);
}

TEST(GltfGeometry, LinesAreSkippedAndTrianglesKept) {
    GltfBuilder b = quad();
    json lines = b.primitive();
    lines["mode"] = 1;
    b.doc["meshes"][0]["primitives"].push_back(lines);
    const Scene s = loadGltfScene(b.write("lines_and_triangles.gltf").string());
    EXPECT_EQ(s.draws.size(), 1u);

    b.doc["meshes"][0]["primitives"].erase(0);  // lines only: nothing drawable
    expectErrorNames(b.write("lines_only.gltf"), {"no triangles"});
}

TEST(GltfNodes, TrsHierarchyComposesParentThenChildTranslateRotateScale) {
    GltfBuilder b = quad();
    const float h = std::sqrt(0.5f);
    b.doc["nodes"] = json::array({{{"translation", {10, 0, 0}}, {"children", {1}}},
                                  {{"mesh", 0}, {"rotation", {0, h, 0, h}}, {"scale", {2, 2, 2}}}});  // 90 deg about +Y
    const Scene s = loadGltfScene(b.write("trs.gltf").string());
    ASSERT_EQ(s.draws.size(), 1u);
    const glm::mat4 expected = glm::translate(glm::mat4(1), glm::vec3(10, 0, 0)) *
                               glm::rotate(glm::mat4(1), glm::radians(90.0f), glm::vec3(0, 1, 0)) *
                               glm::scale(glm::mat4(1), glm::vec3(2));
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(s.draws[0].model[c][r], expected[c][r], 1e-5f);
    // The quad (x, y in 0..1 at z = 0) scaled by 2, turned so +X goes to -Z, moved by +10 in x.
    EXPECT_NEAR(s.bounds.min.x, 10.0f, 1e-5f);
    EXPECT_NEAR(s.bounds.max.x, 10.0f, 1e-5f);
    EXPECT_NEAR(s.bounds.max.y, 2.0f, 1e-5f);
    EXPECT_NEAR(s.bounds.min.z, -2.0f, 1e-5f);
    EXPECT_NEAR(s.bounds.max.z, 0.0f, 1e-5f);
}

TEST(GltfNodes, MatrixIsColumnMajor) {
    GltfBuilder b = quad();
    b.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1};
    const Scene s = loadGltfScene(b.write("matrix.gltf").string());
    EXPECT_EQ(s.draws[0].model[3], glm::vec4(5, 6, 7, 1));
    EXPECT_EQ(s.bounds.min, glm::vec3(5, 6, 7));
}

TEST(GltfNodes, NodeWithTwoParentsIsRejected) {
    GltfBuilder b = quad();
    b.doc["nodes"] = json::array({{{"children", {2}}}, {{"children", {2}}}, {{"mesh", 0}}});
    b.doc["scenes"][0]["nodes"] = {0, 1};
    expectErrorNames(b.write("two_parents.gltf"), {"node 2", "second time", "tree"});
}

TEST(GltfNodes, MirroredInstanceKeepsFrontFacesAndTangentHandedness) {
    GltfBuilder b = quad();
    b.doc["nodes"] = json::array({{{"mesh", 0}}, {{"mesh", 0}, {"scale", {-1, 1, 1}}}});
    b.doc["scenes"][0]["nodes"] = {0, 1};
    const Scene s = loadGltfScene(b.write("mirrored.gltf").string());
    ASSERT_EQ(s.draws.size(), 2u);
    for (const Draw& d : s.draws) {
        const glm::mat3 m(d.model);
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(m));
        const auto vertex = [&](size_t k) { return s.vertices[s.indices[d.firstIndex + k] + uint32_t(d.vertexOffset)]; };
        // Counter-clockwise in world space must still face along the world normal.
        const glm::vec3 p0 = m * vertex(0).position, p1 = m * vertex(1).position, p2 = m * vertex(2).position;
        const glm::vec3 worldNormal = glm::normalize(normalMatrix * vertex(0).normal);
        EXPECT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), worldNormal), 0.0f);
        // The shader's bitangent, cross(N, T) * w in world space, must still point where the
        // mesh's bitangent (decreasing v: +Y here) is mapped to.
        const glm::vec3 worldTangent = glm::normalize(m * glm::vec3(vertex(0).tangent));
        const glm::vec3 bitangent = glm::cross(worldNormal, worldTangent) * vertex(0).tangent.w;
        EXPECT_GT(glm::dot(bitangent, m * glm::vec3(0, 1, 0)), 0.99f);
    }
}

TEST(GltfCameraLights, CameraAndPunctualLightsComeFromTheirNodes) {
    GltfBuilder b = quad();
    const float h = std::sqrt(0.5f);
    b.doc["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.05}}}}});
    b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array(
        {{{"type", "directional"}, {"color", {1, 0.5, 0.25}}, {"intensity", 3}},
         {{"type", "point"}, {"intensity", 40}, {"range", 12}},
         {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}}});
    b.doc["nodes"] = json::array({{{"mesh", 0}},
                                  {{"camera", 0}, {"translation", {0.5, 0.5, 5}}},
                                  {{"rotation", {-h, 0, 0, h}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
                                  {{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}},
                                  {{"translation", {0, 0, 4}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}}});
    b.doc["scenes"][0]["nodes"] = {0, 1, 2, 3, 4};
    const Scene s = loadGltfScene(b.write("camera_lights.gltf").string());
    expectRenderable(s);
    EXPECT_TRUE(s.camera.fromFile);
    EXPECT_EQ(s.camera.position, glm::vec3(0.5f, 0.5f, 5));
    EXPECT_NEAR(glm::dot(glm::normalize(s.camera.target - s.camera.position), glm::vec3(0, 0, -1)), 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(s.camera.yFovRadians, 0.5f);
    EXPECT_FLOAT_EQ(s.camera.zNear, 0.05f);
    EXPECT_GT(s.camera.zFar, 5.0f);  // no zfar in the file: finite, beyond the quad
    EXPECT_TRUE(std::isfinite(s.camera.zFar));
    expectCameraSeesBounds(s.camera, s.bounds, 1.0f);

    ASSERT_EQ(s.lights.size(), 3u);  // the file's; no default sun
    EXPECT_EQ(s.lights[0].type, LightType::Directional);
    EXPECT_NEAR(s.lights[0].direction.y, -1.0f, 1e-5f);  // -Z turned -90 degrees about X: down
    EXPECT_EQ(s.lights[0].color, glm::vec3(1, 0.5f, 0.25f));
    EXPECT_EQ(s.lights[0].intensity, 3.0f);
    EXPECT_EQ(s.lights[1].type, LightType::Point);
    EXPECT_EQ(s.lights[1].position, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.lights[1].range, 12.0f);
    EXPECT_EQ(s.lights[2].type, LightType::Spot);
    EXPECT_EQ(s.lights[2].direction, glm::vec3(0, 0, -1));
    EXPECT_FLOAT_EQ(s.lights[2].innerConeAngle, 0.2f);
    EXPECT_FLOAT_EQ(s.lights[2].outerConeAngle, 0.5f);
}

// Copies a small real PNG next to the generated file; empty path when the source is absent.
fs::path scratchPng() {
    const fs::path source = test::assimpGltf2() / "BoxTextured-glTF/CesiumLogoFlat.png";
    if (!fs::exists(source)) return {};
    const fs::path target = scratchDir() / "logo.png";
    fs::copy_file(source, target, fs::copy_options::overwrite_existing);
    return target;
}

TEST(GltfMaterials, FactorsTexturesSpecularExtensionAndSrgbDuplication) {
    const fs::path png = scratchPng();
    if (png.empty()) GTEST_SKIP() << "missing CesiumLogoFlat.png from assimp-testmodels";
    GltfBuilder b = quad();
    b.doc["images"] = json::array({{{"uri", "logo.png"}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    b.doc["extensionsUsed"] = {"KHR_materials_specular"};
    b.doc["materials"] = json::array({{
        {"name", "everything"},
        {"pbrMetallicRoughness",
         {{"baseColorFactor", {0.5, 0.25, 1, 1}}, {"metallicFactor", 0.25}, {"roughnessFactor", 0.75},
          {"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 0}}}}},
        {"normalTexture", {{"index", 0}, {"scale", 0.8}}},
        {"occlusionTexture", {{"index", 0}, {"strength", 0.6}}},
        {"emissiveTexture", {{"index", 0}}},
        {"emissiveFactor", {0.1, 0.2, 0.3}},
        {"doubleSided", true},
        {"extensions",
         {{"KHR_materials_specular",
           {{"specularFactor", 0.5}, {"specularColorFactor", {2, 1, 0.5}}, {"specularTexture", {{"index", 0}}},
            {"specularColorTexture", {{"index", 0}}}}}}},
    }});
    b.primitive()["material"] = 0;
    json plain = b.primitive();  // a second primitive without a material gets the default one
    plain.erase("material");
    b.doc["meshes"][0]["primitives"].push_back(plain);
    const Scene s = loadGltfScene(b.write("materials.gltf").string());
    expectRenderable(s);

    ASSERT_EQ(s.materials.size(), 2u);
    const Material& m = s.materials[0];
    EXPECT_EQ(m.baseColorFactor, glm::vec4(0.5f, 0.25f, 1, 1));
    EXPECT_EQ(m.metallicFactor, 0.25f);
    EXPECT_EQ(m.roughnessFactor, 0.75f);
    EXPECT_FLOAT_EQ(m.normalScale, 0.8f);
    EXPECT_FLOAT_EQ(m.occlusionStrength, 0.6f);
    EXPECT_EQ(m.emissiveFactor, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_TRUE(m.doubleSided);
    EXPECT_EQ(m.specularFactor, 0.5f);
    EXPECT_EQ(m.specularColorFactor, glm::vec3(2, 1, 0.5f));  // > 1 is legal in the extension

    // One image, read as colour and as data: two textures with equal pixels and each flag.
    ASSERT_EQ(s.textures.size(), 2u);
    EXPECT_EQ(s.textures[0].rgba, s.textures[1].rgba);
    EXPECT_NE(s.textures[0].srgb, s.textures[1].srgb);
    auto srgb = [&](int t) { return s.textures[size_t(t)].srgb; };
    EXPECT_TRUE(srgb(m.baseColorTexture));
    EXPECT_TRUE(srgb(m.emissiveTexture));
    EXPECT_TRUE(srgb(m.specularColorTexture));
    EXPECT_FALSE(srgb(m.metallicRoughnessTexture));
    EXPECT_FALSE(srgb(m.normalTexture));
    EXPECT_FALSE(srgb(m.occlusionTexture));
    EXPECT_FALSE(srgb(m.specularTexture));
    EXPECT_EQ(m.baseColorTexture, m.emissiveTexture);
    EXPECT_EQ(m.normalTexture, m.metallicRoughnessTexture);

    ASSERT_EQ(s.draws.size(), 2u);
    EXPECT_EQ(s.draws[1].material, 1);
    EXPECT_EQ(s.materials[1].metallicFactor, 1.0f);  // glTF default material
    EXPECT_EQ(s.materials[1].baseColorTexture, kNoTexture);
}

TEST(GltfMaterials, MissingImageFileIsAnErrorNamingTheImage) {
    GltfBuilder b = quad();
    b.doc["images"] = json::array({{{"uri", "not_there.png"}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    b.primitive()["material"] = 0;
    expectErrorNames(b.write("missing_image.gltf"), {"image 0", "not_there.png"});
}

TEST(GltfMaterials, ImagesOfAnyChannelCountAndDepthBecomeRgba8) {
    tinygltf::Model model;
    auto addImage = [&](int component, int bits, std::vector<uint8_t> bytes) {
        tinygltf::Image image;
        image.width = 1;
        image.height = 1;
        image.component = component;
        image.bits = bits;
        image.image = std::move(bytes);
        model.images.push_back(image);
    };
    addImage(1, 8, {100});
    addImage(2, 8, {100, 50});
    addImage(3, 8, {10, 20, 30});
    const uint16_t rgba16[4] = {65535, 32896, 257, 0};  // 32896 = 128.5 * 256: rounds to 128
    addImage(4, 16, std::vector<uint8_t>(reinterpret_cast<const uint8_t*>(rgba16), reinterpret_cast<const uint8_t*>(rgba16) + 8));
    addImage(3, 8, {1, 2});  // too few bytes
    const GltfContext ctx{"images.gltf", model};
    EXPECT_EQ(convertImageToRgba8(ctx, 0, false).rgba, (std::vector<uint8_t>{100, 100, 100, 255}));
    EXPECT_EQ(convertImageToRgba8(ctx, 1, false).rgba, (std::vector<uint8_t>{100, 100, 100, 50}));
    EXPECT_EQ(convertImageToRgba8(ctx, 2, true).rgba, (std::vector<uint8_t>{10, 20, 30, 255}));
    EXPECT_TRUE(convertImageToRgba8(ctx, 2, true).srgb);
    EXPECT_EQ(convertImageToRgba8(ctx, 3, false).rgba, (std::vector<uint8_t>{255, 128, 1, 0}));
    EXPECT_THROW(convertImageToRgba8(ctx, 4, false), UserError);
}

// ---------------------------------------------------------------------------------------------
// Tangent and normal generation

// A unit quad facing +Z with glTF uvs (v = 0 at the top), optionally mirrored in u.
std::vector<Vertex> uvQuad(bool mirrorU) {
    std::vector<Vertex> v(4);
    const glm::vec3 p[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const glm::vec2 uv[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    for (int i = 0; i < 4; ++i) {
        v[size_t(i)].position = p[i];
        v[size_t(i)].normal = glm::vec3(0, 0, 1);
        v[size_t(i)].uv = mirrorU ? glm::vec2(1.0f - uv[i].x, uv[i].y) : uv[i];
    }
    return v;
}

const std::vector<uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

TEST(Tangents, TangentFollowsUAndBitangentPointsUpTheImage) {
    std::vector<Vertex> v = uvQuad(false);
    generateTangents(v, kQuadIndices);
    for (const Vertex& x : v) {
        EXPECT_NEAR(glm::dot(glm::vec3(x.tangent), glm::vec3(1, 0, 0)), 1.0f, 1e-6f);
        EXPECT_EQ(x.tangent.w, 1.0f);  // B = cross(+Z, +X) = +Y: decreasing v, up the image
    }
    std::vector<Vertex> mirrored = uvQuad(true);
    generateTangents(mirrored, kQuadIndices);
    for (const Vertex& x : mirrored) {
        EXPECT_NEAR(glm::dot(glm::vec3(x.tangent), glm::vec3(-1, 0, 0)), 1.0f, 1e-6f);
        EXPECT_EQ(x.tangent.w, -1.0f);  // cross(+Z, -X) = -Y, but up the image is still +Y
    }
}

TEST(Tangents, GeneratedMatchAnalyticSphereTangents) {
    const ShapeMesh sphere = makeUvSphere(1.0f, 64, 32);
    std::vector<Vertex> generated = sphere.vertices;
    generateTangents(generated, sphere.indices);
    for (size_t i = 0; i < generated.size(); ++i) {
        if (std::abs(generated[i].normal.y) > 0.999f) continue;  // poles: u direction is undefined
        EXPECT_GT(glm::dot(glm::vec3(generated[i].tangent), glm::vec3(sphere.vertices[i].tangent)), 0.99f) << i;
        EXPECT_EQ(generated[i].tangent.w, sphere.vertices[i].tangent.w) << i;
    }
}

TEST(Tangents, DegenerateUvsGiveAUnitPerpendicularTangent) {
    std::vector<Vertex> v = uvQuad(false);
    for (Vertex& x : v) {
        x.uv = glm::vec2(0.5f);
        x.normal = glm::normalize(glm::vec3(1, 2, 3));
    }
    generateTangents(v, kQuadIndices);
    for (const Vertex& x : v) {
        EXPECT_TRUE(isUnit(glm::vec3(x.tangent), 1e-5f));
        EXPECT_LT(std::abs(glm::dot(glm::vec3(x.tangent), x.normal)), 1e-5f);
        EXPECT_EQ(std::abs(x.tangent.w), 1.0f);
    }
}

TEST(Tangents, SuppliedTangentIsOrthonormalizedOrRejected) {
    glm::vec4 t(2, 0, 1, 0.3f);  // not unit, not orthogonal to +Z, w not +-1
    ASSERT_TRUE(orthonormalizeTangent(glm::vec3(0, 0, 1), t));
    EXPECT_EQ(t, glm::vec4(1, 0, 0, 1));
    glm::vec4 parallel(0, 0, 5, 1);
    EXPECT_FALSE(orthonormalizeTangent(glm::vec3(0, 0, 1), parallel));
    glm::vec4 nan(NAN, 0, 0, 1);
    EXPECT_FALSE(orthonormalizeTangent(glm::vec3(0, 0, 1), nan));
}

TEST(Normals, ZeroAndNanNormalsAreReplacedByTheFaceNormal) {
    std::vector<Vertex> v = uvQuad(false);
    v[0].normal = glm::vec3(0);
    v[1].normal = glm::vec3(NAN);
    v[2].normal = glm::vec3(0, 0, 7);  // usable, just not unit
    EXPECT_EQ(repairNormals(v, kQuadIndices), 2u);
    for (const Vertex& x : v) EXPECT_EQ(x.normal, glm::vec3(0, 0, 1));
}

// ---------------------------------------------------------------------------------------------
// Framing and bounds

TEST(Camera, FrameBoundsSeesEveryCornerAndScalesNearFarWithTheScene) {
    for (float scale : {0.05f, 1.0f, 500.0f}) {
        const Bounds b{glm::vec3(-1, 0, -0.5f) * scale + glm::vec3(3), glm::vec3(1, 2, 0.5f) * scale + glm::vec3(3)};
        for (float aspect : {0.5f, 1.0f, 16.0f / 9.0f}) {
            SCOPED_TRACE("scale " + std::to_string(scale) + " aspect " + std::to_string(aspect));
            const Camera c = frameBounds(b, aspect);
            expectCameraSeesBounds(c, b, aspect);
            EXPECT_FALSE(c.fromFile);
            EXPECT_LT(c.zFar / scale, 40.0f);   // proportional to the scene's size
            EXPECT_GT(c.zNear / scale, 0.05f);  // not a fixed tiny near plane
        }
    }
    const Camera point = frameBounds(Bounds{glm::vec3(1), glm::vec3(1)}, 1.0f);  // degenerate: still usable
    EXPECT_GT(point.zNear, 0.0f);
    EXPECT_GT(point.zFar, point.zNear);
}

TEST(SceneBounds, WorldBoundsAppliesEachDrawsModelMatrix) {
    Scene s;
    const ShapeMesh sphere = makeUvSphere(1.0f, 16, 8);
    s.vertices = sphere.vertices;
    s.indices = sphere.indices;
    Draw a;
    a.indexCount = uint32_t(s.indices.size());
    Draw b = a;
    b.model = glm::translate(glm::mat4(1), glm::vec3(10, 0, 0)) * glm::scale(glm::mat4(1), glm::vec3(2));
    s.draws = {a, b};
    const Bounds bounds = worldBounds(s);
    EXPECT_NEAR(bounds.min.x, -1.0f, 1e-5f);
    EXPECT_NEAR(bounds.max.x, 12.0f, 1e-5f);
    EXPECT_NEAR(bounds.max.y, 2.0f, 1e-5f);
    EXPECT_EQ(worldBounds(Scene{}).min, glm::vec3(0));
}


}  // namespace
}  // namespace gbl
