#pragma once
// Turns a Genome (search_space.h) into layout text: the fields it stores, packed into render
// targets of real formats (R8, RG8, R16, RGBA8, RGB10A2, RG16, R32UI, RGBA16, RG32UI) under a
// byte budget that counts every target and the depth-stencil attachment, as bytesPerPixel
// (layout.h) and measure/bandwidth.h count them. The text is then read by the real parser and
// validator (parseLayout): a candidate exists only if `gbufferlab layouts check` accepts it.
#include <functional>
#include <string>
#include <vector>

#include "search_space.h"

namespace gbl::search {

// One field the genome stores: its attribute, encoding and the width of each code, in the
// encoding's code order.
struct PlannedField {
    std::string attribute;
    std::string encoding;
    std::vector<int> codeBits;
    // A layer's field under a shading-model selector (Genome::layerSelector): the model it is held
    // under ("clear_coat", "cloth", "anisotropic"); empty: an unconditional field. The selector
    // itself is attribute "shading_model", encoding "id".
    std::string model;
    int totalBits() const;
};

std::vector<PlannedField> plannedFields(const Genome& g);

struct PackResult {
    bool ok = false;
    std::string why;   // when !ok: "needs 18 bytes per pixel, over the budget of 16", ...
    std::string body;  // the layout text after the name line (canonical: equal genomes, equal text)
    int bytesPerPixel = 0;
};

// Packs the genome's fields: first-fit decreasing by bits into 32-bit bins (64-bit for a field
// wider than 32), each bin then given the smallest real format whose channels hold its codes
// without splitting one across channels. Fails over `budgetBytes` or past 8 targets. With a
// selector, the layers' fields of each model are placed in one target of their own, every model's
// from its first bit (they share the bits: each pixel holds one model's), and the selector (2 bits:
// default 0, clear_coat 1, cloth 2, anisotropic 3) is packed like any field.
PackResult packGenome(const Genome& g, int budgetBytes);

// The fewest bytes per pixel a genome packs into: every encoding at its fewest bits, the
// smallest depth format, and nothing stored that a fallback can supply (metallic, occlusion,
// specular), over every choice of normal, roughness and colour encoding. A budget below it
// admits no layout at all (search refuses it before rendering).
int smallestPackedBytes();
// The same over genomes first passed through `adjust` (search_constraints.h: the engine
// constraints); an empty function adjusts nothing.
int smallestPackedBytes(const std::function<void(Genome&)>& adjust);

// The whole file: `comment` (each line prefixed "# "), then name, then body.
std::string layoutText(const std::string& name, const std::string& comment, const std::string& body);

}  // namespace gbl::search
