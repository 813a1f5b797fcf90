#pragma once
// Helpers shared by the scene tests: cached loads of the real models, what every loaded scene
// must satisfy, and a builder of small glTF files that pin down one rule each.
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


namespace gbl::scene_test {

namespace fs = std::filesystem;
using nlohmann::json;

// ---------------------------------------------------------------------------------------------
// Helpers

// Loading a 2048^2-textured model costs ~0.2 s (much more under ASan); load each file once.
inline const Scene& loadCached(const fs::path& path) {
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
inline std::string loadError(const fs::path& path) {
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
inline void expectRenderable(const Scene& s) {
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

inline glm::vec4 toClip(const Camera& c, float aspect, const glm::vec3& p) {
    const glm::mat4 proj = glm::perspective(c.yFovRadians, aspect, c.zNear, c.zFar);
    return proj * glm::lookAt(c.position, c.target, c.up) * glm::vec4(p, 1.0f);
}

// Inside the view frustum, depth range [0, 1] (GLM_FORCE_DEPTH_ZERO_TO_ONE).
inline bool insideFrustum(const glm::vec4& clip) {
    return clip.w > 0.0f && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w && clip.z >= 0.0f &&
           clip.z <= clip.w;
}

inline void expectCameraSeesBounds(const Camera& camera, const Bounds& b, float aspect) {
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
        EXPECT_TRUE(insideFrustum(toClip(camera, aspect, corner))) << "corner " << i << " aspect " << aspect;
    }
}

fs::path waterBottle() { return test::sharedAssets() / "models/WaterBottle/WaterBottle.gltf"; }
fs::path avocado() { return test::sharedAssets() / "models/Avocado/Avocado.gltf"; }


// ---------------------------------------------------------------------------------------------
// Generated glTF files: one rule each

inline std::string base64(const std::vector<uint8_t>& data) {
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

inline fs::path scratchDir() {
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
inline GltfBuilder quad() {
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

inline void expectErrorNames(const fs::path& path, std::initializer_list<const char*> parts) {
    const std::string message = loadError(path);
    EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
    for (const char* part : parts) EXPECT_NE(message.find(part), std::string::npos) << "want '" << part << "' in: " << message;
}

// Spec violations tinygltf accepts (issue 13): each is refused with the JSON path and a fix.

}  // namespace gbl::scene_test
