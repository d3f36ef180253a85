// Colour from a chart in the package metadata (issue 54): a ColourCorrection step that corrected
// is a PREMIS "modification" event whose details give the chart's edition, the model and its
// coefficients and whose outcome gives the CIEDE2000 figures and quality levels; in CIDOC-CRM a
// measurement (E16) of the chart image with the figures as dimensions (E54); in the RO-Crate
// the figures are PropertyValues in the execution's result. A step that found no chart is still
// an event (a search happened) that says why the colours were kept.
// The carrier is the sample capture with the step patched in as the stage records it
// (docs/carrier.md, "ColourCorrection"); the figures are the carrier's strings.
#include <catch2/catch.hpp>

#include <regex>

#include "mapping/mapping.h"
#include "archival_checks.h"
#include "colour_carrier.h"

using namespace surrogate;
using colourcarrier::Sample;

namespace {
bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

const archival::Premis::Event* eventOf(const archival::Premis& p, const std::string& id) {
  for (const auto& e : p.events)
    if (e.id == id) return &e;
  return nullptr;
}

bool hasTriple(const std::vector<archival::Triple>& triples, const std::string& s, const std::string& p,
               const std::string& o) {
  for (const auto& t : triples)
    if ((s.empty() || t.s == s) && t.p == p && (o.empty() || t.o == o)) return true;
  return false;
}

const std::string kCrm = "http://www.cidoc-crm.org/cidoc-crm/";
}  // namespace

TEST_CASE("a colour correction is a PREMIS modification event with the chart, model, figures and levels",
          "[mapping][mets][colour]") {
  const Sample s = colourcarrier::sample("colour-mets", colourcarrier::Outcome::Corrected);
  const std::string mets = mapping::deriveMets(s.carrierXml, s.facts);
  CHECK_NOTHROW(mapping::validateMets(mets, "mets.xml"));

  const archival::Premis p = archival::readPremis(mets);
  for (const std::string& problem : archival::linkProblems(p)) FAIL_CHECK(problem);
  const auto* e = eventOf(p, "event-s9");
  REQUIRE(e);
  // LoC PREMIS eventType "modification": the step changed the images' colours as the fit reads them.
  CHECK(e->type == "modification");
  CHECK(e->typeUri == "http://id.loc.gov/vocabulary/preservation/eventType/mod");
  CHECK(e->outcome == "success");

  // The details: edition (referenceTitle), where the chart was, model, coefficients, figures, levels.
  CHECK(contains(mets, "Colour corrected to a ColorChecker Classic (charts made after November 2014) "
                       "(reference values colorchecker-classic-2014: X-Rite, New color specifications"));
  CHECK(contains(mets, ", chart found in data/jpeg-exports/IMG_0001.jpg; model matrix, coefficients "
                       "1.08 -0.05 -0.03 -0.04 1.1 -0.06 0.01 -0.09 1.08 (rows R, G, B over the model"));
  CHECK(contains(mets, "; CIEDE2000 to the reference (1 of 2 patches measured): mean 6.3, max 10.1 before correction, "
                       "mean 1.2, max 3.1 after, mean 1.4, max 3.5 held out"));
  CHECK(contains(mets, "quality levels: FADGI 2023: 4 star; Metamorfoze 2019: Light"));
  // The outcome in one line, first of the event's outcome notes.
  CHECK(contains(mets, "<premis:eventOutcomeDetailNote>CIEDE2000 mean 1.2, max 3.1 after correction "
                       "(mean 6.3, max 10.1 before; mean 1.4, max 3.5 held out); FADGI 2023: 4 star; "
                       "Metamorfoze 2019: Light</premis:eventOutcomeDetailNote>"));

  // Its source: the image the chart was found in; its libraries OpenCV and Eigen.
  bool chartSource = false;
  for (const auto& o : e->objects)
    if (o.value == "data/jpeg-exports/IMG_0001.jpg" && o.role == "source") chartSource = true;
  CHECK(chartSource);
  std::set<std::string> libraries;
  for (const auto& a : e->agents)
    if (a.role == "software library") libraries.insert(a.value.substr(0, a.value.find(' ')));
  CHECK(libraries == std::set<std::string>{"Eigen", "OpenCV"});
}

TEST_CASE("a chart search that kept the colours is an event that says why", "[mapping][mets][colour]") {
  const Sample s = colourcarrier::sample("colour-none", colourcarrier::Outcome::NoChart);
  const std::string mets = mapping::deriveMets(s.carrierXml, s.facts);
  CHECK_NOTHROW(mapping::validateMets(mets, "mets.xml"));
  const archival::Premis p = archival::readPremis(mets);
  const auto* e = eventOf(p, "event-s9");
  REQUIRE(e);
  CHECK(e->type == "metadata extraction");
  CHECK(contains(mets, "<premis:eventOutcomeDetailNote>colours not corrected: no ColorChecker found in "
                       "jpeg-exports/IMG_0001.jpg: the images keep their colours</premis:eventOutcomeDetailNote>"));
  CHECK_FALSE(contains(mets, "Colour corrected to"));
  bool searched = false;
  for (const auto& o : e->objects)
    if (o.value == "data/jpeg-exports/IMG_0001.jpg" && o.role == "source") searched = true;
  CHECK(searched);
}

