// The report's text sections, straight from the carrier: summary, provenance timeline, camera
// and lens, verification, files. Each returns a <section> with every carrier string escaped.
#pragma once

#include <functional>
#include <optional>
#include <map>
#include <string>
#include <vector>

#include "carrier/carrier.h"
#include "report/hemisphere.h"
#include "report/report.h"

namespace surrogate::report {

// The first section: object (title, creators, rights), capture (images, camera, lens, dates),
// the verdict of `checks` when given, and key figures (spheres, light spread, coverage, each
// fit's PSNR, interventions, log).
std::string summarySection(const carrier::Carrier& c, const std::vector<LightPoint>& lights,
                           const Coverage& coverage,
                           const std::optional<std::vector<VerificationCheck>>& checks);
// A step as people name it: "Fit: PTM (LRGB)", "Web copy of HSH order 2", "Sphere
// detection"; its component otherwise. Steps of one component made per model (RtiFit,
// WebCopy, DerivedMaps) are told apart by their model.
std::string stepTitle(const carrier::Step& step);
// EXIF's date and time a photograph was taken ("2026:01:01 12:00:00") as ISO 8601
// ("2026-01-01T12:00:00", meta::dateTimeText: the form of the page's other times, without a
// zone since the carrier records none); other text as it is.
std::string takenText(const std::string& exifDateTime);
// A fitted model as people name it: "ptm-lrgb" -> "PTM (LRGB)", "hsh2" -> "HSH order 2".
std::string modelTitle(const std::string& basis);
// A step result's values that are numbers, by name (a value that is not a number is left out).
std::map<std::string, double> numericValues(const carrier::Result& result);
// The learned fits' figures (learned_fits.cpp), "" when the carrier has none.
std::string learnedFitsTable(const carrier::Carrier& c);
// Every fit's PSNR and SSIM at the photographs `--holdout` left out, when a PTM or HSH fit has
// them (held_out_table.cpp); "" otherwise.
std::string heldOutTable(const carrier::Carrier& c);

// Software and machine, then one timeline entry per step: component, version, algorithm,
// status, start, duration, parameters, interventions (who, when, why) and the step's log.
std::string provenanceSection(const carrier::Carrier& c);
// Camera bodies, lenses and exposure settings of the originals, with how many files share each.
std::string cameraSection(const carrier::Carrier& c);
// One row per check, or a sentence saying no verification was run for this report.
std::string verificationSection(const std::optional<std::vector<VerificationCheck>>& checks);
// Every file with its role, size and SHA-256 (folded), for an auditor comparing copies.
std::string filesSection(const carrier::Carrier& c);

// The checks on the lights (the `check` items, hrti/light_checks.h): a table of each check's
// status and figures; empty when the carrier records none (lights from an .lp file, or a
// carrier older than LightDirections version 4).
std::string lightChecksTable(const carrier::Carrier& c);

// "Audit of prior work", when the carrier has an Audit result (audit/recorded.h): the verdicts,
// the lights above the threshold, the PSNR table, each prior model's error per photograph on
// the hemisphere (errorHemisphereSvg) and its difference images (read from `source`, embedded
// at their own size up to 4000 pixels, each counted in `picturesEmbedded`); empty otherwise.
std::string auditSection(const carrier::Carrier& c, const ReportSource& source, int* picturesEmbedded);
// The audit's verdict in parts, first of the report (empty without an Audit result).
std::string auditSummarySection(const carrier::Carrier& c);
// The prior lights the Audit result records, for the hemisphere plot; empty without one.
std::vector<PriorLightPoint> priorLightPoints(const carrier::Carrier& c);

}  // namespace surrogate::report
