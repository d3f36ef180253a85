// Offline validation of METS + PREMIS against the vendored schemas, and RDF/XML checks.
#include <libxml/parser.h>
#include <libxml/tree.h>

#include <cstring>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "carrier/xml.h"
#include "core/error.h"
#include "core/resources.h"
#include "mapping/mapping.h"
#include "mapping/schemas_internal.h"

namespace surrogate::mapping {

namespace internal {
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

}  // namespace internal

void validateMets(const std::string& metsXml, const std::string& source) {
  internal::initialiseXml();
  xml::validateAgainstSchema(metsXml, source, resourcePath("xsd/mets-premis.xsd"));
}

void checkRdfWellFormed(const std::string& rdfXml, const std::string& source) {
  internal::initialiseXml();
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

std::vector<std::string> packagedResources() {
  return {
      "mappings/carrier-to-crm.md",
      "mappings/carrier-to-mets.md",
      "xsd/SOURCE.md",
      "xsd/carrier.xsd",
      "xsd/catalog.xml",
      "xsd/mets-1.12.1.xsd",
      "xsd/mets-premis.xsd",
      "xsd/premis-3.0.xsd",
      "xsd/xlink.xsd",
      "xslt/carrier-to-crm.xsl",
      "xslt/carrier-to-mets.xsl",
  };
}

}  // namespace surrogate::mapping
