// Running the stylesheets (libxslt) safely: no network, no file access from the stylesheet, no
// DTDs; the one document a stylesheet may load is the in-memory payload list.
#include "mapping/mapping.h"

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxslt/documents.h>
#include <libxslt/security.h>
#include <libxslt/transform.h>
#include <libxslt/xslt.h>
#include <libxslt/xsltInternals.h>
#include <libxslt/xsltutils.h>

#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "carrier/xml.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "mapping/schemas.h"

namespace surrogate::mapping {

namespace {

constexpr const char* kPayloadUri = "surrogate:payload";
constexpr int kParseOptions = XML_PARSE_NONET | XML_PARSE_NOWARNING | XML_PARSE_NOERROR;

// The payload list of the transformation running on this thread (document("surrogate:payload")).
thread_local const std::string* currentPayload = nullptr;

// libxslt's document loader: only the payload list; every other document is refused.
xmlDocPtr payloadOnlyLoader(const xmlChar* uri, xmlDictPtr, int, void*, xsltLoadType type) {
  if (type != XSLT_LOAD_DOCUMENT || !uri || !currentPayload) return nullptr;
  if (std::strcmp(reinterpret_cast<const char*>(uri), kPayloadUri) != 0) return nullptr;
  return xmlReadMemory(currentPayload->data(), static_cast<int>(currentPayload->size()),
                       kPayloadUri, "UTF-8", kParseOptions);
}

int allowPayloadOnly(xsltSecurityPrefsPtr, xsltTransformContextPtr, const char* value) {
  return value && std::strcmp(value, kPayloadUri) == 0 ? 1 : 0;
}

void initialiseXslt() {
  static std::once_flag once;
  std::call_once(once, [] {
    initialiseXml();
    xsltInit();
    xsltSetLoaderFunc(payloadOnlyLoader);
  });
}

struct ErrorText {
  std::string text;
  int count = 0;
  static void collect(void* user, const char* format, ...) {
    auto* self = static_cast<ErrorText*>(user);
    if (++self->count > 20) return;
    char buffer[1024];
    va_list args;
    va_start(args, format);
    std::vsnprintf(buffer, sizeof buffer, format, args);
    va_end(args);
    self->text += buffer;
  }
  std::string summary() const {
    std::string s = text;
    for (char& c : s)
      if (c == '\n') c = ' ';
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s.empty() ? "no detail from libxslt" : s;
  }
};

struct DocFree { void operator()(xmlDoc* d) const { xmlFreeDoc(d); } };
struct StyleFree { void operator()(xsltStylesheet* s) const { xsltFreeStylesheet(s); } };
struct CtxtFree { void operator()(xsltTransformContext* c) const { xsltFreeTransformContext(c); } };
struct PrefsFree { void operator()(xsltSecurityPrefs* p) const { xsltFreeSecurityPrefs(p); } };
using DocPtr = std::unique_ptr<xmlDoc, DocFree>;

// XSLT string parameters are XPath expressions: quote a value as an XPath string literal.
// (No XPath 1.0 literal holds both quote kinds; our values never need that.)
std::string xpathLiteral(const std::string& value, const std::string& name) {
  if (value.find('\'') == std::string::npos) return "'" + value + "'";
  if (value.find('"') == std::string::npos) return "\"" + value + "\"";
  throw Error(ErrorKind::Usage, name, "metadata",
              "contains both kinds of quotation marks, which an XSLT parameter cannot carry; "
              "change the value");
}

// A finished transformation: the result tree and what it refers to (destroyed in reverse
// order: the result first, the input last).
struct Transformed {
  DocPtr input;
  std::unique_ptr<xsltStylesheet, StyleFree> style;
  DocPtr result;
};

Transformed runTransform(const std::filesystem::path& stylesheet, const std::string& carrierXml,
                         const std::string& source,
                         const std::vector<std::pair<std::string, std::string>>& params,
                         const std::string* payload) {
  initialiseXslt();
  Transformed t;
  // The carrier: checked by the same safe parser as everywhere (no DOCTYPE, no network).
  xml::checkWellFormed(carrierXml, source);
  t.input.reset(xmlReadMemory(carrierXml.data(), static_cast<int>(carrierXml.size()),
                              source.c_str(), nullptr, kParseOptions));
  if (!t.input) throwInputError(source, "metadata", "is not well-formed XML");

  const std::string styleText = readFile(stylesheet, "metadata");
  xml::checkWellFormed(styleText, stylesheet.string());
  xmlDocPtr styleDoc = xmlReadMemory(styleText.data(), static_cast<int>(styleText.size()),
                                     stylesheet.c_str(), nullptr, kParseOptions);
  if (!styleDoc) throw Error(ErrorKind::Internal, stylesheet.string(), "metadata",
                             "the stylesheet is not well-formed; reinstall Surrogate");
  t.style.reset(xsltParseStylesheetDoc(styleDoc));
  if (!t.style) {
    xmlFreeDoc(styleDoc);
    throw Error(ErrorKind::Internal, stylesheet.string(), "metadata",
                "the stylesheet could not be compiled; reinstall Surrogate");
  }

  std::unique_ptr<xsltSecurityPrefs, PrefsFree> prefs(xsltNewSecurityPrefs());
  xsltSetSecurityPrefs(prefs.get(), XSLT_SECPREF_READ_FILE, xsltSecurityForbid);
  xsltSetSecurityPrefs(prefs.get(), XSLT_SECPREF_WRITE_FILE, xsltSecurityForbid);
  xsltSetSecurityPrefs(prefs.get(), XSLT_SECPREF_CREATE_DIRECTORY, xsltSecurityForbid);
  xsltSetSecurityPrefs(prefs.get(), XSLT_SECPREF_READ_NETWORK, allowPayloadOnly);
  xsltSetSecurityPrefs(prefs.get(), XSLT_SECPREF_WRITE_NETWORK, xsltSecurityForbid);

  std::unique_ptr<xsltTransformContext, CtxtFree> ctxt(
      xsltNewTransformContext(t.style.get(), t.input.get()));
  if (!ctxt) throw Error(ErrorKind::Internal, stylesheet.string(), "metadata", "libxslt could not start");
  xsltSetCtxtSecurityPrefs(prefs.get(), ctxt.get());
  ErrorText errors;
  xsltSetTransformErrorFunc(ctxt.get(), &errors, &ErrorText::collect);
  xsltSetGenericErrorFunc(&errors, &ErrorText::collect);

  std::vector<std::string> texts;
  texts.reserve(params.size() * 2);
  for (const auto& [name, value] : params) {
    texts.push_back(name);
    texts.push_back(xpathLiteral(value, name));
  }
  std::vector<const char*> raw;
  for (const std::string& text : texts) raw.push_back(text.c_str());
  raw.push_back(nullptr);

  currentPayload = payload;
  t.result.reset(xsltApplyStylesheetUser(t.style.get(), t.input.get(), raw.data(), nullptr, nullptr,
                                         ctxt.get()));
  currentPayload = nullptr;
  const bool failed = !t.result || ctxt->state != XSLT_STATE_OK;
  xsltSetGenericErrorFunc(nullptr, nullptr);
  if (failed) {
    throw Error(ErrorKind::Input, source, "metadata",
                "deriving metadata with " + stylesheet.filename().string() + " failed (" +
                    errors.summary() + ")");
  }
  return t;
}

std::string transform(const std::filesystem::path& stylesheet, const std::string& carrierXml,
                      const std::string& source,
                      const std::vector<std::pair<std::string, std::string>>& params,
                      const std::string* payload) {
  const Transformed t = runTransform(stylesheet, carrierXml, source, params, payload);
  xmlChar* bytes = nullptr;
  int length = 0;
  if (xsltSaveResultToString(&bytes, &length, t.result.get(), t.style.get()) != 0 || !bytes) {
    throw Error(ErrorKind::Internal, stylesheet.string(), "metadata",
                "libxslt could not serialise the result");
  }
  std::string out(reinterpret_cast<const char*>(bytes), static_cast<std::size_t>(length));
  xmlFree(bytes);
  return out;
}

// The result serialised as xsltSaveResultToString does (UTF-8 needs no encoder), piece by
// piece into `sink`.
void serialiseTo(const Transformed& t, const std::filesystem::path& stylesheet, const TextSink& sink) {
  struct Target {
    const TextSink* sink;
    std::exception_ptr failure;
  } target{&sink, nullptr};
  auto write = [](void* context, const char* data, int length) -> int {
    auto* to = static_cast<Target*>(context);
    if (to->failure) return -1;
    try {
      (*to->sink)(data, static_cast<std::size_t>(length));
    } catch (...) {
      to->failure = std::current_exception();  // never across libxml2
      return -1;
    }
    return length;
  };
  xmlOutputBufferPtr buffer = xmlOutputBufferCreateIO(write, nullptr, &target, nullptr);
  if (!buffer) throw Error(ErrorKind::Internal, stylesheet.string(), "metadata", "libxml2 could not start");
  const int written = xsltSaveResultTo(buffer, t.result.get(), t.style.get());
  const int closed = xmlOutputBufferClose(buffer);
  if (target.failure) std::rethrow_exception(target.failure);
  if (written < 0 || closed < 0)
    throw Error(ErrorKind::Internal, stylesheet.string(), "metadata",
                "libxslt could not serialise the result");
}

// Escapes text for an XML attribute value (CR, LF and tab as character references so that they
// survive attribute-value normalisation). Control characters XML 1.0 cannot hold are refused.
std::string attributeText(const std::string& value, const std::string& what) {
  std::string out;
  for (const char ch : value) {
    const auto c = static_cast<unsigned char>(ch);
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\n': out += "&#10;"; break;
      case '\r': out += "&#13;"; break;
      case '\t': out += "&#9;"; break;
      default:
        if (c < 0x20) {
          throwInputError(what, "metadata",
                          "has a control character in its name, which XML metadata cannot "
                          "record; rename the file");
        }
        out.push_back(ch);
    }
  }
  return out;
}

std::string payloadXml(const std::vector<PayloadFile>& payload) {
  std::string xml = "<payload>\n";
  for (const PayloadFile& f : payload) {
    xml += "<file path=\"" + attributeText(f.path, f.path) + "\" size=\"" +
           std::to_string(f.size) + "\" sha256=\"" + attributeText(f.sha256, f.path) +
           "\" sha512=\"" + attributeText(f.sha512, f.path) + "\"/>\n";
  }
  xml += "</payload>\n";
  return xml;
}

}  // namespace

