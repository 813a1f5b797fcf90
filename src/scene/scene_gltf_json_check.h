#pragma once
// Checks a glTF file's JSON against the parts of the glTF 2.0 specification that tinygltf lets
// through silently, before tinygltf sees it: the JSON types of the core properties (a string
// where a number belongs is dropped by tinygltf, not reported), array lengths, factors outside
// [0, 1], an orthographic camera with xmag or ymag 0, a texCoord set no primitive using the
// material has, and an asset version other than 2.x. Each is refused with one line naming the
// file and the JSON path ("materials[0].pbrMetallicRoughness.metallicFactor").
#include <string>
#include <vector>

namespace gbl {

// `bytes` is the whole file (.gltf text or .glb container). Throws UserError.
void checkGltfJson(const std::string& path, const std::vector<unsigned char>& bytes);

}  // namespace gbl
