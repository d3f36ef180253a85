// Issue 56 on a generated capture run with --publish and packed: every file of the package has
// in mets.xml the media type and the PRONOM identifier of its kind, as PRONOM's tools name it
// (Siegfried, fido): JSON (the web copy's info.json and data/ro-crate-metadata.json alike) is
// application/json and fmt/817, JavaScript text/javascript and x-fmt/423, the .lp text/plain
// and x-fmt/111; no file is "unknown" or application/octet-stream.
#include <catch2/catch.hpp>

#include <map>
#include <set>
#include <string>

#include "archival_checks.h"
#include "e2e_support.h"

namespace fs = std::filesystem;

namespace {

struct Published {
  fs::path package;
  std::string mets;
};

const Published& published() {
  static Published p = [] {
    Published r;
    const fs::path dir = e2e::freshDir("archival-kinds");
    const fs::path capture = e2e::smallCapture(dir, 8);
    const auto run = e2e::surrogate("run " + e2e::quote(capture) + " --publish --quiet");
    if (run.exitCode != 0) throw std::runtime_error("surrogate run failed: " + run.output);
    r.package = dir / "pkg";
    const auto pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(r.package) + " --quiet");
    if (pack.exitCode != 0) throw std::runtime_error("surrogate pack failed: " + pack.output);
    r.mets = e2e::bytesOf(r.package / "metadata/mets.xml");
    return r;
  }();
  return p;
}

// The techMD of the PREMIS object of a payload path.
std::string objectText(const std::string& mets, const std::string& path) {
  const auto at = mets.find("<premis:objectIdentifierValue>" + path + "</premis:objectIdentifierValue>");
  if (at == std::string::npos) return "";
  const auto from = mets.rfind("<mets:techMD ", at);
  return mets.substr(from, mets.find("</mets:techMD>", at) - from);
}

std::string extensionOf(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? "" : path.substr(dot);
}

}  // namespace

TEST_CASE("published capture: every file of the package has the media type and PUID of its kind in mets.xml",
          "[mapping][generated][premis][formats]") {
  const Published& p = published();
  // The kind of each extension a published run writes, and what mets.xml must say of it.
  struct Kind {
    std::string mime, puid;  // puid "": PRONOM has none (.rti)
  };
  const std::map<std::string, Kind> kinds = {
      {".dng", {"image/x-adobe-dng", "fmt/730"}}, {".jpg", {"image/jpeg", ""}},
      {".png", {"image/png", "fmt/13"}},          {".lp", {"text/plain", "x-fmt/111"}},
      {".ptm", {"application/x-ptm", "fmt/519"}}, {".rti", {"application/x-rti", ""}},
      {".xml", {"application/xml", "fmt/101"}},   {".html", {"text/html", "fmt/471"}},
      {".json", {"application/json", "fmt/817"}}, {".js", {"text/javascript", "x-fmt/423"}}};
  const archival::Premis premis = archival::readPremis(p.mets);
  std::set<std::string> extensions;
  int files = 0;
  for (const auto& [href, mime] : premis.files) {
    INFO(href);
    ++files;
    const std::string ext = extensionOf(href);
    extensions.insert(ext);
    const auto kind = kinds.find(ext);
    REQUIRE(kind != kinds.end());
    CHECK(mime == kind->second.mime);
    CHECK(mime != "application/octet-stream");
    const std::string object = objectText(p.mets, href);
    REQUIRE_FALSE(object.empty());
    CHECK(object.find("<premis:formatName>unknown</premis:formatName>") == std::string::npos);
    if (!kind->second.puid.empty())
      CHECK(object.find("<premis:formatRegistryKey>" + kind->second.puid + "</premis:formatRegistryKey>") !=
            std::string::npos);
    else if (ext == ".rti")
      CHECK(object.find("<premis:formatRegistryKey>") == std::string::npos);
  }
  // Every kind is there: the web copies' JSON and JavaScript, and the crate's own metadata.
  CHECK(extensions == std::set<std::string>{".dng", ".jpg", ".png", ".lp", ".ptm", ".rti", ".xml", ".html", ".json", ".js"});
  CHECK(files > 40);
  const std::string crate = objectText(p.mets, "data/ro-crate-metadata.json");
  CHECK(crate.find("<premis:formatName>JSON</premis:formatName>") != std::string::npos);
  CHECK(crate.find("<premis:formatRegistryKey>fmt/817</premis:formatRegistryKey>") != std::string::npos);
  CHECK(p.mets.find("MIMETYPE=\"application/octet-stream\"") == std::string::npos);
}
