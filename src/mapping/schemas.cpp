// Offline validation of METS + PREMIS against the vendored schemas, and RDF/XML checks.
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xmlschemas.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "carrier/xml.h"
#include "core/error.h"
#include "core/resources.h"
#include "mapping/mapping.h"
#include "mapping/schemas.h"

namespace surrogate::mapping {

namespace {

// Remote schema locations used by the vendored schemas, and their local copies (xsd/).
const std::vector<std::pair<std::string, std::string>>& schemaMap() {
  static const std::vector<std::pair<std::string, std::string>> map = {
      {"http://www.loc.gov/standards/xlink/xlink.xsd", "xsd/xlink.xsd"},
      {"https://www.loc.gov/standards/xlink/xlink.xsd", "xsd/xlink.xsd"},
      {"http://www.loc.gov/standards/mets/version1121/mets.xsd", "xsd/mets-1.12.1.xsd"},
      {"http://www.loc.gov/standards/mets/mets.xsd", "xsd/mets-1.12.1.xsd"},
      {"http://www.loc.gov/standards/premis/v3/premis.xsd", "xsd/premis-3.0.xsd"},
      {"http://www.loc.gov/standards/premis/v3/premis-v3-0.xsd", "xsd/premis-3.0.xsd"},
  };
  return map;
}

// The loader in force before ours: carrier/xml's, which refuses every network URL.
xmlExternalEntityLoader previousLoader = nullptr;

xmlParserInputPtr mappedLoader(const char* url, const char* id, xmlParserCtxtPtr ctxt) {
  if (url) {
    for (const auto& [remote, local] : schemaMap()) {
      if (remote == url) {
        std::string path;
        try {
          path = resourcePath(local).string();
        } catch (...) {
          return nullptr;  // never let an exception cross libxml2; the schema then fails to load
        }
        return previousLoader(path.c_str(), id, ctxt);
      }
    }
  }
  return previousLoader ? previousLoader(url, id, ctxt) : nullptr;
}

}  // namespace

void initialiseXml() {
  static std::once_flag once;
  std::call_once(once, [] {
    // carrier/xml installs its network-refusing loader on first use: make sure it is in place,
    // then put ours in front of it (ours only turns known schema URLs into local files).
    xml::checkWellFormed("<init/>", "initialisation");
    previousLoader = xmlGetExternalEntityLoader();
    xmlSetExternalEntityLoader(mappedLoader);
  });
}

void validateMets(const std::string& metsXml, const std::string& source) {
  initialiseXml();
  xml::validateAgainstSchema(metsXml, source, resourcePath("xsd/mets-premis.xsd"));
}

struct MetsValidator::State {
  std::string source;
  xmlSchemaPtr schema = nullptr;
  xmlSchemaValidCtxtPtr valid = nullptr;
  xmlSAXHandler sax{};
  xmlSAXHandlerPtr saxPtr = &sax;
  void* user = nullptr;
  xmlSchemaSAXPlugPtr plug = nullptr;
  xmlParserCtxtPtr parser = nullptr;
  std::string errors;
  int count = 0;
  bool finished = false;
  // xs:ID and xs:IDREF(S) of METS and PREMIS, which a streaming validation does not check
  // (libxml2 checks them on a document tree only): IDs unique, references to existing IDs.
  std::set<std::string> ids;
  // References to IDs not yet seen, with the line of the first (METS and PREMIS mostly refer
  // back to IDs already read: few are ever held).
  std::map<std::string, long> references;

