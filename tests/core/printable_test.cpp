// Error text from data (core/printable.h, core/json_text.h): control characters never reach the
// terminal, long values are cut to 80 characters, and a JSON value nested 100 000 deep is
// described by its type without a recursive dump (which overflowed the stack: issue 42).

#include "core/printable.h"

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/json_text.h"

namespace vegstream {
namespace {
using nlohmann::json;

bool hasControl(const std::string& s) {
  for (unsigned char c : s)
    if (c < 0x20 || c == 0x7f) return true;
  return false;
}

TEST(Printable, EscapesControlCharactersAndKeepsUtf8) {
  EXPECT_EQ(printable("a\x1b[31mred\n\tb\x7f"), "a\\x1b[31mred\\n\\tb\\x7f");
  EXPECT_EQ(printable("Zion — Kolob"), "Zion — Kolob");
  EXPECT_EQ(printable("\xc2\x9b"
                      "2J"),
            "\\u009b2J");  // C1 CSI as UTF-8
  EXPECT_EQ(printable("\x9b"
                      "2J"),
            "\\x9b2J");  // a lone byte that is no UTF-8
  EXPECT_FALSE(hasControl(printable(std::string("\0\r\x01", 3))));
}

TEST(Printable, CutsLongTextToItsFirstCharacters) {
  const std::string longText(100000, 'x');
  const std::string p = printable(longText);
  EXPECT_EQ(p, std::string(80, 'x') + "...");
  EXPECT_EQ(printable("short", 80), "short");
  EXPECT_EQ(printablePath(std::string(1000, 'p')).size(), kPrintablePathChars + 3);
}

json nested(int depth) {
  // Built from the inside out without recursion; parsed the same way a file would be.
  return json::parse(std::string(static_cast<size_t>(depth), '[') + std::string(static_cast<size_t>(depth), ']'));
}

TEST(JsonText, DescribesContainersByTypeWithoutDumpingThem) {
  const json deep = nested(100000);
  EXPECT_EQ(jsonValueText(deep), "an array of 1 value(s)");  // a dump() here overflowed the stack
  EXPECT_EQ(jsonValueText(json::object({{"a", 1}, {"b", 2}})), "an object of 2 member(s)");
  EXPECT_EQ(jsonValueText(json(std::string(500, 'k'))), "\"" + std::string(80, 'k') + "...\"");
  EXPECT_EQ(jsonValueText(json("\x1b]0;owned\x07")), "\"\\x1b]0;owned\\x07\"");
  EXPECT_EQ(jsonValueText(json(2.5)), "2.5");
  EXPECT_EQ(jsonValueText(json(nullptr)), "null");
}

TEST(JsonText, DepthIsMeasuredWithoutRecursion) {
  const json deep = nested(100000);
  EXPECT_FALSE(jsonDepthAtMost(deep, 64));
  EXPECT_TRUE(jsonDepthAtMost(nested(64), 64));
  EXPECT_FALSE(jsonDepthAtMost(nested(65), 64));
  EXPECT_TRUE(jsonDepthAtMost(json(3), 0));
}

TEST(JsonText, ParseErrorsAreBoundedAndNameTheLine) {
  const std::string text = "{\n  \"a\": \"" + std::string(100000, 'z') + "\x01\"\n}";
  try {
    const json parsed = json::parse(text);
    FAIL() << parsed.size() << " a control character inside a string is not JSON";
  } catch (const json::exception& e) {
    const std::string t = jsonExceptionText(e.what());
    EXPECT_LE(t.size(), 2 * kPrintableChars + 3);
    EXPECT_EQ(t.rfind("parse error at line 2, column", 0), 0u) << t;
    EXPECT_FALSE(hasControl(t)) << t;
  }
}

TEST(JsonText, ParseErrorPositionsAreCountedFromTheByte) {
  const std::string text = "{\n  \"a\": 1 2\n}";  // nlohmann says "line 2, column 0" here
  try {
    const json parsed = json::parse(text);
    FAIL() << parsed.size() << " two numbers in a row are not JSON";
  } catch (const json::parse_error& e) {
    const std::string t = jsonParseErrorText(text, e.byte, e.what());
    EXPECT_EQ(t.rfind("line 2, column 10: syntax error while parsing object", 0), 0u) << t;
  }
}

}  // namespace
}  // namespace vegstream
