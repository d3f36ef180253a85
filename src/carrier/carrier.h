// The carrier: the provenance document of one capture (schema: xsd/carrier.xsd).
//
// One XML document in five sections (header, files, process, data, log), after RTIBuilder's
// XMLcarrier. It is both the record a scholar audits and the way pipeline stages talk to each
// other: a stage reads its parameters and interventions from its `Step`, reads the results of
// earlier steps from `data`, and appends its own `Result` and log entries.
//
//   Carrier c = newCarrier("Stela 12", {{"A. Photographer", "photographer"}});
//   c.files.push_back(...);
//   Step& s = c.addStep("SphereDetection", "1");
//   s.setParam("minRadius", "20");
//   saveCarrier(c, "assembly-files/carrier.xml");   // validated against the XSD, atomic
//   Carrier again = loadCarrier("assembly-files/carrier.xml");
//
// Numbers are written with formatNumber() (core/text.h: the shortest text that reads back as the
// same double), so a value read back is the same double and re-execution can compare results
// exactly. Carriers from older versions wrote 17 significant digits ("0.80000000000000004");
// that text reads back as the same double too.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace surrogate::carrier {

// The carrier's XML namespace and format version.
inline constexpr const char* kNamespace = "urn:surrogate:carrier:1";
inline constexpr const char* kFormatVersion = "1.0";

using Attributes = std::vector<std::pair<std::string, std::string>>;

// UTC now as xs:dateTime ("2026-11-24T15:04:05Z").
std::string timestampNow();

struct Creator {
  std::string name;
  std::string role = "creator";
};

struct Machine {
  std::string hostname, os, architecture, cpu;
  int cores = 0;
  std::uint64_t memoryBytes = 0;
};
// Reads the machine this process runs on (uname, /proc/cpuinfo, /proc/meminfo).
Machine currentMachine();

struct Software {
  std::string name, version, role;
};

struct Step;  // below: a step of the process list

// One invocation of a command that changed (or tried to change) the capture's record: the
// history an auditor reads to see the iterative process. Failed runs stay too.
struct RunRecord {
  std::string id;       // r1, r2, ...
  std::string command;  // run, lights, pack
  std::string who;
  std::string started, ended;  // xs:dateTime
  std::string outcome;  // completed, failed
  std::vector<std::string> arguments;  // the command line after the command, as given
  std::vector<std::string> notes;      // what changed; for a failed run, the cause
  // A failed run on a capture that kept its previous state: the process list it planned (its
  // steps' parameters and interventions, no results), so that the decisions given on it stand
  // for the next run as those of a completed run do (standingProcess). Empty otherwise.
  std::vector<Step> planned;
};

// The evidence an audit examined (`surrogate audit PRIOR`): another tool's work, copied byte for
// byte from PRIOR into the audit's own work folder, which is this capture. Each copy's file record
// carries its hash as usual; this says where it came from, so that the package of the audit
// names the prior files it examined as they were read.
struct AuditedSource {
  std::string source;  // PRIOR as given, made absolute (escaped text, core/text.h escapedText)
  std::string kind;    // "folder" or "package"
  std::string copied;  // xs:dateTime of the copy
  // A package file (.zip, .tar): its size and SHA-256 as read; 0 and empty for a folder.
  std::uint64_t packageSize = 0;
  std::string packageSha256;
  struct Item {
    std::string path;  // in this capture
    std::string from;  // in PRIOR ('/' separated; a bag's payload path for a package)
    std::uint64_t size = 0;
    std::string sha256;
  };
  std::vector<Item> files;  // sorted by path
};

struct Header {
  std::string title;
  std::vector<Creator> creators;
  std::string created, modified;  // xs:dateTime
  std::vector<std::pair<std::string, std::string>> meta;  // user metadata, in given order
  // Rights statement in the depositor's words (--rights) and the licence's URI (--license);
  // empty when not given (carriers before these existed have neither).
  std::string rights, license;
  std::optional<AuditedSource> audited;  // only in an audit's work folder
  Machine machine;
  std::vector<Software> software;
  std::vector<RunRecord> runs;  // oldest first
};

struct FileRecord {
  std::string id;    // f1, f2, ...
  std::string path;  // relative to the capture folder, '/' separated
  std::string role;  // original, export, lp, sidecar, other, prior, assembly, result
  std::uint64_t size = 0;
  std::string sha256;
  std::string format;     // e.g. "DNG", "JPEG", "PTM_FORMAT_LRGB"
  std::string mediaType;  // optional
  std::string puid;       // optional PRONOM identifier
  std::string createdBy;  // optional: step id
  std::string pairedWith; // optional: file id of the other file of the same shot
  bool unrecordedProcessing = false;
  std::optional<std::pair<int, int>> imageSize;  // width, height
  Attributes camera;      // attributes of <camera>, empty when none
  // Camera text fields whose bytes were not clean text, escaped in `camera` (core/text.h,
  // escapedText): field name and the raw bytes as hex, so the record loses nothing.
  std::vector<std::pair<std::string, std::string>> cameraRaw;
  std::string xmp;        // the XMP packet, verbatim; empty when none
  bool xmpEscaped = false;  // `xmp` is escapedText of a packet that was not clean text
  // Prior work (role "prior": a file in assembly-files/ or finished-files/ that Surrogate did
  // not write, e.g. RTIBuilder's): what it is, "lp", "rti" (a .ptm or .rti result), "log" or
  // "other"; and what the file itself says of the tool or format that made it (a PTM's version
  // and format lines, an .rti's first comment, a log's root element and its attributes), empty
  // when it says nothing. Both empty for every other role.
  std::string priorKind;
  std::string madeBy;
};

