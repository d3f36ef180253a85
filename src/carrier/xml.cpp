#include "carrier/xml.h"
#include "carrier/xml_tree.h"

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xmlschemas.h>
#include <libxml/xmlversion.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "core/error.h"

namespace surrogate::xml {

namespace {

// Refuses every external resource that is not a local file: no document or schema may make
// libxml2 reach the network (a verifier of untrusted packages must not phone anywhere).
xmlExternalEntityLoader defaultLoader = nullptr;

xmlParserInputPtr localOnlyLoader(const char* url, const char* id, xmlParserCtxtPtr ctxt) {
  if (url && (std::strncmp(url, "http://", 7) == 0 || std::strncmp(url, "https://", 8) == 0 ||
              std::strncmp(url, "ftp://", 6) == 0)) {
    return nullptr;
  }
  return defaultLoader ? defaultLoader(url, id, ctxt) : nullptr;
}

void initialiseLibxml2() {
  static std::once_flag once;
  std::call_once(once, [] {
    xmlInitParser();
    defaultLoader = xmlGetExternalEntityLoader();
    xmlSetExternalEntityLoader(localOnlyLoader);
  });
}

constexpr int kSafeParseOptions = XML_PARSE_NONET | XML_PARSE_NOWARNING | XML_PARSE_NOERROR;
// For a tree that is only read: no text nodes for the white space between elements, short
// texts inside their nodes.
constexpr int kReadOnlyTreeOptions = kSafeParseOptions | XML_PARSE_NOBLANKS | XML_PARSE_COMPACT;

// Collects error messages (libxml2 calls this once per error).
struct ErrorCollector {
  std::string text;
  int count = 0;
  static void collect(void* user, xmlErrorPtr error) {
    auto* self = static_cast<ErrorCollector*>(user);
    if (!error || ++self->count > 5) return;
    std::string message = error->message ? error->message : "unknown error";
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
      message.pop_back();
    if (!self->text.empty()) self->text += "; ";
    self->text += "line " + std::to_string(error->line) + ": " + message;
  }
};

DocPtr parseSafely(const std::string& text, const std::string& source,
                   int options = kSafeParseOptions) {
  if (text.size() > static_cast<std::size_t>(INT32_MAX))
    throwInputError(source, "xml", "is too large to be an XML document Surrogate wrote");
  initialiseLibxml2();
  xmlParserCtxtPtr ctxt = xmlNewParserCtxt();
  if (!ctxt) throw Error(ErrorKind::Internal, source, "xml", "libxml2 could not start");
  DocPtr doc(xmlCtxtReadMemory(ctxt, text.data(), static_cast<int>(text.size()),
                               source.c_str(), nullptr, options));
  std::string problem;
  if (!doc) {
    const xmlError* e = xmlCtxtGetLastError(ctxt);
    problem = e && e->message ? "line " + std::to_string(e->line) + ": " + e->message
                              : "not well-formed XML";
    while (!problem.empty() && problem.back() == '\n') problem.pop_back();
  }
  xmlFreeParserCtxt(ctxt);
  if (!doc) throwInputError(source, "xml", "is not well-formed XML (" + problem + ")");
  // None of our documents needs a DTD; one is the vehicle of entity-expansion bombs and
  // external-entity reads, so refuse it outright.
  if (doc->intSubset || doc->extSubset) {
    throwInputError(source, "xml",
                    "contains a DOCTYPE declaration, which Surrogate refuses for safety "
                    "(entity expansion); the file was not made by Surrogate or was altered");
  }
  return doc;
}

}  // namespace

namespace {

using SchemaPtr = std::shared_ptr<xmlSchema>;

// The schema in the file `xsd`, parsed once per process while the file keeps its size and
// modification time: `run` saves its carrier after every step, each save validated, and parsing
// carrier.xsd again every time was about half of each save. A parsed schema is only read while
// validating, so one may serve several validations at once (each with a context of its own).
SchemaPtr loadSchema(const std::filesystem::path& xsd) {
  struct Loaded {
    std::uintmax_t size = 0;
    std::filesystem::file_time_type modified;
    SchemaPtr schema;
  };
  static std::mutex mutex;
  static std::map<std::filesystem::path, Loaded> loaded;
  std::error_code sizeError, timeError;
  const std::uintmax_t size = std::filesystem::file_size(xsd, sizeError);
  const auto modified = std::filesystem::last_write_time(xsd, timeError);
  const bool stamped = !sizeError && !timeError;
  std::lock_guard<std::mutex> lock(mutex);
  const auto it = loaded.find(xsd);
  if (stamped && it != loaded.end() && it->second.size == size && it->second.modified == modified)
    return it->second.schema;
  ErrorCollector schemaErrors;
  xmlSchemaParserCtxtPtr pctxt = xmlSchemaNewParserCtxt(xsd.c_str());
  xmlSchemaSetParserStructuredErrors(pctxt, &ErrorCollector::collect, &schemaErrors);
  SchemaPtr schema(pctxt ? xmlSchemaParse(pctxt) : nullptr, xmlSchemaFree);
  xmlSchemaFreeParserCtxt(pctxt);
  if (!schema) {
    throw Error(ErrorKind::Internal, xsd.string(), "schema",
                "the XML schema could not be loaded (" + schemaErrors.text + ")");
  }
  if (stamped) loaded[xsd] = {size, modified, schema};
  return schema;
}

// Validates a parsed document against the schema file `xsd`.
void validateDocument(xmlDoc* doc, const std::string& source, const std::filesystem::path& xsd) {
  const SchemaPtr schema = loadSchema(xsd);
  ErrorCollector errors;
  xmlSchemaValidCtxtPtr vctxt = xmlSchemaNewValidCtxt(schema.get());
  xmlSchemaSetValidStructuredErrors(vctxt, &ErrorCollector::collect, &errors);
  const int rc = xmlSchemaValidateDoc(vctxt, doc);
  xmlSchemaFreeValidCtxt(vctxt);
  if (rc != 0) {
    throwInputError(source, "schema validation",
                    "does not conform to " + xsd.filename().string() + " (" +
                        (errors.text.empty() ? "internal validation error" : errors.text) + ")");
  }
}

}  // namespace

void checkWellFormed(const std::string& text, const std::string& source) {
  parseSafely(text, source);
}

void validateAgainstSchema(const std::string& text, const std::string& source,
                           const std::filesystem::path& xsd) {
  validateDocument(parseSafely(text, source).get(), source, xsd);
}

DocPtr parseValidated(const std::string& text, const std::string& source,
                      const std::filesystem::path& xsd) {
  DocPtr doc = parseSafely(text, source, kReadOnlyTreeOptions);
  validateDocument(doc.get(), source, xsd);
  return doc;
}

RootElement readRootElement(const std::string& text, const std::string& source) {
  DocPtr doc = parseSafely(text, source);
  const xmlNode* root = xmlDocGetRootElement(doc.get());
  RootElement out;
  if (!root) return out;
  auto utf8 = [](const xmlChar* s) { return std::string(s ? reinterpret_cast<const char*>(s) : ""); };
  out.name = root->ns && root->ns->prefix ? utf8(root->ns->prefix) + ":" + utf8(root->name) : utf8(root->name);
  for (const xmlAttr* a = root->properties; a; a = a->next) {
    xmlChar* value = xmlNodeListGetString(doc.get(), a->children, 1);
    out.attributes.emplace_back(utf8(a->name), utf8(value));
    xmlFree(value);
  }
  return out;
}

namespace {

std::string utf8Text(const xmlChar* s) { return s ? reinterpret_cast<const char*>(s) : ""; }

void copyElement(const xmlDoc* doc, const xmlNode* node, Element& out, std::size_t& elements,
                 std::size_t maxElements, const std::string& source) {
  if (++elements > maxElements)
    throwInputError(source, "xml", "has more than " + std::to_string(maxElements) + " elements, more than Surrogate reads in such a file");
  out.name = utf8Text(node->name);
  if (node->ns) out.namespaceUri = utf8Text(node->ns->href);
  for (const xmlAttr* a = node->properties; a; a = a->next) {
    xmlChar* value = xmlNodeListGetString(const_cast<xmlDoc*>(doc), a->children, 1);
    const std::string name = a->ns && a->ns->prefix ? utf8Text(a->ns->prefix) + ":" + utf8Text(a->name) : utf8Text(a->name);
    out.attributes.emplace_back(name, utf8Text(value));
    xmlFree(value);
  }
  for (const xmlNode* c = node->children; c; c = c->next) {
    if (c->type == XML_ELEMENT_NODE) {
      out.children.emplace_back();
      copyElement(doc, c, out.children.back(), elements, maxElements, source);
    } else if (c->type == XML_TEXT_NODE || c->type == XML_CDATA_SECTION_NODE) {
      out.text += utf8Text(c->content);
    }
  }
  // Indentation around child elements is not text of the element.
  if (!out.children.empty() && out.text.find_first_not_of(" \t\r\n") == std::string::npos) out.text.clear();
}

}  // namespace

const Element* Element::child(const std::string& childName) const {
  for (const Element& c : children)
    if (c.name == childName) return &c;
  return nullptr;
}

std::string Element::attribute(const std::string& attributeName) const {
  for (const auto& [n, v] : attributes)
    if (n == attributeName) return v;
  return "";
}

Element readElementTree(const std::string& text, const std::string& source, std::size_t maxElements) {
  DocPtr doc = parseSafely(text, source);
  const xmlNode* root = xmlDocGetRootElement(doc.get());
  Element out;
  if (!root) return out;
  std::size_t elements = 0;
  copyElement(doc.get(), root, out, elements, maxElements, source);
  return out;
}

std::string libxml2Version() { return LIBXML_DOTTED_VERSION; }

}  // namespace surrogate::xml
