#include "archival_checks.h"

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xpath.h>
#include <libxml/xpathInternals.h>

#include <array>
#include <cstdio>
#include <deque>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace archival {

namespace {

const char* const kPremis = "http://www.loc.gov/premis/v3";
const char* const kMets = "http://www.loc.gov/METS/";
const char* const kXlink = "http://www.w3.org/1999/xlink";

std::string text(xmlNodePtr n) {
  xmlChar* c = xmlNodeGetContent(n);
  std::string s = c ? reinterpret_cast<const char*>(c) : "";
  xmlFree(c);
  return s;
}

std::string attr(xmlNodePtr n, const char* name, const char* ns = nullptr) {
  xmlChar* c = ns ? xmlGetNsProp(n, BAD_CAST name, BAD_CAST ns) : xmlGetProp(n, BAD_CAST name);
  std::string s = c ? reinterpret_cast<const char*>(c) : "";
  xmlFree(c);
  return s;
}

// Children of `n` with the PREMIS local name `name`.
std::vector<xmlNodePtr> kids(xmlNodePtr n, const char* name) {
  std::vector<xmlNodePtr> out;
  for (xmlNodePtr c = n ? n->children : nullptr; c; c = c->next)
    if (c->type == XML_ELEMENT_NODE && xmlStrcmp(c->name, BAD_CAST name) == 0) out.push_back(c);
  return out;
}
xmlNodePtr kid(xmlNodePtr n, const char* name) {
  const auto k = kids(n, name);
  return k.empty() ? nullptr : k.front();
}
std::string kidText(xmlNodePtr n, const char* name) {
  xmlNodePtr k = kid(n, name);
  return k ? text(k) : "";
}

struct Doc {
  xmlDocPtr doc = nullptr;
  xmlXPathContextPtr ctx = nullptr;
  explicit Doc(const std::string& xml) {
    doc = xmlReadMemory(xml.data(), static_cast<int>(xml.size()), "mets.xml", nullptr, XML_PARSE_NONET);
    if (!doc) throw std::runtime_error("METS is not well-formed");
    ctx = xmlXPathNewContext(doc);
    xmlXPathRegisterNs(ctx, BAD_CAST "premis", BAD_CAST kPremis);
    xmlXPathRegisterNs(ctx, BAD_CAST "mets", BAD_CAST kMets);
    xmlXPathRegisterNs(ctx, BAD_CAST "xlink", BAD_CAST kXlink);
  }
  ~Doc() {
    xmlXPathFreeContext(ctx);
    xmlFreeDoc(doc);
  }
  std::vector<xmlNodePtr> all(const char* xpath) const {
    std::vector<xmlNodePtr> out;
    xmlXPathObjectPtr r = xmlXPathEvalExpression(BAD_CAST xpath, ctx);
    if (r && r->nodesetval)
      for (int i = 0; i < r->nodesetval->nodeNr; ++i) out.push_back(r->nodesetval->nodeTab[i]);
    xmlXPathFreeObject(r);
    return out;
  }
};

Premis::Link linkOf(xmlNodePtr n, const char* type, const char* value, const char* role) {
  return {kidText(n, type), kidText(n, value), role ? kidText(n, role) : ""};
}

}  // namespace

