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

#include "archive/digest.h"
#include "carrier/carrier.h"
#ifdef SURROGATE_HAVE_MAPPING
#include "mapping/mapping.h"
#endif

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

std::string escape(const std::string& path) {
  std::string out;
  for (char c : path) {
    if (c == '%') out += "%25";
    else if (c == '\n') out += "%0A";
    else if (c == '\r') out += "%0D";
    else out += c;
  }
  return out;
}

void writeMetadata(const fs::path& bag) {
  const std::string carrierXml = readText(bag / "data/assembly-files/carrier.xml");
#ifdef SURROGATE_HAVE_MAPPING
  surrogate::mapping::PackageFacts facts;
  facts.packageId = "urn:test:bag";
  facts.packagingTime = "2026-11-25T08:00:00Z";
  facts.softwareAgent = "Surrogate test";
  for (const std::string& p : filesUnder(bag, bag / "data")) {
    const auto d = surrogate::archive::digestFile(bag / p, true);
    facts.payload.push_back({p, d.size, d.sha256, d.sha512});
  }
  writeText(bag / "metadata/crm.rdf", surrogate::mapping::deriveCrm(carrierXml));
  writeText(bag / "metadata/mets.xml", surrogate::mapping::deriveMets(carrierXml, facts));
#else
  (void)carrierXml;
  writeText(bag / "metadata/crm.rdf",
            "<?xml version=\"1.0\"?>\n<rdf:RDF xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\"/>\n");
  writeText(bag / "metadata/mets.xml",
            "<?xml version=\"1.0\"?>\n<mets xmlns=\"http://www.loc.gov/METS/\"/>\n");
#endif
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
    const auto d = surrogate::archive::digestFile(bag / p, true);
    t256 += d.sha256 + "  " + escape(p) + "\n";
    t512 += d.sha512 + "  " + escape(p) + "\n";
  }
  writeText(bag / "tagmanifest-sha256.txt", t256);
  writeText(bag / "tagmanifest-sha512.txt", t512);
}

void rehashBag(const fs::path& bag) {
  std::string m256, m512;
  std::uint64_t octets = 0, streams = 0;
  for (const std::string& p : filesUnder(bag, bag / "data")) {
    const auto d = surrogate::archive::digestFile(bag / p, true);
    m256 += d.sha256 + "  " + escape(p) + "\n";
    m512 += d.sha512 + "  " + escape(p) + "\n";
    octets += d.size;
    ++streams;
  }
  writeText(bag / "manifest-sha256.txt", m256);
  writeText(bag / "manifest-sha512.txt", m512);
  writeText(bag / "bagit.txt", "BagIt-Version: 1.0\nTag-File-Character-Encoding: UTF-8\n");
  writeText(bag / "bag-info.txt",
            "Bag-Software-Agent: Surrogate test\nBagging-Date: 2026-11-25\n"
            "Payload-Oxum: " + std::to_string(octets) + "." + std::to_string(streams) + "\n"
            "Surrogate-Package-Identifier: urn:test:bag\n"
            "Surrogate-Packaging-Time: 2026-11-25T08:00:00Z\n");
  writeMetadata(bag);
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
    const auto d = surrogate::archive::digestFile(capture / rel);
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

}  // namespace verify_test
