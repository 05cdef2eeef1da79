// Text inside an XML attribute or element (the JUnit files of `audit` and `conformance`): the five
// predefined entities, and control characters other than tab and newline (not allowed in XML 1.0)
// made spaces.
#pragma once

#include <string>

namespace ra::util {

std::string xml_text(const std::string& s);

}  // namespace ra::util