TEST_CASE("a colour correction in CIDOC-CRM: a measurement of the chart image with CIEDE2000 dimensions",
          "[mapping][crm][colour]") {
  const Sample s = colourcarrier::sample("colour-crm", colourcarrier::Outcome::Corrected);
  const std::string crm = mapping::deriveCrm(s.carrierXml, mapping::crmFactsOf(s.facts));
  const auto triples = archival::rdfTriples(crm, s.capture.parent_path().string());
  REQUIRE(triples.size() > 100);
  for (const std::string& problem :
       archival::crmTermProblems(triples, std::string(SURROGATE_SOURCE_DIR) + "/tests/mapping/data/crm-terms.tsv"))
    FAIL_CHECK(problem);

  const std::string base = "urn:surrogate:capture:" + s.firstSha256 + "/";
  const std::string step = base + "step/s9";
  const std::string measurement = step + "/colour-accuracy";
  CHECK(hasTriple(triples, step, kCrm + "P9_consists_of", measurement));
  CHECK(hasTriple(triples, measurement, "http://www.w3.org/1999/02/22-rdf-syntax-ns#type", kCrm + "E16_Measurement"));
  CHECK(hasTriple(triples, measurement, kCrm + "P39_measured", base + "file/" + s.chartFileId));
  // The chart's edition: the step used an object of that type.
  CHECK(hasTriple(triples, step, kCrm + "P125_used_object_of_type", base + "type/colour-chart/colorchecker-classic-2014"));
  CHECK(hasTriple(triples, base + "type/colour-chart/colorchecker-classic-2014", "http://www.w3.org/2000/01/rdf-schema#label",
                  "\"ColorChecker Classic (charts made after November 2014)\""));
  CHECK(hasTriple(triples, step, kCrm + "P33_used_specific_technique", base + "technique/colour-model/matrix"));
  // Six figures, each an E54 with its value and the CIEDE2000 unit.
  const std::map<std::string, std::string> figures = {
      {"deltaE2000MeanBefore", "6.3"}, {"deltaE2000MaxBefore", "10.1"}, {"deltaE2000Mean", "1.2"},
      {"deltaE2000Max", "3.1"},        {"deltaE2000MeanHeldOut", "1.4"}, {"deltaE2000MaxHeldOut", "3.5"}};
  for (const auto& [name, value] : figures) {
    INFO(name);
    const std::string dim = measurement + "/" + name;
    CHECK(hasTriple(triples, measurement, kCrm + "P40_observed_dimension", dim));
    CHECK(hasTriple(triples, dim, kCrm + "P90_has_value", "\"" + value + "\"^^<http://www.w3.org/2001/XMLSchema#decimal>"));
    CHECK(hasTriple(triples, dim, kCrm + "P91_has_unit", base + "unit/CIEDE2000"));
  }
  CHECK(hasTriple(triples, measurement, kCrm + "P3_has_note", "\"quality level: FADGI 2023: 4 star\""));

  // Without a chart: no measurement, the reason in the step's notes.
  const Sample none = colourcarrier::sample("colour-crm-none", colourcarrier::Outcome::NoChart);
  const auto noneTriples = archival::rdfTriples(mapping::deriveCrm(none.carrierXml, mapping::crmFactsOf(none.facts)), none.capture.parent_path().string());
  CHECK_FALSE(hasTriple(noneTriples, "", kCrm + "P40_observed_dimension", ""));
  CHECK(hasTriple(noneTriples, "", kCrm + "P3_has_note",
                  "\"result outcome = no ColorChecker found in jpeg-exports/IMG_0001.jpg: the images keep their colours\""));
}

TEST_CASE("a colour correction in the RO-Crate: the figures are PropertyValues of the execution's result",
          "[mapping][ro-crate][colour]") {
  const Sample s = colourcarrier::sample("colour-crate", colourcarrier::Outcome::Corrected);
  const std::string crate =
      mapping::deriveRoCrate(s.carrierXml, mapping::CrateFacts{s.facts.packageId, s.facts.packagingTime, true});
  CHECK(contains(crate, "\"@id\": \"#execution-s9-figure-1\""));
  CHECK(std::regex_search(crate, std::regex("\"name\": \"deltaE2000Mean\",\\s*\"value\": \"1.2\",\\s*\"unitText\": \"CIEDE2000\"")));
  CHECK(std::regex_search(crate, std::regex("\"name\": \"qualityLevel\",\\s*\"value\": \"FADGI 2023: 4 star\"")));
  CHECK(std::regex_search(crate, std::regex("\"name\": \"referenceTitle\",\\s*\"value\": \"ColorChecker Classic \\(charts made after November 2014\\)\"")));
}
