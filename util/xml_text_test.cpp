// XML text: every predefined entity escaped, control characters that XML 1.0 forbids made spaces.
#include "util/xml_text.h"

#include <gtest/gtest.h>

namespace ra::util {
namespace {

TEST(XmlText, EntitiesAndForbiddenControlCharacters) {
  EXPECT_EQ(xml_text("a<b>&\"c\"'d'"), "a&lt;b&gt;&amp;&quot;c&quot;&apos;d&apos;");
  EXPECT_EQ(xml_text(std::string("x\x01y\x1fz", 5)), "x y z");
  EXPECT_EQ(xml_text("tab\tnew\nline"), "tab\tnew\nline");  // allowed in XML 1.0
  EXPECT_EQ(xml_text("&amp;"), "&amp;amp;");                 // escaped once more, not left alone
  EXPECT_EQ(xml_text(""), "");
}

}  // namespace
}  // namespace ra::util
