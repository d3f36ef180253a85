// The mapping tables (mappings/*.md) cover the carrier: every element and attribute of
// xsd/carrier.xsd that carries information has a row in each table, and every row that says it
// is mapped names something the stylesheet actually reads.
#include <catch2/catch.hpp>

#include <libxml/parser.h>
#include <libxml/tree.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

namespace {

std::string slurp(const std::string& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

std::string attr(xmlNode* n, const char* name) {
  xmlChar* v = xmlGetProp(n, reinterpret_cast<const xmlChar*>(name));
  std::string s = v ? reinterpret_cast<const char*>(v) : "";
  xmlFree(v);
  return s;
}

bool is(xmlNode* n, const char* local) {
  return n->type == XML_ELEMENT_NODE && std::string(reinterpret_cast<const char*>(n->name)) == local;
}

struct TypeInfo {
  std::vector<std::pair<std::string, std::string>> elements;  // name, type
  std::vector<std::string> attributes;
  bool simpleContent = false;
};

void collect(xmlNode* n, TypeInfo& t) {
  for (xmlNode* c = n->children; c; c = c->next) {
    if (c->type != XML_ELEMENT_NODE) continue;
    if (is(c, "element")) t.elements.emplace_back(attr(c, "name"), attr(c, "type"));
    else if (is(c, "attribute")) t.attributes.push_back(attr(c, "name"));
    else {
      if (is(c, "simpleContent")) t.simpleContent = true;
      collect(c, t);
    }
  }
}

// XPaths (prefix c:) of every element and attribute that carries information.
std::set<std::string> carrierPaths() {
  const std::string xsd = std::string(SURROGATE_SOURCE_DIR) + "/xsd/carrier.xsd";
  xmlDoc* doc = xmlReadFile(xsd.c_str(), nullptr, XML_PARSE_NONET);
  REQUIRE(doc);
  std::map<std::string, TypeInfo> types;
  TypeInfo root;
  for (xmlNode* n = xmlDocGetRootElement(doc)->children; n; n = n->next) {
    if (is(n, "complexType")) collect(n, types[attr(n, "name")]);
    if (is(n, "element") && attr(n, "name") == "carrier") collect(n, root);
  }
  xmlFreeDoc(doc);
  std::set<std::string> paths;
  std::function<void(const std::string&, const TypeInfo&)> walk = [&](const std::string& at, const TypeInfo& t) {
    for (const std::string& a : t.attributes) paths.insert((at.empty() ? "" : at + "/") + "@" + a);
    for (const auto& [name, type] : t.elements) {
      const std::string path = (at.empty() ? "" : at + "/") + "c:" + name;
      auto it = types.find(type);
      if (it == types.end()) {  // a simple type: text content
        paths.insert(path);
        continue;
      }
      const TypeInfo& child = it->second;
      if (!child.attributes.empty() || child.simpleContent || child.elements.empty()) paths.insert(path);
      walk(path, child);
    }
  };
  walk("", root);
  return paths;
}

// Table rows: first-column XPath -> the rest of the row.
std::map<std::string, std::string> tableRows(const std::string& markdown) {
  std::map<std::string, std::string> rows;
  const std::regex row("^\\| `((c:|@)[^`]+)` \\| (.*) \\|$");
  std::istringstream in(markdown);
  std::string line;
  std::smatch m;
  while (std::getline(in, line))
    if (std::regex_match(line, m, row)) rows[m[1]] = m[3];
  return rows;
}

std::string lastStep(const std::string& path) {
  const auto slash = path.rfind('/');
  std::string step = slash == std::string::npos ? path : path.substr(slash + 1);
  return step;
}

std::string parentStep(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? "" : lastStep(path.substr(0, slash));
}

}  // namespace

TEST_CASE("the carrier schema is read: paths of data-carrying elements and attributes", "[mapping][coverage]") {
  const std::set<std::string> paths = carrierPaths();
  CHECK(paths.count("c:header/c:title"));
  CHECK(paths.count("c:files/c:file/c:camera/@serial"));
  CHECK(paths.count("c:process/c:step/c:intervention"));
  CHECK(paths.count("c:data/c:result/c:sphere/@cx"));
  CHECK_FALSE(paths.count("c:header"));  // a container carries nothing itself
  CHECK(paths.size() > 100);
}

TEST_CASE("every carrier element that carries information has a row in each mapping table", "[mapping][coverage]") {
  const std::set<std::string> paths = carrierPaths();
  for (const char* table : {"carrier-to-crm.md", "carrier-to-mets.md", "carrier-to-ro-crate.md"}) {
    const auto rows = tableRows(slurp(std::string(SURROGATE_SOURCE_DIR) + "/mappings/" + table));
    for (const std::string& p : paths) {
      // Attributes of measurement results (sphere, highlight, ...) are covered by their
      // element's row, which says where they stay.
      const std::string parent = p.substr(0, p.rfind('/'));
      const bool coveredByParent = p.find("/@") != std::string::npos && rows.count(parent) &&
                                   rows.at(parent).rfind("not mapped", 0) == 0;
      INFO(table << ": " << p);
      CHECK((rows.count(p) == 1 || coveredByParent));
    }
    // No row for something the schema does not have.
    for (const auto& [p, text] : rows) {
      INFO(table << " has a row for " << p << ", which xsd/carrier.xsd does not define");
      CHECK(paths.count(p) == 1);
    }
  }
}

TEST_CASE("every row that says it is mapped names something its stylesheet reads", "[mapping][coverage]") {
  const std::map<std::string, std::string> pairs = {{"carrier-to-crm.md", "carrier-to-crm.xsl"},
                                                    {"carrier-to-mets.md", "carrier-to-mets.xsl"},
                                                    {"carrier-to-ro-crate.md", "carrier-to-ro-crate.xsl"}};
  for (const auto& [table, stylesheet] : pairs) {
    const auto rows = tableRows(slurp(std::string(SURROGATE_SOURCE_DIR) + "/mappings/" + table));
    const std::string xsl = slurp(std::string(SURROGATE_SOURCE_DIR) + "/xslt/" + stylesheet);
    for (const auto& [path, text] : rows) {
      if (text.rfind("not mapped", 0) == 0 || text.rfind("(", 0) == 0) continue;
      const std::string step = lastStep(path);
      // Read by name, or (attributes) copied wholesale with @* from their element.
      const bool named = xsl.find(step) != std::string::npos;
      const bool wholesale = step[0] == '@' && xsl.find(parentStep(path)) != std::string::npos &&
                             xsl.find("select=\"@*\"") != std::string::npos;
      INFO(stylesheet << " does not read " << path << " although " << table << " maps it");
      CHECK((named || wholesale));
    }
  }
}
