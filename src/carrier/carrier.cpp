#include "carrier/carrier.h"

#include <sys/utsname.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <thread>

#include "core/error.h"
#include "core/text.h"
#include "core/version.h"

namespace surrogate::carrier {

bool isEvidenceRole(const std::string& role) {
  return role == "original" || role == "export" || role == "sidecar" || role == "lp" || role == "prior";
}

std::string timestampNow() {
  const std::time_t t = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&t, &utc);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buffer;
}

Machine currentMachine() {
  Machine m;
  utsname u{};
  if (uname(&u) == 0) {
    m.hostname = u.nodename;
    m.os = std::string(u.sysname) + " " + u.release;
    m.architecture = u.machine;
  }
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) m.cpu = line.substr(colon + 2);
      break;
    }
  }
  m.cores = static_cast<int>(std::thread::hardware_concurrency());
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kb = 0;
  if (meminfo >> key >> kb && key == "MemTotal:") m.memoryBytes = kb * 1024;
  return m;
}

std::string Step::param(const std::string& name, const std::string& fallback) const {
  for (const Param& p : params)
    if (p.name == name) return p.value;
  return fallback;
}

bool Step::hasParam(const std::string& name) const {
  for (const Param& p : params)
    if (p.name == name) return true;
  return false;
}

void Step::setParam(const std::string& name, const std::string& value) {
  for (Param& p : params)
    if (p.name == name) {
      p.value = value;
      return;
    }
  params.push_back({name, value});
}

std::vector<const Intervention*> Step::interventionsOfKind(const std::string& kind) const {
  std::vector<const Intervention*> out;
  for (const Intervention& i : interventions)
    if (i.kind == kind) out.push_back(&i);
  return out;
}

DataItem& DataItem::set(const std::string& name, const std::string& rawValue) {
  const std::string value = escapedText(rawValue);  // text from files is data (core/text.h)
  for (auto& a : attributes)
    if (a.first == name) {
      a.second = value;
      return *this;
    }
  attributes.emplace_back(name, value);
  return *this;
}

DataItem& DataItem::set(const std::string& name, double value) {
  return set(name, formatNumber(value));
}

DataItem& DataItem::set(const std::string& name, int value) {
  return set(name, std::to_string(value));
}

std::optional<std::string> DataItem::get(const std::string& name) const {
  for (const auto& a : attributes)
    if (a.first == name) return a.second;
  return std::nullopt;
}

double DataItem::number(const std::string& name) const {
  const auto text = get(name);
  if (!text) throwInputError("carrier", "data", "<" + element + "> has no attribute " + name);
  try {
    std::size_t used = 0;
    const double v = std::stod(*text, &used);
    if (used == text->size()) return v;
  } catch (const std::exception&) {
  }
  throwInputError("carrier", "data",
                  "<" + element + "> attribute " + name + " is not a number: " + *text);
}

DataItem& Result::add(const std::string& element) {
  items.push_back(DataItem{element, {}});
  return items.back();
}

std::vector<const DataItem*> Result::itemsOf(const std::string& element) const {
  std::vector<const DataItem*> out;
  for (const DataItem& i : items)
    if (i.element == element) out.push_back(&i);
  return out;
}

const FileRecord* Carrier::findFile(const std::string& id) const {
  for (const FileRecord& f : files)
    if (f.id == id) return &f;
  return nullptr;
}

const FileRecord* Carrier::findFileByPath(const std::string& path) const {
  for (const FileRecord& f : files)
    if (f.path == path) return &f;
  return nullptr;
}

namespace {
// What a file says of itself reaches the record as text the XML can hold (core/text.h); the
// camera's fields are escaped where they are read, with their raw bytes (meta/metadata.h).
void escapeFileText(FileRecord& record) {
  for (std::string* text : {&record.format, &record.mediaType, &record.madeBy, &record.priorKind})
    *text = escapedText(*text);
  for (auto& [name, value] : record.camera) value = escapedText(value);
}
}  // namespace