Premis readPremis(const std::string& metsXml) {
  Doc d(metsXml);
  Premis p;
  for (xmlNodePtr o : d.all("//premis:object")) {
    Premis::Object obj;
    obj.kind = attr(o, "type", "http://www.w3.org/2001/XMLSchema-instance");
    for (xmlNodePtr id : kids(o, "objectIdentifier"))
      obj.ids.emplace_back(kidText(id, "objectIdentifierType"), kidText(id, "objectIdentifierValue"));
    for (xmlNodePtr r : kids(o, "relationship")) {
      const bool derivation = kidText(r, "relationshipType") == "derivation" &&
                              kidText(r, "relationshipSubType") == "has source";
      for (xmlNodePtr ro : kids(r, "relatedObjectIdentifier")) {
        const auto l = linkOf(ro, "relatedObjectIdentifierType", "relatedObjectIdentifierValue", nullptr);
        obj.relatedObjects.push_back(l);
        if (derivation) obj.derivedFrom.push_back(l);
      }
      for (xmlNodePtr re : kids(r, "relatedEventIdentifier"))
        if (derivation) obj.derivationEvents.push_back(kidText(re, "relatedEventIdentifierValue"));
    }
    for (xmlNodePtr e : kids(o, "linkingEventIdentifier")) obj.events.push_back(kidText(e, "linkingEventIdentifierValue"));
    for (xmlNodePtr r : kids(o, "linkingRightsStatementIdentifier"))
      obj.rights.push_back(kidText(r, "linkingRightsStatementIdentifierValue"));
    p.objects.push_back(obj);
  }
  for (xmlNodePtr e : d.all("//premis:event")) {
    Premis::Event ev;
    ev.id = kidText(kid(e, "eventIdentifier"), "eventIdentifierValue");
    xmlNodePtr type = kid(e, "eventType");
    ev.type = type ? text(type) : "";
    ev.typeUri = type ? attr(type, "valueURI") : "";
    ev.dateTime = kidText(e, "eventDateTime");
    ev.outcome = kidText(kid(e, "eventOutcomeInformation"), "eventOutcome");
    for (xmlNodePtr a : kids(e, "linkingAgentIdentifier"))
      ev.agents.push_back(linkOf(a, "linkingAgentIdentifierType", "linkingAgentIdentifierValue", "linkingAgentRole"));
    for (xmlNodePtr o : kids(e, "linkingObjectIdentifier"))
      ev.objects.push_back(linkOf(o, "linkingObjectIdentifierType", "linkingObjectIdentifierValue", "linkingObjectRole"));
    p.events.push_back(ev);
  }
  for (xmlNodePtr a : d.all("//premis:agent")) {
    xmlNodePtr id = kid(a, "agentIdentifier");
    p.agents.push_back({kidText(id, "agentIdentifierType"), kidText(id, "agentIdentifierValue"),
                        kidText(a, "agentName"), kidText(a, "agentType")});
  }
  for (xmlNodePtr r : d.all("//premis:rightsStatement"))
    p.rightsStatements.push_back(kidText(kid(r, "rightsStatementIdentifier"), "rightsStatementIdentifierValue"));
  for (xmlNodePtr f : d.all("//mets:fileSec//mets:file")) {
    xmlNodePtr loc = nullptr;
    for (xmlNodePtr c = f->children; c; c = c->next)
      if (c->type == XML_ELEMENT_NODE && xmlStrcmp(c->name, BAD_CAST "FLocat") == 0) loc = c;
    p.files.emplace_back(loc ? attr(loc, "href", kXlink) : "", attr(f, "MIMETYPE"));
  }
  return p;
}