std::string deriveCrm(const std::string& carrierXml, const std::string& source) {
  return transform(crmStylesheetPath(), carrierXml, source, {}, nullptr);
}

std::string deriveMets(const std::string& carrierXml, const PackageFacts& facts,
                       const std::string& source) {
  const std::string payload = payloadXml(facts.payload);
  std::vector<std::pair<std::string, std::string>> params = {
      {"package-id", facts.packageId},
      {"packaging-time", facts.packagingTime},
      {"software-agent", facts.softwareAgent.empty() ? "Surrogate" : facts.softwareAgent},
  };
  params.emplace_back("payload-uri", kPayloadUri);  // always: document('') would read the stylesheet
  return transform(metsStylesheetPath(), carrierXml, source, params, &payload);
}

void deriveCrmTo(const std::string& carrierXml, const TextSink& sink, const std::string& source) {
  const std::filesystem::path stylesheet = crmStylesheetPath();
  const Transformed t = runTransform(stylesheet, carrierXml, source, {}, nullptr);
  const xmlNode* root = xmlDocGetRootElement(t.result.get());
  const bool rdf = root && std::strcmp(reinterpret_cast<const char*>(root->name), "RDF") == 0 &&
                   root->ns &&
                   std::strcmp(reinterpret_cast<const char*>(root->ns->href),
                               "http://www.w3.org/1999/02/22-rdf-syntax-ns#") == 0;
  if (!rdf)
    throw Error(ErrorKind::Internal, stylesheet.string(), "metadata",
                "the stylesheet did not give RDF/XML (its root is not rdf:RDF); reinstall Surrogate");
  serialiseTo(t, stylesheet, sink);
}

void deriveMetsTo(const std::string& carrierXml, const PackageFacts& facts, const TextSink& sink,
                  const std::string& source) {
  const std::filesystem::path stylesheet = metsStylesheetPath();
  std::string payload = payloadXml(facts.payload);
  std::vector<std::pair<std::string, std::string>> params = {
      {"package-id", facts.packageId},
      {"packaging-time", facts.packagingTime},
      {"software-agent", facts.softwareAgent.empty() ? "Surrogate" : facts.softwareAgent},
  };
  params.emplace_back("payload-uri", kPayloadUri);
  Transformed t = runTransform(stylesheet, carrierXml, source, params, &payload);
  std::string().swap(payload);  // the payload document was read: its text is not needed
  serialiseTo(t, stylesheet, sink);
}

std::string libxsltVersion() { return xsltEngineVersion; }

}  // namespace surrogate::mapping