std::string Carrier::putFile(FileRecord record) {
  escapeFileText(record);
  for (FileRecord& f : files) {
    if (f.path == record.path) {
      record.id = f.id;
      f = std::move(record);
      return f.id;
    }
  }
  // Ids are never reused, so a removed file's id cannot be confused with a new one.
  int next = 1;
  for (const FileRecord& f : files) {
    if (f.id.size() > 1 && f.id[0] == 'f') next = std::max(next, std::atoi(f.id.c_str() + 1) + 1);
  }
  record.id = "f" + std::to_string(next);
  files.push_back(std::move(record));
  return files.back().id;
}

void Carrier::putFiles(std::vector<FileRecord> records) {
  std::unordered_map<std::string, std::size_t> byPath;
  byPath.reserve(files.size() + records.size());
  int next = 1;
  for (std::size_t i = 0; i < files.size(); ++i) {
    byPath.emplace(files[i].path, i);
    const FileRecord& f = files[i];
    if (f.id.size() > 1 && f.id[0] == 'f') next = std::max(next, std::atoi(f.id.c_str() + 1) + 1);
  }
  files.reserve(files.size() + records.size());
  for (FileRecord& record : records) {
    escapeFileText(record);
    if (const auto it = byPath.find(record.path); it != byPath.end()) {
      record.id = files[it->second].id;
      files[it->second] = std::move(record);
      continue;
    }
    record.id = "f" + std::to_string(next++);
    byPath.emplace(record.path, files.size());
    files.push_back(std::move(record));
  }
}

std::unordered_map<std::string, const FileRecord*> Carrier::filesByPath() const {
  std::unordered_map<std::string, const FileRecord*> out;
  out.reserve(files.size());
  for (const FileRecord& f : files) out.emplace(f.path, &f);
  return out;
}

Step& Carrier::addStep(const std::string& component, const std::string& version) {
  Step s;
  s.id = "s" + std::to_string(process.size() + 1);
  s.component = component;
  s.version = version;
  process.push_back(std::move(s));
  return process.back();
}

Step* Carrier::findStep(const std::string& id) {
  for (Step& s : process)
    if (s.id == id) return &s;
  return nullptr;
}

const Step* Carrier::findStep(const std::string& id) const {
  for (const Step& s : process)
    if (s.id == id) return &s;
  return nullptr;
}

const Result* Carrier::findResult(const std::string& stepId) const {
  for (const Result& r : data)
    if (r.step == stepId) return &r;
  return nullptr;
}

const Result* Carrier::lastResultWith(const std::string& element) const {
  const Result* last = nullptr;
  for (const Result& r : data)
    if (!r.itemsOf(element).empty()) last = &r;
  return last;
}

void Carrier::clearResult(const std::string& stepId) {
  std::vector<Result> kept;
  for (Result& r : data)
    if (r.step != stepId) kept.push_back(std::move(r));
  data = std::move(kept);
}

void Carrier::addLog(const std::string& level, const std::string& step, const std::string& text,
                     const std::string& who) {
  log.push_back(LogEntry{timestampNow(), level, step, who, escapedText(text, true)});
}

const std::vector<Step>& standingProcess(const Carrier& carrier) {
  const std::vector<RunRecord>& runs = carrier.header.runs;
  if (!runs.empty() && runs.back().outcome == "failed" && !runs.back().planned.empty()) return runs.back().planned;
  return carrier.process;
}

Carrier newCarrier(const std::string& title, const std::vector<Creator>& creators) {
  Carrier c;
  c.header.title = title;
  c.header.creators = creators;
  c.header.created = c.header.modified = timestampNow();
  c.header.machine = currentMachine();
  c.header.software.push_back({"Surrogate", surrogateVersion(), "pipeline"});
  return c;
}

}  // namespace surrogate::carrier
