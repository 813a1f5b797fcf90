#pragma once
// Error policy (after Falcor's): asserts for our own bugs; a UserError for anything the user
// can fix (a file, a flag, a missing driver). A UserError's message is one line that names the
// file or flag, the place, what is wrong and the fix; main() prints it and exits non-zero.
#include <stdexcept>
#include <string>
#include <string_view>

namespace gbl {

struct UserError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Builds "file: message" (or "file:line:col: message" when line > 0).
std::string formatPlace(const std::string& file, int line = 0, int column = 0);

[[noreturn]] void throwUserError(const std::string& message);

// Text from a file or flag made safe for a one-line message: control characters, backslashes
// and quotes become C-style escapes (\n, \\, \', \xNN), so a name can neither break the line
// nor put control bytes on the terminal. Well-formed UTF-8 is kept as it is ("über.png" prints
// as über.png), except the code points that would break the line or hide or reorder the text
// around them (C1 controls, Unicode line and paragraph separators, zero-width and bidirectional
// marks, the BOM): those, and bytes that are not UTF-8, are escaped byte by byte.
std::string escapeText(std::string_view text);
// escapeText in single quotes (not "quoted": std::quoted would be found by ADL): the way messages quote names.
std::string quoteName(std::string_view text);
// Every byte >= 0x80 escaped too: for messages about the characters themselves (a layout file's
// non-ASCII character outside a string), where a lookalike must not pass for ASCII.
std::string escapeBytes(std::string_view text);
std::string quoteBytes(std::string_view text);

// The JSON library's parse error as gbufferlab's own: "file:line:col: not valid JSON: what",
// the place computed from the byte offset it reports, its "[json.exception...] parse error at
// ..." prefix dropped and the rest escaped (it quotes bytes from the file).
std::string jsonParseErrorMessage(const std::string& file, std::string_view text, size_t byte, const std::string& what);

}  // namespace gbl
