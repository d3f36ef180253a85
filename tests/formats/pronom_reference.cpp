#include "pronom_reference.h"

#include <libxml/parser.h>
#include <libxml/tree.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace pronom_reference {

namespace {

using Pattern = std::vector<std::pair<int, int>>;  // each byte: lowest and highest value

// One step of a subsequence read left to right: the gap before it and its alternatives.
struct Link {
  long gapMin = 0, gapMax = 0;
  std::vector<Pattern> alternatives;
};

struct SubSequence {
  long min = 0, max = -1;  // -1: no limit
  std::vector<Link> chain;
};

struct ByteSequence {
  std::string reference;  // "BOFoffset", "EOFoffset" or "" (anywhere)
  std::vector<SubSequence> subsequences;  // by Position
};

struct Format {
  std::string puid;
  std::vector<std::vector<ByteSequence>> signatures;
  std::vector<std::string> over;  // format IDs
  std::string id;
};

struct Excerpt {
  std::string release;
  std::map<std::string, Format> byPuid;
  std::map<std::string, std::string> puidById;
};

std::string attr(xmlNode* n, const char* name) {
  xmlChar* v = xmlGetProp(n, reinterpret_cast<const xmlChar*>(name));
  if (!v) return "";
  std::string s(reinterpret_cast<const char*>(v));
  xmlFree(v);
  return s;
}

std::string text(xmlNode* n) {
  xmlChar* v = xmlNodeGetContent(n);
  std::string s(reinterpret_cast<const char*>(v));
  xmlFree(v);
  s.erase(std::remove_if(s.begin(), s.end(), [](char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }), s.end());
  return s;
}

bool named(xmlNode* n, const char* name) {
  return n->type == XML_ELEMENT_NODE && std::string(reinterpret_cast<const char*>(n->name)) == name;
}

std::vector<xmlNode*> children(xmlNode* n, const char* name) {
  std::vector<xmlNode*> out;
  for (xmlNode* c = n->children; c; c = c->next)
    if (named(c, name)) out.push_back(c);
  return out;
}

// "FFD8[30:39]", hex pairs and bracketed ranges (all these entries use).
Pattern pattern(const std::string& s) {
  Pattern p;
  for (std::size_t i = 0; i < s.size();) {
    if (s[i] == '[') {
      const std::size_t close = s.find(']', i);
      const std::string inside = s.substr(i + 1, close - i - 1);
      const std::size_t colon = inside.find(':');
      const int lo = std::stoi(inside.substr(0, 2), nullptr, 16);
      p.emplace_back(lo, colon == std::string::npos ? lo : std::stoi(inside.substr(colon + 1, 2), nullptr, 16));
      i = close + 1;
    } else {
      const int b = std::stoi(s.substr(i, 2), nullptr, 16);
      p.emplace_back(b, b);
      i += 2;
    }
  }
  return p;
}

// The fragments of one side grouped by Position (1 nearest the sequence).
std::map<int, std::vector<xmlNode*>> byPosition(xmlNode* sub, const char* side) {
  std::map<int, std::vector<xmlNode*>> out;
  for (xmlNode* f : children(sub, side)) out[std::stoi(attr(f, "Position"))].push_back(f);
  return out;
}

SubSequence subsequence(xmlNode* sub) {
  SubSequence s;
  s.min = attr(sub, "SubSeqMinOffset").empty() ? 0 : std::stol(attr(sub, "SubSeqMinOffset"));
  s.max = attr(sub, "SubSeqMaxOffset").empty() ? -1 : std::stol(attr(sub, "SubSeqMaxOffset"));
  const auto left = byPosition(sub, "LeftFragment"), right = byPosition(sub, "RightFragment");
  // Left fragments from the farthest: the gap before each is the offset the fragment to its
  // left records (the space between that fragment and the next one towards the sequence).
  long gapMin = 0, gapMax = 0;
  for (auto it = left.rbegin(); it != left.rend(); ++it) {
    Link l{gapMin, gapMax, {}};
    for (xmlNode* f : it->second) l.alternatives.push_back(pattern(text(f)));
    s.chain.push_back(l);
    gapMin = std::stol(attr(it->second[0], "MinOffset"));
    gapMax = std::stol(attr(it->second[0], "MaxOffset"));
  }
  s.chain.push_back({gapMin, gapMax, {pattern(text(children(sub, "Sequence").at(0)))}});
  for (const auto& [position, fragments] : right) {
    Link l{std::stol(attr(fragments[0], "MinOffset")), std::stol(attr(fragments[0], "MaxOffset")), {}};
    for (xmlNode* f : fragments) l.alternatives.push_back(pattern(text(f)));
    s.chain.push_back(l);
  }
  return s;
}

const Excerpt& excerpt() {
  static const Excerpt kExcerpt = [] {
    const std::string path = std::string(SURROGATE_SOURCE_DIR) + "/tests/data/pronom/DROID_SignatureFile_V118-excerpt.xml";
    xmlDoc* doc = xmlReadFile(path.c_str(), nullptr, XML_PARSE_NONET);
    if (!doc) throw std::runtime_error("cannot read " + path);
    Excerpt e;
    xmlNode* root = xmlDocGetRootElement(doc);
    e.release = attr(root, "Version");
    std::map<std::string, std::vector<ByteSequence>> signatures;
    for (xmlNode* collection : children(root, "InternalSignatureCollection"))
      for (xmlNode* sig : children(collection, "InternalSignature")) {
        std::vector<ByteSequence>& sequences = signatures[attr(sig, "ID")];
        for (xmlNode* bs : children(sig, "ByteSequence")) {
          ByteSequence b{attr(bs, "Reference"), {}};
          auto subs = children(bs, "SubSequence");
          std::sort(subs.begin(), subs.end(), [](xmlNode* x, xmlNode* y) {
            return std::stoi(attr(x, "Position")) < std::stoi(attr(y, "Position"));
          });
          for (xmlNode* s : subs) b.subsequences.push_back(subsequence(s));
          sequences.push_back(b);
        }
      }
    for (xmlNode* collection : children(root, "FileFormatCollection"))
      for (xmlNode* f : children(collection, "FileFormat")) {
        Format format{attr(f, "PUID"), {}, {}, attr(f, "ID")};
        for (xmlNode* s : children(f, "InternalSignatureID")) format.signatures.push_back(signatures.at(text(s)));
        for (xmlNode* o : children(f, "HasPriorityOverFileFormatID")) format.over.push_back(text(o));
        e.puidById[format.id] = format.puid;
        e.byPuid[format.puid] = format;
      }
    xmlFreeDoc(doc);
    return e;
  }();
  return kExcerpt;
}

bool patternAt(std::string_view d, long at, const Pattern& p) {
  if (at < 0 || at + static_cast<long>(p.size()) > static_cast<long>(d.size())) return false;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const int b = static_cast<unsigned char>(d[at + k]);
    if (b < p[k].first || b > p[k].second) return false;
  }
  return true;
}

