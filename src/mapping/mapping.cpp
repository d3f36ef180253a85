// Running the stylesheets (libxslt) safely: no network, no file access from the stylesheet, no
// DTDs; the one document a stylesheet may load is the in-memory payload list.
#include "mapping/mapping.h"

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xpath.h>
#include <libexslt/exslt.h>
#include <libxslt/documents.h>
#include <libxslt/security.h>
#include <libxslt/transform.h>
#include <libxslt/xslt.h>
#include <libxslt/xsltInternals.h>
#include <libxslt/xsltutils.h>

#include <cstdarg>
#include <cstdio>
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "carrier/carrier.h"
#include "carrier/xml.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "mapping/result_stream.h"
#include "mapping/schemas.h"

namespace surrogate::mapping {

namespace {

constexpr const char* kPayloadUri = "surrogate:payload";
constexpr int kParseOptions = XML_PARSE_NONET | XML_PARSE_NOWARNING | XML_PARSE_NOERROR;
// The documents a transformation reads (the carrier, the payload list) are never changed by
// it: short texts (ids, sizes, roles, the indentation) are kept inside their nodes, which saves
// about a tenth of the trees (100 000 files: 300 MB of carrier and 130 MB of payload list).
// The indentation between elements is not kept at all (the stylesheets strip it anyway,
// xsl:strip-space): one text node fewer per element.
constexpr int kInputOptions = kParseOptions | XML_PARSE_COMPACT | XML_PARSE_NOBLANKS;

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

// What the carrier records of a file: the texts of its <file> element's path, size and sha256
// attributes (views into the carrier's tree, or into `owned`).
struct RecordedFile {
  std::string_view path, size, sha256, role;
};

// The carrier's file records (c:files/c:file anywhere, as the stylesheet's key matches them),
// sorted by path; of records with the same path, the first in document order, as
// key('file-by-bag-path', ...)[1] takes it.
struct RecordedFiles {
  std::vector<RecordedFile> byPath;
  std::deque<std::string> owned;  // values that are not one plain text node in the tree

  explicit RecordedFiles(const xmlDoc* carrier) {
    // Every node in document order, by the tree's own links (no list of pending nodes).
    const xmlNode* root = xmlDocGetRootElement(carrier);
    for (const xmlNode* n = root; n;) {
      if (isCarrierElement(n, "file") && isCarrierElement(n->parent, "files"))
        byPath.push_back({value(n, "path"), value(n, "size"), value(n, "sha256"), value(n, "role")});
      if (n->type == XML_ELEMENT_NODE && n->children) {
        n = n->children;
        continue;
      }
      while (n != root && !n->next) n = n->parent;
      n = n == root ? nullptr : n->next;
    }
    std::stable_sort(byPath.begin(), byPath.end(),
                     [](const RecordedFile& a, const RecordedFile& b) { return a.path < b.path; });
  }

  // The record of a payload path ("data/" + carrier path), or nullptr.
  const RecordedFile* find(const std::string& bagPath) const {
    if (bagPath.rfind("data/", 0) != 0) return nullptr;
    const std::string_view path = std::string_view(bagPath).substr(5);
    const auto it = std::lower_bound(byPath.begin(), byPath.end(), path,
                                     [](const RecordedFile& r, std::string_view p) { return r.path < p; });
    return it != byPath.end() && it->path == path ? &*it : nullptr;
  }

