// The HTML report: what a photographer or an archivist looks at to judge a capture or a package.
//
// One self-contained file (inline CSS and JavaScript, pictures as data: URIs, no network
// access, enforced by a Content-Security-Policy), built from a carrier and the files it names:
//   - the light directions on a hemisphere plot, coloured by the fit's per-image residual, with
//     the gaps in coverage pointed out (no raking light, an empty azimuth sector);
//   - the sphere detection overlay and the highlight overviews;
//   - first, a summary (object, capture, verdict of verification, key figures) and an
//     interactive relighting view of each fitted model, PTM or HSH, at its own resolution
//     (drag the light, in the hemisphere plot's angles);
//   - the normal map, the albedo and the relit previews;
//   - the provenance as a timeline (steps, software, parameters, durations, interventions with
//     who and why), the camera and lens from EXIF;
//   - when given, the verifier's result per check.
// The report is a derived view, not a pipeline step: it is not recorded in the carrier and it
// holds the time it was made, so two reports of the same carrier differ.
//
//   auto source = openReportSource("/data/stela12");          // capture, bag dir, .tar, .zip
//   Report r = buildReport(source->carrier(), *source, ReportOptions());
//   writeFileAtomically("stela12-report.html", r.html);
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "carrier/carrier.h"
#include "report/embed.h"

namespace surrogate::report {

// One check of a verification (fixity, schema, re-execution, ...), as the verifier reports it.
struct VerificationCheck {
  std::string name;
  bool passed = false;
  std::string detail;
};

// Where the carrier's files are: a capture folder, a BagIt directory (files under data/), or a
// .tar/.zip bag read with the package reader (archive/package_reader.h), the files a report shows unpacked into
// a private temporary folder removed with the source. Paths are the
// carrier's: relative, '/'-separated ("finished-files/normals.png").
class ReportSource {
 public:
  virtual ~ReportSource() = default;
  ReportSource() = default;
  ReportSource(const ReportSource&) = delete;
  ReportSource& operator=(const ReportSource&) = delete;

  virtual const carrier::Carrier& carrier() const = 0;
  // The bytes of a file named by the carrier, or nullopt when it is not there. Called from
  // several threads at once (the pictures are made in parallel): it must not change the source.
  virtual std::optional<std::string> read(const std::string& relativePath) const = 0;
  // "capture folder /data/stela12", "bag stela12.zip", for the report's header.
  virtual std::string describe() const = 0;
  // A package (bag directory, .tar, .zip), as opposed to a capture folder.
  virtual bool isPackage() const = 0;
};

// Opens a capture folder (assembly-files/carrier.xml), a bag directory
// (data/assembly-files/carrier.xml), a .tar or .zip bag, or a carrier.xml file directly.
// Throws Error(Input) naming the path when none of these is found. `progress` follows the
// reading and unpacking of an archive: (label, fraction done 0..1); may be empty.
std::unique_ptr<ReportSource> openReportSource(
    const std::filesystem::path& path, const std::function<void(const std::string&, double)>& progress = {});

struct ReportOptions {
  int maxImageSide = 720;    // embedded pictures are downscaled to this; larger = sharper, bigger file
  // The interactive copy of each model: at its own resolution up to this longer side, else
  // downscaled by a whole factor. Its size in the page grows with the square of this.
  int relightMaxSide = 1200;
  // And all the models together at most this many bytes of coefficients (kRelightModelsBytes;
  // 0 = no limit), each its share (relightShare), downscaled by a whole factor too: the page's
  // size does not grow with the capture's or with the number of models.
  std::size_t relightModelsBytes = kRelightModelsBytes;
  std::string generatedAt;   // shown in the header; empty = now (UTC)
  // The verifier's checks; absent = the section says the package was not verified here.
  std::optional<std::vector<VerificationCheck>> verification;
  // Threads that make the embedded pictures at once; 0 = all cores. The page is the same at
  // any count.
  int threads = 0;
  // Display copies of pictures already in memory, by carrier path ("finished-files/normals.png"):
  // surrogate run passes those of the pictures its steps have just written (displayPicture of
  // the pixels each PNG holds), which spares decoding the files again. One made for another
  // maxImageSide is not used; the other pictures are read from the source and decoded. The
  // page is the same either way.
  std::shared_ptr<const std::map<std::string, DisplayPicture>> displayed;
  // The same for the fitted models, by carrier path ("finished-files/hsh2.rti"): surrogate run
  // passes the interactive copies of the models its fits have just written (relightJson of
  // each model in memory), which spares reading and parsing the files again. One made for
  // another relightMaxSide or another share of relightModelsBytes is not used. The page is the same either way.
  std::shared_ptr<const std::map<std::string, RelightCopy>> relightCopies;
  // Called with (kProgressLabel, fraction done 0..1) as the page is built; may be empty.
  std::function<void(const std::string&, double)> progress;
};

// The page's size budget, its pictures aside: the models of the relighting view (at most
// kRelightModelsBytes together, 4 MB with base64) and the text, whatever the
// capture's size. Each picture adds at most a JPEG of maxImageSide pixels a side (0.03-0.1 MB
// each at 720 px for the generated captures, 7 of them). Before the budget the page of 24 x
// 1200x800 was 27.4 MB and that of 24 x 2000x1500 21.6 MB, the models 98 % of it.
inline constexpr std::size_t kReportBudgetBytes = 5'000'000;

// The fitted models (PTM and HSH) a carrier lists, which the relighting view shares
// ReportOptions::relightModelsBytes among.
std::size_t relightModelCount(const carrier::Carrier& c);

// The label of the report's progress.
inline constexpr const char* kProgressLabel = "Writing the report";

// What the report shows, for the CLI's summary and --json.
struct Report {
  std::string html;
  int lightsPlotted = 0;
  int picturesEmbedded = 0;
  bool relightable = false;            // an interactive view of a PTM or HSH model is in the page
  std::vector<std::string> coverageGaps;  // sentences, as shown in the page
};

// Builds the page. Missing files (a lights-only run, a package without previews) leave their
// section saying what is absent; they are not errors. All text from the carrier is escaped.
Report buildReport(const carrier::Carrier& carrier, const ReportSource& source,
                   const ReportOptions& options);

// The report of a capture folder after `surrogate run`: builds it and writes
// CAPTURE/finished-files/report.html atomically. Returns what it wrote.
Report writeCaptureReport(const std::filesystem::path& capture, const ReportOptions& options = {});

}  // namespace surrogate::report
