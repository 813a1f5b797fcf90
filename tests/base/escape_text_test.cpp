// Names in messages (base/error.h escapeText): UTF-8 printed as UTF-8, while what could break the
// line, hide text or reorder it, and bytes that are not UTF-8, are escaped.
#include <gtest/gtest.h>

#include "error.h"

namespace gbl {
namespace {

TEST(EscapeText, Utf8NamesPrintAsThemselves) {
    EXPECT_EQ(escapeText("\xc3\xbc" "ber.png"), "\xc3\xbc" "ber.png");                   // u with diaeresis
    EXPECT_EQ(escapeText("\xe6\x97\xa5\xe6\x9c\xac/\xf0\x9f\x8c\x85.exr"), "\xe6\x97\xa5\xe6\x9c\xac/\xf0\x9f\x8c\x85.exr");
    EXPECT_EQ(quoteName("\xc3\xa9t\xc3\xa9"), "'\xc3\xa9t\xc3\xa9'");
}

TEST(EscapeText, ControlsQuotesAndBackslashesAreEscaped) {
    EXPECT_EQ(escapeText("a\nb\tc\\d'e\x01\x7f"), "a\\nb\\tc\\\\d\\'e\\x01\\x7f");
}

TEST(EscapeText, WhatHidesOrBreaksTextIsEscapedByteByByte) {
    EXPECT_EQ(escapeText("a\xc2\x85" "b"), "a\\xc2\\x85b");             // NEL (C1 control)
    EXPECT_EQ(escapeText("a\xe2\x80\xa8" "b"), "a\\xe2\\x80\\xa8b");     // line separator
    EXPECT_EQ(escapeText("evil\xe2\x80\xae" "gnp.exe"), "evil\\xe2\\x80\\xaegnp.exe");  // right-to-left override
    EXPECT_EQ(escapeText("\xe2\x80\x8b"), "\\xe2\\x80\\x8b");            // zero-width space
    EXPECT_EQ(escapeText("\xef\xbb\xbfx"), "\\xef\\xbb\\xbfx");          // byte order mark
}

TEST(EscapeText, BytesThatAreNotUtf8AreEscaped) {
    EXPECT_EQ(escapeText("\xff\xfe"), "\\xff\\xfe");
    EXPECT_EQ(escapeText("\xc3"), "\\xc3");                   // cut off
    EXPECT_EQ(escapeText("\xc0\xaf"), "\\xc0\\xaf");          // overlong '/'
    EXPECT_EQ(escapeText("\xed\xa0\x80"), "\\xed\\xa0\\x80"); // a surrogate
    EXPECT_EQ(escapeText("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");  // beyond U+10FFFF
}

TEST(EscapeText, EscapeBytesKeepsNoNonAsciiByte) {
    EXPECT_EQ(escapeBytes("\xc3\xa9"), "\\xc3\\xa9");
    EXPECT_EQ(quoteBytes("\xc2\xa0"), "'\\xc2\\xa0'");  // a no-break space must not pass for a space
}

}  // namespace
}  // namespace gbl
