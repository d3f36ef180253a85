// ReportSource: a capture folder, a bag directory, or a .tar/.zip bag read in place.
#include <archive.h>
#include <archive_entry.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "core/error.h"
#include "report/report.h"

namespace surrogate::report {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "report";
constexpr const char* kCarrierPath = "assembly-files/carrier.xml";

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// A relative carrier path that stays inside its root.
bool safeRelative(const std::string& path) {
  if (path.empty() || path.front() == '/' || path.find('\\') != std::string::npos) return false;
  for (const auto& part : fs::path(path))
    if (part == "..") return false;
  return true;
}

// Files on disk under `root` (a capture folder, or a bag's data/ folder).
class FolderSource : public ReportSource {
 public:
  FolderSource(fs::path root, std::string description, bool package)
      : root_(std::move(root)), description_(std::move(description)), package_(package),
        carrier_(carrier::loadCarrier(root_ / kCarrierPath)) {}

  const carrier::Carrier& carrier() const override { return carrier_; }
  std::string describe() const override { return description_; }
  bool isPackage() const override { return package_; }
  std::optional<std::string> read(const std::string& relativePath) const override {
    if (!safeRelative(relativePath)) return std::nullopt;
    std::ifstream in(root_ / relativePath, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }

 private:
  fs::path root_;
  std::string description_;
  bool package_;
  carrier::Carrier carrier_;
};

// A .tar or .zip bag: the files the report can show (the carrier, pictures, PTMs) under
// data/assembly-files/ and data/finished-files/ are read into memory in one pass; originals,
// .rti and everything else are skipped.
class ArchiveSource : public ReportSource {
 public:
  explicit ArchiveSource(const fs::path& path) : description_("bag " + path.string()) {
    struct archive* a = archive_read_new();
    archive_read_support_filter_all(a);
    archive_read_support_format_tar(a);
    archive_read_support_format_zip(a);
    if (archive_read_open_filename(a, path.c_str(), 1 << 16) != ARCHIVE_OK) {
      const std::string why = archive_error_string(a) ? archive_error_string(a) : "unreadable";
      archive_read_free(a);
      throwInputError(path.string(), kStep, "cannot be read as a .tar or .zip bag: " + why);
    }
    struct archive_entry* entry = nullptr;
    int status;
    while ((status = archive_read_next_header(a, &entry)) == ARCHIVE_OK) {
      const char* name = archive_entry_pathname(entry);
      const std::string relative = name ? underData(name) : "";
      if (archive_entry_filetype(entry) != AE_IFREG || !shown(relative)) {
        archive_read_data_skip(a);
        continue;
      }
      std::string content;
      char buffer[1 << 16];
      la_ssize_t n;
      while ((n = archive_read_data(a, buffer, sizeof buffer)) > 0) content.append(buffer, n);
      if (n < 0) {
        const std::string why = archive_error_string(a) ? archive_error_string(a) : "read error";
        archive_read_free(a);
        throwInputError(path.string(), kStep, "is damaged at " + std::string(name) + ": " + why);
      }
      files_[relative] = std::move(content);
    }
    const std::string why = status != ARCHIVE_EOF && archive_error_string(a) ? archive_error_string(a) : "";
    archive_read_free(a);
    if (status != ARCHIVE_EOF) throwInputError(path.string(), kStep, "is damaged: " + why);
    const auto it = files_.find(kCarrierPath);
    if (it == files_.end())
      throwInputError(path.string(), kStep,
                      "holds no data/assembly-files/carrier.xml: it is not a Surrogate package");
    carrier_ = carrier::parseCarrier(it->second, path.string() + ":data/" + kCarrierPath);
  }

  const carrier::Carrier& carrier() const override { return carrier_; }
  std::string describe() const override { return description_; }
  bool isPackage() const override { return true; }
  std::optional<std::string> read(const std::string& relativePath) const override {
    const auto it = files_.find(relativePath);
    if (it == files_.end()) return std::nullopt;
    return it->second;
  }

 private:
  static bool shown(const std::string& relative) {
    if (relative.rfind("assembly-files/", 0) != 0 && relative.rfind("finished-files/", 0) != 0) return false;
    const std::string ext = lower(fs::path(relative).extension().string());
    for (const char* e : {".xml", ".png", ".jpg", ".jpeg", ".tif", ".tiff", ".ptm"})
      if (ext == e) return true;
    return false;
  }

  // "data/x" or "TOP/data/x" (a bag packed with its folder) -> "x"; else "".
  static std::string underData(std::string name) {
    if (name.rfind("./", 0) == 0) name.erase(0, 2);
    std::size_t at = std::string::npos;
    if (name.rfind("data/", 0) == 0) at = 5;
    else if (const auto slash = name.find('/');
             slash != std::string::npos && name.compare(slash + 1, 5, "data/") == 0)
      at = slash + 6;
    if (at == std::string::npos) return "";
    const std::string rest = name.substr(at);
    return safeRelative(rest) ? rest : "";
  }

  std::string description_;
  std::map<std::string, std::string> files_;
  carrier::Carrier carrier_;
};

}  // namespace

std::unique_ptr<ReportSource> openReportSource(const fs::path& path) {
  if (!fs::exists(path)) throwInputError(path.string(), kStep, "does not exist");
  if (fs::is_directory(path)) {
    if (fs::is_regular_file(path / kCarrierPath))
      return std::make_unique<FolderSource>(path, "capture folder " + path.string(), false);
    if (fs::is_regular_file(path / "data" / kCarrierPath))
      return std::make_unique<FolderSource>(path / "data", "bag " + path.string(), true);
    throwInputError(path.string(), kStep,
                    "has no assembly-files/carrier.xml (a capture processed by surrogate run) "
                    "and no data/assembly-files/carrier.xml (a package made by surrogate pack)");
  }
  const std::string name = lower(path.filename().string());
  const auto endsWith = [&](const std::string& suffix) {
    return name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (endsWith(".tar") || endsWith(".zip") || endsWith(".tar.gz") || endsWith(".tgz"))
    return std::make_unique<ArchiveSource>(path);
  if (endsWith(".xml")) {
    // CAPTURE/assembly-files/carrier.xml: the capture is two levels up.
    const fs::path root = fs::absolute(path).parent_path().parent_path();
    if (fs::is_regular_file(root / kCarrierPath) && fs::equivalent(root / kCarrierPath, path))
      return std::make_unique<FolderSource>(root, "capture folder " + root.string(), false);
  }
  throwInputError(path.string(), kStep,
                  "is neither a capture folder, a package (directory, .tar or .zip) nor "
                  "CAPTURE/assembly-files/carrier.xml");
}

}  // namespace surrogate::report
