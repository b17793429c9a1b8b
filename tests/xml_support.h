// XML read back in tests through expat (an independent, strict parser): for checking that SVG
// output is well-formed and holds what it should.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace bluetile::test {

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;  // character data directly inside, concatenated
  std::vector<std::unique_ptr<XmlElement>> children;

  // Every element below (and including) this one named `name`, in document order.
  std::vector<const XmlElement*> find_all(const std::string& name) const;
  double number(const std::string& attribute) const;  // throws when absent or not a number
};

// Parses `text`; on malformed XML returns null and sets `error` to expat's message and line.
std::unique_ptr<XmlElement> parse_xml(const std::string& text, std::string* error = nullptr);

}  // namespace bluetile::test
