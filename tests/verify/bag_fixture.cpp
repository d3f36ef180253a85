#include "bag_fixture.h"

#include <archive.h>
#include <archive_entry.h>
#include <unistd.h>

#include <algorithm>
#include <clocale>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "archive/bag.h"
#include "archive/package.h"
#include "archive/package_readme.h"
#include "carrier/carrier.h"
#include "core/digest.h"
#include "core/resources.h"
#include "mapping/mapping.h"

namespace fs = std::filesystem;

namespace verify_test {

namespace {
// Removes the folders the tests made when the test program ends (set
// SURROGATE_KEEP_TEST_DIRS=1 to keep them for a look).
struct Cleanup {
  std::vector<fs::path> dirs;
  ~Cleanup() {
    if (std::getenv("SURROGATE_KEEP_TEST_DIRS")) return;
    for (const fs::path& d : dirs) {
      std::error_code ec;
      fs::remove_all(d, ec);
    }
  }
};
Cleanup& cleanup() {
  static Cleanup c;
  return c;
}
}  // namespace

fs::path freshDir(const std::string& name) {
  static int counter = 0;
  const fs::path dir = fs::temp_directory_path() /
                       ("surrogate-verify-test-" + std::to_string(::getpid()) + "-" + name + "-" +
                        std::to_string(counter++));
  fs::remove_all(dir);
  fs::create_directories(dir);
  cleanup().dirs.push_back(dir);
  return dir;
}

void writeText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

namespace {

std::vector<std::string> filesUnder(const fs::path& root, const fs::path& dir) {
  std::vector<std::string> out;
  if (!fs::exists(dir)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out.push_back(fs::relative(e.path(), root).generic_string());
  std::sort(out.begin(), out.end());
  return out;
}


// A bag-info.txt label's value in the bag, or "".
std::string bagInfoValue(const fs::path& bag, const std::string& label) {
  std::error_code ec;
  if (!fs::exists(bag / "bag-info.txt", ec)) return "";
  std::istringstream in(readText(bag / "bag-info.txt"));
  std::string line;
  while (std::getline(in, line))
    if (line.compare(0, label.size() + 2, label + ": ") == 0) return line.substr(label.size() + 2);
  return "";
}

void writeMetadata(const fs::path& bag, const std::string& agent, const std::string& time, int mappingEdition) {
  const std::string carrierXml = readText(bag / "data/assembly-files/carrier.xml");
  // The stylesheets, schemas and tables the verifier bundles, as `surrogate pack` copies them.
  for (const std::string& rel : surrogate::mapping::packagedResources())
    writeText(bag / "metadata" / rel, readText(surrogate::resourcePath(rel)));
  surrogate::mapping::PackageFacts facts;
  facts.packageId = surrogate::archive::packageIdentifier(surrogate::sha256Hex(carrierXml));
  facts.packagingTime = time;
  facts.softwareAgent = agent;
  for (const std::string& p : filesUnder(bag, bag / "data")) {
    const auto d = surrogate::digestFile(bag / p, true);
    facts.payload.push_back({p, d.size, d.sha256, d.sha512});
  }
  facts.previousPackageId = bagInfoValue(bag, "Surrogate-Previous-Package-Identifier");
  facts.baseUri = bagInfoValue(bag, "Surrogate-Base-URI");
  facts.mappingEdition = mappingEdition;
  writeText(bag / "metadata/crm.rdf", surrogate::mapping::deriveCrm(carrierXml, surrogate::mapping::crmFactsOf(facts)));
  writeText(bag / "metadata/mets.xml", surrogate::mapping::deriveMets(carrierXml, facts));
  for (const std::string& rel : surrogate::archive::bundledDocuments())
    writeText(bag / "metadata" / rel, readText(surrogate::resourcePath(rel)));
  // README.txt as packing writes it (a carrier that does not parse gets none: the tests that
  // break the carrier look at other checks).
  try {
    const auto c = surrogate::carrier::parseCarrier(carrierXml, "carrier.xml");
    surrogate::archive::ReadmeFacts readme;
    readme.packageId = facts.packageId;
    readme.packagingTime = time;
    readme.softwareAgent = agent;
    readme.previousPackageId = facts.previousPackageId;
    readme.baseUri = facts.baseUri;
    std::error_code ec;
    readme.hasReport = fs::exists(bag / "data/finished-files/report.html", ec);
    writeText(bag / surrogate::archive::kReadmePath, surrogate::archive::packageReadme(c, readme));
  } catch (const std::exception&) {
  }
}

}  // namespace

void rehashTagManifests(const fs::path& bag) {
  std::vector<std::string> tags;
  for (const auto& e : fs::recursive_directory_iterator(bag)) {
    if (!e.is_regular_file()) continue;
    const std::string rel = fs::relative(e.path(), bag).generic_string();
    if (rel.compare(0, 5, "data/") == 0 || rel.compare(0, 12, "tagmanifest-") == 0) continue;
    tags.push_back(rel);
  }
  std::sort(tags.begin(), tags.end());
  std::string t256, t512;
  for (const std::string& p : tags) {
    const auto d = surrogate::digestFile(bag / p, true);
    t256 += d.sha256 + "  " + escapedPath(p) + "\n";
    t512 += d.sha512 + "  " + escapedPath(p) + "\n";
  }
  writeText(bag / "tagmanifest-sha256.txt", t256);
  writeText(bag / "tagmanifest-sha512.txt", t512);
}

void rehashBag(const fs::path& bag, bool keepRoCrate, int mappingEdition) {
  // The RO-Crate's metadata first: it is payload, in the manifests (a carrier that does not
  // derive gets none: the tests that break the carrier look at other checks).
  if (!keepRoCrate) {
    std::string time = bagInfoValue(bag, "Surrogate-Packaging-Time");
    if (time.empty()) time = "2026-11-25T08:00:00Z";
    try {
      const std::string carrierXml = readText(bag / "data/assembly-files/carrier.xml");
      surrogate::mapping::CrateFacts facts;
      facts.packageId = surrogate::archive::packageIdentifier(surrogate::sha256Hex(carrierXml));
      facts.packagingTime = time;
      std::error_code ec;
      facts.hasReport = fs::exists(bag / "data/finished-files/report.html", ec);
      facts.mappingEdition = mappingEdition;
      writeText(bag / surrogate::mapping::kRoCratePath, surrogate::mapping::deriveRoCrate(carrierXml, facts));
    } catch (const std::exception&) {
    }
  }
  std::string m256, m512;
  std::uint64_t octets = 0, streams = 0;
  for (const std::string& p : filesUnder(bag, bag / "data")) {
    const auto d = surrogate::digestFile(bag / p, true);
    m256 += d.sha256 + "  " + escapedPath(p) + "\n";
    m512 += d.sha512 + "  " + escapedPath(p) + "\n";
    octets += d.size;
    ++streams;
  }
  writeText(bag / "manifest-sha256.txt", m256);
  writeText(bag / "manifest-sha512.txt", m512);
  writeText(bag / "bagit.txt", "BagIt-Version: 1.0\nTag-File-Character-Encoding: UTF-8\n");
  // bag-info.txt as `surrogate pack` writes it for the carrier now in the bag (its agent and
  // packaging time kept when the bag has them).
  std::string agent = bagInfoValue(bag, "Bag-Software-Agent");
  if (agent.empty()) agent = "Surrogate test";
  std::string time = bagInfoValue(bag, "Surrogate-Packaging-Time");
  if (time.empty()) time = "2026-11-25T08:00:00Z";
  const std::string carrierXml = readText(bag / "data/assembly-files/carrier.xml");
  const std::string id = surrogate::archive::packageIdentifier(surrogate::sha256Hex(carrierXml));
  surrogate::archive::PackageInfo labels;
  try {
    labels = surrogate::archive::packageInfo(
        surrogate::carrier::parseCarrier(carrierXml, "carrier.xml"), id, time,
        bagInfoValue(bag, "Surrogate-Previous-Package-Identifier"), bagInfoValue(bag, "Surrogate-Base-URI"));
  } catch (const std::exception&) {
    labels.own = {{"Surrogate-Package-Identifier", id}, {"Surrogate-Packaging-Time", time}};
  }
  std::string info = "Bag-Software-Agent: " + agent + "\nBagging-Date: " + time.substr(0, 10) +
                     "\nBag-Size: " + surrogate::archive::humanSize(octets) +
                     "\nPayload-Oxum: " + std::to_string(octets) + "." + std::to_string(streams) + "\n";
  for (const auto* list : {&labels.user, &labels.own})
    for (const auto& [label, value] : *list) info += label + ": " + value + "\n";
  writeText(bag / "bag-info.txt", info);
  writeMetadata(bag, agent, time, mappingEdition);
  rehashTagManifests(bag);
}

fs::path tinyCapture(const fs::path& dir) {
  const fs::path capture = dir / "capture";
  surrogate::carrier::Carrier c = surrogate::carrier::newCarrier("Tiny", {{"A. Tester", "creator"}});
  c.header.software.push_back({"LibRaw", "0.20.2-Release", "camera raw decoding"});
  for (int i = 1; i <= 2; ++i) {
    const std::string rel = "original-captures/IMG_000" + std::to_string(i) + ".jpg";
    writeText(capture / rel, "not really a JPEG, image " + std::to_string(i) + "\n");
    surrogate::carrier::FileRecord f;
    f.path = rel;
    f.role = "original";
    const auto d = surrogate::digestFile(capture / rel);
    f.size = d.size;
    f.sha256 = d.sha256;
    f.format = "JPEG";
    c.putFile(f);
  }
  fs::create_directories(capture / "assembly-files");
  surrogate::carrier::saveCarrier(c, capture / "assembly-files/carrier.xml");
  return capture;
}

void makeBag(const fs::path& capture, const fs::path& bag) {
  fs::create_directories(bag);
  fs::copy(capture, bag / "data", fs::copy_options::recursive);
  rehashBag(bag);
}

void writeArchive(const fs::path& path, const std::vector<Entry>& entries) {
  // Names are UTF-8; libarchive converts them from the locale's encoding.
  static const bool utf8 = std::setlocale(LC_CTYPE, "C.UTF-8") != nullptr;
  (void)utf8;
  ::archive* a = archive_write_new();
  if (path.extension() == ".zip") archive_write_set_format_zip(a);
  else {
    archive_write_set_format_pax_restricted(a);
    // Names exactly as given (no conversion, which would also normalise Unicode).
    archive_write_set_options(a, "hdrcharset=BINARY");
  }
  if (archive_write_open_filename(a, path.c_str()) != ARCHIVE_OK)
    throw std::runtime_error(archive_error_string(a));
  for (const Entry& e : entries) {
    archive_entry* entry = archive_entry_new();
    archive_entry_set_pathname(entry, e.name.c_str());
    archive_entry_set_perm(entry, 0644);
    archive_entry_set_mtime(entry, 1764000000, 0);
    switch (e.type) {
      case Entry::File: archive_entry_set_filetype(entry, AE_IFREG); break;
      case Entry::Directory: archive_entry_set_filetype(entry, AE_IFDIR); archive_entry_set_perm(entry, 0755); break;
      case Entry::Symlink: archive_entry_set_filetype(entry, AE_IFLNK); archive_entry_set_symlink(entry, e.linkTarget.c_str()); break;
      case Entry::Hardlink: archive_entry_set_filetype(entry, AE_IFREG); archive_entry_set_hardlink(entry, e.linkTarget.c_str()); break;
      case Entry::Fifo: archive_entry_set_filetype(entry, AE_IFIFO); break;
      case Entry::CharDevice: archive_entry_set_filetype(entry, AE_IFCHR); archive_entry_set_rdev(entry, 0x0105); break;
    }
    const bool hasData = e.type == Entry::File;
    archive_entry_set_size(entry, hasData ? e.claimedSize.value_or(std::int64_t(e.content.size())) : 0);
    if (archive_write_header(a, entry) != ARCHIVE_OK)
      throw std::runtime_error(std::string("archive_write_header: ") + archive_error_string(a));
    if (hasData && !e.content.empty()) archive_write_data(a, e.content.data(), e.content.size());
    archive_entry_free(entry);
  }
  archive_write_close(a);
  archive_write_free(a);
}

void archiveDirectory(const fs::path& dir, const fs::path& archive, const std::string& prefix) {
  std::vector<Entry> entries;
  std::vector<fs::path> paths;
  for (const auto& e : fs::recursive_directory_iterator(dir)) paths.push_back(e.path());
  std::sort(paths.begin(), paths.end());
  for (const fs::path& p : paths) {
    Entry e;
    e.name = prefix + fs::relative(p, dir).generic_string();
    if (fs::is_directory(p)) {
      e.type = Entry::Directory;
      e.name += "/";
    } else {
      e.content = readText(p);
    }
    entries.push_back(std::move(e));
  }
  writeArchive(archive, entries);
}

std::vector<std::uint64_t> tarEntryOffsets(const std::string& tar) {
  std::vector<std::uint64_t> out;
  std::uint64_t at = 0;
  while (at + 512 <= tar.size()) {
    const std::string block = tar.substr(at, 512);
    if (block.find_first_not_of('\0') == std::string::npos) {
      out.push_back(at);  // the end-of-archive marker
      return out;
    }
    out.push_back(at);
    const std::uint64_t size = std::strtoull(block.substr(124, 12).c_str(), nullptr, 8);
    const char type = block[156];
    const std::uint64_t data = (type >= '1' && type <= '6') ? 0 : size;
    at += 512 + (data + 511) / 512 * 512;
  }
  throw std::runtime_error("not a well-formed tar");
}

std::vector<std::uint64_t> zipEntryOffsets(const std::string& zip) {
  auto u16 = [&](std::size_t p) {
    return std::uint64_t(static_cast<unsigned char>(zip[p])) |
           std::uint64_t(static_cast<unsigned char>(zip[p + 1])) << 8;
  };
  auto u32 = [&](std::size_t p) { return u16(p) | u16(p + 2) << 16; };
  const std::size_t end = zip.rfind(std::string("PK\x05\x06", 4));
  if (end == std::string::npos) throw std::runtime_error("not a zip");
  const std::uint64_t entries = u16(end + 10), cdOffset = u32(end + 16);
  std::vector<std::uint64_t> out;
  std::size_t p = static_cast<std::size_t>(cdOffset);
  for (std::uint64_t i = 0; i < entries; ++i) {
    if (u32(p) != 0x02014b50) throw std::runtime_error("bad central directory");
    out.push_back(u32(p + 42));
    p += 46 + u16(p + 28) + u16(p + 30) + u16(p + 32);
  }
  std::sort(out.begin(), out.end());
  out.push_back(cdOffset);
  out.push_back(end);
  return out;
}

std::vector<std::string> filesInWriteOrder(const fs::path& bag) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(bag))
    if (e.is_regular_file()) out.push_back(fs::relative(e.path(), bag).generic_string());
  std::sort(out.begin(), out.end());
  return out;
}

std::string escapedPath(const std::string& path) {
  std::string out;
  for (char c : path) {
    if (c == '%') out += "%25";
    else if (c == '\n') out += "%0A";
    else if (c == '\r') out += "%0D";
    else out += c;
  }
  return out;
}

}  // namespace verify_test
