#include "light_buffer_wiring.h"

#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "glsl_text.h"
#include "light_buffer_encodings.h"
#include "wiring_field_codegen.h"  // wiring::kComp

namespace gbl {

namespace {

using wiring::kComp;

const char* kChannel[] = {"r", "g", "b", "a"};

const TargetFormatInfo& formatOf(const LightBuffer& b) {
    const TargetFormatInfo* info = findTargetFormat(b.format);
    if (!info) throw std::logic_error("light buffer: unknown format " + b.format);
    return *info;
}

// Bit offset and width of logical channel i (r, g, b, a) in the buffer's pixel; width 0 when absent.
void channelPlace(const TargetFormatInfo& info, int i, int& offset, int& bits) {
    offset = 0;
    bits = 0;
    for (const Channel& c : info.channels)
        if (c.name == kChannel[i]) {
            offset = c.offset;
            bits = c.bits;
        }
}

uint32_t maskOf(int bits) { return bits >= 32 ? 0xffffffffu : (1u << bits) - 1u; }

bool holdsLuminance(const Layout& layout) {
    for (const LightBuffer& b : layout.lightBuffers)
        for (LightQuantity q : b.holds)
            if (q == LightQuantity::SpecularLuminance) return true;
    return false;
}

}  // namespace

int lightBufferWords(const LightBuffer& buffer) { return (formatOf(buffer).bits + 31) / 32; }

int lightBufferWordsPerPixel(const Layout& layout) {
    int n = 0;
    for (const LightBuffer& b : layout.lightBuffers) n += lightBufferWords(b);
    return n;
}

float rgbkUnit(const LightBuffer& buffer) { return float(buffer.range / 65025.0); }

void encodeLightBuffer(const LightBuffer& buffer, glm::vec4 v, uint32_t* words) {
    const TargetFormatInfo& info = formatOf(buffer);
    glm::uvec4 c(0u);
    switch (buffer.encoding) {
        case LightBufferEncoding::Float16:
            c = glm::uvec4(enc::encodeFloat16(v.x), enc::encodeFloat16(v.y), enc::encodeFloat16(v.z),
                           enc::encodeFloat16(v.w));
            break;
        case LightBufferEncoding::Float111110:
            c = glm::uvec4(enc::encodeFloat11(v.x), enc::encodeFloat11(v.y), enc::encodeFloat10(v.z), 0u);
            break;
        case LightBufferEncoding::Float7e3:
            c = glm::uvec4(enc::encodeFloat7e3(v.x), enc::encodeFloat7e3(v.y), enc::encodeFloat7e3(v.z), 0u);
            break;
        case LightBufferEncoding::Rgbk:
            c = enc::encodeRgbk(glm::vec3(v), rgbkUnit(buffer));
            break;
    }
    const int n = lightBufferWords(buffer);
    for (int k = 0; k < n; ++k) words[k] = 0u;
    for (int i = 0; i < 4; ++i) {
        int offset = 0, bits = 0;
        channelPlace(info, i, offset, bits);
        if (bits) words[offset / 32] |= (c[i] & maskOf(bits)) << (offset % 32);
    }
}

glm::vec4 decodeLightBuffer(const LightBuffer& buffer, const uint32_t* words) {
    const TargetFormatInfo& info = formatOf(buffer);
    glm::uvec4 c(0u);
    for (int i = 0; i < 4; ++i) {
        int offset = 0, bits = 0;
        channelPlace(info, i, offset, bits);
        if (bits) c[i] = (words[offset / 32] >> (offset % 32)) & maskOf(bits);
    }
    switch (buffer.encoding) {
        case LightBufferEncoding::Float16:
            return {enc::decodeFloat16(c.x), enc::decodeFloat16(c.y), enc::decodeFloat16(c.z), enc::decodeFloat16(c.w)};
        case LightBufferEncoding::Float111110:
            return {enc::decodeFloat11(c.x), enc::decodeFloat11(c.y), enc::decodeFloat10(c.z), 0.0f};
        case LightBufferEncoding::Float7e3:
            return {enc::decodeFloat7e3(c.x), enc::decodeFloat7e3(c.y), enc::decodeFloat7e3(c.z), 0.0f};
        case LightBufferEncoding::Rgbk:
            return glm::vec4(enc::decodeRgbk(c, rgbkUnit(buffer)), 0.0f);
    }
    return glm::vec4(0.0f);
}

glm::vec4 lightBufferChannels(const LightBuffer& buffer, glm::vec3 diffuse, glm::vec3 specular) {
    glm::vec4 v(0.0f);
    int i = 0;
    for (LightQuantity q : buffer.holds) {
        if (q == LightQuantity::SpecularLuminance) {
            if (i < 4) v[i++] = enc::lightLuminance(specular);
            continue;
        }
        const glm::vec3 x = q == LightQuantity::DiffuseRgb ? diffuse : specular;
        for (int c = 0; c < 3 && i < 4; ++c) v[i++] = x[c];
    }
    return v;
}

void accumulateLight(const Layout& layout, std::vector<glm::vec4>& ch, uint32_t* words, glm::vec3 diffuse,
                     glm::vec3 specular) {
    uint32_t* w = words;
    for (size_t b = 0; b < layout.lightBuffers.size(); ++b) {
        const LightBuffer& lb = layout.lightBuffers[b];
        ch[b] = ch[b] + lightBufferChannels(lb, diffuse, specular);
        encodeLightBuffer(lb, ch[b], w);
        ch[b] = decodeLightBuffer(lb, w);
        w += lightBufferWords(lb);
    }
}

std::string generateLightBufferGlsl(const Layout& layout) {
    if (layout.pipeline != Pipeline::DeferredLighting || layout.lightBuffers.empty()) return "";
    std::ostringstream o;
    o << "// generated from the layout '" << glslCommentText(layout.name)
      << "' by gbufferlab -- do not edit: the light buffers (src/codec/light_buffer_wiring.h)\n";
    o << "#include \"light_buffer_encodings.glsl\"\n";
    o << "#define LIGHT_BUFFER_COUNT " << layout.lightBuffers.size() << "\n";
    o << "#define LIGHT_BUFFER_WORDS " << lightBufferWordsPerPixel(layout) << "\n";
    o << "#define LPP_FRESNEL " << (layout.materialPass.fresnel == MaterialFresnel::SchlickNv ? 1 : 0) << "\n";
    o << "#define LPP_SPECULAR_LUMINANCE " << (holdsLuminance(layout) ? 1 : 0) << "\n";
    int first = 0;
    for (size_t b = 0; b < layout.lightBuffers.size(); ++b) {
        const LightBuffer& lb = layout.lightBuffers[b];
        const TargetFormatInfo& info = formatOf(lb);
        std::string holds;
        for (LightQuantity q : lb.holds) holds += std::string(holds.empty() ? "" : ", ") + lightQuantityName(q);
        o << "\n// light buffer " << b << " '" << glslCommentText(lb.name) << "': " << lb.format << ", "
          << lightBufferEncodingName(lb.encoding);
        if (lb.encoding == LightBufferEncoding::Rgbk) o << " (range " << lb.range << ")";
        o << "; holds " << holds << "\n";
        const std::string unit = glslFloatLiteral(rgbkUnit(lb));
        // encode
        o << "void encodeLightBuffer" << b << "(vec4 v, inout uint w[LIGHT_BUFFER_WORDS]) {\n";
        switch (lb.encoding) {
            case LightBufferEncoding::Float16:
                o << "    uvec4 c = uvec4(encodeFloat16(v.x), encodeFloat16(v.y), encodeFloat16(v.z), "
                     "encodeFloat16(v.w));\n";
                break;
            case LightBufferEncoding::Float111110:
                o << "    uvec4 c = uvec4(encodeFloat11(v.x), encodeFloat11(v.y), encodeFloat10(v.z), 0u);\n";
                break;
            case LightBufferEncoding::Float7e3:
                o << "    uvec4 c = uvec4(encodeFloat7e3(v.x), encodeFloat7e3(v.y), encodeFloat7e3(v.z), 0u);\n";
                break;
            case LightBufferEncoding::Rgbk:
                o << "    uvec4 c = encodeRgbk(v.xyz, " << unit << ");\n";
                break;
        }
        const int n = lightBufferWords(lb);
        for (int k = 0; k < n; ++k) o << "    w[" << first + k << "] = 0u;\n";
        for (int i = 0; i < 4; ++i) {
            int offset = 0, bits = 0;
            channelPlace(info, i, offset, bits);
            if (!bits) continue;
            o << "    w[" << first + offset / 32 << "] |= (c." << kComp[i] << " & " << maskOf(bits) << "u) << "
              << offset % 32 << "u;\n";
        }
        o << "}\n";
        // decode
        o << "vec4 decodeLightBuffer" << b << "(uint w[LIGHT_BUFFER_WORDS]) {\n    uvec4 c = uvec4(0u);\n";
        for (int i = 0; i < 4; ++i) {
            int offset = 0, bits = 0;
            channelPlace(info, i, offset, bits);
            if (!bits) continue;
            o << "    c." << kComp[i] << " = (w[" << first + offset / 32 << "] >> " << offset % 32 << "u) & "
              << maskOf(bits) << "u;\n";
        }
        switch (lb.encoding) {
            case LightBufferEncoding::Float16:
                o << "    return vec4(decodeFloat16(c.x), decodeFloat16(c.y), decodeFloat16(c.z), decodeFloat16(c.w));\n";
                break;
            case LightBufferEncoding::Float111110:
                o << "    return vec4(decodeFloat11(c.x), decodeFloat11(c.y), decodeFloat10(c.z), 0.0);\n";
                break;
            case LightBufferEncoding::Float7e3:
                o << "    return vec4(decodeFloat7e3(c.x), decodeFloat7e3(c.y), decodeFloat7e3(c.z), 0.0);\n";
                break;
            case LightBufferEncoding::Rgbk:
                o << "    return vec4(decodeRgbk(c, " << unit << "), 0.0);\n";
                break;
        }
        o << "}\n";
        // what one light adds
        o << "vec4 lightBufferChannels" << b << "(vec3 diffuse, vec3 specular) {\n    vec4 v = vec4(0.0);\n";
        int i = 0;
        for (LightQuantity q : lb.holds) {
            if (q == LightQuantity::SpecularLuminance) {
                if (i < 4) o << "    v." << kComp[i++] << " = lightLuminance(specular);\n";
                continue;
            }
            const char* x = q == LightQuantity::DiffuseRgb ? "diffuse" : "specular";
            for (int c = 0; c < 3 && i < 4; ++c) o << "    v." << kComp[i++] << " = " << x << "." << kComp[c] << ";\n";
        }
        o << "    return v;\n}\n";
        first += n;
    }
    o << "\nvoid accumulateLight(inout vec4 ch[LIGHT_BUFFER_COUNT], inout uint w[LIGHT_BUFFER_WORDS], vec3 diffuse,\n"
         "                     vec3 specular) {\n";
    for (size_t b = 0; b < layout.lightBuffers.size(); ++b) {
        o << "    ch[" << b << "] = ch[" << b << "] + lightBufferChannels" << b << "(diffuse, specular);\n";
        o << "    encodeLightBuffer" << b << "(ch[" << b << "], w);\n";
        o << "    ch[" << b << "] = decodeLightBuffer" << b << "(w);\n";
    }
    o << "}\n";
    // read back: diffuse light and specular light (luminance-only specular takes the diffuse
    // light's chromaticity, Engel 2008-09)
    o << "\nvoid lightFromBuffers(vec4 ch[LIGHT_BUFFER_COUNT], out vec3 diffuse, out vec3 specular) {\n"
         "    diffuse = vec3(0.0);\n    specular = vec3(0.0);\n    float specularLuminance = 0.0;\n";
    for (size_t b = 0; b < layout.lightBuffers.size(); ++b) {
        int i = 0;
        for (LightQuantity q : layout.lightBuffers[b].holds) {
            if (q == LightQuantity::SpecularLuminance) {
                if (i < 4) o << "    specularLuminance = ch[" << b << "]." << kComp[i++] << ";\n";
                continue;
            }
            const char* x = q == LightQuantity::DiffuseRgb ? "diffuse" : "specular";
            o << "    " << x << " = vec3(ch[" << b << "]." << kComp[i] << ", ch[" << b << "]." << kComp[i + 1]
              << ", ch[" << b << "]." << kComp[i + 2] << ");\n";
            i += 3;
        }
    }
    if (holdsLuminance(layout))
        o << "    float diffuseLuminance = lightLuminance(diffuse);\n"
             "    specular = diffuseLuminance > 1e-8 ? diffuse * (specularLuminance / diffuseLuminance)\n"
             "                                       : vec3(specularLuminance);\n";
    o << "}\n";
    return o.str();
}

}  // namespace gbl
