// An E-ARK SIP (what pack --layout eark writes: CSIP 2.2 and the SIP 2.2 profile) verified by
// its METS files, then as the bag its files make up again:
//
//   eark.read          the SIP's folder holds regular files and folders only (no link)
//   eark.mets          METS.xml and each representation METS it points to (mptr) are METS
//                      1.12.1 (the bundled schema) with what CSIP makes mandatory and Surrogate
//                      writes: OBJID, TYPE, an E-ARK SIP PROFILE, metsHdr with CREATEDATE,
//                      OAISPACKAGETYPE SIP and the software agent, the CSIP structural map;
//                      every file reference a safe relative path with SIZE and a SHA-256 or
//                      SHA-512 CHECKSUM
//   eark.complete      every file a METS references is there, and every file of the SIP but
//                      METS.xml is referenced (the representation METS by the package METS)
//   eark.fixity-METS   every referenced file has the size and checksum its METS gives it
//
// A failure is fixity (3) but for eark.read and eark.mets (invalid, 2). A METS reference that is
// not a safe relative path inside the SIP ("../../etc/passwd", "/etc/passwd", "a/../../b") makes
// the METS unusable as the list of the SIP's files, as an unsafe path makes an OCFL inventory
// unusable (ocfl_checks.h): verify stops after eark.mets with exit 2, rather than go on to judge
// completeness and fixity from a list that names what is not the SIP's. The SIP's files are then
// put back where the bag had them (archive::bagPathOf; hard links where the temporary folder is
// on the SIP's file system, copies otherwise) and given to verifyBag, which checks the bag's
// manifests, the carrier and the metadata derived from it: a METS whose checksums were redone
// to cover a changed file still leaves the bag's own manifests to disagree.
#include "verify/eark_checks.h"

#include <libxml/parser.h>
#include <libxml/xpath.h>
#include <libxml/xpathInternals.h>

#include <algorithm>
#include <map>
#include <memory>
#include <set>

#include "archive/bag_text.h"
#include "archive/eark_layout.h"
#include "core/atomic_file.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/temp_dir.h"
#include "core/text.h"
#include "mapping/mapping.h"
#include "verify/checks.h"
#include "verify/ocfl_checks.h"

namespace fs = std::filesystem;

