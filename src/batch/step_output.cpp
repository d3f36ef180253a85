#include "batch/step_output.h"

namespace surrogate::batch {

nlohmann::json jsonReport(const std::string& out) {
  std::size_t end = out.size();
  while (end > 0) {
    std::size_t begin = out.rfind('\n', end - 1);
    begin = begin == std::string::npos ? 0 : begin + 1;
    const std::string line = out.substr(begin, end - begin);
    if (!line.empty() && line[0] == '{') {
      nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
      if (j.is_object()) return j;
    }
    if (begin == 0) break;
    end = begin - 1;
  }
  return nullptr;
}

std::string textOf(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : "";
}

std::string lastErrorLine(const std::string& err) {
  std::string text = err;
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  const std::size_t nl = text.rfind('\n');
  std::string line = nl == std::string::npos ? text : text.substr(nl + 1);
  if (line.rfind("surrogate ", 0) == 0)
    if (const std::size_t colon = line.find(": "); colon != std::string::npos) line = line.substr(colon + 2);
  return line;
}

std::string failedChecks(const nlohmann::json& report) {
  std::string out;
  if (!report.contains("checks") || !report["checks"].is_array()) return out;
  for (const nlohmann::json& c : report["checks"]) {
    if (!c.is_object() || !c.contains("passed") || !c["passed"].is_boolean() || c["passed"].get<bool>()) continue;
    std::string one = textOf(c, "name");
    const std::string what = textOf(c, "what");
    if (!what.empty()) one += ": " + what;
    if (c.contains("where") && c["where"].is_array() && !c["where"].empty()) {
      std::string where;
      for (const nlohmann::json& w : c["where"])
        if (w.is_string()) where += (where.empty() ? "" : ", ") + w.get<std::string>();
      one += " (" + where + ")";
    }
    out += (out.empty() ? "" : "; ") + one;
  }
  return out;
}

}  // namespace surrogate::batch
