#pragma once
// Finding layouts: the layouts/ directory (env GBL_LAYOUT_DIR, else the source tree's layouts/
// fixed at build time), its layout names (file stems of *.toml), and loading one by name or path.
#include <filesystem>
#include <string>
#include <vector>

#include "layout.h"

namespace gbl {

// The directory layouts are read from. Throws UserError naming GBL_LAYOUT_DIR when it is missing.
std::filesystem::path layoutDirectory();

// Sorted names of the layouts in `dir` (the stems of its *.toml files).
std::vector<std::string> listLayoutNames(const std::filesystem::path& dir);
std::vector<std::string> listLayoutNames();

// `nameOrPath` is a layout name ("ue4": <dir>/ue4.toml) or a path to a .toml file (it contains a '/'
// or ends in ".toml"). Throws UserError for an unknown name (listing the known ones) and
// LayoutError for an invalid file.
std::filesystem::path findLayoutFile(const std::string& nameOrPath);
Layout loadLayout(const std::string& nameOrPath);

// The float reference of a scene whose materials have the layers `sceneLayers` (attributeLayerBit's
// bits; the renderer's GpuScene::layers): layouts/reference.toml less the fields of every layer no
// material has, the targets those fields leave empty and their [clear] values. A layer no material
// has decodes as 0 from either, so the image is the same bit for bit; a scene without layers writes
// and reads the five targets of a reference without them (80 bytes a pixel, not 128).
Layout loadReferenceLayout(int sceneLayers);

}  // namespace gbl