std::vector<std::string> linkProblems(const Premis& p) {
  std::vector<std::string> problems;
  std::map<std::pair<std::string, std::string>, int> agents, objects;
  std::map<std::string, int> events;
  for (const auto& a : p.agents) ++agents[{a.type, a.value}];
  for (const auto& e : p.events) ++events[e.id];
  for (const auto& o : p.objects)
    for (const auto& id : o.ids) ++objects[id];
  for (const auto& [k, n] : agents)
    if (n != 1) problems.push_back("agent " + k.first + " \"" + k.second + "\" is defined " + std::to_string(n) + " times");
  for (const auto& [k, n] : events)
    if (n != 1) problems.push_back("event " + k + " is defined " + std::to_string(n) + " times");
  for (const auto& [k, n] : objects)
    if (n != 1) problems.push_back("object " + k.first + " \"" + k.second + "\" is defined " + std::to_string(n) + " times");
  const std::set<std::string> rights(p.rightsStatements.begin(), p.rightsStatements.end());
  for (const auto& e : p.events) {
    for (const auto& a : e.agents)
      if (!agents.count({a.type, a.value}))
        problems.push_back("event " + e.id + " links agent " + a.type + " \"" + a.value + "\", which is not defined");
    for (const auto& o : e.objects)
      if (!objects.count({o.type, o.value}))
        problems.push_back("event " + e.id + " links object " + o.type + " \"" + o.value + "\", which is not defined");
    if (e.typeUri.rfind("http://id.loc.gov/vocabulary/preservation/eventType/", 0) != 0)
      problems.push_back("event " + e.id + " has no eventType URI of the LoC vocabulary");
  }
  for (const auto& o : p.objects) {
    const std::string name = o.ids.empty() ? "?" : o.ids.front().second;
    for (const auto& e : o.events)
      if (!events.count(e)) problems.push_back("object " + name + " links event " + e + ", which is not defined");
    for (const auto& e : o.derivationEvents)
      if (!events.count(e)) problems.push_back("object " + name + " is derived by event " + e + ", which is not defined");
    for (const auto& r : o.relatedObjects)
      if (!objects.count({r.type, r.value}))
        problems.push_back("object " + name + " relates to " + r.type + " \"" + r.value + "\", which is not defined");
    for (const auto& r : o.rights)
      if (!rights.count(r)) problems.push_back("object " + name + " links rights statement " + r + ", which is not defined");
  }
  return problems;
}

std::vector<std::string> derivationProblems(const Premis& p, const std::vector<std::string>& derived) {
  std::vector<std::string> problems;
  std::map<std::string, const Premis::Object*> byPath;
  for (const auto& o : p.objects)
    for (const auto& id : o.ids)
      if (id.first == "BagIt payload path") byPath[id.second] = &o;
  std::map<std::string, const Premis::Event*> eventById;
  for (const auto& e : p.events) eventById[e.id] = &e;
  // The photographs: the outcomes of the capture event.
  std::set<std::string> photographs;
  if (eventById.count("event-capture"))
    for (const auto& o : eventById.at("event-capture")->objects)
      if (o.role == "outcome") photographs.insert(o.value);
  for (const std::string& start : derived) {
    std::set<std::string> seen{start};
    std::deque<std::string> todo{start};
    bool reached = false;
    while (!todo.empty() && !reached) {
      const std::string path = todo.front();
      todo.pop_front();
      if (photographs.count(path)) {
        reached = true;
        break;
      }
      const auto it = byPath.find(path);
      if (it == byPath.end()) continue;
      for (const auto& src : it->second->derivedFrom)
        if (seen.insert(src.value).second) todo.push_back(src.value);
      // Each derivation by a Surrogate step names that step's event, which lists this object as
      // its outcome and the sources as its sources.
      for (const std::string& ev : it->second->derivationEvents) {
        const auto e = eventById.find(ev);
        if (e == eventById.end()) continue;
        bool outcome = false;
        for (const auto& o : e->second->objects) outcome = outcome || (o.value == path && o.role == "outcome");
        if (!outcome) problems.push_back(path + ": its event " + ev + " does not list it as its outcome");
        for (const auto& src : it->second->derivedFrom) {
          bool listed = false;
          for (const auto& o : e->second->objects) listed = listed || (o.value == src.value && o.role == "source");
          if (!listed) problems.push_back(path + ": its event " + ev + " does not list its source " + src.value);
        }
      }
    }
    if (!reached) problems.push_back(start + " has no PREMIS path back to a photograph");
  }
  return problems;
}