namespace surrogate::verify {

namespace {

constexpr const char* kProfilePrefix = "https://earksip.dilcis.eu/profile/";

struct Doc {
  std::unique_ptr<xmlDoc, decltype(&xmlFreeDoc)> doc{nullptr, xmlFreeDoc};
  std::unique_ptr<xmlXPathContext, decltype(&xmlXPathFreeContext)> xpath{nullptr, xmlXPathFreeContext};
};

bool load(const std::string& text, Doc& d) {
  d.doc.reset(xmlReadMemory(text.data(), static_cast<int>(text.size()), "METS.xml", nullptr,
                            XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING));
  if (!d.doc) return false;
  d.xpath.reset(xmlXPathNewContext(d.doc.get()));
  xmlXPathRegisterNs(d.xpath.get(), BAD_CAST "mets", BAD_CAST "http://www.loc.gov/METS/");
  xmlXPathRegisterNs(d.xpath.get(), BAD_CAST "xlink", BAD_CAST "http://www.w3.org/1999/xlink");
  xmlXPathRegisterNs(d.xpath.get(), BAD_CAST "csip", BAD_CAST "https://DILCIS.eu/XML/METS/CSIPExtensionMETS");
  return true;
}

std::vector<xmlNodePtr> nodes(const Doc& d, const char* expression) {
  std::vector<xmlNodePtr> out;
  std::unique_ptr<xmlXPathObject, decltype(&xmlXPathFreeObject)> r(
      xmlXPathEvalExpression(BAD_CAST expression, d.xpath.get()), xmlXPathFreeObject);
  if (r && r->nodesetval)
    for (int i = 0; i < r->nodesetval->nodeNr; ++i) out.push_back(r->nodesetval->nodeTab[i]);
  return out;
}

std::string attribute(xmlNodePtr node, const char* name, const char* ns = nullptr) {
  xmlChar* v = ns ? xmlGetNsProp(node, BAD_CAST name, BAD_CAST ns) : xmlGetNoNsProp(node, BAD_CAST name);
  if (!v) return "";
  std::string s(reinterpret_cast<const char*>(v));
  xmlFree(v);
  return s;
}

constexpr const char* kXlink = "http://www.w3.org/1999/xlink";

// A file a METS references: where (in the SIP), its size and checksum as the METS gives them.
struct Reference {
  std::string path, size, checksum, checksumType, from;
};

// The checks of one METS (the package's, or a representation's in `folder`), its references
// appended to `refs`; returns the representation METS it points to (package METS only).
// `unsafe` is set when a reference is not a safe relative path inside the SIP.
std::vector<std::string> checkMets(const fs::path& sip, const std::string& path, bool package,
                                   std::vector<Reference>& refs, std::vector<std::string>& problems, bool& unsafe) {
  const std::string text = [&] {
    try {
      return readFile(sip / path, "verifying");
    } catch (const Error&) {
      return std::string();
    }
  }();
  if (text.empty()) {
    problems.push_back(path + ": missing or empty");
    return {};
  }
  try {
    mapping::validateMets(text, path);
  } catch (const Error& e) {
    problems.push_back(e.text());
  }
  Doc d;
  if (!load(text, d)) {
    problems.push_back(path + ": not well-formed XML");
    return {};
  }
  const auto roots = nodes(d, "/mets:mets");
  if (roots.empty()) {
    problems.push_back(path + ": its root is not mets:mets");
    return {};
  }
  xmlNodePtr root = roots.front();
  for (const char* a : {"OBJID", "TYPE"})
    if (attribute(root, a).empty()) problems.push_back(path + ": mets/@" + std::string(a) + " is missing (CSIP1, CSIP2)");
  if (attribute(root, "PROFILE").rfind(kProfilePrefix, 0) != 0)
    problems.push_back(path + ": mets/@PROFILE is not an E-ARK SIP profile (" + std::string(kProfilePrefix) + "...)");
  const auto header = nodes(d, "/mets:mets/mets:metsHdr[@CREATEDATE][@csip:OAISPACKAGETYPE='SIP']");
  if (header.size() != 1) problems.push_back(path + ": metsHdr with CREATEDATE and csip:OAISPACKAGETYPE SIP is missing (CSIP7, SIP4)");
  if (nodes(d, "/mets:mets/mets:metsHdr/mets:agent[@ROLE='CREATOR'][@TYPE='OTHER'][@OTHERTYPE='SOFTWARE']"
               "[mets:name][mets:note[@csip:NOTETYPE='SOFTWARE VERSION']]").size() != 1)
    problems.push_back(path + ": the software agent (CSIP10-16) is missing");
  if (nodes(d, "/mets:mets/mets:structMap[@TYPE='PHYSICAL'][@LABEL='CSIP']/mets:div").size() != 1)
    problems.push_back(path + ": the CSIP structural map (CSIP80-85) is missing");

  const std::string folder = path.find('/') == std::string::npos ? "" : path.substr(0, path.rfind('/') + 1);
  auto reference = [&](xmlNodePtr holder, xmlNodePtr located) {
    Reference r;
    r.from = path;
    const std::string href = attribute(located, "href", kXlink);
    std::string why;
    const auto safe = archive::safeBagPath(folder + href, &why);
    if (href.empty() || !safe || *safe != folder + href) {
      problems.push_back(path + ": a file reference \"" + escapedText(href) + "\" is not a safe relative path inside the SIP" +
                         (why.empty() ? "" : " (" + why + ")"));
      unsafe = true;
      return;
    }
    r.path = *safe;
    r.size = attribute(holder, "SIZE");
    r.checksum = attribute(holder, "CHECKSUM");
    std::transform(r.checksum.begin(), r.checksum.end(), r.checksum.begin(), [](unsigned char ch) { return std::tolower(ch); });
    r.checksumType = attribute(holder, "CHECKSUMTYPE");
    if (r.size.empty() || r.checksum.empty() || (r.checksumType != "SHA-256" && r.checksumType != "SHA-512"))
      problems.push_back(path + ": " + href + " lacks SIZE, or a SHA-256 or SHA-512 CHECKSUM (CSIP69-72)");
    else refs.push_back(r);
  };
  for (xmlNodePtr file : nodes(d, "//mets:fileSec//mets:file")) {
    xmlNodePtr flocat = nullptr;
    for (xmlNodePtr c = file->children; c; c = c->next)
      if (c->type == XML_ELEMENT_NODE && xmlStrEqual(c->name, BAD_CAST "FLocat")) flocat = c;
    if (!flocat) problems.push_back(path + ": a mets:file with no FLocat (CSIP76)");
    else reference(file, flocat);
  }
  for (xmlNodePtr md : nodes(d, "//mets:mdRef")) reference(md, md);

  std::vector<std::string> pointed;
  if (package)
    for (xmlNodePtr mptr : nodes(d, "/mets:mets/mets:structMap[@LABEL='CSIP']//mets:mptr")) {
      const std::string href = attribute(mptr, "href", kXlink);
      std::string why;
      const auto safe = archive::safeBagPath(href, &why);
      if (!safe || *safe != href || href.size() < 9 || href.compare(href.size() - 9, 9, "/METS.xml") != 0) {
        problems.push_back(path + ": a representation pointer \"" + escapedText(href) + "\" is not a safe path to a METS.xml" +
                           (why.empty() ? "" : " (" + why + ")"));
        unsafe = true;
      } else {
        pointed.push_back(href);
      }
    }
  return pointed;
}

void add(Report& report, const std::string& name, Severity severity, const std::string& passed,
         const std::string& failed, const std::vector<std::string>& problems) {
  report.checks.push_back(makeCheck(name, severity, passed, failed, problems));
}

// The SIP's files put back where the bag had them, in `into`.
void assembleSip(const fs::path& sip, const FolderWalk& walk, const fs::path& into) {
  fs::create_directories(into);
  for (const std::string& f : walk.files) {
    const auto back = archive::bagPathOf(f);
    if (!back) continue;
    const fs::path target = into / fs::path(*back);
    std::error_code ec;
    fs::create_directories(target.parent_path(), ec);
    fs::create_hard_link(sip / f, target, ec);
    if (ec) {
      ec.clear();
      fs::copy_file(sip / f, target, ec);
      if (ec)
        throw Error(ErrorKind::Internal, target.string(), "reading an E-ARK SIP",
                    "cannot put the SIP's bag together in a temporary folder (" + ec.message() +
                        "): free space in the temporary folder (TMPDIR) and try again");
    }
  }
}

}  // namespace

void assembleSipBag(const fs::path& sip, const fs::path& into) {
  const FolderWalk walk = walkFolder(sip, "an E-ARK SIP");
  if (!walk.problems.empty())
    throw Error(ErrorKind::Usage, sip.string(), "reading an E-ARK SIP",
                walk.problems.front() + "; surrogate verify " + shellWord(sip.string()) + " says what is wrong");
  assembleSip(sip, walk, into);
}

bool isEarkSip(const fs::path& package) {
  std::error_code ec;
  if (!fs::is_directory(package, ec) || !fs::is_regular_file(package / archive::kSipMets, ec)) return false;
  std::string head;
  try {
    head = readFile(package / archive::kSipMets, "verifying").substr(0, 4096);
  } catch (const Error&) {
    return false;
  }
  return head.find(kProfilePrefix) != std::string::npos;
}

Report verifyEarkSip(const fs::path& sip, const VerifyOptions& options) {
  Report report;
  report.package = sip.string();
  report.kind = "E-ARK SIP";
  const FolderWalk walk = walkFolder(sip, "an E-ARK SIP");
  add(report, "eark.read", Severity::Invalid, "the SIP holds files and folders only",
      "the SIP holds what a package may not", walk.problems);

  std::vector<std::string> problems;
  std::vector<Reference> refs;
  bool unsafe = false;
  const std::vector<std::string> representations = checkMets(sip, archive::kSipMets, true, refs, problems, unsafe);
  if (representations.empty() && !unsafe)
    problems.push_back(std::string(archive::kSipMets) + ": points to no representation METS (CSIP109)");
  for (const std::string& rep : representations) checkMets(sip, rep, false, refs, problems, unsafe);
  add(report, "eark.mets", Severity::Invalid,
      std::string(archive::kSipMets) + " and " + std::to_string(representations.size()) +
          " representation METS are METS 1.12.1 with the CSIP and SIP essentials, " + std::to_string(refs.size()) +
          " file references",
      "the SIP's METS are not what an E-ARK SIP needs", problems);
  if (unsafe) return report;  // invalid (2): the METS cannot say which files are the SIP's

  problems.clear();
  std::set<std::string> referenced;
  for (const Reference& r : refs) {
    referenced.insert(r.path);
    if (!walk.files.count(r.path)) problems.push_back(r.path + ": referenced by " + r.from + ", missing");
  }
  for (const std::string& rep : representations)
    if (!referenced.count(rep)) problems.push_back(rep + ": a representation METS no file group of " + std::string(archive::kSipMets) + " lists with its checksum");
  for (const std::string& f : walk.files)
    if (f != archive::kSipMets && !referenced.count(f)) problems.push_back(f + ": in the SIP, referenced by no METS");
  add(report, "eark.complete", Severity::Fixity, "every file the METS reference is there, and nothing else",
      "the SIP's files are not those its METS list", problems);

  problems.clear();
  std::size_t checked = 0;
  for (const Reference& r : refs) {
    if (!walk.files.count(r.path)) continue;
    if (options.progress) options.progress("checking the SIP's files", double(checked) / double(refs.size()));
    try {
      const FileDigests d = digestFile(sip / r.path, r.checksumType == "SHA-512");
      const std::string actual = r.checksumType == "SHA-512" ? d.sha512 : d.sha256;
      if (std::to_string(d.size) != r.size)
        problems.push_back(r.path + ": " + std::to_string(d.size) + " bytes, " + r.from + " says " + r.size);
      else if (actual != r.checksum)
        problems.push_back(r.path + ": its " + r.checksumType + " is not the one " + r.from + " gives");
    } catch (const Error& e) {
      problems.push_back(r.path + ": cannot be read (" + e.text() + ")");
    }
    ++checked;
  }
  add(report, "eark.fixity-mets", Severity::Fixity,
      std::to_string(checked) + " files match the size and checksum their METS give",
      "files differ from their METS", problems);

  // The bag, put back together.
  TempDir temp("verify-eark");
  const fs::path bag = temp.path() / sip.filename();
  assembleSip(sip, walk, bag);
  Report held = verifyBag(bag, options);
  const std::string tempText = bag.string(), shown = (sip / "(bag)").string();
  for (Check& c : held.checks) {
    for (std::string& w : c.where)
      for (auto at = w.find(tempText); at != std::string::npos; at = w.find(tempText, at + shown.size()))
        w.replace(at, tempText.size(), shown);
    report.checks.push_back(std::move(c));
  }
  for (std::string& w : held.warnings) report.warnings.push_back("the SIP's bag: " + w);
  report.surrogatePackage = held.surrogatePackage;
  report.holderFields = std::move(held.holderFields);
  report.reexecuted = held.reexecuted;
  report.softwareDifferences = std::move(held.softwareDifferences);
  return report;
}

}  // namespace surrogate::verify
