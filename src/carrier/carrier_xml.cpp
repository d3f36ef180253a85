// Serialising the carrier model to XML and back (libxml2 tree API).
#include <libxml/parser.h>
#include <libxml/tree.h>

#include <cstring>
#include <memory>

#include "carrier/carrier.h"
#include "carrier/xml.h"
#include "carrier/xml_tree.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/resources.h"
#include "core/text.h"

namespace surrogate::carrier {

namespace {

const xmlChar* X(const char* s) { return reinterpret_cast<const xmlChar*>(s); }
const xmlChar* X(const std::string& s) { return X(s.c_str()); }

using xml::DocPtr;

// ---- writing ----------------------------------------------------------------------------

xmlNodePtr child(xmlNodePtr parent, const char* name) {
  return xmlNewChild(parent, parent->ns, X(name), nullptr);
}

xmlNodePtr textChild(xmlNodePtr parent, const char* name, const std::string& text) {
  // xmlNewTextChild escapes the text (xmlNewChild would not).
  return xmlNewTextChild(parent, parent->ns, X(name), X(text));
}

void attr(xmlNodePtr node, const char* name, const std::string& value) {
  xmlNewProp(node, X(name), X(value));
}

void optionalAttr(xmlNodePtr node, const char* name, const std::string& value) {
  if (!value.empty()) attr(node, name, value);
}

void writeAudited(xmlNodePtr header, const AuditedSource& a) {
  xmlNodePtr n = child(header, "audited");
  attr(n, "source", a.source);
  attr(n, "kind", a.kind);
  attr(n, "copied", a.copied);
  if (!a.packageSha256.empty()) {
    attr(n, "packageSize", std::to_string(a.packageSize));
    attr(n, "packageSha256", a.packageSha256);
  }
  for (const AuditedSource::Item& f : a.files) {
    xmlNodePtr e = child(n, "evidence");
    attr(e, "path", f.path);
    attr(e, "from", f.from);
    attr(e, "size", std::to_string(f.size));
    attr(e, "sha256", f.sha256);
  }
}

void writeStep(xmlNodePtr list, const Step& s) {
  xmlNodePtr n = child(list, "step");
  attr(n, "id", s.id);
  attr(n, "component", s.component);
  attr(n, "version", s.version);
  optionalAttr(n, "algorithm", s.algorithm);
  if (!s.description.empty()) textChild(n, "description", s.description);
  for (const Param& p : s.params) {
    xmlNodePtr pn = child(n, "param");
    attr(pn, "name", p.name);
    attr(pn, "value", p.value);
  }
  for (const Intervention& i : s.interventions) {
    xmlNodePtr in = textChild(n, "intervention", i.reason);
    attr(in, "kind", i.kind);
    attr(in, "target", i.target);
    optionalAttr(in, "value", i.value);
    attr(in, "who", i.who);
    attr(in, "time", i.time);
  }
}

void writeHeader(xmlNodePtr root, const Header& h) {
  xmlNodePtr header = child(root, "header");
  textChild(header, "title", h.title);
  for (const Creator& c : h.creators) {
    xmlNodePtr n = textChild(header, "creator", c.name);
    attr(n, "role", c.role);
  }
  textChild(header, "created", h.created);
  textChild(header, "modified", h.modified);
  for (const auto& [key, value] : h.meta) attr(textChild(header, "meta", value), "key", key);
  if (!h.rights.empty()) textChild(header, "rights", h.rights);
  if (!h.license.empty()) textChild(header, "license", h.license);
  if (h.audited) writeAudited(header, *h.audited);
  xmlNodePtr m = child(header, "machine");
  attr(m, "hostname", h.machine.hostname);
  attr(m, "os", h.machine.os);
  attr(m, "architecture", h.machine.architecture);
  optionalAttr(m, "cpu", h.machine.cpu);
  if (h.machine.cores > 0) attr(m, "cores", std::to_string(h.machine.cores));
  if (h.machine.memoryBytes > 0) attr(m, "memoryBytes", std::to_string(h.machine.memoryBytes));
  for (const Software& s : h.software) {
    xmlNodePtr n = child(header, "software");
    attr(n, "name", s.name);
    attr(n, "version", s.version);
    optionalAttr(n, "role", s.role);
  }
  for (const RunRecord& r : h.runs) {
    xmlNodePtr n = child(header, "run");
    attr(n, "id", r.id);
    attr(n, "command", r.command);
    attr(n, "who", r.who);
    attr(n, "started", r.started);
    attr(n, "ended", r.ended);
    attr(n, "outcome", r.outcome);
    for (const std::string& a : r.arguments) textChild(n, "arg", a);
    for (const std::string& note : r.notes) textChild(n, "note", note);
    if (!r.planned.empty()) {
      xmlNodePtr planned = child(n, "planned");
      for (const Step& s : r.planned) writeStep(planned, s);
    }
  }
}

void writeFiles(xmlNodePtr root, const std::vector<FileRecord>& files) {
  xmlNodePtr list = child(root, "files");
  for (const FileRecord& f : files) {
    xmlNodePtr n = child(list, "file");
    attr(n, "id", f.id);
    attr(n, "path", f.path);
    attr(n, "role", f.role);
    attr(n, "size", std::to_string(f.size));
    attr(n, "sha256", f.sha256);
    attr(n, "format", f.format);
    optionalAttr(n, "mediaType", f.mediaType);
    optionalAttr(n, "puid", f.puid);
    optionalAttr(n, "createdBy", f.createdBy);
    optionalAttr(n, "pairedWith", f.pairedWith);
    if (f.unrecordedProcessing) attr(n, "unrecordedProcessing", "true");
    optionalAttr(n, "priorKind", f.priorKind);
    optionalAttr(n, "madeBy", f.madeBy);
    if (f.imageSize) {
      xmlNodePtr im = child(n, "image");
      attr(im, "width", std::to_string(f.imageSize->first));
      attr(im, "height", std::to_string(f.imageSize->second));
    }
    if (!f.camera.empty() || !f.cameraRaw.empty()) {
      xmlNodePtr cam = child(n, "camera");
      for (const auto& [k, v] : f.camera) attr(cam, k.c_str(), v);
      for (const auto& [field, hex] : f.cameraRaw) {
        xmlNodePtr raw = child(cam, "raw");
        attr(raw, "field", field);
        attr(raw, "hex", hex);
      }
    }
    if (!f.xmp.empty()) {
      xmlNodePtr xmp = textChild(n, "xmp", f.xmp);
      if (f.xmpEscaped) attr(xmp, "escaped", "true");
    }
  }
}

void writeProcess(xmlNodePtr root, const std::vector<Step>& steps) {
  xmlNodePtr list = child(root, "process");
  for (const Step& s : steps) writeStep(list, s);
}

void writeData(xmlNodePtr root, const std::vector<Result>& results) {
  xmlNodePtr list = child(root, "data");
  for (const Result& r : results) {
    xmlNodePtr n = child(list, "result");
    attr(n, "step", r.step);
    attr(n, "status", r.status);
    attr(n, "started", r.started);
    attr(n, "ended", r.ended);
    attr(n, "seconds", formatNumber(r.seconds));
    for (const DataItem& item : r.items) {
      xmlNodePtr in = child(n, item.element.c_str());
      for (const auto& [k, v] : item.attributes) attr(in, k.c_str(), v);
    }
  }
}

void writeLog(xmlNodePtr root, const std::vector<LogEntry>& log) {
  xmlNodePtr list = child(root, "log");
  for (const LogEntry& e : log) {
    xmlNodePtr n = textChild(list, "entry", e.text);
    attr(n, "time", e.time);
    attr(n, "level", e.level);
    optionalAttr(n, "step", e.step);
    optionalAttr(n, "who", e.who);
  }
}

// ---- reading ----------------------------------------------------------------------------

std::string prop(xmlNodePtr n, const char* name) {
  xmlChar* v = xmlGetProp(n, X(name));
  if (!v) return "";
  std::string s(reinterpret_cast<const char*>(v));
  xmlFree(v);
  return s;
}

std::string text(xmlNodePtr n) {
  xmlChar* v = xmlNodeGetContent(n);
  if (!v) return "";
  std::string s(reinterpret_cast<const char*>(v));
  xmlFree(v);
  return s;
}

bool is(xmlNodePtr n, const char* name) {
  return n->type == XML_ELEMENT_NODE && std::strcmp(reinterpret_cast<const char*>(n->name), name) == 0;
}

template <typename F>
void forChildren(xmlNodePtr parent, F f) {
  for (xmlNodePtr c = parent->children; c; c = c->next)
    if (c->type == XML_ELEMENT_NODE) f(c);
}

Attributes allProps(xmlNodePtr n) {
  Attributes out;
  for (xmlAttrPtr a = n->properties; a; a = a->next) {
    const char* name = reinterpret_cast<const char*>(a->name);
    out.emplace_back(name, prop(n, name));
  }
  return out;
}

AuditedSource readAudited(xmlNodePtr node) {
  AuditedSource a;
  a.source = prop(node, "source");
  a.kind = prop(node, "kind");
  a.copied = prop(node, "copied");
  a.packageSha256 = prop(node, "packageSha256");
  if (!a.packageSha256.empty()) a.packageSize = std::stoull(prop(node, "packageSize"));
  forChildren(node, [&](xmlNodePtr e) {
    if (is(e, "evidence"))
      a.files.push_back({prop(e, "path"), prop(e, "from"), std::stoull(prop(e, "size")), prop(e, "sha256")});
  });
  return a;
}

Step readStep(xmlNodePtr n);

Header readHeader(xmlNodePtr node) {
  Header h;
  forChildren(node, [&](xmlNodePtr c) {
    if (is(c, "title")) h.title = text(c);
    else if (is(c, "creator")) h.creators.push_back({text(c), prop(c, "role")});
    else if (is(c, "created")) h.created = text(c);
    else if (is(c, "modified")) h.modified = text(c);
    else if (is(c, "meta")) h.meta.emplace_back(prop(c, "key"), text(c));
    else if (is(c, "rights")) h.rights = text(c);
    else if (is(c, "license")) h.license = text(c);
    else if (is(c, "audited")) h.audited = readAudited(c);
    else if (is(c, "machine")) {
      h.machine.hostname = prop(c, "hostname");
      h.machine.os = prop(c, "os");
      h.machine.architecture = prop(c, "architecture");
      h.machine.cpu = prop(c, "cpu");
      const std::string cores = prop(c, "cores"), mem = prop(c, "memoryBytes");
      if (!cores.empty()) h.machine.cores = std::stoi(cores);
      if (!mem.empty()) h.machine.memoryBytes = std::stoull(mem);
    } else if (is(c, "software")) {
      h.software.push_back({prop(c, "name"), prop(c, "version"), prop(c, "role")});
    } else if (is(c, "run")) {
      RunRecord r{prop(c, "id"), prop(c, "command"), prop(c, "who"), prop(c, "started"),
                  prop(c, "ended"), prop(c, "outcome"), {}, {}, {}};
      forChildren(c, [&](xmlNodePtr a) {
        if (is(a, "arg")) r.arguments.push_back(text(a));
        else if (is(a, "note")) r.notes.push_back(text(a));
        else if (is(a, "planned"))
          forChildren(a, [&](xmlNodePtr step) {
            if (is(step, "step")) r.planned.push_back(readStep(step));
          });
      });
      h.runs.push_back(std::move(r));
    }
  });
  return h;
}

FileRecord readFileRecord(xmlNodePtr n) {
  FileRecord f;
  f.id = prop(n, "id");
  f.path = prop(n, "path");
  f.role = prop(n, "role");
  f.size = std::stoull(prop(n, "size"));
  f.sha256 = prop(n, "sha256");
  f.format = prop(n, "format");
  f.mediaType = prop(n, "mediaType");
  f.puid = prop(n, "puid");
  f.createdBy = prop(n, "createdBy");
  f.pairedWith = prop(n, "pairedWith");
  const std::string unrecorded = prop(n, "unrecordedProcessing");
  f.unrecordedProcessing = unrecorded == "true" || unrecorded == "1";
  f.priorKind = prop(n, "priorKind");
  f.madeBy = prop(n, "madeBy");
  forChildren(n, [&](xmlNodePtr c) {
    if (is(c, "image")) f.imageSize = {std::stoi(prop(c, "width")), std::stoi(prop(c, "height"))};
    else if (is(c, "camera")) {
      f.camera = allProps(c);
      forChildren(c, [&](xmlNodePtr raw) {
        if (is(raw, "raw")) f.cameraRaw.emplace_back(prop(raw, "field"), prop(raw, "hex"));
      });
    } else if (is(c, "xmp")) {
      f.xmp = text(c);
      f.xmpEscaped = prop(c, "escaped") == "true";
    }
  });
  return f;
}

Step readStep(xmlNodePtr n) {
  Step s;
  s.id = prop(n, "id");
  s.component = prop(n, "component");
  s.version = prop(n, "version");
  s.algorithm = prop(n, "algorithm");
  forChildren(n, [&](xmlNodePtr c) {
    if (is(c, "description")) s.description = text(c);
    else if (is(c, "param")) s.params.push_back({prop(c, "name"), prop(c, "value")});
    else if (is(c, "intervention"))
      s.interventions.push_back({prop(c, "kind"), prop(c, "target"), prop(c, "value"),
                                 prop(c, "who"), prop(c, "time"), text(c)});
  });
  return s;
}

Result readResult(xmlNodePtr n) {
  Result r;
  r.step = prop(n, "step");
  r.status = prop(n, "status");
  r.started = prop(n, "started");
  r.ended = prop(n, "ended");
  const std::string seconds = prop(n, "seconds");
  r.seconds = seconds.empty() ? 0 : std::stod(seconds);
  forChildren(n, [&](xmlNodePtr c) {
    r.items.push_back(DataItem{reinterpret_cast<const char*>(c->name), allProps(c)});
  });
  return r;
}

}  // namespace

std::string toXml(const Carrier& carrier) {
  DocPtr doc(xmlNewDoc(X("1.0")));
  xmlNodePtr root = xmlNewDocNode(doc.get(), nullptr, X("carrier"), nullptr);
  xmlDocSetRootElement(doc.get(), root);
  xmlNsPtr ns = xmlNewNs(root, X(kNamespace), nullptr);
  xmlSetNs(root, ns);
  attr(root, "version", kFormatVersion);
  writeHeader(root, carrier.header);
  writeFiles(root, carrier.files);
  writeProcess(root, carrier.process);
  writeData(root, carrier.data);
  writeLog(root, carrier.log);
  xmlChar* buffer = nullptr;
  int size = 0;
  xmlDocDumpFormatMemoryEnc(doc.get(), &buffer, &size, "UTF-8", 1);
  std::string out(reinterpret_cast<const char*>(buffer), static_cast<std::size_t>(size));
  xmlFree(buffer);
  return out;
}

Carrier parseCarrier(const std::string& xmlText, const std::string& source) {
  const DocPtr doc = xml::parseValidated(xmlText, source, resourcePath("xsd/carrier.xsd"));
  Carrier c;
  forChildren(xmlDocGetRootElement(doc.get()), [&](xmlNodePtr section) {
    // Sized first: growing a list of 100 000 file records by doubling would hold two copies.
    const std::size_t count = xmlChildElementCount(section);
    if (is(section, "header")) {
      c.header = readHeader(section);
    } else if (is(section, "files")) {
      c.files.reserve(count);
      forChildren(section, [&](xmlNodePtr n) { c.files.push_back(readFileRecord(n)); });
    } else if (is(section, "process")) {
      c.process.reserve(count);
      forChildren(section, [&](xmlNodePtr n) { c.process.push_back(readStep(n)); });
    } else if (is(section, "data")) {
      c.data.reserve(count);
      forChildren(section, [&](xmlNodePtr n) { c.data.push_back(readResult(n)); });
    } else if (is(section, "log")) {
      c.log.reserve(count);
      forChildren(section, [&](xmlNodePtr n) {
        c.log.push_back({prop(n, "time"), prop(n, "level"), prop(n, "step"), prop(n, "who"), text(n)});
      });
    }
  });
  return c;
}

void saveCarrier(const Carrier& carrier, const std::filesystem::path& path) {
  saveCarrierXml(toXml(carrier), path);
}

void saveCarrierXml(const std::string& text, const std::filesystem::path& path) {
  // Found before the try: a schema missing from the installation is the installation's fault
  // (resourcePath says to reinstall), not a carrier that does not validate.
  const std::filesystem::path schema = resourcePath("xsd/carrier.xsd");
  try {
    xml::validateAgainstSchema(text, path.string(), schema);
  } catch (const Error& e) {
    // The program built this document: an invalid one is a bug, not the user's fault.
    throw Error(ErrorKind::Internal, path.string(), "carrier",
                "Surrogate produced a carrier that does not validate; please report this bug: " +
                    e.message());
  }
  writeFileAtomically(path, text);
}

Carrier loadCarrier(const std::filesystem::path& path) {
  return parseCarrier(readFile(path, "carrier"), path.string());
}

}  // namespace surrogate::carrier
