#include "archive/package_readme.h"

#include <algorithm>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "archive/package.h"
#include "capture/capture.h"

namespace surrogate::archive {

namespace {

constexpr std::size_t kWidth = 78;

// Characters (not bytes) of UTF-8 text: for the line width.
std::size_t displayWidth(const std::string& s) {
  std::size_t n = 0;
  for (unsigned char ch : s)
    if ((ch & 0xC0) != 0x80) ++n;
  return n;
}

// Text from the carrier on one line: control characters (a line break in a title) as spaces.
std::string oneLine(const std::string& s) {
  std::string out = s;
  for (char& ch : out)
    if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ch = ' ';
  return out;
}

// `text` wrapped at kWidth, each line after the first indented by `indent` spaces (the first
// is assumed to start at that column already). A word longer than a line stays whole.
std::string wrapped(const std::string& text, std::size_t indent) {
  std::string out, line;
  std::size_t lineWidth = indent;
  std::size_t i = 0;
  const std::string words = oneLine(text);
  while (i < words.size()) {
    while (i < words.size() && words[i] == ' ') ++i;
    if (i >= words.size()) break;
    const std::size_t end = words.find(' ', i);
    const std::string word = words.substr(i, end == std::string::npos ? std::string::npos : end - i);
    i = end == std::string::npos ? words.size() : end;
    const std::size_t w = displayWidth(word);
    if (!line.empty() && lineWidth + 1 + w > kWidth) {
      out += line + "\n" + std::string(indent, ' ');
      line.clear();
      lineWidth = indent;
    }
    if (!line.empty()) {
      line += ' ';
      ++lineWidth;
    }
    line += word;
    lineWidth += w;
  }
  return out + line + "\n";
}

void paragraph(std::string& out, const std::string& text) { out += wrapped(text, 0) + "\n"; }

// "  LABEL  text...", the text wrapped under itself.
void item(std::string& out, const std::string& label, std::size_t labelWidth, const std::string& text) {
  std::string head = "  " + label;
  const std::size_t column = 2 + labelWidth + 2;
  if (displayWidth(head) + 2 > column) {
    out += head + "\n" + std::string(column, ' ');
  } else {
    head += std::string(column - displayWidth(head), ' ');
    out += head;
  }
  out += wrapped(text, column);
}

void heading(std::string& out, const std::string& title) {
  out += title + "\n" + std::string(displayWidth(title), '-') + "\n\n";
}

std::string plural(std::size_t n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

std::string topFolder(const std::string& path) {
  const auto slash = path.find('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

// What each of the capture's folders holds, in the words of docs/package.md.
std::string folderPurpose(const std::string& folder) {
  if (folder == "original-captures/")
    return "the camera's files, byte for byte as they came from the card: the evidence "
           "everything else is derived from";
  if (folder == "jpeg-exports/")
    return "JPEG or TIFF exports another program made from the camera files (what that "
           "program did is not on record; the carrier flags them so)";
  if (folder == "assembly-files/")
    return "the working record: carrier.xml (the provenance: every file with its SHA-256, "
           "every processing step with its software version and parameters, every decision "
           "made by hand, with who and why), the light directions (.lp), the sphere and "
           "highlight overlays";
  if (folder == "finished-files/")
    return "the results: relightable models (.ptm, .rti), normals and albedo, relit "
           "previews, the report";
  return "files of the capture as the photographer arranged them, each listed in the carrier";
}

// Which program opens a result, by the format the carrier records for it.
std::string opensWith(const carrier::FileRecord& f) {
  const std::string& fmt = f.format;
  if (fmt.rfind("PTM_FORMAT", 0) == 0)
    return "Polynomial Texture Map: RTIViewer (Cultural Heritage Imaging) and other RTI "
           "viewers relight it; format in metadata/docs/formats.md";
  if (fmt.rfind("RTI", 0) == 0)
    return "Hemispherical Harmonics RTI: RTIViewer (Cultural Heritage Imaging) relights it; "
           "format in metadata/docs/formats.md";
  if (fmt == "LP")
    return "light directions, plain text (a count, then one line per photograph): "
           "RTIBuilder and other RTI fitters read it with the photographs";
  if (fmt == "PNG" || fmt == "JPEG" || fmt == "TIFF") return "an image: any image viewer";
  if (fmt == "XML") return "XML: any text editor or XML viewer";
  return "";
}

std::string runsSummary(const carrier::Header& h) {
  if (h.runs.empty()) return "";
  std::size_t failed = 0;
  for (const carrier::RunRecord& r : h.runs) failed += r.outcome != "completed";
  std::string s = plural(h.runs.size(), "command", "commands") + " recorded, from " +
                  h.runs.front().started + " to " + h.runs.back().ended;
  if (failed) s += " (" + std::to_string(failed) + " failed, kept in the record)";
  return s;
}

}  // namespace

std::vector<std::string> bundledDocuments() {
  return {"docs/carrier.md", "docs/formats.md", "docs/hrti-math.md", "docs/package.md"};
}

std::string packageReadme(const carrier::Carrier& c, const ReadmeFacts& facts) {
  std::string out;
  const std::string title = c.header.title.empty() ? "Untitled capture" : oneLine(c.header.title);
  out += title + "\n" + std::string(displayWidth(title), '=') + "\n\n";
  paragraph(out, "A Highlight-RTI capture (Reflectance Transformation Imaging: photographs of "
                 "an object under a light moved around it, with a glossy sphere that shows "
                 "where the light was) and the relightable models made from it, packed as a "
                 "BagIt 1.0 package (RFC 8493) by " + facts.softwareAgent + " on " +
                 facts.packagingTime + ". This file is written from the package's provenance "
                 "record, data/" + std::string(capture::kCarrierPath) + ".");

  heading(out, "What it is");
  std::vector<std::pair<std::string, std::string>> facts2;
  facts2.emplace_back("Identifier", facts.packageId + " (this package: the SHA-256 of the carrier)");
  facts2.emplace_back("Capture", captureIdentifier(c) + " (the capture, the same in every package of it)");
  for (const carrier::Creator& cr : c.header.creators)
    facts2.emplace_back("Made by", oneLine(cr.name) + " (" + oneLine(cr.role) + ")");
  if (!c.header.rights.empty()) facts2.emplace_back("Rights", c.header.rights);
  if (!c.header.license.empty()) facts2.emplace_back("Licence", c.header.license);
  for (const auto& [key, value] : c.header.meta) facts2.emplace_back(key, value);
  std::size_t originals = 0, exports = 0;
  for (const carrier::FileRecord& f : c.files) {
    originals += f.role == "original";
    exports += f.role == "export";
  }
  std::string shots = plural(originals, "camera file", "camera files");
  if (exports) shots += ", " + plural(exports, "export", "exports");
  facts2.emplace_back("Photographs", shots);
  if (!c.header.created.empty()) facts2.emplace_back("Record begun", c.header.created);
  if (const std::string runs = runsSummary(c.header); !runs.empty()) facts2.emplace_back("History", runs);
  std::size_t width = 0;
  for (const auto& [label, value] : facts2) width = std::max(width, displayWidth(oneLine(label)) + 1);
  width = std::min<std::size_t>(width, 20);
  for (const auto& [label, value] : facts2) item(out, oneLine(label) + ":", width, value);
  out += "\n";

  heading(out, "What each folder holds");
  std::map<std::string, std::size_t> perFolder;
  for (const carrier::FileRecord& f : c.files) ++perFolder[topFolder(f.path)];
  // Beside the files it lists, the payload holds the carrier itself and the report.
  ++perFolder[std::string(capture::kAssemblyDir) + "/"];
  if (facts.hasReport) ++perFolder[std::string(capture::kFinishedDir) + "/"];
  // The capture's own folders in the order of its making, then any other.
  std::vector<std::pair<std::string, std::size_t>> folders;
  for (const char* known : {"original-captures/", "jpeg-exports/", "assembly-files/", "finished-files/"})
    if (const auto it = perFolder.find(known); it != perFolder.end()) {
      folders.push_back(*it);
      perFolder.erase(it);
    }
  folders.insert(folders.end(), perFolder.begin(), perFolder.end());
  for (const auto& [folder, count] : folders) {
    const std::string where = folder.empty() ? "data/ (top level)" : "data/" + folder;
    item(out, where, 24, plural(count, "file", "files") + ": " +
                             (folder.empty() ? std::string("files of the capture beside its folders")
                                             : folderPurpose(folder)));
  }
  item(out, "data/ro-crate-metadata.json", 24,
       "the same record as RO-Crate 1.1 metadata (JSON-LD), so that data/ is a crate research "
       "repositories and RO-Crate tools open: every file, every processing step as an action");
  item(out, "metadata/", 24,
       "the same record for repositories: mets.xml (METS and PREMIS: every file with its "
       "fixity and format, every step as an event), crm.rdf (CIDOC-CRM and CRMdig), the "
       "stylesheets that derive them from the carrier (xslt/), the tables that explain them "
       "(mappings/), the schemas (xsd/) and documentation (docs/: the file formats, the "
       "mathematics, the carrier and the package explained)");
  item(out, "bag-info.txt", 24, "who packed it, when, its size and identifier");
  item(out, "manifest-*.txt", 24, "the SHA-256 and SHA-512 of every file under data/");
  item(out, "tagmanifest-*.txt", 24,
       "the same for the files outside data/ (this README, bag-info.txt, the manifests, "
       "metadata/)");
  out += "\n";

  heading(out, "The results and what opens them");
  std::set<std::string> webFolders;
  for (const carrier::FileRecord& f : c.files) {
    if (f.role != "result" && f.role != "assembly") continue;
    const std::string web = std::string(capture::kFinishedDir) + "/web/";
    if (f.path.rfind(web, 0) == 0) {
      const auto slash = f.path.find('/', web.size());
      if (slash != std::string::npos) webFolders.insert(f.path.substr(0, slash + 1));
      continue;
    }
    const std::string opens = opensWith(f);
    if (!opens.empty()) item(out, "data/" + oneLine(f.path), 24, opens);
  }
  for (const std::string& folder : webFolders)
    item(out, "data/" + oneLine(folder), 24,
         "a web copy of a model: open its index.html in a web browser (from disk, no network "
         "needed), or serve the folder to OpenLIME (its info.json)");
  if (facts.hasReport)
    item(out, "data/" + std::string(capture::kReportPath), 24,
         "the report: what was done, with what, and how well; open it in a web browser");
  item(out, "data/" + std::string(capture::kCarrierPath), 24,
       "the provenance record (XML), explained element by element in metadata/docs/carrier.md");
  out += "\n";

  heading(out, "How to check it without Surrogate");
  paragraph(out, "In the package's folder (unpack a .zip or .tar first), every line of these "
                 "commands (GNU coreutils) must end in OK; a file that changed, is missing or was "
                 "cut short is named:");
  out += "    sha256sum -c manifest-sha256.txt\n"
         "    sha512sum -c manifest-sha512.txt\n"
         "    sha256sum -c tagmanifest-sha256.txt\n"
         "    sha512sum -c tagmanifest-sha512.txt\n\n";
  paragraph(out, "Then check that data/ holds no file the manifests do not list. Any BagIt "
                 "validator does all of this (bagit-python: bagit.py --validate .). A file "
                 "name with a line break or a percent sign is written percent-encoded in the "
                 "manifests, as RFC 8493 asks; sha256sum then reports it missing, a BagIt "
                 "validator does not.");
  paragraph(out, "The metadata can be derived again from the carrier with any XSLT 1.0 "
                 "processor; crm.rdf, for example, with xsltproc (the parameters are the ones "
                 "bag-info.txt records), and cmp says nothing when the two are the same:");
  // One argument a line, each but the last ended by a backslash, so the shell reads one command.
  const std::string more = " \\\n      ";
  std::string command = "    xsltproc --stringparam package-id " + facts.packageId;
  if (!facts.previousPackageId.empty())
    command += more + "--stringparam previous-package-id " + facts.previousPackageId;
  if (!facts.baseUri.empty()) command += more + "--stringparam base-uri '" + oneLine(facts.baseUri) + "'";
  command += more + "metadata/xslt/carrier-to-crm.xsl data/" + std::string(capture::kCarrierPath) +
             more + "| cmp - metadata/crm.rdf\n\n";
  out += command;
  paragraph(out, "mets.xml needs the manifests too, and ro-crate-metadata.json the packaging "
                 "time (metadata/mappings/ says how). With Surrogate, `surrogate verify "
                 "PACKAGE --reexecute` checks all of this and runs every recorded step again on "
                 "the originals, comparing the results.");
  return out;
}

}  // namespace surrogate::archive
