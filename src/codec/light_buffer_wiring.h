#pragma once
// Deferred lighting's light buffers as code: the GLSL that quantises light into a layout's
// [[light_buffer]]s (its declared encodings, layouts/README.md) and the bit-exact CPU mirror.
//
// The light pre-pass (shaders/light_pre_pass.glsl) keeps, per pixel, the decoded value of every
// light buffer's four channels, ch[b]. Each light adds its diffuse and specular light, and the
// sum is written back through the buffer's format at once (blending reads, adds and stores at
// the format's precision, light by light):
//   ch[b] = decode_b(encode_b(ch[b] + channels_b(diffuse, specular)))
// The GLSL defines, for a deferred-lighting layout:
//   LIGHT_BUFFER_COUNT, LIGHT_BUFFER_WORDS (32-bit words per pixel, all buffers), LPP_FRESNEL
//   (0 none, 1 schlick_nv: [material_pass] fresnel), LPP_SPECULAR_LUMINANCE (1 when specular
//   light is kept as luminance only, Engel's light pre-pass);
//   void encodeLightBuffer<b>(vec4 v, inout uint w[LIGHT_BUFFER_WORDS]);
//   vec4 decodeLightBuffer<b>(uint w[LIGHT_BUFFER_WORDS]);
//   void accumulateLight(inout vec4 ch[LIGHT_BUFFER_COUNT], inout uint w[LIGHT_BUFFER_WORDS],
//                        vec3 diffuse, vec3 specular);
//   void lightFromBuffers(vec4 ch[LIGHT_BUFFER_COUNT], out vec3 diffuse, out vec3 specular).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "layout.h"

namespace gbl {

// 32-bit words of one pixel of a buffer, and of all the layout's buffers.
int lightBufferWords(const LightBuffer& buffer);
int lightBufferWordsPerPixel(const Layout& layout);
// RGBK's unit, range / 255^2 as a float (the GLSL literal is this float).
float rgbkUnit(const LightBuffer& buffer);

// The GLSL described above ("" for a deferred-shading layout).
std::string generateLightBufferGlsl(const Layout& layout);

// CPU mirror, per buffer: the four channel values -> words (lightBufferWords of them) and back.
void encodeLightBuffer(const LightBuffer& buffer, glm::vec4 channels, uint32_t* words);
glm::vec4 decodeLightBuffer(const LightBuffer& buffer, const uint32_t* words);
// What one light adds to a buffer's channels (its `holds`, in order; the rest 0).
glm::vec4 lightBufferChannels(const LightBuffer& buffer, glm::vec3 diffuse, glm::vec3 specular);
// accumulateLight: ch has one vec4 per buffer, words lightBufferWordsPerPixel(layout).
void accumulateLight(const Layout& layout, std::vector<glm::vec4>& ch, uint32_t* words, glm::vec3 diffuse,
                     glm::vec3 specular);

}  // namespace gbl