 private:
  static bool isCarrierElement(const xmlNode* n, const char* name) {
    return n && n->type == XML_ELEMENT_NODE && n->ns && n->ns->href &&
           std::strcmp(reinterpret_cast<const char*>(n->ns->href), carrier::kNamespace) == 0 &&
           std::strcmp(reinterpret_cast<const char*>(n->name), name) == 0;
  }
  std::string_view value(const xmlNode* element, const char* name) {
    const xmlAttr* a = xmlHasNsProp(element, reinterpret_cast<const xmlChar*>(name), nullptr);
    if (!a) return {};
    const xmlNode* text = a->children;
    if (text && !text->next && text->type == XML_TEXT_NODE && text->content)
      return reinterpret_cast<const char*>(text->content);
    xmlChar* joined = xmlNodeListGetString(element->doc, a->children, 1);
    owned.emplace_back(joined ? reinterpret_cast<const char*>(joined) : "");
    xmlFree(joined);
    return owned.back();
  }
};

// The file groups of METS (the carrier's file roles, xsd/carrier.xsd FileRole): a payload
// entry is named after its group.
bool isGroupName(std::string_view role) {
  for (const char* group : {"original", "export", "lp", "sidecar", "other", "prior", "assembly", "result"})
    if (role == group) return true;
  return false;
}

// The web copy (`run --publish`, stages/web_copy_stage.h): results in finished-files/web/, the
// package's access copy (fileGrp USE="access"; docs/package.md).
bool isAccessCopy(const RecordedFile& r) {
  return r.role == "result" && r.path.rfind("finished-files/web/", 0) == 0;
}

// A payload file as the stylesheet reads it. Its size and SHA-256 are left out when the
// carrier's record of the same path gives the same ones (the stylesheet then takes the
// record's): two attributes fewer per file is about 50 MB less of tree for 100 000 files, and
// the result is the same. With the carrier's records, the element is named after the file's
// group (the record's role, "other" when there is no record, as the stylesheet would look it
// up; "file" when the role is none of the groups): the METS file groups and structure then
// test a name instead of looking the path up once per group (8 groups x 3 passes x 100 000
// files was 40 % of deriving METS). A name costs no memory; an attribute would cost 20 MB.
std::string payloadEntry(const PayloadFile& f, const RecordedFiles* recorded = nullptr) {
  const RecordedFile* r = recorded ? recorded->find(f.path) : nullptr;
  const bool asRecorded = r && r->sha256 == f.sha256 && r->size == std::to_string(f.size);
  const std::string_view group = !recorded            ? "file"
                                 : !r                   ? "other"
                                 : isAccessCopy(*r)     ? "access"
                                 : isGroupName(r->role) ? r->role
                                                        : "file";
  std::string out = "<" + std::string(group) + " path=\"" + attributeText(f.path, f.path) + "\"";
  if (!asRecorded)
    out += " size=\"" + std::to_string(f.size) + "\" sha256=\"" + attributeText(f.sha256, f.path) + "\"";
  return out + " sha512=\"" + attributeText(f.sha512, f.path) + "\"/>";
}

// The payload list as XML ("<payload>", one element per payload file, "</payload>", with no
// white space between them: the stylesheet selects payload/* only, and a line break would
// be one more text node per file, 13 MB for 100 000 files), made
// a few entries at a time as the parser reads it: the whole text (30 MB for 100 000 files)
// would otherwise be held, and copied by libxml2, beside the document it becomes.
// Every entry is checked (checkPayload) before a transformation starts, so that making one
// never throws inside libxml2.
struct PayloadText {
  const std::vector<PayloadFile>* files = nullptr;
  const RecordedFiles* recorded = nullptr;
  std::size_t next = 0;
  bool opened = false, closed = false;
  std::string pending;
  std::size_t at = 0;

