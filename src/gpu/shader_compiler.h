#pragma once
// GLSL -> SPIR-V at run time with glslang as a library. Shaders live in shaders/ and may
// #include other files from there or "virtual" files held in memory (the generated layout
// wiring). A compile error throws ShaderCompileError whose message names the shader, prints the
// offending source lines with line numbers, and glslang's log.
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace gbl {

struct ShaderCompileError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct ShaderSource {
    std::string name;  // for messages: "lighting_pass.comp.glsl" or "generated wiring of ue4"
    std::string text;
    VkShaderStageFlagBits stage = VK_SHADER_STAGE_COMPUTE_BIT;
    std::vector<std::pair<std::string, std::string>> defines;  // #define NAME VALUE
    std::map<std::string, std::string> virtualFiles;          // include name -> text
};

// The shaders/ directory: $GBL_SHADER_DIR, else the source tree's shaders/.
std::string shaderDirectory();
// Reads shaders/<fileName> into a ShaderSource with the stage taken from the name
// (*.vert.glsl, *.frag.glsl, *.comp.glsl).
ShaderSource loadShaderFile(const std::string& fileName);

// What `#include "name"` reads: the virtual file of that name, else shaders/<name>; nullopt when
// neither exists. The SPIR-V cache key (shader_cache.h) resolves includes through this too.
std::optional<std::string> resolveShaderInclude(const std::string& name,
                                                const std::map<std::string, std::string>& virtualFiles);

// SPIR-V from the disk cache (shader_cache.h) when it holds this exact input, else glslang (and
// the result is stored). Both are timed as Stage::ShaderCompile.
std::vector<uint32_t> compileGlsl(const ShaderSource& source);
// glslang, always (tests, and the cache's miss path).
std::vector<uint32_t> compileGlslUncached(const ShaderSource& source);

// HLSL through glslang's HLSL front end (what `glslangValidator -D -e ENTRY` runs), uncached:
// for the layouts export's tests. Entry point `entry`, renamed to "main" in the SPIR-V.
std::vector<uint32_t> compileHlslUncached(const ShaderSource& source, const std::string& entry = "main");

VkShaderModule createShaderModule(VkDevice device, const std::vector<uint32_t>& spirv);

}  // namespace gbl
