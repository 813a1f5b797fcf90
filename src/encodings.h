#pragma once
// Encoding primitives, C++ mirror of shaders/encodings.glsl (same names, same expressions, same
// order, float only). Each function's range, bits, error bound and source is stated above its
// definition in both files. GPU-written codes and these functions' codes agree to the bit for
// every encoder (quantise with floor(x * s + 0.5), only IEEE-exact operations); decoders are
// compared with a tolerance. The layout-language names live in encoding_registry.h.
#include <glm/glm.hpp>

namespace gbl::enc {

// GLSL spellings, so that the mirror reads like the shader.
using glm::ivec2;
using glm::mat4;
using glm::uint;
using glm::uvec2;
using glm::uvec3;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using glm::abs;
using glm::clamp;
using glm::dot;
using glm::floatBitsToUint;
using glm::floor;
using glm::max;
using glm::min;
using glm::normalize;
using glm::sqrt;
using glm::step;
using glm::uintBitsToFloat;

// 1. Fixed point (bits: unorm 1..24, snorm 2..24).
uint quantizeUnorm(float x, uint bits);
float dequantizeUnorm(uint code, uint bits);
uint quantizeSnorm(float x, uint bits);
float dequantizeSnorm(uint code, uint bits);

// 2. Small floats (round to nearest even, overflow clamps to max finite).
uint encodeSmallFloatMagnitude(uint a, uint mantissaBits);
float decodeSmallFloatMagnitude(uint code, uint mantissaBits);
uint encodeFloat16(float x);
float decodeFloat16(uint code);
uint encodeFloat11(float x);
float decodeFloat11(uint code);
uint encodeFloat10(float x);
float decodeFloat10(uint code);
uint encodeFloat32(float x);
float decodeFloat32(uint code);

// 3. sRGB 8-bit, exact, table based.
extern const float kSrgbDecode[256];
extern const float kSrgbEncodeThresholds[255];
uint encodeSrgb8(float x);
float decodeSrgb8(uint code);

// 4. Unit normals.
uvec3 encodeNormalXyz(vec3 n, uint bits);
vec3 decodeNormalXyz(uvec3 code, uint bits);
uvec3 encodeNormalBestFit(vec3 n);
vec3 decodeNormalBestFit(uvec3 code);
uvec3 encodeNormalXyZSign(vec3 n, uint bits);
vec3 decodeNormalXyZSign(uvec3 code, uint bits);
uvec2 encodeNormalSpheremap(vec3 n, uint bits);
vec3 decodeNormalSpheremap(uvec2 code, uint bits);
uvec2 encodeNormalStereographic(vec3 n, uint bits);
vec3 decodeNormalStereographic(uvec2 code, uint bits);
vec2 signNotZero(vec2 v);
vec2 octEncode(vec3 n);
vec3 octDecode(vec2 e);
uvec2 encodeNormalOctahedral(vec3 n, uint bits);
vec3 decodeNormalOctahedral(uvec2 code, uint bits);
uvec2 encodeNormalOctahedralPrecise(vec3 n, uint bits);
vec3 decodeNormalOctahedralPrecise(uvec2 code, uint bits);

// 5. Colour transforms.
vec3 rgbToYCbCr(vec3 c);
vec3 yCbCrToRgb(vec3 c);
float lumaBt601(vec3 c);
vec3 rgbToYCbCrSqrt(vec3 c);
vec3 yCbCrSqrtToRgb(vec3 c);
vec3 rgbToYCoCg(vec3 c);
vec3 yCoCgToRgb(vec3 c);

// 6. Chroma checkerboard (Mavridis & Papaioannou 2012).
inline constexpr float kChromaEdgeThreshold = 0.11764706f;  // 30/255, the paper's THRESH
bool chromaIsSecond(ivec2 pixel);
float chromaForPixel(ivec2 pixel, vec2 chroma);
vec2 reconstructChroma(float lumaCentre, float chromaCentre, vec4 lumaNeighbours, vec4 chromaNeighbours);
vec2 reconstructChroma(ivec2 pixel, float lumaCentre, float chromaCentre, vec4 lumaNeighbours,
                       vec4 chromaNeighbours);

// 7. Roughness maps.
float glossFromRoughness(float r);
float roughnessFromGloss(float g);
float smoothnessFromRoughnessCry(float r);
float roughnessFromSmoothnessCry(float s);

// 8. UE4 specular colour, depth.
vec3 specularColorUE4(vec3 baseColor, float metallic, float specular);
uint quantizeDepth24(float d);
float dequantizeDepth24(uint code);
vec3 positionFromDepth(vec2 uv, float depth, mat4 invViewProj);

}  // namespace gbl::enc
