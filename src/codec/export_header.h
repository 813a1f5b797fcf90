#pragma once
// Internal to the layout export (layout_export.h): how a real target format stores a channel, and
// the header comment of an exported file (bit map, formats, clear values, what is derived instead
// of stored, provenance, and why the values written are exact).
#include <string>

#include "layout.h"

namespace gbl {

struct ExportOptions;

// What the hardware does with a channel's value on a write to a target of its real format.
enum class RealKind { Unorm, Snorm, Srgb, Float16, Float32, Float11, Float10, Uint };
RealKind realKind(const Target& t, const Channel& c);

// The // comment block at the top of an exported file. Layout text passes only through
// glslCommentText: printable ASCII, no backslash (which would continue a // comment).
std::string exportHeaderComment(const Layout& layout, const ExportOptions& options);

}  // namespace gbl