  long line() const { return parser && parser->input ? parser->input->line : 0; }
  void add(long at, const std::string& message) {
    if (++count > 5) return;
    if (!errors.empty()) errors += "; ";
    errors += "line " + std::to_string(at) + ": " + message;
  }
  static void collect(void* self, xmlErrorPtr error) {
    auto* s = static_cast<State*>(self);
    if (!error) return;
    std::string message = error->message ? error->message : "unknown error";
    while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
    s->add(error->line > 0 ? error->line : s->line(), message);
  }
  static void startElement(void* self, const xmlChar*, const xmlChar*, const xmlChar*, int, const xmlChar**,
                           int attributeCount, int, const xmlChar** attributes) {
    static const std::set<std::string> idNames = {"ID", "xmlID"};
    static const std::set<std::string> referenceNames = {
        "ADMID", "DMDID", "STRUCTID", "FILEID", "TRANSFORMBEHAVIOR", "LinkAgentXmlID",
        "LinkEventXmlID", "LinkObjectXmlID", "LinkPermissionStatementXmlID", "RelEventXmlID",
        "RelObjectXmlID"};
    auto* s = static_cast<State*>(self);
    for (int i = 0; i < attributeCount; ++i) {
      const xmlChar** a = attributes + 5 * i;  // localname, prefix, URI, value, end
      if (a[2] != nullptr) continue;           // a namespaced attribute (xlink:, xsi:)
      const std::string name = reinterpret_cast<const char*>(a[0]);
      const bool id = idNames.count(name) > 0, reference = referenceNames.count(name) > 0;
      if (!id && !reference) continue;
      const std::string value(reinterpret_cast<const char*>(a[3]), static_cast<std::size_t>(a[4] - a[3]));
      std::size_t at = 0;
      while (at < value.size()) {  // IDREFS: whitespace-separated
        const std::size_t start = value.find_first_not_of(" \t\r\n", at);
        if (start == std::string::npos) break;
        const std::size_t end = std::min(value.find_first_of(" \t\r\n", start), value.size());
        const std::string token = value.substr(start, end - start);
        if (id && !s->ids.insert(token).second)
          s->add(s->line(), "attribute '" + name + "': '" + token + "' is not unique (xs:ID)");
        if (reference && !s->ids.count(token)) s->references.emplace(token, s->line());
        at = end;
        if (id) break;
      }
    }
  }
  ~State() {
    if (parser) xmlFreeParserCtxt(parser);
    if (plug) xmlSchemaSAXUnplug(plug);
    if (valid) xmlSchemaFreeValidCtxt(valid);
    if (schema) xmlSchemaFree(schema);
  }
};

MetsValidator::MetsValidator(const std::string& source) : state_(std::make_unique<State>()) {
  initialiseXml();
  State& s = *state_;
  s.source = source;
  const std::string xsd = resourcePath("xsd/mets-premis.xsd").string();
  std::string schemaErrors;
  xmlSchemaParserCtxtPtr pctxt = xmlSchemaNewParserCtxt(xsd.c_str());
  s.schema = pctxt ? xmlSchemaParse(pctxt) : nullptr;
  xmlSchemaFreeParserCtxt(pctxt);
  if (!s.schema)
    throw Error(ErrorKind::Internal, xsd, "schema", "the XML schema could not be loaded");
  s.valid = xmlSchemaNewValidCtxt(s.schema);
  if (!s.valid) throw Error(ErrorKind::Internal, xsd, "schema", "libxml2 could not start");
  xmlSchemaSetValidStructuredErrors(s.valid, &State::collect, &s);
  // No tree is built: an empty SAX2 handler, with the validator plugged in front of it.
  std::memset(&s.sax, 0, sizeof s.sax);
  s.sax.initialized = XML_SAX2_MAGIC;
  s.sax.startElementNs = &State::startElement;
  s.user = &s;
  s.plug = xmlSchemaSAXPlug(s.valid, &s.saxPtr, &s.user);
  if (!s.plug) throw Error(ErrorKind::Internal, xsd, "schema", "libxml2 could not start");
  s.parser = xmlCreatePushParserCtxt(s.saxPtr, s.user, nullptr, 0, source.c_str());
  if (!s.parser) throw Error(ErrorKind::Internal, source, "schema", "libxml2 could not start");
  xmlCtxtUseOptions(s.parser, XML_PARSE_NONET | XML_PARSE_NOWARNING | XML_PARSE_NOERROR);
}

MetsValidator::~MetsValidator() = default;

void MetsValidator::feed(const char* data, std::size_t size) {
  State& s = *state_;
  while (size > 0 && !s.finished) {
    const int n = static_cast<int>(std::min<std::size_t>(size, 1 << 20));
    xmlParseChunk(s.parser, data, n, 0);
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

void MetsValidator::finish() {
  State& s = *state_;
  if (!s.finished) {
    xmlParseChunk(s.parser, nullptr, 0, 1);
    for (const auto& [token, at] : s.references)
      if (!s.ids.count(token)) s.add(at, "'" + token + "' refers to no ID in the document (xs:IDREF)");
  }
  s.finished = true;
  std::string problem = s.errors;
  if (!s.parser->wellFormed && problem.empty()) {
    const xmlError* e = xmlCtxtGetLastError(s.parser);
    problem = e && e->message ? "line " + std::to_string(e->line) + ": " + e->message
                              : "not well-formed XML";
    while (!problem.empty() && problem.back() == '\n') problem.pop_back();
  }
  if (s.parser->myDoc && (s.parser->myDoc->intSubset || s.parser->myDoc->extSubset))
    problem = "it contains a DOCTYPE declaration";
  if (!problem.empty() || !s.parser->wellFormed)
    throwInputError(s.source, "schema validation",
                    "does not conform to mets-premis.xsd (" +
                        (problem.empty() ? std::string("internal validation error") : problem) + ")");
}

void checkRdfWellFormed(const std::string& rdfXml, const std::string& source) {
  initialiseXml();
  xml::checkWellFormed(rdfXml, source);  // no DOCTYPE, well-formed, size limits
  xmlDocPtr doc = xmlReadMemory(rdfXml.data(), static_cast<int>(rdfXml.size()), source.c_str(),
                                nullptr, XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
  if (!doc) throwInputError(source, "rdf", "is not well-formed XML");
  const xmlNode* root = xmlDocGetRootElement(doc);
  const bool ok = root && std::strcmp(reinterpret_cast<const char*>(root->name), "RDF") == 0 &&
                  root->ns &&
                  std::strcmp(reinterpret_cast<const char*>(root->ns->href),
                              "http://www.w3.org/1999/02/22-rdf-syntax-ns#") == 0;
  xmlFreeDoc(doc);
  if (!ok) {
    throwInputError(source, "rdf",
                    "is not RDF/XML (its root element is not rdf:RDF); re-derive it from the "
                    "carrier with xslt/carrier-to-crm.xsl");
  }
}

std::filesystem::path crmStylesheetPath() { return resourcePath("xslt/carrier-to-crm.xsl"); }
std::filesystem::path metsStylesheetPath() { return resourcePath("xslt/carrier-to-mets.xsl"); }
std::filesystem::path roCrateStylesheetPath() { return resourcePath("xslt/carrier-to-ro-crate.xsl"); }

std::vector<std::string> packagedResources() {
  return {
      "mappings/carrier-to-crm.md",
      "mappings/carrier-to-mets.md",
      "mappings/carrier-to-ro-crate.md",
      "mappings/pronom.md",  // the PRONOM identifiers carrier-to-mets.md refers to
      "xsd/SOURCE.md",
      "xsd/carrier.xsd",
      "xsd/catalog.xml",
      "xsd/mets-1.12.1.xsd",
      "xsd/mets-premis.xsd",
      "xsd/premis-3.0.xsd",
      "xsd/xlink.xsd",
      "xslt/carrier-to-crm.xsl",
      "xslt/carrier-to-mets.xsl",
      "xslt/carrier-to-ro-crate.xsl",
  };
}

}  // namespace surrogate::mapping
