// XML depth pre-scan and strict number lists (planning/robot/internal/xml_text.h).
#include "planning/robot/internal/xml_text.h"

#include <tinyxml.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <locale>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "base/numbers.h"

namespace planning::internal {

void FailAt(const std::string& source, int line, const std::string& message) {
  throw std::invalid_argument(source + (line > 0 ? ":" + std::to_string(line) : "") + ": " +
                              message);
}

void CheckXmlUtf8(const std::string& xml, const std::string& source) {
  int line = 1;
  for (size_t i = 0; i < xml.size();) {
    const unsigned char c = static_cast<unsigned char>(xml[i]);
    if (c == '\n') ++line;
    const int length = c < 0x80                 ? 1
                       : c >= 0xC2 && c <= 0xDF ? 2
                       : c >= 0xE0 && c <= 0xEF ? 3
                       : c >= 0xF0 && c <= 0xF4 ? 4
                                                : 0;
    bool ok = length > 0 && i + length <= xml.size();
    for (int k = 1; ok && k < length; ++k) {
      ok = (static_cast<unsigned char>(xml[i + k]) & 0xC0) == 0x80;
    }
    if (!ok) {
      char byte[8];
      std::snprintf(byte, sizeof(byte), "0x%02X", c);
      throw std::invalid_argument(source + ":" + std::to_string(line) + ": not UTF-8 text (byte " +
                                  byte + " at offset " + std::to_string(i) + ")");
    }
    i += length;
  }
}

void CheckXmlDepth(const std::string& xml, const std::string& source, int max_depth) {
  int depth = 0, line = 1;
  const size_t n = xml.size();
  // Advances i to just past `end`, counting lines; false if `end` never comes.
  auto skip_to = [&](size_t* i, const char* end) {
    const size_t at = xml.find(end, *i);
    const size_t stop = at == std::string::npos ? n : at + std::char_traits<char>::length(end);
    for (size_t k = *i; k < stop; ++k) line += xml[k] == '\n';
    *i = stop;
  };
  for (size_t i = 0; i < n;) {
    const char c = xml[i];
    if (c == '\n') ++line;
    if (c != '<') {
      ++i;
      continue;
    }
    if (xml.compare(i, 4, "<!--") == 0) {
      skip_to(&i, "-->");
    } else if (xml.compare(i, 9, "<![CDATA[") == 0) {
      skip_to(&i, "]]>");
    } else if (xml.compare(i, 2, "<?") == 0 || xml.compare(i, 2, "<!") == 0) {
      skip_to(&i, ">");
    } else if (xml.compare(i, 2, "</") == 0) {
      if (depth > 0) --depth;
      skip_to(&i, ">");
    } else {
      const int start_line = line;
      // Start tag: find its '>' outside quoted attribute values.
      char quote = 0;
      size_t k = i + 1;
      for (; k < n; ++k) {
        const char d = xml[k];
        if (d == '\n') ++line;
        if (quote) {
          if (d == quote) quote = 0;
        } else if (d == '"' || d == '\'') {
          quote = d;
        } else if (d == '>') {
          break;
        }
      }
      const bool self_closing = k < n && k > i + 1 && xml[k - 1] == '/';
      if (!self_closing && ++depth > max_depth) {
        throw std::invalid_argument(source + ":" + std::to_string(start_line) +
                                    ": XML elements nested deeper than " +
                                    std::to_string(max_depth) + " levels");
      }
      i = k < n ? k + 1 : n;
    }
  }
}

bool ParseNumbers(const std::string& text, int count, std::vector<double>* out) {
  out->clear();
  std::istringstream ss(text);
  ss.imbue(std::locale::classic());  // "0.5" whatever the global locale
  std::string token;
  while (ss >> token) {
    const std::optional<double> v = base::ParseFiniteDouble(token);  // locale-independent
    if (!v) return false;
    out->push_back(*v);
  }
  if (out->empty()) return false;
  return count <= 0 || static_cast<int>(out->size()) == count;
}

std::string XmlAttr(const TiXmlElement* e, const char* name) {
  const char* v = e->Attribute(name);
  return v ? std::string(v) : std::string();
}

namespace {

// The line (1-based) of `pos` in `text`.
int LineOf(const std::string& text, std::size_t pos) {
  int line = 1;
  for (std::size_t i = 0; i < pos && i < text.size(); ++i) line += text[i] == '\n';
  return line;
}

}  // namespace

void CheckNoTrailingText(const std::string& xml, const std::string& source) {
  // Comments and processing instructions blanked out (newlines kept, so positions still map to
  // lines); what is left must end with the '>' of the document's element.
  std::string t = xml;
  for (const auto& [open, close] : {std::pair<const char*, const char*>{"<!--", "-->"},
                                    std::pair<const char*, const char*>{"<?", "?>"}}) {
    std::size_t i = 0;
    while ((i = t.find(open, i)) != std::string::npos) {
      const std::size_t j = t.find(close, i);
      const std::size_t end = j == std::string::npos ? t.size() : j + std::string(close).size();
      for (std::size_t k = i; k < end; ++k) {
        if (t[k] != '\n') t[k] = ' ';
      }
      i = end;
    }
  }
  const std::size_t last = t.find_last_not_of(" \t\r\n");
  if (last == std::string::npos || t[last] == '>') return;
  std::size_t start = t.rfind('>', last);
  start = start == std::string::npos ? 0 : start + 1;
  start = t.find_first_not_of(" \t\r\n", start);
  throw std::invalid_argument(source + ":" + std::to_string(LineOf(xml, start)) +
                              ": text after the document's element");
}

void CheckSingleRoot(const TiXmlDocument& doc, const std::string& source) {
  int elements = 0;
  for (const TiXmlNode* n = doc.FirstChild(); n != nullptr; n = n->NextSibling()) {
    const int type = n->Type();
    if (type == TiXmlNode::TINYXML_DECLARATION || type == TiXmlNode::TINYXML_COMMENT) continue;
    if (type == TiXmlNode::TINYXML_ELEMENT && ++elements == 1) continue;
    const int row = n->Row();
    throw std::invalid_argument(
        source + (row > 0 ? ":" + std::to_string(row) : "") + ": " +
        (type == TiXmlNode::TINYXML_ELEMENT
             ? "a second top-level element <" + std::string(n->Value()) + "> (a file holds one)"
             : std::string("text after the document's element")));
  }
}

}  // namespace planning::internal
