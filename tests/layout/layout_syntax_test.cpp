// The layout language's syntax and names: TOML syntax errors (including the inputs toml++ 3.3.0
// must never see, src/layout/layout_toml_guard.cpp), unknown keys, types and names, each with its
// file:line:col.
#include "layout_test_support.h"

using namespace gbl;
using namespace gbl::layout_test;

// ---- syntax -------------------------------------------------------------------------------------

TEST(LayoutParser, TomlSyntaxErrorUsesTomlPlusPlusPlace) {
    const std::string text = edit(kValid, "title = \"A test layout\"", "title = \"A test layout");
    // the place toml++ itself reports
    std::string tomlPlace;
    try {
        (void)toml::parse(std::string_view(text), std::string_view(kFile));
    } catch (const toml::parse_error& e) {
        tomlPlace = std::string(kFile) + ":" + std::to_string(e.source().begin.line) + ":" +
                    std::to_string(e.source().begin.column);
    }
    ASSERT_FALSE(tomlPlace.empty());
    EXPECT_EQ(tomlPlace.substr(0, std::string(kFile).size() + 3), std::string(kFile) + ":2:");
    expectOnlyError(text, tomlPlace, {"TOML syntax error"});
}

// toml++ 3.3.0 assumes, without checking, that a table header's first character after '[' (or
// "[[") can start a key; "[#" (2 bytes: the crash scripts/fuzz.sh found, minimised with
// -minimize_crash=1) tripped its assertion in parse_key. The parser refuses such a header itself,
// at the place toml++ names, before toml++ sees the text (layout_toml_guard.cpp).
TEST(LayoutParser, TableHeaderWithoutAKeyIsRefusedBeforeTomlPlusPlusSeesIt) {
    const std::string file(kFile);
    struct Case {
        std::string text, place, saw;
    };
    const std::vector<Case> cases = {
        {"[#", file + ":1:2", "saw '#'"},  // the fuzzer's minimised input
        {"[&", file + ":1:2", "saw '&'"},
        {"[ +x]", file + ":1:3", "saw '+'"},
        {"[[ {}]]", file + ":1:4", "saw '{'"},
        {"[[[1]]]", file + ":1:3", "saw '['"},
        {"[\n", file + ":1:2", "saw the end of the line"},
        {"[\r\n", file + ":1:2", "saw the end of the line"},
        {"[\x01]", file + ":1:2", "saw '\\x01'"},
        {"[\xc3\xa9]", file + ":1:2", "saw '\\xc3\\xa9'"},
        {"\xEF\xBB\xBF[#", file + ":1:2", "saw '#'"},  // a BOM is not a column
        {edit(kValid, "[depth]", "[#depth]"), placeOf(kValid, "depth]"), "saw '#'"},
        {edit(kValid, "[[target]]", "[[=target]]"), placeOf(kValid, "target]]"), "saw '='"},
        {"[[\t=x]]", file + ":1:4", "saw '='"},
        // after a multi-line string, a multi-line array, an inline table and comments holding brackets
        {"a = \"\"\"\n[x\n\"\"\"\nb = [\n  [1],\n  '[', # [\n]\n# [#\nc = { d = \"]\" }\n[.e]\n", file + ":10:2",
         "saw '.'"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(escapeText(c.text));
        const auto diags = checkLayout(c.text, kFile);
        ASSERT_EQ(diags.size(), 1u) << joined(diags);
        const std::string t = diags[0].text();
        EXPECT_EQ(t.rfind(c.place + ": TOML syntax error: a table header must start with a key", 0), 0u) << t;
        EXPECT_NE(t.find(c.saw), std::string::npos) << t;
        EXPECT_EQ(t.find('\n'), std::string::npos) << t;
    }
    // The same place toml++ names where it reports the error itself (the Release build: g++, NDEBUG).
    try {
        (void)toml::parse(std::string_view("[ +x]"), std::string_view(kFile));
        ADD_FAILURE() << "toml++ accepted '[ +x]'";
    } catch (const toml::parse_error& e) {
        EXPECT_EQ(e.source().begin.line, 1u);
        EXPECT_EQ(e.source().begin.column, 3u);
    }
}

// The second toml++ 3.3.0 precondition the fuzzer broke: parse_array() hands '}' (or a Unicode
// line break) to parse_value(), which assumes no value terminator follows. "l=[}" (4 bytes) is
// the minimised input that tripped its assertion.
TEST(LayoutParser, ValueTerminatorInAnArrayIsRefusedBeforeTomlPlusPlusSeesIt) {
    const std::string file(kFile);
    struct Case {
        std::string text, place, words;
    };
    const std::vector<Case> cases = {
        {"l=[}", file + ":1:4", "'}' in an array"},  // the fuzzer's minimised input
        {"l = [ 1,\n  # }\n  }", file + ":3:3", "'}' in an array"},
        {"l = [[{a = [1]}], }]", file + ":1:19", "'}' in an array"},
        {"l = [1,\n\xe2\x80\xa8]", file + ":2:1", "'\\xe2\\x80\\xa8' (a Unicode line break) in an array"},
        {"l = [\xc2\x85]", file + ":1:6", "'\\xc2\\x85' (a Unicode line break) in an array"},
        {edit(kValid, "stencil = [ {", "stencil = [ } {"), placeOf(kValid, "{ attribute = \"ambient_id\""), "'}' in an array"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(escapeText(c.text));
        const auto diags = checkLayout(c.text, kFile);
        ASSERT_EQ(diags.size(), 1u) << joined(diags);
        const std::string t = diags[0].text();
        EXPECT_EQ(t.rfind(c.place + ": TOML syntax error: " + c.words, 0), 0u) << t;
        EXPECT_EQ(t.find('\n'), std::string::npos) << t;
    }
}

// The third: toml++ 3.3.0's is_non_ascii_horizontal_whitespace() reaches TOML_UNREACHABLE for
// U+00A1..U+0499 ('é', Greek, Cyrillic), asked of characters outside strings (UBSan, on the
// fuzzer's " \xcf\x9al+f%%%%=h...") and after a line-ending backslash in a multi-line string.
TEST(LayoutParser, NonAsciiOutsideStringsIsRefusedBeforeTomlPlusPlusSeesIt) {
    const std::string file(kFile);
    struct Case {
        std::string text, place, words;
    };
    const std::vector<Case> cases = {
        {" \xcf\x9al+f%%%%=h", file + ":1:2", "non-ASCII character '\\xcf\\x9a' outside a string"},
        {"\xc3\xa9 = 1", file + ":1:1", "non-ASCII character '\\xc3\\xa9'"},
        {"a = 1 \xc3\xa9", file + ":1:7", "non-ASCII character"},
        {"a = [1, \xd0\x96]", file + ":1:9", "non-ASCII character"},
        {"[a \xc3\xa9]", file + ":1:4", "non-ASCII character"},
        // a quote inside a bare value does not start a string: toml++ scans on (fuzzer, minimised)
        {"t=0\"\xc8\xb8", file + ":1:5", "non-ASCII character '\\xc8\\xb8'"},
        {"t = true'\xc3\xa9'", file + ":1:10", "non-ASCII character"},
        {"a = \"\"\"x\\\n   \xc3\xa9\"\"\"", file + ":2:4", "'\\xc3\\xa9' right after a line-ending backslash"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(escapeText(c.text));
        const auto diags = checkLayout(c.text, kFile);
        ASSERT_EQ(diags.size(), 1u) << joined(diags);
        const std::string t = diags[0].text();
        EXPECT_EQ(t.rfind(c.place + ": TOML syntax error: ", 0), 0u) << t;
        EXPECT_NE(t.find(c.words), std::string::npos) << t;
    }
    // Strings and comments may hold any of them.
    for (const std::string text : {"a = \"caf\xc3\xa9\" # \xc3\xa9\n", "\"\xc3\xa9\" = 1\n",
                                   "a.\"\xc3\xa9\" = [\"\xc3\xa9\",'\xc3\xa9']\n",
                                   "a = {b.\"\xc3\xa9\" = \"\xc3\xa9\", \"\xc3\xa9\" = 1}\n", "a = '''\n\xd0\x96'''\n"})
        for (const auto& d : checkLayout(text, kFile))
            EXPECT_EQ(d.message.find("TOML syntax error"), std::string::npos) << d.text();
}

// The guard refuses nothing that toml++ reads: brackets and '#' in strings, multi-line strings,
// comments, arrays of arrays and inline tables; valid headers with spaces or quoted keys.
TEST(LayoutParser, TableHeaderGuardLeavesValidTomlAlone) {
    const std::vector<std::string> texts = {
        "a = \"[#\"\nb = '[&'\n",
        "a = \"\"\"\n[#\n[&\"\"\"\"\nb = '''\n[+\n'''''\n",
        "a = \"x\\\"\\\\\"\n[ b ]\n[[ c ]]\n[\"d\".'e']\n[ 'f' . g]\n",
        "a = [\n  [+1, -2],\n  [{x = 1}],\n  [ # [#\n  ],\n]\n[b]\n",
        "a = { b = [\n[+1]\n], c = \"[#\" }\n[[d]]\n",
        "# [#\n  # [&\n\t[e]\r\n[f] # [#\n",
        "\xEF\xBB\xBF[a]\n",
    };
    for (const std::string& text : texts) {
        SCOPED_TRACE(escapeText(text));
        EXPECT_NO_THROW((void)toml::parse(std::string_view(text), std::string_view(kFile)));
        for (const auto& d : checkLayout(text, kFile))
            EXPECT_EQ(d.message.find("TOML syntax error"), std::string::npos) << d.text();
    }
}

TEST(LayoutParser, UnknownKeyNamesTheKnownOnes) {
    const std::string text = edit(kValid, "encoding = \"gloss\"", "encodng = \"gloss\"");
    expectError(text, placeOf(text, "encodng"), {"unknown key 'encodng'", "known:", "encoding", "interleave"});
}

TEST(LayoutParser, WrongTypeSaysWhatWasExpected) {
    const std::string text = edit(kValid, "title = \"A test layout\"", "title = 3");
    expectOnlyError(text, placeOf(text, "3\n"), {"'title' must be a string, not an integer"});
}

// ---- names --------------------------------------------------------------------------------------

TEST(LayoutParser, UnknownEncodingListsKnownOnes) {
    const std::string text = edit(kValid, "\"normal_xy_zsign\"", "\"octt\"");
    expectOnlyError(text, placeOf(text, "\"octt\""),
                    {"unknown encoding 'octt'", "known:", "unorm", "normal_octahedral", "ycbcr"});
}

TEST(LayoutParser, UnknownAttributeListsKnownOnes) {
    const std::string text = edit(kValid, "\"base_color\", encoding", "\"base_colour\", encoding");
    expectError(text, placeOf(text, "\"base_colour\""),
                {"unknown attribute 'base_colour'", "known:", "base_color", "specular_color"});
}

TEST(LayoutParser, UnknownFormatListsKnownOnes) {
    const std::string text = edit(kValid, "\"R8G8B8A8_UNORM\"", "\"R8G8B8A8_UNROM\"");
    expectOnlyError(text, placeOf(text, "\"R8G8B8A8_UNROM\""),
                    {"unknown format 'R8G8B8A8_UNROM'", "known:", "R8G8B8A8_UNORM", "A2B10G10R10_UNORM_PACK32"});
}

TEST(LayoutParser, UnknownDepthFormatListsKnownOnes) {
    const std::string text = edit(kValid, "\"D24_UNORM_S8_UINT\"", "\"D24S8\"");
    expectError(text, placeOf(text, "\"D24S8\""), {"unknown depth format 'D24S8'", "D24_UNORM_S8_UINT", "D32_SFLOAT"});
}

TEST(LayoutParser, UnknownChannelNamesTheFormatsChannels) {
    const std::string text = edit(kValid, "\"b[0:6]\"", "\"x[0:6]\"");
    expectError(text, placeOf(text, "\"x[0:6]\""), {"unknown channel 'x'", "R8G8B8A8_UNORM has r, g, b, a"});
}

TEST(LayoutParser, BadBitRangeSyntax) {
    const std::string text = edit(kValid, "\"b[0:6]\"", "\"b[0:6\"");
    expectError(text, placeOf(text, "\"b[0:6\""), {"bad bit range 'b[0:6'", "channel[first:last]"});
    const std::string reversed = edit(kValid, "\"b[0:6]\"", "\"b[6:0]\"");
    expectError(reversed, placeOf(reversed, "\"b[6:0]\""), {"lower bit first", "'b[0:6]'"});
}

TEST(LayoutParser, UnknownPipeline) {
    const std::string text = edit(kValid, "\"deferred-shading\"", "\"forward\"");
    expectError(text, placeOf(text, "\"forward\""), {"unknown pipeline 'forward'", "deferred-lighting"});
}
