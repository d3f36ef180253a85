// The package explains itself without Surrogate: README.txt at the bag's root, and the
// documents in metadata/docs/. What the README claims is checked with the outside tools it
// names (GNU coreutils' sha256sum/sha512sum, xsltproc) and by counting the bag's own files.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <regex>
#include <set>
#include <sstream>

#include "archive/package.h"
#include "archive/package_readme.h"
#include "carrier/carrier.h"
#include "core/resources.h"
#include "sample_capture.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace surrogate;
using namespace surrogate::archive;
using testfiles::freshDir;
using testfiles::slurp;

namespace {

struct Ran {
  int status = -1;
  std::string output;
};

// Runs a shell command in `dir`, its output (stdout and stderr) collected.
Ran runIn(const fs::path& dir, const std::string& command) {
  Ran r;
  const std::string line = "cd '" + dir.string() + "' && " + command + " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(line.c_str(), "r"), &pclose);
  REQUIRE(p);
  char buffer[4096];
  std::size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, p.get())) > 0) r.output.append(buffer, n);
  r.status = pclose(p.release());
  return r;
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::size_t filesUnder(const fs::path& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) n += e.is_regular_file();
  return n;
}

std::size_t characters(const std::string& s) {
  std::size_t n = 0;
  for (unsigned char ch : s) n += (ch & 0xC0) != 0x80;
  return n;
}

}  // namespace

