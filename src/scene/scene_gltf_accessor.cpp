// Accessor reading with bounds, type and sparse handling (glTF 2.0 section 3.6).
#include "scene_gltf_accessor.h"

#include <algorithm>
#include <cstring>

namespace gbl {
namespace {

// Far beyond any real mesh; stops a corrupt count from asking for terabytes of zeros.
constexpr size_t kMaxElements = size_t(1) << 28;

int componentSize(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;  // INT and DOUBLE are not valid accessor types in glTF 2.0
    }
}

std::string componentTypeName(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return "byte";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "unsigned byte";
        case TINYGLTF_COMPONENT_TYPE_SHORT: return "short";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "unsigned short";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "unsigned int";
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return "float";
        default: return "invalid component type " + std::to_string(componentType);
    }
}

std::string typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return "SCALAR";
        case TINYGLTF_TYPE_VEC2: return "VEC2";
        case TINYGLTF_TYPE_VEC3: return "VEC3";
        case TINYGLTF_TYPE_VEC4: return "VEC4";
        case TINYGLTF_TYPE_MAT2: return "MAT2";
        case TINYGLTF_TYPE_MAT3: return "MAT3";
        case TINYGLTF_TYPE_MAT4: return "MAT4";
        default: return "an invalid type";
    }
}

std::string attributeName(GltfVertexAttribute kind) {
    switch (kind) {
        case GltfVertexAttribute::Position: return "POSITION";
        case GltfVertexAttribute::Normal: return "NORMAL";
        case GltfVertexAttribute::Tangent: return "TANGENT";
        case GltfVertexAttribute::TexCoord: return "TEXCOORD_0";
    }
    return "?";
}

int expectedType(GltfVertexAttribute kind) {
    switch (kind) {
        case GltfVertexAttribute::Position:
        case GltfVertexAttribute::Normal: return TINYGLTF_TYPE_VEC3;
        case GltfVertexAttribute::Tangent: return TINYGLTF_TYPE_VEC4;
        case GltfVertexAttribute::TexCoord: return TINYGLTF_TYPE_VEC2;
    }
    return -1;
}

bool isOneOf(int value, std::initializer_list<int> allowed) {
    return std::find(allowed.begin(), allowed.end(), value) != allowed.end();
}

// glTF 2.0 core allows float everywhere plus normalised unsigned byte/short texcoords;
// KHR_mesh_quantization adds the integer forms (see its README's attribute table).
bool componentTypeAllowed(GltfVertexAttribute kind, int ct, bool normalized, bool quantized) {
    using enum GltfVertexAttribute;
    constexpr int B = TINYGLTF_COMPONENT_TYPE_BYTE, UB = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    constexpr int S = TINYGLTF_COMPONENT_TYPE_SHORT, US = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    if (ct == TINYGLTF_COMPONENT_TYPE_FLOAT) return true;
    switch (kind) {
        case Position: return quantized && isOneOf(ct, {B, UB, S, US});
        case Normal:
        case Tangent: return quantized && normalized && isOneOf(ct, {B, S});
        case TexCoord:
            return (normalized && isOneOf(ct, {UB, US})) || (quantized && isOneOf(ct, {B, UB, S, US}));
    }
    return false;
}

template <typename T>
T loadUnaligned(const uint8_t* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));  // buffer data has no alignment guarantee
    return value;
}

// glTF 2.0 section 3.11 "Animations"/"Meshes": the normalised-integer decoding equations.
float componentToFloat(const uint8_t* p, int ct, bool normalized) {
    switch (ct) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const float v = loadUnaligned<int8_t>(p);
            return normalized ? std::max(v / 127.0f, -1.0f) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            const float v = loadUnaligned<uint8_t>(p);
            return normalized ? v / 255.0f : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const float v = loadUnaligned<int16_t>(p);
            return normalized ? std::max(v / 32767.0f, -1.0f) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const float v = loadUnaligned<uint16_t>(p);
            return normalized ? v / 65535.0f : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return static_cast<float>(loadUnaligned<uint32_t>(p));
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return loadUnaligned<float>(p);
        default: return 0.0f;  // rejected before reading
    }
}

uint32_t componentToIndex(const uint8_t* p, int ct, bool /*normalized*/) {
    switch (ct) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return loadUnaligned<uint8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return loadUnaligned<uint16_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return loadUnaligned<uint32_t>(p);
        default: return 0;  // rejected before reading
    }
}

