#include "cli/version_text.h"

#include <algorithm>

#include "core/error.h"
#include "core/json.h"
#include "core/resources.h"
#include "core/version.h"
#include "run/plan.h"

namespace surrogate::cli {

namespace {
// The data folder, or why there is none usable (a --version still answers on a broken install,
// and says what is broken).
std::string dataFolderText(bool& complete) {
  try {
    complete = true;
    return requireDataFiles().string();
  } catch (const Error& e) {
    complete = false;
    return e.message();
  }
}
}  // namespace

std::string versionText() {
  std::string out = std::string("surrogate ") + surrogateVersion() + "\n";
  bool complete = false;
  const std::string data = dataFolderText(complete);
  out += std::string(complete ? "data files: " : "data files: MISSING: ") + data + "\n";
  out += "libraries that decide results (every run records them in its carrier):\n";
  const auto libraries = run::softwareVersions();
  size_t nameWidth = 0, versionWidth = 0;
  for (const auto& s : libraries) {
    nameWidth = std::max(nameWidth, s.name.size());
    versionWidth = std::max(versionWidth, s.version.size());
  }
  for (const auto& s : libraries)
    out += "  " + s.name + std::string(nameWidth + 2 - s.name.size(), ' ') + s.version +
           std::string(versionWidth + 2 - s.version.size(), ' ') + s.role + "\n";
  return out;
}

std::string versionJson() {
  bool complete = false;
  const std::string data = dataFolderText(complete);
  JsonWriter j;
  j.beginObject().key("surrogate").value(surrogateVersion());
  j.key(complete ? "dataFolder" : "dataFolderProblem").value(data);
  j.key("libraries").beginArray();
  for (const auto& s : run::softwareVersions())
    j.beginObject().key("name").value(s.name).key("version").value(s.version).key("role").value(s.role).endObject();
  j.endArray().endObject();
  return j.str();
}

std::string withVersion(const std::string& objectJson) {
  const auto close = objectJson.rfind('}');
  if (close == std::string::npos) return objectJson;
  const auto last = objectJson.find_last_not_of(" \n\t", close == 0 ? 0 : close - 1);
  const bool empty = last == std::string::npos || objectJson[last] == '{';
  return objectJson.substr(0, close) + (empty ? "" : ",") + "\"version\":" + versionJson() +
         objectJson.substr(close);
}

}  // namespace surrogate::cli
