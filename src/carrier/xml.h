// Safe XML parsing and XSD validation (libxml2), shared by the carrier, the mappings and the
// verifier.
//
// Every document is parsed with the network off (XML_PARSE_NONET), without substituting
// entities or loading external DTDs (no billion-laughs, no XXE), and with libxml2's size
// limits in force. Schema validation errors are collected with their line numbers and reported
// in one Error naming the document.
#pragma once

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

// libxml2's version, e.g. "2.9.14".
std::string libxml2Version();

}  // namespace surrogate::xml
