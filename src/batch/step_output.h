// What a job's step printed, read back for the ledger: the command's --json report (the last
// line of its standard output that is a JSON object), its last line of standard error, and a
// verification's failed checks in a sentence.
//
//   const nlohmann::json report = jsonReport(child.out);
//   e.message = textOf(report, "packageId");
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace surrogate::batch {

// The last line of a command's output that is a JSON object (its --json report), parsed; null
// when there is none.
nlohmann::json jsonReport(const std::string& out);

// j[key] when it is a string, else "".
std::string textOf(const nlohmann::json& j, const char* key);

// The last non-empty line of a command's standard error, without "surrogate COMMAND: ".
std::string lastErrorLine(const std::string& err);

// verify --json's failed checks as "check: what (where, where, ...)", the files named.
std::string failedChecks(const nlohmann::json& report);

}  // namespace surrogate::batch
