#pragma once
// Where a layout stores an attribute, by shading model: the questions validation asks of a
// conditional field's reads and of the normal and roughness, which every pixel needs
// (layouts/README.md, "Shading models: the selector").
#include <cstdint>

#include "layout.h"

namespace gbl {

// Stored on every pixel of the models `models` (bit m = ShadingModel m): unconditionally, or by
// conditional fields whose models together include them.
inline bool storesUnder(const Layout& l, Attribute a, uint32_t models) {
    return l.storesAlways(a) || (models != 0 && (l.conditionalModels(a) & models) == models);
}

// Stored on every pixel of every model the selector names: unconditionally, or per model by
// fields that together cover the selector (UE's ClearCoat with r.ClearCoatNormal = 1 stores the
// normal in GBufferA under Default Lit and Cloth, in CustomData under ClearCoat).
inline bool storesOnEveryModel(const Layout& l, Attribute a) { return storesUnder(l, a, l.selectorModels()); }

}  // namespace gbl
