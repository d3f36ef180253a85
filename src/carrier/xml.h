// Safe XML parsing and XSD validation (libxml2), shared by the carrier, the mappings and the
// verifier.
//
// Every document is parsed with the network off (XML_PARSE_NONET), without substituting
// entities or loading external DTDs (no billion-laughs, no XXE), and with libxml2's size
// limits in force. Schema validation errors are collected with their line numbers and reported
// in one Error naming the document.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace surrogate::xml {

// Checks that `text` is well-formed XML without DTD tricks; throws Error(kind) naming
// `source` otherwise.
void checkWellFormed(const std::string& text, const std::string& source);

// Validates `text` against the schema file `xsd`. Throws Error(Input) naming `source` with the
// first validation errors (and their line numbers) when the document is not valid.
void validateAgainstSchema(const std::string& text, const std::string& source,
                           const std::filesystem::path& xsd);

// The root element of a document: its name (with its prefix, if any) and its attributes in
// document order (namespace declarations are not attributes).
struct RootElement {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
};
// Parses `text` as safely as above and returns its root element; throws Error(Input) naming
// `source` when it is not well-formed XML or holds a DOCTYPE.
RootElement readRootElement(const std::string& text, const std::string& source);

// An element of a document read whole as data (another tool's XML, such as RTIBuilder's log):
// its local name, its namespace URI, its attributes in document order (a prefixed attribute
// keeps its prefix, "xlink:href"), the text directly inside it (white space between child
// elements left out) and its child elements.
struct Element {
  std::string name;
  std::string namespaceUri;
  std::vector<std::pair<std::string, std::string>> attributes;
  std::string text;
  std::vector<Element> children;
  // The first child named `name` (any namespace), or null.
  const Element* child(const std::string& name) const;
  // The value of the attribute `name`, or "" when it has none.
  std::string attribute(const std::string& name) const;
};
// Parses `text` as safely as above and returns its root element with everything under it.
// Throws Error(Input) naming `source` when it is not well-formed XML, holds a DOCTYPE, or has
// more than `maxElements` elements (libxml2 limits the depth to 256).
Element readElementTree(const std::string& text, const std::string& source, std::size_t maxElements);

// libxml2's version, e.g. "2.9.14".
std::string libxml2Version();

}  // namespace surrogate::xml
