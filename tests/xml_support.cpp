#include "xml_support.h"

#include <stdexcept>

#include <expat.h>

namespace bluetile::test {
namespace {

struct ParseState {
  std::unique_ptr<XmlElement> root;
  std::vector<XmlElement*> open;
};

void on_start(void* data, const XML_Char* name, const XML_Char** attributes) {
  auto* state = static_cast<ParseState*>(data);
  auto element = std::make_unique<XmlElement>();
  element->name = name;
  for (int i = 0; attributes[i]; i += 2) element->attributes[attributes[i]] = attributes[i + 1];
  XmlElement* raw = element.get();
  if (state->open.empty()) state->root = std::move(element);
  else state->open.back()->children.push_back(std::move(element));
  state->open.push_back(raw);
}

void on_end(void* data, const XML_Char*) { static_cast<ParseState*>(data)->open.pop_back(); }

void on_text(void* data, const XML_Char* s, int length) {
  auto* state = static_cast<ParseState*>(data);
  if (!state->open.empty()) state->open.back()->text.append(s, static_cast<std::size_t>(length));
}

void collect(const XmlElement& e, const std::string& name, std::vector<const XmlElement*>& out) {
  if (e.name == name) out.push_back(&e);
  for (const auto& c : e.children) collect(*c, name, out);
}

}  // namespace

std::vector<const XmlElement*> XmlElement::find_all(const std::string& wanted) const {
  std::vector<const XmlElement*> out;
  collect(*this, wanted, out);
  return out;
}

double XmlElement::number(const std::string& attribute) const {
  auto it = attributes.find(attribute);
  if (it == attributes.end()) throw std::runtime_error("<" + name + "> has no attribute " + attribute);
  std::size_t used = 0;
  double v = std::stod(it->second, &used);
  if (used != it->second.size()) throw std::runtime_error(attribute + "=\"" + it->second + "\" is not a number");
  return v;
}

std::unique_ptr<XmlElement> parse_xml(const std::string& text, std::string* error) {
  XML_Parser parser = XML_ParserCreate("UTF-8");
  ParseState state;
  XML_SetUserData(parser, &state);
  XML_SetElementHandler(parser, on_start, on_end);
  XML_SetCharacterDataHandler(parser, on_text);
  const bool ok = XML_Parse(parser, text.data(), static_cast<int>(text.size()), 1) == XML_STATUS_OK;
  if (!ok && error)
    *error = std::string(XML_ErrorString(XML_GetErrorCode(parser))) + " at line " +
             std::to_string(XML_GetCurrentLineNumber(parser));
  XML_ParserFree(parser);
  if (!ok) return nullptr;
  return std::move(state.root);
}

}  // namespace bluetile::test