  static int read(void* context, char* buffer, int size) {
    auto* t = static_cast<PayloadText*>(context);
    try {
      while (t->pending.size() - t->at < static_cast<std::size_t>(size) && !t->closed) {
        t->pending.erase(0, t->at);
        t->at = 0;
        if (!t->opened) {
          t->pending += "<payload>";
          t->opened = true;
        } else if (t->next < t->files->size()) {
          for (int i = 0; i < 64 && t->next < t->files->size(); ++i) t->pending += payloadEntry((*t->files)[t->next++], t->recorded);
        } else {
          t->pending += "</payload>\n";
          t->closed = true;
        }
      }
    } catch (...) {
      return -1;  // never across libxml2 (checkPayload has already refused what would throw)
    }
    const std::size_t n = std::min(t->pending.size() - t->at, static_cast<std::size_t>(size));
    std::memcpy(buffer, t->pending.data() + t->at, n);
    t->at += n;
    return static_cast<int>(n);
  }
};

void checkPayload(const std::vector<PayloadFile>& payload) {
  for (const PayloadFile& f : payload) (void)payloadEntry(f);
}

// The payload list of the transformation running on this thread (document("surrogate:payload")).
thread_local const std::vector<PayloadFile>* currentPayload = nullptr;
// The carrier's tree of that transformation (whose file records the payload list refers to).
thread_local const xmlDoc* currentCarrier = nullptr;
// The same list when the caller gave it away (deriveMetsTo with PackageFacts&&): released
// once its document is made.
thread_local std::vector<PayloadFile>* releasablePayload = nullptr;

// libxslt's document loader: only the payload list; every other document is refused.
xmlDocPtr payloadOnlyLoader(const xmlChar* uri, xmlDictPtr, int, void*, xsltLoadType type) {
  if (type != XSLT_LOAD_DOCUMENT || !uri || !currentPayload) return nullptr;
  if (std::strcmp(reinterpret_cast<const char*>(uri), kPayloadUri) != 0) return nullptr;
  const RecordedFiles recorded(currentCarrier);
  PayloadText text;
  text.files = currentPayload;
  text.recorded = &recorded;
  xmlDocPtr doc = xmlReadIO(&PayloadText::read, nullptr, &text, kPayloadUri, nullptr, kInputOptions);
  // libxslt orders a loaded document's elements for XPath only when its debugger hook is off;
  // a streamed transformation (result_stream.h) has it on.
  if (doc) xmlXPathOrderDocElems(doc);
  if (doc && releasablePayload == currentPayload) {
    // libxslt keeps the loaded document for the rest of the transformation (document() of
    // the same URI is not loaded again): the list is not read after this.
    std::vector<PayloadFile>().swap(*releasablePayload);
    releasablePayload = nullptr;
  }
  return doc;
}

int allowPayloadOnly(xsltSecurityPrefsPtr, xsltTransformContextPtr, const char* value) {
  return value && std::strcmp(value, kPayloadUri) == 0 ? 1 : 0;
}

void initialiseXslt() {
  static std::once_flag once;
  std::call_once(once, [] {
    initialiseXml();
    xsltInit();
    // EXSLT's string functions only (str:encode-uri for the RO-Crate's identifiers): not the
    // other modules, whose exsl:document would write files.
    exsltStrRegister();
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

// With `stream`, the result is written to it as it is built (result_stream.h), and freed as
// it is written; `streamed` then says whether the bytes are xsltSaveResultTo's.
Transformed runTransform(const std::filesystem::path& stylesheet, const std::string& carrierXml,
                         const std::string& source,
                         const std::vector<std::pair<std::string, std::string>>& params,
                         const std::vector<PayloadFile>* payload, xmlOutputBufferPtr stream = nullptr,
                         bool* streamed = nullptr,
                         const std::function<void(xmlDoc*)>& check = {},
                         std::vector<PayloadFile>* releasable = nullptr,
                         std::string* releasableCarrier = nullptr) {
  initialiseXslt();
  Transformed t;
  // The carrier, parsed once with the safe parser's options (no network); a document that
  // fails its rules (not well-formed, a DOCTYPE, too large) is given to it to say why.
  // (Read in pieces: xmlReadMemory would first copy the whole text.)
  struct Pieces {
    const std::string* text;
    std::size_t at = 0;
    static int read(void* context, char* buffer, int size) {
      auto* p = static_cast<Pieces*>(context);
      const std::size_t n = std::min(p->text->size() - p->at, static_cast<std::size_t>(size));
      std::memcpy(buffer, p->text->data() + p->at, n);
      p->at += n;
      return static_cast<int>(n);
    }
  } pieces{&carrierXml};
  if (carrierXml.size() <= static_cast<std::size_t>(INT32_MAX))
    t.input.reset(xmlReadIO(&Pieces::read, nullptr, &pieces, source.c_str(), nullptr, kInputOptions));
  if (!t.input || t.input->intSubset || t.input->extSubset) {
    t.input.reset();
    xml::checkWellFormed(carrierXml, source);
    throwInputError(source, "metadata", "is not well-formed XML");
  }
  if (releasableCarrier) std::string().swap(*releasableCarrier);  // the tree holds it now

  const std::string styleText = readFile(stylesheet, "metadata");
  xml::checkWellFormed(styleText, stylesheet.string());
  xmlDocPtr styleDoc = xmlReadMemory(styleText.data(), static_cast<int>(styleText.size()),
                                     stylesheet.c_str(), nullptr, kParseOptions);
  // A stylesheet of the installation damaged: the installation to repair, as a missing one
  // (core/resources.h), exit 1.
  if (!styleDoc) throw Error(ErrorKind::Input, stylesheet.string(), "metadata",
                             "the stylesheet is not well-formed; reinstall Surrogate");
  t.style.reset(xsltParseStylesheetDoc(styleDoc));
  if (!t.style) {
    xmlFreeDoc(styleDoc);
    throw Error(ErrorKind::Input, stylesheet.string(), "metadata",
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

  std::unique_ptr<ResultStream> writer;
  if (stream) {
    writer = std::make_unique<ResultStream>(t.style.get(), stream);
    writer->attach(ctxt.get());
  }
  currentPayload = payload;
  currentCarrier = t.input.get();
  releasablePayload = releasable;
  t.result.reset(xsltApplyStylesheetUser(t.style.get(), t.input.get(), raw.data(), nullptr, nullptr,
                                         ctxt.get()));
  currentPayload = nullptr;
  currentCarrier = nullptr;
  releasablePayload = nullptr;
  const bool failed = !t.result || ctxt->state != XSLT_STATE_OK;
  xsltSetGenericErrorFunc(nullptr, nullptr);
  if (failed) {
    throw Error(ErrorKind::Input, source, "metadata",
                "deriving metadata with " + stylesheet.filename().string() + " failed (" +
                    errors.summary() + ")");
  }
  if (writer) {
    // The context (with the payload document it loaded) and the input are no longer needed:
    // free them before the rest of the result is written.
    ctxt.reset();
    t.input.reset();
    if (check) check(t.result.get());
    *streamed = writer->finish(t.result.get());
  }
  return t;
}

std::string transform(const std::filesystem::path& stylesheet, const std::string& carrierXml,
                      const std::string& source,
                      const std::vector<std::pair<std::string, std::string>>& params,
                      const std::vector<PayloadFile>* payload) {
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

// The transformation run with its result written into `sink` as it is built (UTF-8, as
// xsltSaveResultToString writes it: no encoder). `check` sees the result tree before its last
// part is written. Returns whether the bytes given are xsltSaveResultTo's (see deriveMetsTo).
bool transformTo(const std::filesystem::path& stylesheet, const std::string& carrierXml,
                 const std::string& source,
                 const std::vector<std::pair<std::string, std::string>>& params,
                 const std::vector<PayloadFile>* payload, const TextSink& sink,
                 const std::function<void(xmlDoc*)>& check = {},
                 std::vector<PayloadFile>* releasable = nullptr,
                 std::string* releasableCarrier = nullptr) {
  struct Target {
    const TextSink* sink;
    std::exception_ptr failure;
  } target{&sink, nullptr};
  auto write = [](void* context, const char* data, int length) -> int {
    // After a failure the rest is dropped rather than refused: libxml2 would print its own
    // "I/O error" before the caller's message, which says what failed and what to do.
    auto* to = static_cast<Target*>(context);
    if (to->failure) return length;
    try {
      (*to->sink)(data, static_cast<std::size_t>(length));
    } catch (...) {
      to->failure = std::current_exception();  // never across libxml2
    }
    return length;
  };
  xmlOutputBufferPtr buffer = xmlOutputBufferCreateIO(write, nullptr, &target, nullptr);
  if (!buffer) throw Error(ErrorKind::Internal, stylesheet.string(), "metadata", "libxml2 could not start");
  bool streamed = false;
  try {
    runTransform(stylesheet, carrierXml, source, params, payload, buffer, &streamed, check,
                 releasable, releasableCarrier);
  } catch (...) {
    xmlOutputBufferClose(buffer);
    throw;
  }
  const int closed = xmlOutputBufferClose(buffer);
  if (target.failure) std::rethrow_exception(target.failure);
  if (closed < 0)
    throw Error(ErrorKind::Internal, stylesheet.string(), "metadata",
                "libxslt could not serialise the result");
  return streamed;
}

void requireRdf(xmlDoc* result, const std::filesystem::path& stylesheet) {
  const xmlNode* root = xmlDocGetRootElement(result);
  const bool rdf = root && std::strcmp(reinterpret_cast<const char*>(root->name), "RDF") == 0 &&
                   root->ns &&
                   std::strcmp(reinterpret_cast<const char*>(root->ns->href),
                               "http://www.w3.org/1999/02/22-rdf-syntax-ns#") == 0;
  if (!rdf)
    throw Error(ErrorKind::Internal, stylesheet.string(), "metadata",
                "the stylesheet did not give RDF/XML (its root is not rdf:RDF); reinstall Surrogate");
}

// The METS stylesheet's parameters for a package (its payload list checked first).
std::vector<std::pair<std::string, std::string>> metsParams(const PackageFacts& facts) {
  checkPayload(facts.payload);
  return {
      {"package-id", facts.packageId},
      {"packaging-time", facts.packagingTime},
      {"software-agent", facts.softwareAgent.empty() ? "Surrogate" : facts.softwareAgent},
      {"previous-package-id", facts.previousPackageId},
      {"payload-uri", kPayloadUri},  // always: document('') would read the stylesheet
      {"mapping-edition", std::to_string(facts.mappingEdition)},
  };
}

std::vector<std::pair<std::string, std::string>> crmParams(const CrmFacts& facts) {
  return {{"package-id", facts.packageId},
          {"previous-package-id", facts.previousPackageId},
          {"base-uri", facts.baseUri}};
}

}  // namespace

CrmFacts crmFactsOf(const PackageFacts& facts) {
  return {facts.packageId, facts.previousPackageId, facts.baseUri};
}

std::string deriveCrm(const std::string& carrierXml, const std::string& source) {
  return deriveCrm(carrierXml, CrmFacts{}, source);
}

std::string deriveCrm(const std::string& carrierXml, const CrmFacts& facts, const std::string& source) {
  return transform(crmStylesheetPath(), carrierXml, source, crmParams(facts), nullptr);
}

std::string deriveRoCrate(const std::string& carrierXml, const CrateFacts& facts,
                          const std::string& source) {
  return transform(roCrateStylesheetPath(), carrierXml, source,
                   {{"package-id", facts.packageId},
                    {"packaging-time", facts.packagingTime},
                    {"has-report", facts.hasReport ? "true" : ""},
                    {"mapping-edition", std::to_string(facts.mappingEdition)}},
                   nullptr);
}

std::string deriveMets(const std::string& carrierXml, const PackageFacts& facts,
                       const std::string& source) {
  return transform(metsStylesheetPath(), carrierXml, source, metsParams(facts), &facts.payload);
}

bool deriveCrmTo(const std::string& carrierXml, const TextSink& sink, const std::string& source) {
  return deriveCrmTo(carrierXml, CrmFacts{}, sink, source);
}

bool deriveCrmTo(const std::string& carrierXml, const CrmFacts& facts, const TextSink& sink,
                 const std::string& source) {
  const std::filesystem::path stylesheet = crmStylesheetPath();
  return transformTo(stylesheet, carrierXml, source, crmParams(facts), nullptr, sink,
                     [&](xmlDoc* result) { requireRdf(result, stylesheet); });
}

bool deriveMetsTo(const std::string& carrierXml, const PackageFacts& facts, const TextSink& sink,
                  const std::string& source) {
  return transformTo(metsStylesheetPath(), carrierXml, source, metsParams(facts), &facts.payload, sink);
}

bool deriveMetsTo(const std::string& carrierXml, PackageFacts&& facts, const TextSink& sink,
                  const std::string& source) {
  return transformTo(metsStylesheetPath(), carrierXml, source, metsParams(facts), &facts.payload,
                     sink, {}, &facts.payload);
}

bool deriveMetsTo(std::string&& carrierXml, PackageFacts&& facts, const TextSink& sink,
                  const std::string& source) {
  return transformTo(metsStylesheetPath(), carrierXml, source, metsParams(facts), &facts.payload,
                     sink, {}, &facts.payload, &carrierXml);
}

std::string libxsltVersion() {
  // The library linked (xsltLibxsltVersion, e.g. 10135), written as its releases are: 1.1.35.
  const int v = xsltLibxsltVersion;
  return std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." + std::to_string(v % 100);
}

}  // namespace surrogate::mapping