std::vector<Triple> parseNTriples(const std::string& textIn) {
  std::vector<Triple> out;
  std::istringstream in(textIn);
  std::string line;
  const std::regex iri("^<([^>]*)> <([^>]*)> (.*) \\.$");
  while (std::getline(in, line)) {
    std::smatch m;
    if (!std::regex_match(line, m, iri)) continue;
    std::string o = m[3];
    if (o.size() > 1 && o.front() == '<' && o.back() == '>') o = o.substr(1, o.size() - 2);
    out.push_back({m[1], m[2], o});
  }
  return out;
}

std::vector<Triple> rdfTriples(const std::string& rdfXml, const std::string& scratchDir) {
  const std::string file = scratchDir + "/crm-under-test.rdf";
  std::ofstream(file, std::ios::binary) << rdfXml;
  std::string out;
  FILE* pipe = ::popen(("rapper -q -i rdfxml -o ntriples '" + file + "' 2>&1").c_str(), "r");
  std::array<char, 4096> buffer{};
  while (pipe && std::fgets(buffer.data(), buffer.size(), pipe)) out += buffer.data();
  if (pipe) ::pclose(pipe);
  return parseNTriples(out);
}

namespace {

const std::string kCrm = "http://www.cidoc-crm.org/cidoc-crm/";
const std::string kDig = "http://www.cidoc-crm.org/extensions/crmdig/";
const std::string kType = "http://www.w3.org/1999/02/22-rdf-syntax-ns#type";

// "crm:E7_Activity" -> full IRI.
std::string expand(const std::string& curie) {
  if (curie.rfind("crm:", 0) == 0) return kCrm + curie.substr(4);
  if (curie.rfind("crmdig:", 0) == 0) return kDig + curie.substr(7);
  return curie;
}

bool inCrm(const std::string& iri) { return iri.rfind(kCrm, 0) == 0 || iri.rfind(kDig, 0) == 0; }

struct Table {
  std::map<std::string, std::vector<std::string>> superclasses;
  std::map<std::string, std::pair<std::string, std::string>> properties;  // domain, range
};

Table readTable(const std::string& path) {
  Table t;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f;
    std::istringstream fields(line);
    std::string word;
    while (fields >> word) f.push_back(word);
    if (f.size() >= 2 && f[0] == "class") {
      auto& sup = t.superclasses[expand(f[1])];
      for (std::size_t i = 2; i < f.size(); ++i) sup.push_back(expand(f[i]));
    } else if (f.size() == 4 && f[0] == "property") {
      t.properties[expand(f[1])] = {expand(f[2]), f[3] == "literal" ? "literal" : expand(f[3])};
    }
  }
  return t;
}

// Whether `cls` is `target` or a subclass of it, by the table.
bool isA(const Table& t, const std::string& cls, const std::string& target) {
  if (cls == target) return true;
  const auto it = t.superclasses.find(cls);
  if (it == t.superclasses.end()) return false;
  for (const std::string& s : it->second)
    if (isA(t, s, target)) return true;
  return false;
}

std::string shortName(const std::string& iri) {
  const auto slash = iri.find_last_of('/');
  return slash == std::string::npos ? iri : iri.substr(slash + 1);
}

}  // namespace

std::vector<std::string> crmTermProblems(const std::vector<Triple>& triples, const std::string& tablePath) {
  const Table t = readTable(tablePath);
  std::vector<std::string> problems;
  std::map<std::string, std::set<std::string>> types;
  for (const Triple& x : triples)
    if (x.p == kType) {
      types[x.s].insert(x.o);
      if (inCrm(x.o) && !t.superclasses.count(x.o)) problems.push_back("class " + x.o + " is not in the table");
    }
  const auto hasType = [&](const std::string& node, const std::string& cls) {
    const auto it = types.find(node);
    if (it == types.end()) return false;
    for (const std::string& c : it->second)
      if (isA(t, c, cls)) return true;
    return false;
  };
  std::set<std::string> reported;
  for (const Triple& x : triples) {
    if (!inCrm(x.p)) continue;
    const auto prop = t.properties.find(x.p);
    if (prop == t.properties.end()) {
      if (reported.insert(x.p).second) problems.push_back("property " + x.p + " is not in the table");
      continue;
    }
    const auto& [domain, range] = prop->second;
    if (!hasType(x.s, domain))
      problems.push_back(shortName(x.p) + ": subject " + x.s + " is not a " + shortName(domain));
    if (range == "literal") {
      if (!x.literal()) problems.push_back(shortName(x.p) + ": object " + x.o + " is not a literal");
    } else if (x.literal() || !hasType(x.o, range)) {
      problems.push_back(shortName(x.p) + ": object " + x.o + " of " + x.s + " is not a " + shortName(range));
    }
  }
  return problems;
}