// Whether files of this role are evidence (original, export, sidecar, the dome's lp, prior
// work): once recorded, their bytes may never be re-recorded silently; a change is a fixity
// failure.
bool isEvidenceRole(const std::string& role);

struct Param {
  std::string name, value;
};

struct Intervention {
  std::string kind;    // exclude-image, manual-sphere, manual-highlight, accept-changed-original
  std::string target;  // file path, sphere index, "path:sphere"
  std::string value;   // optional: the value chosen by hand
  std::string who, time, reason;
};

struct Step {
  std::string id;         // s1, s2, ...
  std::string component;  // registered stage name
  std::string version;
  std::string algorithm;  // optional
  std::string description;
  std::vector<Param> params;
  std::vector<Intervention> interventions;

  // The value of a parameter, or `fallback` when absent.
  std::string param(const std::string& name, const std::string& fallback = "") const;
  bool hasParam(const std::string& name) const;
  void setParam(const std::string& name, const std::string& value);
  std::vector<const Intervention*> interventionsOfKind(const std::string& kind) const;
};

// One element inside a <result>: `element` is its name in the schema (input, output, value,
// decoded, sphere, highlight, light, lightPosition, imageValue), attributes in order.
struct DataItem {
  std::string element;
  Attributes attributes;

  DataItem& set(const std::string& name, const std::string& value);
  DataItem& set(const std::string& name, double value);
  DataItem& set(const std::string& name, int value);
  std::optional<std::string> get(const std::string& name) const;
  // The attribute as a number; throws Error(Input) naming the attribute if absent or not one.
  double number(const std::string& name) const;
};

struct Result {
  std::string step;
  std::string status = "completed";  // completed, failed
  std::string started, ended;
  double seconds = 0;
  std::vector<DataItem> items;

  DataItem& add(const std::string& element);
  std::vector<const DataItem*> itemsOf(const std::string& element) const;
};

struct LogEntry {
  std::string time, level, step, who, text;
};

struct Carrier {
  Header header;
  std::vector<FileRecord> files;
  std::vector<Step> process;
  std::vector<Result> data;
  std::vector<LogEntry> log;

  const FileRecord* findFile(const std::string& id) const;
  const FileRecord* findFileByPath(const std::string& path) const;
  // Adds or replaces (same path) a file record and returns its id. Searches the list: for one
  // file at a time (a step's outputs); a capture's files go in with putFiles.
  std::string putFile(FileRecord record);
  // putFile for each record in order (same ids, same list), in one pass over the list: putFile
  // for each of a capture's files was quadratic in their number (100 000 other files: 132 s).
  void putFiles(std::vector<FileRecord> records);
  // The records by path, for a loop that looks up many paths; the first record of a path wins,
  // as with findFileByPath. Pointers into `files`: valid until the list changes.
  std::unordered_map<std::string, const FileRecord*> filesByPath() const;
  Step& addStep(const std::string& component, const std::string& version);
  Step* findStep(const std::string& id);
  const Step* findStep(const std::string& id) const;
  const Result* findResult(const std::string& stepId) const;
  // The last result holding an item of this element (e.g. "light": the lights the capture's
  // last light estimation recorded); null when none does.
  const Result* lastResultWith(const std::string& element) const;
  // Removes the result of a step (before running it again), keeping the others.
  void clearResult(const std::string& stepId);
  void addLog(const std::string& level, const std::string& step, const std::string& text,
              const std::string& who = "");
};

// The process list whose decisions stand: the carrier's own, or, when its last run failed and
// left the previous state in place, the list that run planned. Following a refusal's advice
// one option at a time then adds up, whether or not the runs in between succeeded.
const std::vector<Step>& standingProcess(const Carrier& carrier);

// A new carrier with the header filled in: title, creators, timestamps, this machine, and
// Surrogate's own version. Library versions are added by the caller (software list).
Carrier newCarrier(const std::string& title, const std::vector<Creator>& creators);

// XML text of the carrier (UTF-8, indented, deterministic for the same content).
std::string toXml(const Carrier& carrier);
// Parses and validates carrier XML; `source` names the file in errors.
Carrier parseCarrier(const std::string& xml, const std::string& source);

// Serialises, validates against xsd/carrier.xsd (a failure is a bug: Error(Internal)) and
// writes atomically.
void saveCarrier(const Carrier& carrier, const std::filesystem::path& path);
// saveCarrier's second half, for text toXml made: validates and writes atomically. Safe on
// another thread than the one that goes on changing the carrier (pipeline/runner.cpp saves
// after each step this way).
void saveCarrierXml(const std::string& xml, const std::filesystem::path& path);
// Reads and validates a carrier file; an invalid one gives Error(Input) with the schema's
// complaint and line number.
Carrier loadCarrier(const std::filesystem::path& path);

}  // namespace surrogate::carrier
