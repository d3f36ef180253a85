// ReportSource: a capture folder, a bag directory, a .tar/.zip bag (the files a report shows
// unpacked by the verifier's reader into a temporary folder), or the bag an OCFL object or an
// E-ARK SIP holds (verify/held_bag.h, put together in a temporary folder).

#include <algorithm>
#include <map>
#include <system_error>

#include "archive/package_reader.h"
#include "capture/capture.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/temp_dir.h"
#include "core/text.h"
#include "report/report.h"
#include "verify/held_bag.h"

namespace surrogate::report {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "report";
using capture::kCarrierPath;

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
      : FolderSource(root, std::move(description), package, carrier::loadCarrier(root / kCarrierPath)) {}
  // `keep`: the temporary folder `root` is in, removed with this source.
  FolderSource(fs::path root, std::string description, bool package, carrier::Carrier c,
               std::unique_ptr<TempDir> keep = nullptr)
      : root_(std::move(root)), description_(std::move(description)), package_(package),
        carrier_(std::move(c)), keep_(std::move(keep)) {}

  const carrier::Carrier& carrier() const override { return carrier_; }
  std::string describe() const override { return description_; }
  bool isPackage() const override { return package_; }
  std::optional<std::string> read(const std::string& relativePath) const override {
    if (!safeRelative(relativePath)) return std::nullopt;
    const fs::path path = root_ / relativePath;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return std::nullopt;
    // One read into a string of the file's size: a stream copy of a 70 MB model grew and copied
    // it several times, most of a report's time in fresh memory.
    try {
      return readFile(path, kStep);
    } catch (const Error&) {
      return std::nullopt;  // unreadable: shown as not found, as a missing file
    }
  }

 private:
  fs::path root_;
  std::string description_;
  bool package_;
  carrier::Carrier carrier_;
  std::unique_ptr<TempDir> keep_;
};

// The files of a bag a report can show: pictures, models (.ptm, .rti) and the carrier in its two
// folders.
bool shown(const std::string& relative) {
  if (relative.rfind("assembly-files/", 0) != 0 && relative.rfind("finished-files/", 0) != 0) return false;
  const std::string ext = lowerCase(fs::path(relative).extension().string());
  for (const char* e : {".xml", ".png", ".jpg", ".jpeg", ".tif", ".tiff", ".ptm", ".rti"})
    if (ext == e) return true;
  return false;
}

// A .tar or .zip bag, read with the package reader of src/archive, the verifier's (entry names,
// types, sizes and compression ratios checked before anything is kept): the files the report
// can show are extracted into a private temporary folder; originals and the rest are skipped.
std::unique_ptr<ReportSource> openArchive(const fs::path& path, const archive::Progress& progress) {
  const archive::Limits limits;
  const archive::Inventory inventory = archive::readPackage(path, limits, progress);
  const std::string carrierEntry = std::string("data/") + kCarrierPath;
  const auto it = inventory.files.find(carrierEntry);
  if (it == inventory.files.end() || !it->second.content)
    throwInputError(path.string(), kStep,
                    "holds no data/assembly-files/carrier.xml: it is not a Surrogate package");
  carrier::Carrier c = carrier::parseCarrier(*it->second.content, path.string() + ":" + carrierEntry);
  auto temp = std::make_unique<TempDir>("report");
  archive::extractFiles(
      path, inventory, temp->path(),
      [](const std::string& entry) -> fs::path {
        if (entry.compare(0, 5, "data/") != 0 || !shown(entry.substr(5))) return {};
        return entry.substr(5);
      },
      limits, [&progress](const std::string&, double f) {
        if (progress) progress("extracting the pictures", f);
      });
  const fs::path root = temp->path();
  return std::make_unique<FolderSource>(root, "bag " + path.string(), true, std::move(c), std::move(temp));
}

}  // namespace

std::unique_ptr<ReportSource> openReportSource(const fs::path& path, const archive::Progress& progress) {
  // Error codes, not exceptions: a loop of symbolic links is the user's path, not a bug.
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec == std::errc::too_many_symbolic_link_levels)
    throwInputError(path.string(), kStep, "is a loop of symbolic links; give the capture folder or package itself");
  if (!fs::exists(st)) throwInputError(path.string(), kStep, "does not exist");
  if (fs::is_directory(st)) {
    if (fs::is_regular_file(path / kCarrierPath, ec))
      return std::make_unique<FolderSource>(path, "capture folder " + path.string(), false);
    if (fs::is_regular_file(path / "data" / kCarrierPath, ec))
      return std::make_unique<FolderSource>(path / "data", "bag " + path.string(), true);
    if (std::unique_ptr<verify::HeldBag> held = verify::openHeldBag(path)) {
      const fs::path data = held->bag / "data";
      if (!fs::is_regular_file(data / kCarrierPath, ec))
        throwInputError(path.string(), kStep,
                        "is an " + held->layout + " whose bag holds no data/assembly-files/carrier.xml: "
                        "not a package made by surrogate pack");
      carrier::Carrier c = carrier::loadCarrier(data / kCarrierPath);
      return std::make_unique<FolderSource>(data, held->layout + " " + path.string(), true, std::move(c),
                                            std::move(held->temp));
    }
    throwInputError(path.string(), kStep,
                    "has no assembly-files/carrier.xml (a capture processed by surrogate run) "
                    "and no data/assembly-files/carrier.xml (a package made by surrogate pack)");
  }
  const std::string name = lowerCase(path.filename().string());
  const auto endsWith = [&](const std::string& suffix) {
    return name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (endsWith(".tar") || endsWith(".zip") || endsWith(".tar.gz") || endsWith(".tgz"))
    return openArchive(path, progress);
  if (endsWith(".xml")) {
    // CAPTURE/assembly-files/carrier.xml: the capture is two levels up.
    const fs::path root = fs::absolute(path).parent_path().parent_path();
    if (fs::is_regular_file(root / kCarrierPath, ec) && fs::equivalent(root / kCarrierPath, path, ec))
      return std::make_unique<FolderSource>(root, "capture folder " + root.string(), false);
  }
  throwInputError(path.string(), kStep,
                  "is neither a capture folder, a package (directory, .tar or .zip) nor "
                  "CAPTURE/assembly-files/carrier.xml");
}

}  // namespace surrogate::report
