#include "scene_gltf_json_check.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include <nlohmann/json.hpp>

#include "error.h"

namespace gbl {
namespace {

using nlohmann::json;

// What a property must hold. `Index` is a glTF integer >= 0; `Unit` a number in [0, 1].
enum class Kind { Object, ObjectArray, IndexArray, NumberArray, StringArray, Index, Number, Unit, NonNegative, Ior, String, Boolean };

struct Schema;
struct Property {
    const char* name;
    Kind kind;
    const Schema* object = nullptr;  // for Object / ObjectArray
    size_t length = 0;               // for NumberArray: exact length (0: any)
    bool unitElements = false;       // for NumberArray: each element in [0, 1]
};
struct Schema {
    std::vector<Property> properties;
};

const Schema kTextureInfo{{{"index", Kind::Index}, {"texCoord", Kind::Index}}};
const Schema kNormalTextureInfo{{{"index", Kind::Index}, {"texCoord", Kind::Index}, {"scale", Kind::Number}}};

// The extensions whose data the loader reads (their READMEs' schemas): an object under
// `extensions` with one of these names is checked against it, so a bad factor is refused at its
// place, e.g. materials[3].extensions.KHR_materials_clearcoat.clearcoatFactor: 1.5 is outside [0, 1].
const Schema kTextureTransform{{{"offset", Kind::NumberArray, nullptr, 2},
                                {"rotation", Kind::Number},
                                {"scale", Kind::NumberArray, nullptr, 2},
                                {"texCoord", Kind::Index}}};
const Schema kClearcoat{{{"clearcoatFactor", Kind::Unit},
                         {"clearcoatTexture", Kind::Object, &kTextureInfo},
                         {"clearcoatRoughnessFactor", Kind::Unit},
                         {"clearcoatRoughnessTexture", Kind::Object, &kTextureInfo},
                         {"clearcoatNormalTexture", Kind::Object, &kNormalTextureInfo}}};
const Schema kSheen{{{"sheenColorFactor", Kind::NumberArray, nullptr, 3, true},
                     {"sheenColorTexture", Kind::Object, &kTextureInfo},
                     {"sheenRoughnessFactor", Kind::Unit},
                     {"sheenRoughnessTexture", Kind::Object, &kTextureInfo}}};
const Schema kAnisotropy{{{"anisotropyStrength", Kind::Unit},
                          {"anisotropyRotation", Kind::Number},
                          {"anisotropyTexture", Kind::Object, &kTextureInfo}}};
const Schema kIor{{{"ior", Kind::Ior}}};
const Schema kEmissiveStrength{{{"emissiveStrength", Kind::NonNegative}}};
const Schema kSpecular{{{"specularFactor", Kind::Unit},
                        {"specularTexture", Kind::Object, &kTextureInfo},
                        {"specularColorFactor", Kind::NumberArray, nullptr, 3},
                        {"specularColorTexture", Kind::Object, &kTextureInfo}}};
const Schema kTransmission{{{"transmissionFactor", Kind::Unit}, {"transmissionTexture", Kind::Object, &kTextureInfo}}};
const Schema kVolume{{{"thicknessFactor", Kind::NonNegative},
                      {"thicknessTexture", Kind::Object, &kTextureInfo},
                      {"attenuationDistance", Kind::Number},
                      {"attenuationColor", Kind::NumberArray, nullptr, 3, true}}};

const Schema* extensionSchema(const std::string& name) {
    static const std::map<std::string, const Schema*> schemas = {
        {"KHR_texture_transform", &kTextureTransform},   {"KHR_materials_clearcoat", &kClearcoat},
        {"KHR_materials_sheen", &kSheen},                {"KHR_materials_anisotropy", &kAnisotropy},
        {"KHR_materials_ior", &kIor},                    {"KHR_materials_emissive_strength", &kEmissiveStrength},
        {"KHR_materials_specular", &kSpecular},          {"KHR_materials_transmission", &kTransmission},
        {"KHR_materials_volume", &kVolume}};
    const auto it = schemas.find(name);
    return it == schemas.end() ? nullptr : it->second;
}
const Schema kOcclusionTextureInfo{{{"index", Kind::Index}, {"texCoord", Kind::Index}, {"strength", Kind::Unit}}};
const Schema kPbr{{{"baseColorFactor", Kind::NumberArray, nullptr, 4, true},
                   {"baseColorTexture", Kind::Object, &kTextureInfo},
                   {"metallicFactor", Kind::Unit},
                   {"roughnessFactor", Kind::Unit},
                   {"metallicRoughnessTexture", Kind::Object, &kTextureInfo}}};
const Schema kMaterial{{{"name", Kind::String},
                        {"pbrMetallicRoughness", Kind::Object, &kPbr},
                        {"normalTexture", Kind::Object, &kNormalTextureInfo},
                        {"occlusionTexture", Kind::Object, &kOcclusionTextureInfo},
                        {"emissiveTexture", Kind::Object, &kTextureInfo},
                        {"emissiveFactor", Kind::NumberArray, nullptr, 3, true},
                        {"alphaMode", Kind::String},
                        {"alphaCutoff", Kind::NonNegative},
                        {"doubleSided", Kind::Boolean}}};
const Schema kAttributes{};  // values checked in checkObject: every attribute is an accessor index
const Schema kPrimitive{{{"attributes", Kind::Object, &kAttributes},
                         {"indices", Kind::Index},
                         {"material", Kind::Index},
                         {"mode", Kind::Index},
                         {"targets", Kind::ObjectArray, &kAttributes}}};
const Schema kMesh{{{"name", Kind::String}, {"primitives", Kind::ObjectArray, &kPrimitive}, {"weights", Kind::NumberArray}}};
const Schema kNode{{{"name", Kind::String},
                    {"children", Kind::IndexArray},
                    {"mesh", Kind::Index},
                    {"camera", Kind::Index},
                    {"skin", Kind::Index},
                    {"matrix", Kind::NumberArray, nullptr, 16},
                    {"rotation", Kind::NumberArray, nullptr, 4},
                    {"scale", Kind::NumberArray, nullptr, 3},
                    {"translation", Kind::NumberArray, nullptr, 3},
                    {"weights", Kind::NumberArray}}};
const Schema kScene{{{"name", Kind::String}, {"nodes", Kind::IndexArray}}};
const Schema kAccessor{{{"name", Kind::String},
                        {"bufferView", Kind::Index},
                        {"byteOffset", Kind::Index},
                        {"componentType", Kind::Index},
                        {"normalized", Kind::Boolean},
                        {"count", Kind::Index},
                        {"type", Kind::String},
                        {"max", Kind::NumberArray},
                        {"min", Kind::NumberArray}}};
const Schema kBufferView{{{"name", Kind::String},
                          {"buffer", Kind::Index},
                          {"byteOffset", Kind::Index},
                          {"byteLength", Kind::Index},
                          {"byteStride", Kind::Index},
                          {"target", Kind::Index}}};
const Schema kBuffer{{{"name", Kind::String}, {"uri", Kind::String}, {"byteLength", Kind::Index}}};
const Schema kImage{{{"name", Kind::String}, {"uri", Kind::String}, {"mimeType", Kind::String}, {"bufferView", Kind::Index}}};
const Schema kTexture{{{"name", Kind::String}, {"sampler", Kind::Index}, {"source", Kind::Index}}};
const Schema kSampler{{{"name", Kind::String},
                       {"magFilter", Kind::Index},
                       {"minFilter", Kind::Index},
                       {"wrapS", Kind::Index},
                       {"wrapT", Kind::Index}}};
const Schema kPerspective{{{"aspectRatio", Kind::Number}, {"yfov", Kind::Number}, {"zfar", Kind::Number}, {"znear", Kind::Number}}};
const Schema kOrthographic{{{"xmag", Kind::Number}, {"ymag", Kind::Number}, {"zfar", Kind::Number}, {"znear", Kind::Number}}};
const Schema kCamera{{{"name", Kind::String},
                      {"type", Kind::String},
                      {"perspective", Kind::Object, &kPerspective},
                      {"orthographic", Kind::Object, &kOrthographic}}};
const Schema kAsset{{{"version", Kind::String}, {"minVersion", Kind::String}, {"generator", Kind::String}, {"copyright", Kind::String}}};
const Schema kRoot{{{"asset", Kind::Object, &kAsset},
                    {"scene", Kind::Index},
                    {"scenes", Kind::ObjectArray, &kScene},
                    {"nodes", Kind::ObjectArray, &kNode},
                    {"meshes", Kind::ObjectArray, &kMesh},
                    {"materials", Kind::ObjectArray, &kMaterial},
                    {"accessors", Kind::ObjectArray, &kAccessor},
                    {"bufferViews", Kind::ObjectArray, &kBufferView},
                    {"buffers", Kind::ObjectArray, &kBuffer},
                    {"images", Kind::ObjectArray, &kImage},
                    {"textures", Kind::ObjectArray, &kTexture},
                    {"samplers", Kind::ObjectArray, &kSampler},
                    {"cameras", Kind::ObjectArray, &kCamera},
                    {"extensionsUsed", Kind::StringArray},
                    {"extensionsRequired", Kind::StringArray}}};

const char* jsonTypeName(const json& v) {
    switch (v.type()) {
        case json::value_t::object: return "an object";
        case json::value_t::array: return "an array";
        case json::value_t::string: return "a string";
        case json::value_t::boolean: return "a boolean";
        case json::value_t::null: return "null";
        default: return v.is_number_integer() || v.is_number_unsigned() ? "an integer" : "a number";
    }
}

bool isIndex(const json& v) {
    if (v.is_number_unsigned()) return true;
    if (v.is_number_integer()) return v.get<int64_t>() >= 0;
    return false;
}

// Why `v` is not an index ("" when it is): a negative whole number is named as what it is (-1 is
// an integer, it is only below 0), anything else by its type.
std::string indexProblem(const json& v, const char* what) {
    if (isIndex(v)) return "";
    if (v.is_number_integer()) return std::to_string(v.get<int64_t>()) + " is negative; " + what + " must be >= 0";
    return std::string("must be ") + what + " (a whole number >= 0), not " + jsonTypeName(v);
}

std::string numberText(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

class Checker {
public:
    explicit Checker(std::string path) : path_(std::move(path)) {}

    [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
        throwUserError(formatPlace(escapeText(path_)) + ": " + where + ": " + problem +
                       "; fix the file (glTF 2.0 specification) or re-export it");
    }

    void expectType(const json& v, Kind kind, const std::string& where) const {
        auto need = [&](bool ok, const char* what) {
            if (!ok) fail(where, std::string("must be ") + what + ", not " + jsonTypeName(v));
        };
        switch (kind) {
            case Kind::Object: need(v.is_object(), "an object"); break;
            case Kind::ObjectArray:
            case Kind::IndexArray:
            case Kind::NumberArray:
            case Kind::StringArray: need(v.is_array(), "an array"); break;
            case Kind::Index:
                if (const std::string problem = indexProblem(v, "an index"); !problem.empty()) fail(where, problem);
                break;
            case Kind::Number: need(v.is_number(), "a number"); break;
            case Kind::Unit:
                need(v.is_number(), "a number");
                if (!(v.get<double>() >= 0.0 && v.get<double>() <= 1.0))
                    fail(where, numberText(v.get<double>()) + " is outside [0, 1]");
                break;
            case Kind::NonNegative:
                need(v.is_number(), "a number");
                if (!(v.get<double>() >= 0.0)) fail(where, numberText(v.get<double>()) + " is negative");
                break;
            case Kind::Ior:  // KHR_materials_ior: >= 1, or 0 (the specular-glossiness compatibility mode)
                need(v.is_number(), "a number");
                if (!(v.get<double>() >= 1.0 || v.get<double>() == 0.0))
                    fail(where, numberText(v.get<double>()) + " is below 1 (an index of refraction is >= 1, or 0)");
                break;
            case Kind::String: need(v.is_string(), "a string"); break;
            case Kind::Boolean: need(v.is_boolean(), "true or false"); break;
        }
    }

    void checkObject(const json& object, const Schema& schema, const std::string& where) const {
        if (&schema == &kAttributes) {
            for (const auto& [name, value] : object.items())
                if (const std::string problem = indexProblem(value, "an accessor index"); !problem.empty())
                    fail(where + "." + escapeText(name), problem);
            return;
        }
        if (const auto ext = object.find("extensions"); ext != object.end()) {
            const std::string at = where.empty() ? "extensions" : where + ".extensions";
            expectType(*ext, Kind::Object, at);
            for (const auto& [name, value] : ext->items()) {
                expectType(value, Kind::Object, at + "." + escapeText(name));
                if (const Schema* known = extensionSchema(name)) checkObject(value, *known, at + "." + name);
            }
        }
        for (const Property& p : schema.properties) {
            const auto it = object.find(p.name);
            if (it == object.end()) continue;
            const std::string at = (where.empty() ? "" : where + ".") + p.name;
            expectType(*it, p.kind, at);
            if (p.kind == Kind::Object) checkObject(*it, *p.object, at);
            if (!it->is_array()) continue;
            if (p.length && it->size() != p.length)
                fail(at, "has " + std::to_string(it->size()) + " elements, the specification says " +
                             std::to_string(p.length));
            for (size_t i = 0; i < it->size(); ++i) {
                const std::string item = at + "[" + std::to_string(i) + "]";
                const json& e = (*it)[i];
                switch (p.kind) {
                    case Kind::ObjectArray:
                        expectType(e, Kind::Object, item);
                        checkObject(e, *p.object, item);
                        break;
                    case Kind::IndexArray: expectType(e, Kind::Index, item); break;
                    case Kind::NumberArray: expectType(e, p.unitElements ? Kind::Unit : Kind::Number, item); break;
                    case Kind::StringArray: expectType(e, Kind::String, item); break;
                    default: break;
                }
            }
        }
    }

    // Rules across objects, on a document whose types are now known to be right.
    void checkRules(const json& root) const {
        const auto asset = root.find("asset");
        if (asset == root.end()) fail("asset", "missing; every glTF file states its version");
        const std::string version = asset->value("version", "");
        if (version.rfind("2.", 0) != 0)
            fail("asset.version", quoteName(version) + ": gbufferlab reads glTF 2.x only; convert the file to glTF 2.0");
        const json empty = json::array();
        const json& cameras = root.contains("cameras") ? root["cameras"] : empty;
        for (size_t i = 0; i < cameras.size(); ++i) {
            const auto ortho = cameras[i].find("orthographic");
            if (ortho == cameras[i].end()) continue;
            for (const char* key : {"xmag", "ymag"})
                if (ortho->contains(key) && (*ortho)[key].get<double>() == 0.0)
                    fail("cameras[" + std::to_string(i) + "].orthographic." + key, "is 0 (the view would be empty)");
        }
        const json& nodes = root.contains("nodes") ? root["nodes"] : empty;
        for (size_t i = 0; i < nodes.size(); ++i) {
            const auto r = nodes[i].find("rotation");
            if (r == nodes[i].end()) continue;
            double norm = 0;
            for (const json& c : *r) norm += c.get<double>() * c.get<double>();
            if (!(norm > 0.0)) fail("nodes[" + std::to_string(i) + "].rotation", "is a zero quaternion");
        }
        checkTexCoords(root);
    }

    // A texture asking for TEXCOORD_n needs every primitive drawn with its material to have it.
    void checkTexCoords(const json& root) const {
        if (!root.contains("materials") || !root.contains("meshes")) return;
        const json& materials = root["materials"];
        const json& meshes = root["meshes"];
        for (size_t m = 0; m < meshes.size(); ++m) {
            if (!meshes[m].contains("primitives")) continue;
            const json& prims = meshes[m]["primitives"];
            for (size_t p = 0; p < prims.size(); ++p) {
                const json& prim = prims[p];
                if (!prim.contains("material") || prim["material"].get<uint64_t>() >= materials.size()) continue;
                const size_t mat = prim["material"].get<size_t>();
                forEachTexCoord(materials[mat], "materials[" + std::to_string(mat) + "]", [&](const std::string& at, uint64_t set) {
                    const std::string attribute = "TEXCOORD_" + std::to_string(set);
                    if (set > 1)  // scene.h Vertex: uv and uv1
                        fail(at + ".texCoord", std::to_string(set) + " names " + attribute +
                                                   ": gbufferlab reads TEXCOORD_0 and TEXCOORD_1 only");
                    if (!prim.contains("attributes") || !prim["attributes"].contains(attribute))
                        fail(at + ".texCoord", std::to_string(set) + " names " + attribute + ", which meshes[" +
                                                   std::to_string(m) + "].primitives[" + std::to_string(p) +
                                                   "] using this material does not have");
                });
            }
        }
    }

    // Every texture the loader samples, with the set it samples: its texCoord, or where its
    // KHR_texture_transform gives one, that ("Overrides the textureInfo texCoord value").
    template <class Fn>
    static void forEachTexCoord(const json& material, const std::string& where, Fn&& fn) {
        auto visit = [&](const json& info, const std::string& at) {
            if (!info.is_object() || !info.contains("index")) return;
            const auto ext = info.find("extensions");
            if (ext != info.end() && ext->contains("KHR_texture_transform") &&
                (*ext)["KHR_texture_transform"].contains("texCoord")) {
                fn(at + ".extensions.KHR_texture_transform", (*ext)["KHR_texture_transform"]["texCoord"].get<uint64_t>());
                return;
            }
            if (info.contains("texCoord")) fn(at, info["texCoord"].get<uint64_t>());
        };
        for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"})
            if (material.contains(key)) visit(material[key], where + "." + key);
        if (material.contains("pbrMetallicRoughness"))
            for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"})
                if (material["pbrMetallicRoughness"].contains(key))
                    visit(material["pbrMetallicRoughness"][key], where + ".pbrMetallicRoughness." + key);
        const auto ext = material.find("extensions");
        if (ext == material.end()) return;
        static const std::pair<const char*, std::vector<const char*>> kExtensionTextures[] = {
            {"KHR_materials_clearcoat", {"clearcoatTexture", "clearcoatRoughnessTexture", "clearcoatNormalTexture"}},
            {"KHR_materials_sheen", {"sheenColorTexture", "sheenRoughnessTexture"}},
            {"KHR_materials_anisotropy", {"anisotropyTexture"}},
            {"KHR_materials_specular", {"specularTexture", "specularColorTexture"}}};
        for (const auto& [name, keys] : kExtensionTextures) {
            if (!ext->contains(name)) continue;
            for (const char* key : keys)
                if ((*ext)[name].contains(key)) visit((*ext)[name][key], where + ".extensions." + name + "." + key);
        }
    }

private:
    std::string path_;
};

// The JSON text of a .gltf, or of a .glb's first chunk (which must be JSON).
std::string jsonText(const std::string& path, const std::vector<unsigned char>& bytes) {
    if (bytes.size() < 4 || std::memcmp(bytes.data(), "glTF", 4) != 0) return std::string(bytes.begin(), bytes.end());
    uint32_t length = 0, type = 0;
    if (bytes.size() >= 20) {
        std::memcpy(&length, bytes.data() + 12, 4);
        std::memcpy(&type, bytes.data() + 16, 4);
    }
    if (bytes.size() < 20 || type != 0x4E4F534Au || length > bytes.size() - 20)
        throwUserError(formatPlace(escapeText(path)) +
                       ": not a valid .glb: the first chunk is missing, truncated or not JSON; re-export the file");
    return std::string(bytes.begin() + 20, bytes.begin() + 20 + length);
}

// The library's message for an error it gives no byte for, such as "[json.exception.
// out_of_range.406] number overflow parsing '9e390'": placed at the quoted text's first occurrence
// as a whole token, not inside a string (the start of the file if it is not found).
std::string jsonErrorWithoutPlace(const std::string& path, const std::string& text, const std::string& what) {
    std::string reason = what;
    if (const size_t bracket = reason.find("] "); reason.rfind("[json.exception", 0) == 0 && bracket != std::string::npos)
        reason = reason.substr(bracket + 2);
    size_t byte = 0;
    const size_t open = what.find(" '"), close = what.rfind('\'');
    if (open != std::string::npos && close != std::string::npos && close > open + 2) {
        const std::string token = what.substr(open + 2, close - open - 2);
        const auto partOfNumber = [](char c) {  // or of a string: '"'
            return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-' || c == '"';
        };
        for (size_t at = text.find(token); at != std::string::npos; at = text.find(token, at + 1)) {
            const size_t end = at + token.size();
            if ((at == 0 || !partOfNumber(text[at - 1])) && (end >= text.size() || !partOfNumber(text[end]))) {
                byte = at + 1;
                break;
            }
        }
    }
    if (reason.rfind("number overflow", 0) == 0) reason += " (beyond a double's range)";
    return jsonParseErrorMessage(path, text, byte, "parse error: " + reason);
}

}  // namespace

void checkGltfJson(const std::string& path, const std::vector<unsigned char>& bytes) {
    const std::string text = jsonText(path, bytes);
    json root;
    try {
        root = json::parse(text);
    } catch (const json::parse_error& e) {
        throwUserError(jsonParseErrorMessage(path, text, e.byte, e.what()) + "; fix the file or re-export it");
    } catch (const json::exception& e) {
        // out_of_range 406, a number beyond a double ("9e390", found by scripts/fuzz.sh), comes
        // with no place: the number's own text is looked up instead.
        throwUserError(jsonErrorWithoutPlace(path, text, e.what()) + "; fix the file or re-export it");
    }
    const Checker checker(path);
    if (!root.is_object()) checker.fail("the top level", std::string("must be an object, not ") + jsonTypeName(root));
    checker.checkObject(root, kRoot, "");
    checker.checkRules(root);
}

}  // namespace gbl
