#include "shader_compiler.h"

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <regex>
#include <sstream>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include "error.h"
#include "file_io.h"
#include "shader_cache.h"
#include "stage_clock.h"
#include "vk_context.h"

namespace gbl {
namespace fs = std::filesystem;

namespace {

std::once_flag glslangInitOnce;

void initGlslang() {
    std::call_once(glslangInitOnce, [] {
        glslang::InitializeProcess();
        std::atexit([] { glslang::FinalizeProcess(); });
    });
}

EShLanguage toGlslangStage(VkShaderStageFlagBits stage) {
    switch (stage) {
        case VK_SHADER_STAGE_VERTEX_BIT: return EShLangVertex;
        case VK_SHADER_STAGE_FRAGMENT_BIT: return EShLangFragment;
        default: return EShLangCompute;
    }
}

// Resolves #include "x" against the virtual files first, then shaders/.
class Includer : public glslang::TShader::Includer {
public:
    Includer(const std::map<std::string, std::string>& virtualFiles, std::map<std::string, std::string>& seen)
        : virtualFiles_(virtualFiles), seen_(seen) {}

    IncludeResult* includeLocal(const char* headerName, const char*, size_t) override { return resolve(headerName); }
    IncludeResult* includeSystem(const char* headerName, const char*, size_t) override { return resolve(headerName); }
    void releaseInclude(IncludeResult* result) override {
        if (result) delete static_cast<std::string*>(result->userData);
        delete result;
    }

private:
    IncludeResult* resolve(const std::string& name) {
        std::optional<std::string> found = resolveShaderInclude(name, virtualFiles_);
        if (!found) return nullptr;  // glslang reports "cannot find include file" with the line
        auto* text = new std::string(std::move(*found));
        seen_[name] = *text;
        return new IncludeResult(name, text->data(), text->size(), text);
    }
    const std::map<std::string, std::string>& virtualFiles_;
    std::map<std::string, std::string>& seen_;
};

// Prints lines [line-2, line+2] of `text` with numbers, marking `line`.
std::string sourceContext(const std::string& text, int line) {
    std::istringstream in(text);
    std::string l, out;
    for (int n = 1; std::getline(in, l); ++n) {
        if (n < line - 2 || n > line + 2) continue;
        out += (n == line ? " >" : "  ") + std::to_string(n) + " | " + l + "\n";
    }
    return out;
}

// glslang logs "ERROR: <file>:<line>: message"; show the source around each such line.
std::string explainLog(const std::string& log, const ShaderSource& src, const std::map<std::string, std::string>& files) {
    std::string out;
    static const std::regex re(R"((ERROR|WARNING): ([^:\n]*):(\d+): )");
    int shown = 0;
    for (auto it = std::sregex_iterator(log.begin(), log.end(), re); it != std::sregex_iterator() && shown < 5;
         ++it, ++shown) {
        const std::string file = (*it)[2];
        const int line = std::stoi((*it)[3]);
        const std::string* text = nullptr;
        if (file == src.name || file.empty() || file == "0") text = &src.text;
        else if (auto f = files.find(file); f != files.end()) text = &f->second;
        if (text) out += "in " + (text == &src.text ? src.name : file) + " line " + std::to_string(line) + ":\n" +
                         sourceContext(*text, line);
    }
    return out;
}

}  // namespace

std::string shaderDirectory() {
    if (const char* dir = std::getenv("GBL_SHADER_DIR"); dir && *dir) return dir;
    return GBL_SOURCE_SHADER_DIR;
}

std::optional<std::string> resolveShaderInclude(const std::string& name,
                                                const std::map<std::string, std::string>& virtualFiles) {
    if (auto v = virtualFiles.find(name); v != virtualFiles.end()) return v->second;
    const fs::path path = fs::path(shaderDirectory()) / name;
    if (!fs::exists(path)) return std::nullopt;
    return readTextFile(path);
}

ShaderSource loadShaderFile(const std::string& fileName) {
    ShaderSource s;
    s.name = fileName;
    const fs::path path = fs::path(shaderDirectory()) / fileName;
    if (!fs::exists(path))
        throwUserError(path.string() + ": shader file not found (set GBL_SHADER_DIR to the shaders/ directory)");
    s.text = readTextFile(path);
    if (fileName.find(".vert.") != std::string::npos) s.stage = VK_SHADER_STAGE_VERTEX_BIT;
    else if (fileName.find(".frag.") != std::string::npos) s.stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    else s.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    return s;
}

std::vector<uint32_t> compileGlsl(const ShaderSource& src) {
    ScopedStage timed(Stage::ShaderCompile);
    ShaderCacheCounters& counters = shaderCacheCounters();
    const bool cached = shaderCacheEnabled();
    uint64_t key = 0;
    fs::path cacheFile;
    if (cached) {
        key = spirvCacheKey(src);
        cacheFile = spirvCacheFile(key);
        std::string why;
        if (auto spirv = readSpirvCache(cacheFile, key, &why)) {
            ++counters.spirvCacheHits;
            return std::move(*spirv);
        }
        if (!why.empty()) ++counters.spirvCacheInvalid;  // corrupt or truncated: compiled and rewritten
    }
    std::vector<uint32_t> spirv = compileGlslUncached(src);
    if (cached) {
        try {
            writeSpirvCache(cacheFile, key, spirv);
        } catch (const std::exception&) {
            // A read-only or full cache directory costs the next run a compile, nothing else.
        }
    }
    return spirv;
}

namespace {

std::vector<uint32_t> compileUncached(const ShaderSource& src, const std::string* hlslEntry) {
    ScopedStage timed(Stage::ShaderCompile);
    ++shaderCacheCounters().glslangCompiles;
    initGlslang();
    const EShLanguage stage = toGlslangStage(src.stage);
    glslang::TShader shader(stage);
    const char* text = src.text.c_str();
    const char* name = src.name.c_str();
    shader.setStringsWithLengthsAndNames(&text, nullptr, &name, 1);
    std::string preamble;
    for (const auto& [k, v] : src.defines) preamble += "#define " + k + " " + v + "\n";
    shader.setPreamble(preamble.c_str());
    shader.setEnvInput(hlslEntry ? glslang::EShSourceHlsl : glslang::EShSourceGlsl, stage, glslang::EShClientVulkan, 100);
    if (hlslEntry) {
        shader.setEntryPoint("main");
        shader.setSourceEntryPoint(hlslEntry->c_str());
    }
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
    // SPIR-V 1.5: 1.6 would emit LocalSizeId, which needs maintenance4 for no gain here. HLSL:
    // 1.3, as glslang 12's HLSL front end decorates structured buffers BufferBlock (gone in 1.4).
    shader.setEnvTarget(glslang::EShTargetSpv, hlslEntry ? glslang::EShTargetSpv_1_3 : glslang::EShTargetSpv_1_5);

    std::map<std::string, std::string> included;
    Includer includer(src.virtualFiles, included);
    const auto messages = EShMessages(EShMsgSpvRules | EShMsgVulkanRules | (hlslEntry ? int(EShMsgReadHlsl) : 0));
    if (!shader.parse(GetDefaultResources(), hlslEntry ? 100 : 450, false, messages, includer)) {
        const std::string log = shader.getInfoLog();
        throw ShaderCompileError("shader " + src.name + " failed to compile:\n" + explainLog(log, src, included) +
                                 "glslang log:\n" + log);
    }
    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages))
        throw ShaderCompileError("shader " + src.name + " failed to link:\n" + program.getInfoLog());
    std::vector<uint32_t> spirv;
    glslang::SpvOptions options;
    options.disableOptimizer = true;  // spirv-opt gave no speed-up on lavapipe (STACK-FACTS)
    glslang::GlslangToSpv(*program.getIntermediate(stage), spirv, &options);
    return spirv;
}

}  // namespace

std::vector<uint32_t> compileGlslUncached(const ShaderSource& src) { return compileUncached(src, nullptr); }

std::vector<uint32_t> compileHlslUncached(const ShaderSource& src, const std::string& entry) {
    return compileUncached(src, &entry);
}

VkShaderModule createShaderModule(VkDevice device, const std::vector<uint32_t>& spirv) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = spirv.size() * sizeof(uint32_t);
    info.pCode = spirv.data();
    VkShaderModule module;
    VK_CHECK(vkCreateShaderModule(device, &info, nullptr, &module));
    return module;
}

}  // namespace gbl