// Every end of chain[i...] placed with its first byte at `at` (forwards).
void endsForward(std::string_view d, const std::vector<Link>& chain, std::size_t i, long at, std::vector<long>& ends) {
  if (i == chain.size()) {
    ends.push_back(at);
    return;
  }
  for (const Pattern& p : chain[i].alternatives)
    if (patternAt(d, at, p)) {
      const long end = at + static_cast<long>(p.size());
      if (i + 1 == chain.size()) {
        ends.push_back(end);
        continue;
      }
      for (long g = chain[i + 1].gapMin; g <= chain[i + 1].gapMax && end + g <= static_cast<long>(d.size()); ++g)
        endsForward(d, chain, i + 1, end + g, ends);
    }
}

// Whether chain[0...i] can be placed with the last byte of link i just before `end` (backwards).
bool fitsBackward(std::string_view d, const std::vector<Link>& chain, long i, long end) {
  for (const Pattern& p : chain[i].alternatives) {
    const long start = end - static_cast<long>(p.size());
    if (!patternAt(d, start, p)) continue;
    if (i == 0) return true;
    for (long g = chain[i].gapMin; g <= chain[i].gapMax && start - g >= 0; ++g)
      if (fitsBackward(d, chain, i - 1, start - g)) return true;
  }
  return false;
}

// Whether subsequences[k...] match, the previous one having ended at `previousEnd`.
bool forward(std::string_view d, const ByteSequence& b, std::size_t k, long previousEnd) {
  if (k == b.subsequences.size()) return true;
  const SubSequence& s = b.subsequences[k];
  const long n = static_cast<long>(d.size());
  long first, last;
  if (k == 0 && b.reference.empty()) {
    first = 0;
    last = n;
  } else {
    const long base = k == 0 ? 0 : previousEnd;
    first = base + s.min;
    last = s.max < 0 ? n : std::min(n, base + s.max);
  }
  for (long at = first; at <= last; ++at) {
    std::vector<long> ends;
    endsForward(d, s.chain, 0, at, ends);
    for (long e : ends)
      if (forward(d, b, k + 1, e)) return true;
  }
  return false;
}

bool sequenceMatches(std::string_view d, const ByteSequence& b) {
  if (b.reference != "EOFoffset") return forward(d, b, 0, 0);
  if (b.subsequences.size() != 1) throw std::runtime_error("several subsequences from the end: not in these entries");
  const SubSequence& s = b.subsequences[0];
  const long n = static_cast<long>(d.size());
  for (long distance = s.min; distance <= (s.max < 0 ? n : s.max) && distance <= n; ++distance)
    if (fitsBackward(d, s.chain, static_cast<long>(s.chain.size()) - 1, n - distance)) return true;
  return false;
}

const Format& format(const std::string& puid) {
  const auto it = excerpt().byPuid.find(puid);
  if (it == excerpt().byPuid.end()) throw std::runtime_error(puid + " is not in the kept excerpt");
  return it->second;
}

}  // namespace

std::vector<std::string> puids() {
  std::vector<std::string> out;
  for (const auto& [puid, f] : excerpt().byPuid) out.push_back(puid);
  return out;
}

bool matches(const std::string& puid, std::string_view bytes) {
  for (const auto& signature : format(puid).signatures) {
    bool all = true;
    for (const ByteSequence& b : signature) all = all && sequenceMatches(bytes, b);
    if (all) return true;
  }
  return false;
}

std::vector<std::string> preferredTo(const std::string& puid) {
  const std::string id = format(puid).id;
  std::vector<std::string> out;
  for (const auto& [p, f] : excerpt().byPuid)
    if (std::find(f.over.begin(), f.over.end(), id) != f.over.end()) out.push_back(p);
  return out;
}

std::vector<std::string> identify(std::string_view bytes) {
  std::vector<const Format*> matched;
  for (const auto& [puid, f] : excerpt().byPuid)
    if (matches(puid, bytes)) matched.push_back(&f);
  std::vector<std::string> out;
  for (const Format* f : matched) {
    bool setAside = false;
    for (const Format* g : matched)
      setAside = setAside || std::find(g->over.begin(), g->over.end(), f->id) != g->over.end();
    if (!setAside) out.push_back(f->puid);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string release() { return excerpt().release; }

std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace pronom_reference
