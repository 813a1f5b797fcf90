#pragma once
// The layout's wiring, generated from its data (layouts/*.toml via src/layout/layout.h): GLSL text that
// writes and reads the G-buffer (writeGBuffer / readGBuffer, see gbuffer_wiring.h), plus the
// render-target formats. Nothing about a particular layout is written here: every shift and
// mask comes from the layout's bit places. src/codec/cpu_codec.h interprets the same data on the CPU,
// bit for bit identically (tests/codec/gpu_cpu_bits_test.cpp).
//
// Bits: a target's pixel is a little-endian bit string, word k holds bits [32k, 32k + 32); a code's
// low bits go in its first piece. Targets of <= 32 bits render as one R8/R16/R32_UINT word,
// 64-bit ones as R32G32_UINT, 128-bit ones as R32G32B32A32_UINT.
//
// Attributes a layout does not store come from its declared fallbacks, applied in readGBuffer in
// dependency order (orderedFallbacks). Two fallbacks need the renderer's help:
//   forward        (emissive): writeGBuffer stores nothing, readGBuffer returns vec3(0);
//                  GBufferWiring::emissiveForward tells the renderer to add emissive in a forward pass.
//   material_pass  (deferred lighting): the attributes come from a second geometry pass at full
//                  precision. Compiled with MATERIAL_PASS_WRITE defined, the generated
//                  writeGBuffer writes `materialTarget<i>` (R32G32B32A32_UINT, float32 bits of the
//                  attributes in materialPassSlots order) instead of the G-buffer; under
//                  GBUFFER_READ, readGBuffer reads them from `usampler2D materialTarget<i>` at
//                  set 2, binding i. GBufferWiring::materialPass / materialTargetFormats say so.
// Stencil extras are constants the renderer writes through the stencil reference; no code here.
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "gbuffer_wiring.h"
#include "layout.h"
#include "wiring_plan.h"

namespace gbl {

struct WiringOptions {
    // Render targets with their real formats (UNORM / SRGB / SFLOAT / UFLOAT) where every field maps
    // one code onto one whole channel with the matching native encoding (nativeFormatObstacle);
    // the shader then writes floats and the hardware quantises. Other targets stay UINT.
    bool nativeFormats = false;
};

GBufferWiring generateWiring(const Layout& layout, const WiringOptions& options = {});

// A field of `layout` is encoded with normal_bestfit: writing its G-buffer needs the best-fit
// table (GBufferWiring::bestFitTable; compare starts generating it early, prefetchBestFitNormalTable).
bool usesBestFitTable(const Layout& layout);
// The GLSL alone, with a "generated from the layout 'NAME' by gbufferlab -- do not edit" header
// (the name, not a file: the same layout read from anywhere gives the same text, and the same
// shader cache entries).
std::string generateWiringGlsl(const Layout& layout, const WiringOptions& options = {});

// "" when `target` can render with its native format in nativeFormats mode, else why not.
std::string nativeFormatObstacle(const Target& target);

}  // namespace gbl
