// The glTF loader on small generated files, each pinning down one rule: what the spec forbids,
// where files may live, types and bounds, geometry, node transforms, cameras, lights, materials.
#include <sys/resource.h>

#include "hostile_images.h"
#include "scene_test_support.h"

namespace gbl {
namespace {

using namespace scene_test;

// The memory budget is read once per process: a fixed one here, so that the refusal below does
// not depend on the machine's memory.
const bool kBudgetSet = ::setenv("GBL_MEMORY_BUDGET", "1G", 1) == 0;

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

// KHR_materials_clearcoat, _sheen, _anisotropy, _ior, _emissive_strength and KHR_texture_transform,
// read as their READMEs define them: factors, textures (sRGB only for the sheen colour), the
// texture transform's offset, rotation, scale and texCoord override (TEXCOORD_1 read into uv1),
// the layers a material has, and transmission masking the material as forward.
TEST(GltfMaterials, LayerExtensionsAndTextureTransformAreRead) {
    const fs::path png = scratchPng();
    if (png.empty()) GTEST_SKIP() << "missing CesiumLogoFlat.png from assimp-testmodels";
    GltfBuilder b = quad();
    const int uv1 = b.accessor(b.view<float>({0.5f, 0.5f, 1, 0.5f, 1, 1, 0.5f, 1}), kFloat, 4, "VEC2");
    b.primitive()["attributes"]["TEXCOORD_1"] = uv1;
    b.doc["images"] = json::array({{{"uri", "logo.png"}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    b.doc["extensionsUsed"] = {"KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_anisotropy",
                               "KHR_materials_ior", "KHR_materials_emissive_strength", "KHR_texture_transform",
                               "KHR_materials_transmission"};
    b.doc["extensionsRequired"] = {"KHR_texture_transform", "KHR_materials_clearcoat"};
    const json transform = {{"KHR_texture_transform", {{"offset", {0.25, -0.5}}, {"rotation", 0.5}, {"scale", {2, 3}}, {"texCoord", 1}}}};
    b.doc["materials"] = json::array(
        {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"extensions", transform}}}}},
          {"emissiveFactor", {1, 0.5, 0.25}},
          {"extensions",
           {{"KHR_materials_clearcoat",
             {{"clearcoatFactor", 0.75}, {"clearcoatRoughnessFactor", 0.2}, {"clearcoatTexture", {{"index", 0}}},
              {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}},
            {"KHR_materials_sheen",
             {{"sheenColorFactor", {0.9, 0.5, 0.1}}, {"sheenRoughnessFactor", 0.3}, {"sheenColorTexture", {{"index", 0}}}}},
            {"KHR_materials_anisotropy", {{"anisotropyStrength", 0.6}, {"anisotropyRotation", 1.25}}},
            {"KHR_materials_ior", {{"ior", 1.33}}},
            {"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}},
         {{"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}}},
         {{"extensions", {{"KHR_materials_ior", {{"ior", 0.0}}}}}}});
    b.primitive()["material"] = 0;
    const Scene s = loadGltfScene(b.write("layers.gltf").string());
    expectRenderable(s);
    ASSERT_EQ(s.materials.size(), 3u);
    const Material& m = s.materials[0];
    EXPECT_EQ(m.clearcoatFactor, 0.75f);
    EXPECT_EQ(m.clearcoatRoughnessFactor, 0.2f);
    EXPECT_EQ(m.clearcoatRoughnessTexture, kNoTexture);
    EXPECT_FLOAT_EQ(m.clearcoatNormalScale, 0.5f);
    EXPECT_EQ(m.sheenColorFactor, glm::vec3(0.9f, 0.5f, 0.1f));
    EXPECT_EQ(m.sheenRoughnessFactor, 0.3f);
    EXPECT_FLOAT_EQ(m.anisotropyStrength, 0.6f);
    EXPECT_FLOAT_EQ(m.anisotropyRotation, 1.25f);
    EXPECT_FLOAT_EQ(m.ior, 1.33f);
    EXPECT_FLOAT_EQ(m.emissiveStrength, 4.0f);
    EXPECT_EQ(m.emissiveFactor, glm::vec3(1.0f, 0.5f, 0.25f));  // the strength multiplies it where it is used
    EXPECT_EQ(m.layers(), kLayerCoat | kLayerSheen | kLayerAnisotropy);
    EXPECT_TRUE(m.forward.empty());
    auto srgb = [&](int t) { return s.textures[size_t(t)].srgb; };
    EXPECT_FALSE(srgb(m.clearcoatTexture));  // "All clearcoat textures contain RGB components in linear space"
    EXPECT_FALSE(srgb(m.clearcoatNormalTexture));
    EXPECT_TRUE(srgb(m.sheenColorTexture));  // "The sheen color is in sRGB transfer function"
    // The base colour's transform: offset, rotation, scale, and texCoord 1 overriding the textureInfo's 0.
    const TextureTransform& t = m.uvTransforms[size_t(TextureSlot::BaseColor)];
    EXPECT_EQ(t.offset, glm::vec2(0.25f, -0.5f));
    EXPECT_EQ(t.rotation, 0.5f);
    EXPECT_EQ(t.scale, glm::vec2(2.0f, 3.0f));
    EXPECT_EQ(t.texCoord, 1);
    EXPECT_TRUE(t.transforms());
    EXPECT_FALSE(m.uvTransforms[size_t(TextureSlot::Clearcoat)].transforms());
    // rotation * scale in UV space, v down: u axis (1, 0) -> scale.x (cos r, -sin r).
    const glm::vec2 u = t.matrix() * glm::vec2(1.0f, 0.0f), v = t.matrix() * glm::vec2(0.0f, 1.0f);
    EXPECT_NEAR(u.x, 2.0f * std::cos(0.5f), 1e-6);
    EXPECT_NEAR(u.y, -2.0f * std::sin(0.5f), 1e-6);
    EXPECT_NEAR(v.x, 3.0f * std::sin(0.5f), 1e-6);
    EXPECT_NEAR(v.y, 3.0f * std::cos(0.5f), 1e-6);
    EXPECT_EQ(s.vertices[0].uv1, glm::vec2(0.5f, 0.5f));
    EXPECT_EQ(s.vertices[2].uv1, glm::vec2(1.0f, 1.0f));
    EXPECT_EQ(s.materials[1].forward, "KHR_materials_transmission");
    EXPECT_EQ(s.materials[1].layers(), 0);
    EXPECT_EQ(s.materials[2].ior, 0.0f);  // the specular-glossiness compatibility mode
}

// Bad input in the extensions: one line naming the file and the place, and what to fix.
TEST(GltfMaterials, BadLayerExtensionInputIsRefusedWithItsPlace) {
    struct Case {
        const char* name;
        json material;
        const char* expected;
    };
    const std::vector<Case> cases = {
        {"coat15.gltf", {{"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.5}}}}}},
         "materials[0].extensions.KHR_materials_clearcoat.clearcoatFactor: 1.5 is outside [0, 1]"},
        {"sheen_neg.gltf", {{"extensions", {{"KHR_materials_sheen", {{"sheenColorFactor", {0.5, -1, 0}}}}}}},
         "materials[0].extensions.KHR_materials_sheen.sheenColorFactor[1]: -1 is outside [0, 1]"},
        {"aniso2.gltf", {{"extensions", {{"KHR_materials_anisotropy", {{"anisotropyStrength", 2}}}}}},
         "KHR_materials_anisotropy.anisotropyStrength: 2 is outside [0, 1]"},
        {"ior05.gltf", {{"extensions", {{"KHR_materials_ior", {{"ior", 0.5}}}}}},
         "KHR_materials_ior.ior: 0.5 is below 1"},
        {"strength.gltf", {{"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", -2}}}}}},
         "KHR_materials_emissive_strength.emissiveStrength: -2 is negative"},
        {"sheen_index.gltf", {{"extensions", {{"KHR_materials_sheen", {{"sheenColorTexture", {{"index", 7}}}}}}}},
         "KHR_materials_sheen sheenColorTexture: refers to texture 7, but the file has 1"},
        {"transform_scale.gltf",
         {{"pbrMetallicRoughness",
           {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {1, 2, 3}}}}}}}}}}},
         "KHR_texture_transform.scale: has 3 elements, the specification says 2"},
        {"texcoord3.gltf",
         {{"pbrMetallicRoughness",
           {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 3}}}}}}}}}},
         "KHR_texture_transform.texCoord: 3 names TEXCOORD_3: gbufferlab reads TEXCOORD_0 and TEXCOORD_1 only"},
        {"texcoord1.gltf",
         {{"extensions", {{"KHR_materials_clearcoat", {{"clearcoatTexture", {{"index", 0}, {"texCoord", 1}}}}}}}},
         "KHR_materials_clearcoat.clearcoatTexture.texCoord: 1 names TEXCOORD_1, which meshes[0].primitives[0]"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        GltfBuilder b = quad();
        b.doc["images"] = json::array({{{"uri", "missing.png"}}});
        b.doc["textures"] = json::array({{{"source", 0}}});
        b.doc["materials"] = json::array({c.material});
        b.primitive()["material"] = 0;
        const std::string message = loadError(b.write(c.name));
        EXPECT_NE(message.find(c.name), std::string::npos) << message;
        EXPECT_NE(message.find(c.expected), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    // Still refused with one line: a required extension gbufferlab does not read.
    GltfBuilder b = quad();
    b.doc["extensionsRequired"] = {"KHR_materials_iridescence"};
    b.doc["extensionsUsed"] = {"KHR_materials_iridescence"};
    expectErrorNames(b.write("iridescence.gltf"), {"requires KHR_materials_iridescence", "not support"});
}

// The sample models that need the extensions load (SheenChair and SheenCloth require
// KHR_texture_transform): their layers and transforms as their files state them.
TEST(GltfMaterials, LayeredSampleModelsLoad) {
    const fs::path models = fs::path(GBL_SHARED_DIR) / "assets" / "models";
    for (const char* name : {"SheenChair", "SheenCloth", "ToyCar", "ClearcoatWicker", "AnisotropyStrengthTest"}) {
        const fs::path path = models / name / (std::string(name) + ".gltf");
        if (!fs::exists(path)) {
            std::printf("missing input %s\n", path.string().c_str());
            continue;
        }
        SCOPED_TRACE(name);
        const Scene s = loadGltfScene(path.string());
        int layers = 0, forward = 0;
        for (const Material& m : s.materials) {
            layers |= m.layers();
            forward += m.forward.empty() ? 0 : 1;
        }
        const std::string n = name;
        if (n == "SheenChair") {
            EXPECT_EQ(layers, kLayerSheen);
            // fabric: base colour offset (-3, 3), scale 7; occlusion from TEXCOORD_1
            const Material& fabric = s.materials[0];
            EXPECT_EQ(fabric.uvTransforms[size_t(TextureSlot::BaseColor)].scale, glm::vec2(7.0f));
            EXPECT_EQ(fabric.uvTransforms[size_t(TextureSlot::Occlusion)].texCoord, 1);
            EXPECT_FLOAT_EQ(fabric.sheenRoughnessFactor, 0.8f);
        }
        if (n == "SheenCloth") {
            EXPECT_EQ(layers, kLayerSheen);
            EXPECT_EQ(s.materials[0].uvTransforms[size_t(TextureSlot::SheenColor)].scale, glm::vec2(30.0f, -30.0f));
        }
        if (n == "ToyCar") {
            EXPECT_EQ(layers, kLayerCoat | kLayerSheen);
            EXPECT_EQ(forward, 1);  // the glass: KHR_materials_transmission
        }
        if (n == "ClearcoatWicker") {
            EXPECT_NE(s.materials[0].clearcoatNormalTexture, kNoTexture);
        }
        if (n == "AnisotropyStrengthTest") {
            EXPECT_EQ(layers, kLayerAnisotropy);
        }
    }
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

double peakMiB() {
    rusage usage{};
    ::getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;
}

// A 1 MB PNG of 16384x16384 black pixels: decoded, copied to RGBA8 and uploaded it would take
// about 4.8 GB. Refused from its header, naming the scene, the image and the fix, with the
// process's peak memory unmoved.
TEST(GltfImages, AnImageBeyondTheBudgetIsRefusedFromItsHeader) {
    ASSERT_TRUE(kBudgetSet);
    test::writeFile((scratchDir() / "huge.png").string(), test::blackPng(16384, 16384));
    GltfBuilder b = quad();
    b.doc["images"] = json::array({{{"uri", "huge.png"}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    b.primitive()["material"] = 0;
    const fs::path path = b.write("huge_texture.gltf");
    const double before = peakMiB();
    expectErrorNames(path, {"images[0] 'huge.png'", "16384x16384", "GBL_MEMORY_BUDGET=1G", "smaller textures"});
    EXPECT_LT(peakMiB() - before, 200.0);
    // A header stb_image will not describe (a frame over 2^30 bytes) is still measured, not
    // reported as an unknown format.
    test::writeFile((scratchDir() / "huge.png").string(), test::blackPng(60000, 60000));
    expectErrorNames(path, {"images[0] 'huge.png'", "60000x60000", "GBL_MEMORY_BUDGET=1G"});
}

}  // namespace
}  // namespace gbl