// Where `count` elements of `elementSize` bytes start inside a buffer, and how far apart.
struct ElementRange {
    const uint8_t* base = nullptr;
    size_t stride = 0;
};

constexpr const char* kFixBroken = "the file is corrupt or was written by a broken exporter; re-export it";

ElementRange locate(const GltfContext& ctx, const std::string& what, int viewIndex, size_t byteOffset,
                    size_t count, size_t elementSize, bool useViewStride) {
    const auto& model = ctx.model;
    if (viewIndex < 0 || static_cast<size_t>(viewIndex) >= model.bufferViews.size())
        ctx.fail(what, "refers to bufferView " + std::to_string(viewIndex) + ", but the file has " +
                           std::to_string(model.bufferViews.size()), kFixBroken);
    const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(viewIndex)];
    const std::string viewName = "bufferView " + std::to_string(viewIndex);
    if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size())
        ctx.fail(what, viewName + " refers to buffer " + std::to_string(view.buffer) + ", but the file has " +
                           std::to_string(model.buffers.size()), kFixBroken);
    const size_t bufferSize = model.buffers[static_cast<size_t>(view.buffer)].data.size();
    if (view.byteOffset > bufferSize || view.byteLength > bufferSize - view.byteOffset)
        ctx.fail(what, viewName + " (bytes " + std::to_string(view.byteOffset) + " + " +
                           std::to_string(view.byteLength) + ") runs past the end of buffer " +
                           std::to_string(view.buffer) + " (" + std::to_string(bufferSize) + " bytes)",
                 "the .bin file is truncated or does not belong to this file; re-export it");

    const size_t stride = (useViewStride && view.byteStride != 0) ? view.byteStride : elementSize;
    if (stride < elementSize)
        ctx.fail(what, viewName + " has byteStride " + std::to_string(stride) + ", less than one element (" +
                           std::to_string(elementSize) + " bytes)", kFixBroken);
    // Overflow-free form of: byteOffset + (count - 1) * stride + elementSize <= byteLength.
    const size_t length = view.byteLength;
    const bool fits = count == 0 ||
                      (byteOffset <= length && elementSize <= length - byteOffset &&
                       (count - 1) <= (length - byteOffset - elementSize) / stride);
    if (!fits)
        ctx.fail(what, std::to_string(count) + " elements of " + std::to_string(elementSize) +
                           " bytes at offset " + std::to_string(byteOffset) + " (stride " + std::to_string(stride) +
                           ") run past the end of " + viewName + " (" + std::to_string(length) + " bytes)",
                 kFixBroken);
    const uint8_t* base = model.buffers[static_cast<size_t>(view.buffer)].data.data() + view.byteOffset + byteOffset;
    return ElementRange{base, stride};
}

const tinygltf::Accessor& checkedAccessor(const GltfContext& ctx, int accessorIndex, const std::string& where) {
    if (accessorIndex < 0 || static_cast<size_t>(accessorIndex) >= ctx.model.accessors.size())
        ctx.fail(where, "refers to accessor " + std::to_string(accessorIndex) + ", but the file has " +
                            std::to_string(ctx.model.accessors.size()),
                 kFixBroken);
    return ctx.model.accessors[static_cast<size_t>(accessorIndex)];
}

