// bag-info.txt and the values in it: the time of every entry (SOURCE_DATE_EPOCH, else a fixed
// instant), the Bagging-Date, Bag-Size in decimal units, and which labels a caller may give.
// The descriptive text of a bag, the same whatever its output (bag_output.cpp); the command line
// checks --meta keys with bagInfoLabelProblem before any work, and package.cpp dates a package
// with the same clock.
#include "archive/bag_info.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <optional>
#include <set>

#include "core/error.h"
#include "core/text.h"

namespace surrogate::archive {

namespace {
std::optional<std::int64_t> parseSourceDateEpoch() {
  const char* env = std::getenv("SOURCE_DATE_EPOCH");
  if (!env || !*env) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(env, &end, 10);
  if (errno != 0 || *end != '\0' || value < 0) return std::nullopt;
  return static_cast<std::int64_t>(value);
}
}  // namespace

std::int64_t sourceDateEpoch() { return parseSourceDateEpoch().value_or(kDefaultEpoch); }
bool sourceDateEpochSet() { return parseSourceDateEpoch().has_value(); }
std::int64_t packagingEpoch() {
  if (auto e = parseSourceDateEpoch()) return *e;
  return static_cast<std::int64_t>(std::time(nullptr));
}

std::string humanSize(std::uint64_t bytes) {
  if (bytes < 1000) return std::to_string(bytes) + " bytes";
  static const char* units[] = {"KB", "MB", "GB", "TB", "PB", "EB"};
  double value = static_cast<double>(bytes);
  int unit = -1;
  while (value >= 1000 && unit < 5) {
    value /= 1000;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.1f %s", value, units[unit]);
  return text;
}

namespace {
std::tm utc(std::int64_t epoch) {
  const std::time_t t = static_cast<std::time_t>(epoch);
  std::tm tm{};
  gmtime_r(&t, &tm);
  return tm;
}
}  // namespace

std::string utcDate(std::int64_t epoch) {
  const std::tm tm = utc(epoch);
  char text[16];
  std::strftime(text, sizeof text, "%Y-%m-%d", &tm);
  return text;
}

std::string utcDateTime(std::int64_t epoch) {
  const std::tm tm = utc(epoch);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

namespace {
std::string labelFormProblem(const std::string& label) {
  const bool bad = label.empty() || std::any_of(label.begin(), label.end(), [](unsigned char c) {
                     return c == ':' || c <= ' ' || c == 0x7f;
                   });
  if (bad)
    return "is not a usable bag-info.txt label (no spaces, colons or control characters); "
           "rename the metadata key, e.g. Source-Organization";
  return "";
}
}  // namespace

std::string bagInfoLabelProblem(const std::string& label) {
  static const std::set<std::string> computed = {"payload-oxum", "bagging-date", "bag-size",
                                                  "bag-software-agent"};
  static const std::set<std::string> own = {"surrogate-package-identifier", "surrogate-capture-identifier",
                                             "surrogate-previous-package-identifier", "surrogate-base-uri",
                                             "surrogate-packaging-time"};
  if (computed.count(lowerCase(label)))
    return "is computed by Surrogate for bag-info.txt and cannot be given as metadata; "
           "remove it from the capture's metadata (--meta)";
  if (own.count(lowerCase(label)))
    return "is written by `surrogate pack` itself (the package's and the capture's identifiers, "
           "the package it revises, the base of crm.rdf's URIs and the packaging time) and cannot "
           "be given as metadata; remove it from the capture's metadata (--meta)";
  return labelFormProblem(label);
}

namespace {

void checkLabel(const std::string& label) {
  const std::string problem = bagInfoLabelProblem(label);
  if (!problem.empty()) throw Error(ErrorKind::Usage, label, "packing", problem);
}

// "Label: value", with line breaks in the value folded into continuation lines.
std::string infoLine(const std::string& label, const std::string& value) {
  std::string line = label + ": ";
  for (std::size_t i = 0; i < value.size(); ++i) {
    const char c = value[i];
    if (c == '\r' && i + 1 < value.size() && value[i + 1] == '\n') continue;
    if (c == '\n' || c == '\r') line += "\n  ";
    else line.push_back(c);
  }
  return line + "\n";
}

}  // namespace

// bag-info.txt: the computed labels, then the caller's, then the caller's own, then the
// holder's (checked).
std::string bagInfoText(const BagInput& input, std::uint64_t total, std::size_t files) {
  const std::string baggingDate =
      input.baggingDate.empty() ? utcDate(packagingEpoch()) : input.baggingDate;
  std::string info;
  info += infoLine("Bag-Software-Agent", input.softwareAgent);
  info += infoLine("Bagging-Date", baggingDate);
  info += infoLine("Bag-Size", humanSize(total));
  info += infoLine("Payload-Oxum", std::to_string(total) + "." + std::to_string(files));
  for (const auto& [label, value] : input.info) {
    checkLabel(label);
    info += infoLine(label, value);
  }
  for (const auto& [label, value] : input.ownInfo) {
    if (const std::string problem = labelFormProblem(label); !problem.empty())
      throw Error(ErrorKind::Internal, label, "packing", problem);
    info += infoLine(label, value);
  }
  for (const auto& [label, value] : input.holderInfo) {
    checkLabel(label);
    if (value.find_first_of("\r\n") != std::string::npos)
      throw Error(ErrorKind::Usage, label, "packing",
                  "the value holds a line break; a holder's bag-info.txt value is one line");
    info += infoLine(label, value);
  }
  return info;
}

}  // namespace surrogate::archive
