#pragma once
// A structural check of a Radiance .hdr byte stream, run before stb_image decodes it.
// Why: stb_image does not notice a truncated file (past the end it reads zeros), and a zero
// run-length byte makes its RLE loop spin forever; so a cut-off download would either hang
// or load as a silently black lower half. This walks the same structure stb decodes.
#include <cstddef>
#include <string>

namespace gbl {

// Returns "" when the pixel data is complete and well formed, otherwise what is wrong (one
// phrase, no file name). Header problems (bad magic, format, resolution line) return "" too:
// stb_image reports those itself, with its own reason.
std::string findRadianceStreamProblem(const unsigned char* bytes, size_t size);

}  // namespace gbl