// Reads all elements (zeros when there is no bufferView), then applies sparse substitution.
// Type checks are the caller's; this checks sizes and ranges.
template <typename T, typename Convert>
std::vector<T> readElements(const GltfContext& ctx, const tinygltf::Accessor& acc, const std::string& what,
                            int components, Convert convert) {
    const int compSize = componentSize(acc.componentType);
    const size_t elementSize = static_cast<size_t>(compSize) * static_cast<size_t>(components);
    if (acc.count > kMaxElements)
        ctx.fail(what, "has count " + std::to_string(acc.count) + ", more than gbufferlab accepts (" +
                           std::to_string(kMaxElements) + ")", kFixBroken);
    std::vector<T> out(acc.count * static_cast<size_t>(components), T{});
    auto readInto = [&](const ElementRange& range, size_t element, size_t source) {
        const uint8_t* p = range.base + source * range.stride;
        for (int c = 0; c < components; ++c)
            out[element * static_cast<size_t>(components) + static_cast<size_t>(c)] =
                convert(p + static_cast<size_t>(c) * static_cast<size_t>(compSize), acc.componentType, acc.normalized);
    };
    if (acc.bufferView >= 0) {
        const ElementRange range = locate(ctx, what, acc.bufferView, acc.byteOffset, acc.count, elementSize, true);
        for (size_t e = 0; e < acc.count; ++e) readInto(range, e, e);
    }
    if (acc.sparse.isSparse) {
        const auto& sparse = acc.sparse;
        const std::string sparseWhat = what + " (sparse)";
        const int indexType = sparse.indices.componentType;
        if (!isOneOf(indexType, {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT}))
            ctx.fail(sparseWhat, "has index component type " + componentTypeName(indexType) +
                                     ", glTF requires an unsigned byte, short or int", kFixBroken);
        if (sparse.count < 0 || static_cast<size_t>(sparse.count) > acc.count || sparse.indices.byteOffset < 0 ||
            sparse.values.byteOffset < 0)
            ctx.fail(sparseWhat, "has a negative offset or more substitutions (" + std::to_string(sparse.count) +
                                     ") than elements (" + std::to_string(acc.count) + ")", kFixBroken);
        const size_t count = static_cast<size_t>(sparse.count);
        const ElementRange indices = locate(ctx, sparseWhat + " indices", sparse.indices.bufferView,
                                            static_cast<size_t>(sparse.indices.byteOffset), count,
                                            static_cast<size_t>(componentSize(indexType)), false);
        const ElementRange values = locate(ctx, sparseWhat + " values", sparse.values.bufferView,
                                           static_cast<size_t>(sparse.values.byteOffset), count, elementSize, false);
        for (size_t i = 0; i < count; ++i) {
            const uint32_t target = componentToIndex(indices.base + i * indices.stride, indexType, false);
            if (target >= acc.count)
                ctx.fail(sparseWhat, "substitutes element " + std::to_string(target) + ", but the accessor has " +
                                         std::to_string(acc.count), kFixBroken);
            readInto(values, target, i);
        }
    }
    return out;
}

}  // namespace

int componentsOf(GltfVertexAttribute kind) {
    switch (kind) {
        case GltfVertexAttribute::Position:
        case GltfVertexAttribute::Normal: return 3;
        case GltfVertexAttribute::Tangent: return 4;
        case GltfVertexAttribute::TexCoord: return 2;
    }
    return 0;
}

size_t accessorCount(const GltfContext& ctx, int accessorIndex, const std::string& where) {
    return checkedAccessor(ctx, accessorIndex, where).count;
}

std::vector<float> readAttribute(const GltfContext& ctx, int accessorIndex, GltfVertexAttribute kind,
                                 const std::string& where) {
    const std::string what = where + ": " + attributeName(kind) + " accessor " + std::to_string(accessorIndex);
    const tinygltf::Accessor& acc = checkedAccessor(ctx, accessorIndex, what);
    const std::string want = typeName(expectedType(kind));
    if (acc.type != expectedType(kind))
        ctx.fail(what, "is " + typeName(acc.type) + ", glTF requires " + want,
                 "re-export the file (the exporter wrote the wrong accessor type)");
    const auto& used = ctx.model.extensionsUsed;
    const bool quantized = std::find(used.begin(), used.end(), "KHR_mesh_quantization") != used.end();
    if (!componentTypeAllowed(kind, acc.componentType, acc.normalized, quantized))
        ctx.fail(what, "has components of type " + componentTypeName(acc.componentType) +
                           (acc.normalized ? " (normalized)" : "") + ", which glTF does not allow here" +
                           (quantized ? "" : " without KHR_mesh_quantization"),
                 "re-export with float " + want + " data");
    return readElements<float>(ctx, acc, what, componentsOf(kind), componentToFloat);
}

std::vector<uint32_t> readIndices(const GltfContext& ctx, int accessorIndex, const std::string& where) {
    const std::string what = where + ": indices accessor " + std::to_string(accessorIndex);
    const tinygltf::Accessor& acc = checkedAccessor(ctx, accessorIndex, what);
    if (acc.type != TINYGLTF_TYPE_SCALAR)
        ctx.fail(what, "is " + typeName(acc.type) + ", glTF requires SCALAR indices", kFixBroken);
    if (!isOneOf(acc.componentType, {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT}))
        ctx.fail(what, "has components of type " + componentTypeName(acc.componentType) +
                           ", glTF requires unsigned byte, short or int indices", kFixBroken);
    return readElements<uint32_t>(ctx, acc, what, 1, componentToIndex);
}

}  // namespace gbl
