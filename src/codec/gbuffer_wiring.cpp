#include "gbuffer_wiring.h"

#include "layout_catalog.h"
#include "wiring_codegen.h"

namespace gbl {

GBufferWiring makeReferenceWiring() { return generateWiring(loadLayout("reference")); }

GBufferWiring makeReferenceWiring(int sceneLayers) { return generateWiring(loadReferenceLayout(sceneLayers)); }

}  // namespace gbl
