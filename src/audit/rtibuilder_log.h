// RTIBuilder's processing log, read as data. It lives in src/audit because it is part of the
// prior work an audit weighs (stages/prior_work.h records it, the Audit stage compares it with
// the photographs), and because reading it needs the XML reader of src/carrier, a folder audit
// already builds on (formats, beside carrier, stays free of XML).
//
// RTIBuilder (Cultural Heritage Imaging with the Universidade do Minho) keeps one XML document
// per project in assembly-files/, named after the project: the "XMLCarrier" of the Minho
// (namespace http://alba.di.uminho.pt/XMLCarrier). Its header names the project, author, host
// and dates; its fileSec lists the images (the "Original image files" group, paths such as
// jpeg-exports\name.jpg) and groups of them per step by id; its Processes and dataSec hold the
// sphere and highlight detection steps with their search areas and parameters; computedData
// the spheres, highlights and light directions per image; its Log the tool's own messages,
// among them the fitter's command line. docs/formats.md describes what is read.
//
//   const RtiBuilderLog log = readRtiBuilderLog("assembly-files/Fisch.xml");
//   std::cout << log.toText();                       // or toJson(), for surrogate info
//   for (const std::string& d : logDiscrepancies(log, capture)) ...  // for the audit
//
// Every text taken from the file is passed through escapedText (core/text.h) when it is read,
// so the struct holds only text a terminal, a JSON string or the carrier can carry.
#pragma once

#include "audit/audit.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace surrogate::audit {

// A file larger than this is refused unread: RTIBuilder's logs are tens of kilobytes (58 KB for
// 36 images and two spheres), and the whole document is parsed (the cap of prior_work.cpp).
constexpr std::uintmax_t kMaxLogBytes = 64u << 20;
// More elements than this is not a log RTIBuilder wrote (about 20 per image and sphere).
constexpr std::size_t kMaxLogElements = 500000;
// What is kept of one value (a path, a message): enough for any path or sentence of a log.
constexpr std::size_t kMaxLogValueBytes = 4096;

// The namespace of RTIBuilder's XMLCarrier documents.
constexpr const char* kRtiBuilderLogNamespace = "http://alba.di.uminho.pt/XMLCarrier";

struct LogItem {  // a name and a value as the log writes them
  std::string name, value;
};

struct LogPoint {  // a highlight (x, y in pixels) or a light direction (x, y, z) of one image
  std::string image;  // the image's file name ("fish_fossil_01.jpg"), or its id if unlisted
  double x = 0, y = 0, z = 0;
};

struct LogSphere {
  std::string id;
  int order = -1;                    // RTIBuilder's index of the sphere, -1 when not written
  double x = 0, y = 0, radius = 0;   // centre and radius in pixels of the full image
  std::vector<LogItem> detection;    // sphere detection: search area, algorithm, hough, binarize
  int detectionImages = 0;           // images the sphere was detected on
  std::vector<LogItem> highlightDetection;  // search area, threshold
  std::vector<LogPoint> highlights;
  std::vector<LogPoint> lightDirections;
};

struct LogFitter {
  std::string name;         // the executable's name without ".exe": "hshfitter", "PTMfitter"
  std::string kind;         // "HSH", "PTM" or "" when the name says neither
  std::string basis;        // Surrogate's name of the basis ("hsh2") when known, else ""
  int order = 0;            // HSH order (hshfitter's second argument), 0 when not known
  int threads = 0;          // hshfitter's third argument, 0 when not known
  std::string commandLine;  // as logged
  std::string lightFile;    // the .lp it read, as written
  std::string output;       // the model it wrote, as written
  std::vector<std::string> options;  // other arguments, as written
  std::string result;       // the log's sentence about the fit's end, "" when none
  bool succeeded = false;   // that sentence says it was generated successfully
};

struct LogFile {  // a file the log names, with the group it is in
  std::string path;  // as written (Windows separators kept)
  std::string use;   // the group's USE ("Blend Image"), or "fitter input"/"fitter output"
};

struct LogEvent {
  std::string level, text, started, finished;
};

struct RtiBuilderLog {
  std::string path;
  std::string software = "RTIBuilder";
  std::string version;      // "2.0.2", from the install folder its messages name; "" if none
  std::string versionFrom;  // where the version was read, "" when not known
  std::string projectName, author, host, operatingSystem;
  std::string created, modified;  // as written ("2017/4/5 9:49:21")
  int imageWidth = 0, imageHeight = 0;  // from the header, 0 when not written
  std::vector<LogFile> images;          // the original images, in the log's order
  std::vector<std::string> usedImages;      // file names of the images highlights were sought on
  std::vector<std::string> excludedImages;  // file names of originals that were not used
  int reportedImagesUsed = -1;  // "Number of images used : N" of its messages, -1 when absent
  std::string highlightMethod;  // the detection step's type ("HLTDETECTION"), "" when none
  std::vector<LogSphere> spheres;
  std::optional<LogFitter> fitter;
  std::vector<LogFile> outputs;  // files the steps wrote, as the log names them
  std::vector<LogEvent> events;
  std::vector<LogItem> other;    // everything the reader does not classify, by element path

  std::string toText() const;  // lines for surrogate info
  std::string toJson() const;  // one JSON object for surrogate info --json
};

// Whether the file's first element is named XMLCarrier: a cheap test on its first 4 KiB, for
// choosing a reader (readRtiBuilderLog checks the namespace and everything else).
bool looksLikeRtiBuilderLog(const std::filesystem::path& file);

// Reads the log. Throws Error(Input) naming the file when it is larger than kMaxLogBytes, not
// well-formed XML, not an RTIBuilder log (another root element or namespace: the message says
// what one is), or has more than kMaxLogElements elements.
RtiBuilderLog readRtiBuilderLog(const std::filesystem::path& file);

// What Surrogate knows of the capture, to compare the log with. Zero or empty: not known, not
// compared.
struct CaptureFacts {
  std::vector<std::string> photographs;  // capture-relative paths or file names
  std::size_t photographCount = 0;       // the capture's photographs (shots)
  int width = 0, height = 0;             // the photographs' size in pixels
  int spheres = 0;                       // spheres Surrogate found
  std::string basis;                     // the basis of the prior model audited ("hsh2")
};

// Where the log and the capture disagree, one plain sentence each, in a fixed order: images
// the log used that are not among the photographs, photographs the log does not list, images
// the log lists but did not use, then counts, image size, spheres and basis. Images are
// matched by file name without extension, ignoring case (RTIBuilder reads the JPEG exports of
// raw originals, on Windows). Empty when nothing differs. Pure: reads no file.
std::vector<std::string> logDiscrepancies(const RtiBuilderLog& log, const CaptureFacts& capture);

// The log as the audit records it: what it says of the processing (toText's lines, one fact
// each) and logDiscrepancies with `capture`. `relativePath` names the file in the record.
AuditReport::PriorLog auditedLog(const RtiBuilderLog& log, const std::string& relativePath,
                                 const CaptureFacts& capture);

}  // namespace surrogate::audit
