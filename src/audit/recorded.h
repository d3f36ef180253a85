// An audit as a carrier records it: the result of an Audit step (stages/audit_stage.h), written
// from an AuditReport and read back into one, so that `surrogate audit` and the report print
// what the carrier holds, and `verify --reexecute` compares every figure.
//
// The result is a sequence of sections, one per prior file, each opened by its input:
//   <input file="f31" kind="prior-lp"/>         then <imageValue image="f31" name="medianDegrees" .../>
//                                               and, per photograph, <imageValue image="f3"
//                                               name="lightAngle" .../> and name="priorLight"
//   <input file="f33" kind="prior-model"/>      then the model's figures (image="f33") and, per
//                                               photograph, name="psnr prior" ... rmse ...
//   <imageValue image="f33" name="verdict" .../> and name="finding different-lights" ...
// Figures of a prior file are keyed by its file id (re-execution matches them by the file's
// path); per-photograph figures belong to the section they are in. docs/carrier.md, "Audit",
// lists every name.
#pragma once

#include <map>
#include <string>

#include "audit/audit.h"
#include "carrier/carrier.h"

namespace surrogate::audit {

// The carrier's component name of the Audit step (stages::AuditStage::kComponent).
inline constexpr const char* kAuditComponent = "Audit";

struct RecordedIds {
  std::map<std::string, std::string> priorFiles;   // path as in the AuditReport -> carrier file id
  std::map<std::string, std::string> photographs;  // photograph's file name -> carrier file id
};

// Appends the audit's figures to `result`; numbers through formatNumber (core/text.h).
// Error(Internal) when a file of the report has no id.
void recordAudit(const AuditReport& report, const RecordedIds& ids, carrier::Result& result);

// The audit `result` records, paths as the carrier has them (capture-relative). Error(Input)
// naming the figure when a number cannot be read.
AuditReport recordedAudit(const carrier::Carrier& carrier, const carrier::Result& result);

// The result of the carrier's last Audit step that completed, or null.
const carrier::Result* auditResult(const carrier::Carrier& carrier);

}  // namespace surrogate::audit
