// Private: checks on XML text before it reaches TinyXML (whose parser recurses once per nesting
// level), and strict number lists from attributes. Used by the URDF and SRDF readers.
#pragma once

#include <string>
#include <vector>

class TiXmlDocument;
class TiXmlElement;

namespace planning::internal {

// Deepest element nesting accepted in URDF and SRDF files (robot > link > collision > geometry >
// mesh is 5; 100 leaves room for extensions).
inline constexpr int kMaxXmlDepth = 100;

// Scans `xml` (comments, CDATA, declarations and quoted attribute values skipped) and throws
// std::invalid_argument "SOURCE:LINE: XML elements nested deeper than N" at the first element
// deeper than `max_depth`. O(size), no recursion.
void CheckXmlDepth(const std::string& xml, const std::string& source, int max_depth = kMaxXmlDepth);

// Throws std::invalid_argument "SOURCE:LINE: not UTF-8 text (byte 0xEC at offset N)" unless `xml`
// is UTF-8 (each lead byte followed by its continuation bytes). TinyXML skips a multi-byte
// character by its lead byte's length, so a truncated one at the end reads past the text.
void CheckXmlUtf8(const std::string& xml, const std::string& source);

// Parses `text` as whitespace-separated finite numbers. Returns false on anything else (an empty
// text, a non-number token, inf or nan, or a count other than `count` when count > 0).
// Throws std::invalid_argument "<source>:<line>: ..." when the parsed document has more than one
// top-level element (a second <robot>) or any text after its element: a file is one document.
void CheckSingleRoot(const TiXmlDocument& doc, const std::string& source);
// Throws "<source>:<line>: text after the document's element" when `xml` (the raw text) has
// anything but white space, comments and processing instructions after its last '>'.
void CheckNoTrailingText(const std::string& xml, const std::string& source);

bool ParseNumbers(const std::string& text, int count, std::vector<double>* out);

// Throws std::invalid_argument "<source>:<line>: <message>" (no ":<line>" when line <= 0): the
// error of the URDF and SRDF readers, naming the file and the element's line.
[[noreturn]] void FailAt(const std::string& source, int line, const std::string& message);

// Attribute value or "" when absent.
std::string XmlAttr(const TiXmlElement* e, const char* name);

}  // namespace planning::internal
