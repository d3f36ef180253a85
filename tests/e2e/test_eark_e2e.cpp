// pack --layout eark and verify of an E-ARK SIP, pinned to the CSIP 2.2 and SIP 2.2
// specifications (https://earkcsip.dilcis.eu/, https://earksip.dilcis.eu/), to xmllint with
// the bundled METS schema, and to the E-ARK validator's CSIP schematron rules (kept in
// tests/third_party/eark-validator, run offline by tests/e2e/eark/csip_schematron.py).
#include <catch2/catch.hpp>

#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "core/digest.h"
#include "e2e_support.h"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using e2e::quote;

namespace {

std::string python() { return fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3"; }

e2e::CommandResult pack(const fs::path& capture, const fs::path& out, long epoch, const std::string& more = "") {
  return e2e::runShell("SOURCE_DATE_EPOCH=" + std::to_string(epoch) + " " + SURROGATE_EXE + " pack " +
                       quote(capture) + " -o " + quote(out) + " --quiet " + more);
}

void write(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << bytes;
  REQUIRE(out.good());
}

std::string sha256Of(const std::string& bytes) {
  surrogate::MultiDigest d({surrogate::DigestAlgorithm::Sha256});
  d.update(bytes.data(), bytes.size());
  return d.hex(surrogate::DigestAlgorithm::Sha256);
}

std::string replaceAll(std::string text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// Where docs/package.md says each file of the bag is in the SIP.
std::string placeInSip(const std::string& bagPath) {
  auto under = [&](const std::string& prefix) { return bagPath.rfind(prefix, 0) == 0; };
  if (under("data/")) return "representations/rep1/" + bagPath;
  if (bagPath == "metadata/mets.xml") return "metadata/preservation/mets.xml";
  if (bagPath == "metadata/crm.rdf") return "metadata/descriptive/crm.rdf";
  if (under("metadata/xsd/")) return "schemas/" + bagPath.substr(13);
  if (under("metadata/")) return "documentation/" + bagPath.substr(9);
  return "metadata/other/bagit/" + bagPath;
}

struct Sip {
  fs::path dir, capture, sip, bag;
};

const Sip& packed() {
  static Sip s = [] {
    Sip x;
    x.dir = e2e::freshDir("eark");
    x.capture = e2e::processedCapture(x.dir);
    x.sip = x.dir / "stela-sip";
    x.bag = x.dir / "bag";
    for (const auto& [out, layout] : {std::pair<fs::path, std::string>{x.sip, "--layout eark"}, {x.bag, ""}}) {
      const e2e::CommandResult r = pack(x.capture, out, 1700000000, layout);
      if (r.exitCode != 0) throw std::runtime_error(r.output);
    }
    return x;
  }();
  return s;
}

// `mets` with the xlink:href of the first `element` (FLocat, mptr) replaced by `to`.
std::string withHref(std::string mets, const std::string& element, const std::string& to) {
  const auto at = mets.find(element + " ");
  REQUIRE(at != std::string::npos);
  const auto href = mets.find("xlink:href=\"", at);
  REQUIRE(href != std::string::npos);
  const auto start = href + 12;
  return mets.replace(start, mets.find('"', start) - start, to);
}

fs::path copyOf(const fs::path& sip, const std::string& name) {
  const fs::path target = e2e::freshDir(name) / "stela-sip";
  fs::copy(sip, target, fs::copy_options::recursive);
  return target;
}

}  // namespace

TEST_CASE("pack --layout eark writes a CSIP SIP holding every file of the bag", "[eark]") {
  const Sip& s = packed();
  // CSIP's folders (CSIPSTR): the package METS, one representation with its METS and data,
  // metadata/descriptive and preservation, schemas, documentation.
  for (const char* f : {"METS.xml", "representations/rep1/METS.xml", "metadata/descriptive/crm.rdf",
                        "metadata/preservation/mets.xml", "schemas/mets-1.12.1.xsd", "schemas/premis-3.0.xsd",
                        "documentation/mappings/carrier-to-mets.md", "metadata/other/bagit/bagit.txt",
                        "representations/rep1/data/assembly-files/carrier.xml"})
    CHECK(fs::is_regular_file(s.sip / f));
  // Every file of the bag pack writes as a folder is in the SIP at its documented place, byte
  // for byte; and the SIP holds nothing else but the two METS.
  const auto bag = e2e::snapshot(s.bag), sip = e2e::snapshot(s.sip);
  for (const auto& [path, sha] : bag) {
    INFO(path);
    REQUIRE(sip.count(placeInSip(path)) == 1);
    CHECK(sip.at(placeInSip(path)) == sha);
  }
  CHECK(sip.size() == bag.size() + 2);

  // Both METS validate against METS 1.12.1 (the bundled schema, xmllint).
  const e2e::CommandResult xsd = e2e::runShell(
      "XML_CATALOG_FILES=" + quote(fs::path(SOURCE_DIR) / "xsd" / "catalog.xml") + " xmllint --noout --schema " +
      quote(fs::path(SOURCE_DIR) / "xsd" / "mets-1.12.1.xsd") + " " + quote(s.sip / "METS.xml") + " " +
      quote(s.sip / "representations/rep1/METS.xml"));
  INFO(xsd.output);
  CHECK(xsd.exitCode == 0);

  // The package METS: CSIP and SIP attributes.
  const std::string mets = e2e::bytesOf(s.sip / "METS.xml");
  CHECK_THAT(mets, Contains("OBJID=\"stela-sip\""));
  CHECK_THAT(mets, Contains("PROFILE=\"https://earksip.dilcis.eu/profile/E-ARK-SIP-v2-2-0.xml\""));
  CHECK_THAT(mets, Contains("TYPE=\"Photographs \u2013 Digital\""));
  CHECK_THAT(mets, Contains("csip:CONTENTINFORMATIONTYPE=\"OTHER\""));
  CHECK_THAT(mets, Contains("csip:OAISPACKAGETYPE=\"SIP\""));
  CHECK_THAT(mets, Contains("CREATEDATE=\"2023-11-14T22:13:20Z\""));
  CHECK_THAT(mets, Contains("ROLE=\"CREATOR\" TYPE=\"OTHER\" OTHERTYPE=\"SOFTWARE\""));
  CHECK_THAT(mets, Contains("csip:NOTETYPE=\"SOFTWARE VERSION\""));
  CHECK_THAT(mets, Contains("xlink:href=\"representations/rep1/METS.xml\""));
  // Checksums and sizes: the representation METS's SHA-256 and size, as the package METS gives them.
  const std::string rep = e2e::bytesOf(s.sip / "representations/rep1/METS.xml");
  CHECK_THAT(mets, Contains("SIZE=\"" + std::to_string(rep.size()) + "\"") && Contains(sha256Of(rep)));
  const std::string carrier = e2e::bytesOf(s.sip / "representations/rep1/data/assembly-files/carrier.xml");
  CHECK_THAT(rep, Contains("CHECKSUM=\"" + sha256Of(carrier) + "\""));
  CHECK_THAT(rep, Contains("xlink:href=\"data/assembly-files/carrier.xml\""));

  // The E-ARK validator's CSIP 2.1.0 rules on the package METS: no error but CSIP63, whose
  // 2.1.0 test fails every file group without a content information type (it requires
  // @csip:CONTENTINFORMATIONTYPE != 'OTHER' and not(@csip:CONTENTINFORMATIONTYPE) at once);
  // CSIP 2.2 made it a MAY on groups whose type is OTHER, which ours names.
  const e2e::CommandResult sch = e2e::runShell(python() + " " + quote(fs::path(SOURCE_DIR) / "tests/e2e/eark/csip_schematron.py") +
                                               " " + quote(s.sip / "METS.xml"));
  INFO(sch.output);
  CHECK_THAT(sch.output, Contains("8 rule files"));
  std::size_t errors = 0, csip63 = 0;
  for (std::size_t at = 0; (at = sch.output.find("CSIP", at)) != std::string::npos; ++at) {
    if (at > 0 && sch.output[at - 1] != '\n') continue;
    ++errors;
    csip63 += sch.output.compare(at, 7, "CSIP63:") == 0;
  }
  CHECK(errors == 2);
  CHECK(csip63 == 2);

  std::string out;
  const e2e::CommandResult v = e2e::surrogate("verify " + quote(s.sip));
  INFO(v.output);
  CHECK(v.exitCode == 0);
  CHECK_THAT(v.output, Contains("E-ARK SIP") && Contains("\nSOUND"));
}

TEST_CASE("the CSIP schematron rules reject a METS without what CSIP requires", "[eark]") {
  // The rules are not vacuous: without the PROFILE and the structural map's label they fail.
  const Sip& s = packed();
  const fs::path sip = copyOf(s.sip, "eark-rules");
  std::string mets = e2e::bytesOf(sip / "METS.xml");
  mets = replaceAll(mets, " PROFILE=\"https://earksip.dilcis.eu/profile/E-ARK-SIP-v2-2-0.xml\"", "");
  mets = replaceAll(mets, "LABEL=\"CSIP\"", "LABEL=\"other\"");
  write(sip / "METS.xml", mets);
  const e2e::CommandResult sch = e2e::runShell(python() + " " + quote(fs::path(SOURCE_DIR) / "tests/e2e/eark/csip_schematron.py") +
                                               " " + quote(sip / "METS.xml"));
  CHECK(sch.exitCode == 1);
  CHECK_THAT(sch.output, Contains("CSIP6:") && Contains("CSIP82:"));
}

TEST_CASE("pack --layout eark refuses a folder that is not empty", "[eark]") {
  const Sip& s = packed();
  const fs::path folder = e2e::freshDir("eark-full");
  write(folder / "notes.txt", "mine\n");
  const e2e::CommandResult r = pack(s.capture, folder, 1700000000, "--layout eark");
  // An output that exists is one the output rule forbids: exit 1, as for an archive.
  CHECK(r.exitCode == 1);
  CHECK(r.output.find("already exists") != std::string::npos);
  CHECK(e2e::snapshot(folder).size() == 1);
  CHECK(pack(s.capture, e2e::freshDir("eark-zip") / "x.zip", 1700000000, "--layout eark").exitCode == 2);
}

TEST_CASE("verify never says SOUND of an E-ARK SIP cut, flipped, forged, missing a file or pointing out of it", "[eark]") {
  const Sip& s = packed();
  const std::string original = "representations/rep1/data/original-captures/" +
                               e2e::snapshot(s.sip / "representations/rep1/data/original-captures").begin()->first;
  struct Fault {
    std::string name, check;
    int exit;
    std::function<void(const fs::path&)> make;
  };
  const std::vector<Fault> faults = {
      {"a byte flipped in an original", "eark.fixity-mets", 3,
       [&](const fs::path& sip) {
         std::string b = e2e::bytesOf(sip / original);
         b[b.size() / 2] = static_cast<char>(b[b.size() / 2] ^ 0x20);
         write(sip / original, b);
       }},
      {"an original cut short", "eark.fixity-mets", 3,
       [&](const fs::path& sip) { fs::resize_file(sip / original, fs::file_size(sip / original) / 2); }},
      {"an original removed", "eark.complete", 3, [&](const fs::path& sip) { fs::remove(sip / original); }},
      {"the representation METS removed", "eark.complete", 3,
       [](const fs::path& sip) { fs::remove(sip / "representations/rep1/METS.xml"); }},
      {"a file added", "eark.complete", 3,
       [](const fs::path& sip) { write(sip / "documentation" / "extra.txt", "x\n"); }},
      // A changed original whose checksum and size are redone in the representation METS, and
      // that METS's in the package METS: the METS agree, the bag's manifests do not.
      {"an original changed and every METS checksum redone", "bagit.fixity-sha256", 3,
       [&](const fs::path& sip) {
         const std::string before = e2e::bytesOf(sip / original);
         std::string after = before;
         after[after.size() / 2] = static_cast<char>(after[after.size() / 2] ^ 0x20);
         write(sip / original, after);
         const fs::path repPath = sip / "representations/rep1/METS.xml";
         const std::string repBefore = e2e::bytesOf(repPath);
         const std::string repAfter = replaceAll(repBefore, sha256Of(before), sha256Of(after));
         write(repPath, repAfter);
         write(sip / "METS.xml", replaceAll(replaceAll(e2e::bytesOf(sip / "METS.xml"), sha256Of(repBefore), sha256Of(repAfter)),
                                            "SIZE=\"" + std::to_string(repBefore.size()) + "\"",
                                            "SIZE=\"" + std::to_string(repAfter.size()) + "\""));
       }},
      // Issue 51: a reference out of the SIP is an invalid package (2), as an unsafe OCFL path
      // is, not a fixity failure (3) of the file it no longer references.
      {"a file reference out of the SIP", "eark.mets", 2,
       [](const fs::path& sip) {
         const fs::path rep = sip / "representations/rep1/METS.xml";
         write(rep, withHref(e2e::bytesOf(rep), "mets:FLocat", "../../../../etc/passwd"));
       }},
      {"an absolute file reference", "eark.mets", 2,
       [](const fs::path& sip) {
         const fs::path rep = sip / "representations/rep1/METS.xml";
         write(rep, withHref(e2e::bytesOf(rep), "mets:FLocat", "/etc/passwd"));
       }},
      {"a representation pointer out of the SIP", "eark.mets", 2,
       [](const fs::path& sip) {
         write(sip / "METS.xml", withHref(e2e::bytesOf(sip / "METS.xml"), "mets:mptr", "../other-sip/METS.xml"));
       }},
  };
  for (const Fault& f : faults) {
    SECTION(f.name) {
      const fs::path sip = copyOf(s.sip, "eark-fault");
      f.make(sip);
      const e2e::CommandResult r = e2e::surrogate("verify " + quote(sip));
      INFO(r.output);
      CHECK(r.exitCode == f.exit);
      CHECK_THAT(r.output, Contains("FAIL  " + f.check));
      CHECK(r.output.find("\nSOUND") == std::string::npos);
      if (f.exit == 2) {
        CHECK_THAT(r.output, Contains("is not a safe"));
        CHECK_THAT(r.output, !Contains("FAIL  eark.complete") && !Contains("FAIL  eark.fixity"));
      }
    }
  }
}

TEST_CASE("info and report show the bag an E-ARK SIP holds as they show the same bag packed plainly", "[eark]") {
  const Sip& s = packed();
  const e2e::CommandResult sipInfo = e2e::surrogate("info " + quote(s.sip) + " --json");
  const e2e::CommandResult bagInfo = e2e::surrogate("info " + quote(s.bag) + " --json");
  INFO(sipInfo.output);
  REQUIRE(sipInfo.exitCode == 0);
  REQUIRE(bagInfo.exitCode == 0);
  nlohmann::json fromSip = nlohmann::json::parse(sipInfo.output), fromBag = nlohmann::json::parse(bagInfo.output);
  CHECK(fromSip["format"] == "eark");
  CHECK(fromBag["format"] == "directory");
  // Packed at the same SOURCE_DATE_EPOCH: the same bag, so the same description but for the
  // layout and the verify commands (which name each package).
  for (const char* member : {"surrogatePackage", "files", "bytes", "bagInfo", "manifests", "roles", "results", "carrier"}) {
    INFO(member);
    CHECK(fromSip[member] == fromBag[member]);
  }
  CHECK_THAT(e2e::surrogate("info " + quote(s.sip)).output, Contains("Surrogate package (E-ARK SIP)"));

  const fs::path html = s.dir / "sip-report.html";
  const e2e::CommandResult report =
      e2e::surrogate("report " + quote(s.sip) + " -o " + quote(html) + " --verify --json");
  INFO(report.output);
  REQUIRE(report.exitCode == 0);
  const nlohmann::json r = nlohmann::json::parse(report.output);
  CHECK_THAT(r["source"].get<std::string>(), Contains("E-ARK SIP " + s.sip.string()));
  CHECK(r["relightable"] == true);
  CHECK(r["verification"]["failed"] == 0);
}