TEST_CASE("the package's README says what the bag holds and how to check it with sha256sum",
          "[archive][package][readme]") {
  const fs::path dir = freshDir("readme");
  const fs::path capture = samplecapture::make(dir);
  const fs::path bag = dir / "pkg";
  const PackResult packed = packCapture(capture, bag);
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  REQUIRE(fs::is_regular_file(bag / "README.txt"));
  const std::string readme = slurp(bag / "README.txt");

  SECTION("it is a tag file, in both tag manifests") {
    CHECK(slurp(bag / "tagmanifest-sha256.txt").find("  README.txt\n") != std::string::npos);
    CHECK(slurp(bag / "tagmanifest-sha512.txt").find("  README.txt\n") != std::string::npos);
  }

  SECTION("the commands it gives pass with GNU coreutils, and fail on a changed file") {
    std::vector<std::string> commands;
    for (const std::string& line : linesOf(readme))
      if (std::regex_match(line, std::regex(R"(    sha(256|512)sum -c [a-z0-9-]+\.txt)")))
        commands.push_back(line.substr(4));
    REQUIRE(commands.size() == 4);
    for (const std::string& command : commands) {
      const Ran r = runIn(bag, command);
      INFO(command << "\n" << r.output);
      CHECK(r.status == 0);
      CHECK(r.output.find(": OK") != std::string::npos);
    }
    // The same commands name a payload file changed after packing.
    {
      std::ofstream(bag / "data/assembly-files/lights.lp", std::ios::app) << "1 0 0 1\n";
    }
    const Ran r = runIn(bag, commands.front());
    CHECK(r.status != 0);
    CHECK(r.output.find("data/assembly-files/lights.lp: FAILED") != std::string::npos);
  }

  SECTION("what it says of the object is the carrier's") {
    CHECK(readme.rfind(c.header.title + "\n" + std::string(c.header.title.size(), '=') + "\n", 0) == 0);
    CHECK(readme.find(packed.packageId) != std::string::npos);
    CHECK(readme.find(packed.captureId) != std::string::npos);
    CHECK(readme.find(packed.packagingTime) != std::string::npos);
    for (const carrier::Creator& cr : c.header.creators)
      CHECK(readme.find(cr.name + " (" + cr.role + ")") != std::string::npos);
    for (const auto& [key, value] : c.header.meta) {
      INFO(key);
      CHECK(readme.find(key + ":") != std::string::npos);
    }
  }

  SECTION("each folder's count is the number of files the bag holds there") {
    std::size_t folders = 0;
    const std::regex folderLine(R"(  data/([a-z-]+)/ +([0-9]+) files?: .*)");
    for (const std::string& line : linesOf(readme)) {
      std::smatch m;
      if (!std::regex_match(line, m, folderLine)) continue;
      INFO(line);
      CHECK(std::stoul(m[2].str()) == filesUnder(bag / "data" / m[1].str()));
      ++folders;
    }
    std::size_t inBag = 0;
    for (const auto& e : fs::directory_iterator(bag / "data")) inBag += e.is_directory();
    CHECK(folders == inBag);
  }

  SECTION("every path it names is in the bag, and every result is named") {
    const std::regex pathToken(R"((data|metadata)/[A-Za-z0-9._/-]*[A-Za-z0-9_/])");
    std::set<std::string> named;
    for (auto it = std::sregex_iterator(readme.begin(), readme.end(), pathToken); it != std::sregex_iterator(); ++it)
      named.insert(it->str());
    CHECK(named.size() > 10);
    for (const std::string& p : named) {
      INFO(p);
      CHECK(fs::exists(bag / p));
    }
    for (const carrier::FileRecord& f : c.files)
      if (f.role == "result") {
        INFO(f.path);
        CHECK(named.count("data/" + f.path) == 1);
      }
    CHECK(named.count("data/finished-files/report.html") == 1);
  }

  SECTION("its lines fit 78 characters unless one word is longer") {
    for (const std::string& line : linesOf(readme)) {
      if (characters(line) <= 78) continue;
      INFO(line);
      // Only a word too long for any line (an identifier, a path) makes one longer.
      std::size_t longest = 0;
      std::istringstream words(line);
      for (std::string w; words >> w;) longest = std::max(longest, characters(w));
      CHECK(longest > 40);
    }
  }

  SECTION("the derivation it gives reproduces crm.rdf with xsltproc") {
    // The indented command from "    xsltproc" to its last continued line, run as written.
    std::string command;
    bool in = false;
    for (const std::string& line : linesOf(readme)) {
      if (line.rfind("    xsltproc ", 0) == 0) in = true;
      if (!in) continue;
      command += line + "\n";
      if (line.empty() || line.back() != '\\') break;
    }
    command.pop_back();  // the last line's end: runIn appends to the command
    REQUIRE(command.find("metadata/xslt/carrier-to-crm.xsl") != std::string::npos);
    REQUIRE(command.find("| cmp - metadata/crm.rdf") != std::string::npos);
    const Ran r = runIn(bag, command);
    INFO(command << r.output);
    CHECK(r.status == 0);
    CHECK(r.output.empty());
    // And it would say so were crm.rdf changed.
    {
      std::ofstream(bag / "metadata/crm.rdf", std::ios::app) << "\n";
    }
    CHECK(runIn(bag, command).status != 0);
  }

  SECTION("the documents it points to travel in metadata/docs/, as written") {
    for (const std::string& rel : bundledDocuments()) {
      INFO(rel);
      REQUIRE(fs::is_regular_file(bag / "metadata" / rel));
      CHECK(slurp(bag / "metadata" / rel) == slurp(resourcePath(rel)));
      // and installed with the program (SURROGATE_DATA_FILES, core/resources.h)
      CHECK(std::count(dataFileNames().begin(), dataFileNames().end(), rel) == 1);
    }
    CHECK(readme.find("metadata/docs/formats.md") != std::string::npos);
    CHECK(readme.find("metadata/docs/carrier.md") != std::string::npos);
  }
}

TEST_CASE("the README is the same bytes for the same carrier and facts, and follows them",
          "[archive][package][readme]") {
  const fs::path dir = freshDir("readme-facts");
  const fs::path capture = samplecapture::make(dir);
  carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  ReadmeFacts facts;
  facts.packageId = "urn:sha256:00";
  facts.packagingTime = "2026-12-05T00:00:00Z";
  facts.softwareAgent = "Surrogate 9";
  facts.hasReport = true;
  const std::string first = packageReadme(c, facts);
  CHECK(packageReadme(c, facts) == first);
  facts.hasReport = false;
  const std::string without = packageReadme(c, facts);
  CHECK(without.find("report.html") == std::string::npos);
  CHECK(first.find("data/finished-files/report.html") != std::string::npos);
  // A title with a line break stays one heading line.
  c.header.title = "Stela\n12";
  const std::string titled = packageReadme(c, facts);
  CHECK(titled.rfind("Stela 12\n========\n", 0) == 0);
  c.header.rights = "All rights reserved by the Museum of Tests";
  CHECK(std::regex_search(packageReadme(c, facts),
                          std::regex("\n  Rights: +All rights reserved by the Museum of Tests\n")));
}
