#pragma once
// `gbufferlab layouts ...`: check, list and show layout files. Each function takes the arguments
// after "layouts", writes to `out` (results) and `err` (problems), and returns the exit status.
#include <iosfwd>
#include <string>
#include <vector>

#include "layout.h"

namespace gbl {

// Dispatches "check FILE...", "list", "show NAME", "glsl NAME [--native-formats]"; prints usage and returns 2 otherwise.
int runLayoutsCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// Prints "ok FILE" per valid file, else its diagnostics (file:line:col: message); returns 1 when any
// file is invalid. With no files, checks every layout in the layouts directory.
int checkLayoutsCommand(const std::vector<std::string>& files, std::ostream& out, std::ostream& err);

// One line per layout in the layouts directory: name, year, bytes per pixel, provenance counts, title.
int listLayoutsCommand(std::ostream& out, std::ostream& err);

// A readable table of one layout (name or path): targets and their bits, stencil, bits per
// attribute, fallbacks, clear values, light buffers, bytes per pixel, and each entry's provenance
// (status and citations, known differences) with the citations in full.
int showLayoutCommand(const std::string& nameOrPath, std::ostream& out, std::ostream& err);
std::string describeLayout(const Layout& layout);

// The generated GLSL wiring of one layout (name or path), optionally in native-formats mode.
int printLayoutGlslCommand(const std::string& nameOrPath, bool nativeFormats, std::ostream& out, std::ostream& err);

}  // namespace gbl