std::vector<std::string> timeSpanNestingProblems(const std::vector<Triple>& triples) {
  std::map<std::string, std::string> spanOf, begin, end;
  const auto unquote = [](const std::string& lit) {
    const auto close = lit.find('"', 1);
    return lit.substr(1, close == std::string::npos ? std::string::npos : close - 1);
  };
  for (const Triple& x : triples) {
    if (x.p == kCrm + "P4_has_time-span") spanOf[x.s] = x.o;
    if (x.p == kCrm + "P82a_begin_of_the_begin") begin[x.s] = unquote(x.o);
    if (x.p == kCrm + "P82b_end_of_the_end") end[x.s] = unquote(x.o);
  }
  std::vector<std::string> problems;
  const auto utc = [](const std::string& t) { return !t.empty() && t.back() == 'Z' && t.size() == 20; };
  for (const Triple& x : triples) {
    if (x.p != kCrm + "P9_consists_of") continue;
    if (!spanOf.count(x.s) || !spanOf.count(x.o)) continue;
    const std::string wb = begin[spanOf[x.s]], we = end[spanOf[x.s]];
    const std::string pb = begin[spanOf[x.o]], pe = end[spanOf[x.o]];
    if (!utc(wb) || !utc(we) || !utc(pb) || !utc(pe)) {
      problems.push_back(x.s + " P9 " + x.o + ": time-spans not comparable (" + wb + ".." + we + " / " + pb + ".." + pe + ")");
      continue;
    }
    if (pb < wb || pe > we)
      problems.push_back(x.s + " (" + wb + ".." + we + ") P9 " + x.o + " (" + pb + ".." + pe + "): not within");
  }
  return problems;
}

std::vector<std::string> crmDerivationProblems(const std::vector<Triple>& triples) {
  std::map<std::string, std::vector<std::string>> madeBy, used;  // file -> events; event -> files
  std::set<std::string> photographs;
  std::set<std::string> digitizations, results;
  for (const Triple& x : triples) {
    if (x.p == kType && x.o == kDig + "D2_Digitization_Process") digitizations.insert(x.s);
    if (x.p == kType && x.o == kCrm + "E36_Visual_Item") results.insert(x.s);
  }
  for (const Triple& x : triples) {
    if (x.p == kDig + "L11_had_output") {
      if (digitizations.count(x.s)) photographs.insert(x.o);
      else madeBy[x.o].push_back(x.s);
    }
    if (x.p == kDig + "L10_had_input") used[x.s].push_back(x.o);
  }
  std::vector<std::string> problems;
  if (results.empty()) problems.push_back("no result is typed E36_Visual_Item");
  for (const std::string& r : results) {
    std::set<std::string> seen{r};
    std::deque<std::string> todo{r};
    bool reached = false;
    while (!todo.empty()) {
      const std::string f = todo.front();
      todo.pop_front();
      if (photographs.count(f)) {
        reached = true;
        break;
      }
      for (const std::string& e : madeBy[f])
        for (const std::string& in : used[e])
          if (seen.insert(in).second) todo.push_back(in);
    }
    if (!reached) problems.push_back(r + " has no L11/L10 chain back to the photographs");
  }
  return problems;
}

}  // namespace archival
