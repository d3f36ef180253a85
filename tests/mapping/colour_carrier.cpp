// See colour_carrier.h. The carrier text is patched (as test_mapping.cpp's history sample is)
// and written back, so that the payload digests are those of the patched carrier.
#include "colour_carrier.h"

#include <catch2/catch.hpp>

#include <fstream>
#include <regex>

#include "carrier/carrier.h"
#include "sample_capture.h"
#include "sample_facts.h"
#include "test_files.h"

namespace fs = std::filesystem;

namespace colourcarrier {
namespace {

std::string fileIdOf(const std::string& xml, const std::string& path) {
  std::smatch m;
  REQUIRE(std::regex_search(xml, m, std::regex("<file id=\"([^\"]+)\" path=\"" + path + "\"")));
  return m[1];
}

void insertBefore(std::string& xml, std::size_t at, const std::string& text) {
  REQUIRE(at != std::string::npos);
  xml.insert(at, text);
}

std::string correctedItems(const std::string& chart) {
  return "      <input file=\"" + chart + "\" kind=\"chart\"/>\n"
         "      <value name=\"method\" value=\"found\"/>\n"
         "      <value name=\"corners\" value=\"12,20,30,20,30,28,12,28\" "
         "unit=\"pixels x,y: dark skin, bluish green, black, white\"/>\n"
         "      <value name=\"patchSide\" value=\"3.1\" unit=\"pixels\"/>\n"
         "      <value name=\"framesMeasured\" value=\"2\"/>\n"
         "      <chartPatch index=\"0\" name=\"dark skin\" reference=\"37.54 14.37 14.92\" measured=\"0.1 0.08 0.06\" "
         "frames=\"2\" before=\"35.10 18.20 19.05\" corrected=\"37.20 15.01 14.40\" deltaE2000Before=\"6.1\" "
         "deltaE2000=\"0.9\" deltaE2000HeldOut=\"1.2\"/>\n"
         "      <chartPatch index=\"1\" name=\"light skin\" reference=\"64.66 19.27 17.50\" frames=\"0\"/>\n"
         "      <value name=\"reference\" value=\"colorchecker-classic-2014\"/>\n"
         "      <value name=\"referenceTitle\" value=\"ColorChecker Classic (charts made after November 2014)\"/>\n"
         "      <value name=\"referenceSource\" value=\"X-Rite, New color specifications for ColorChecker SG and "
         "Classic Charts (2016): CIELAB D50 for charts made after November 2014\"/>\n"
         "      <value name=\"model\" value=\"matrix\"/>\n"
         "      <value name=\"coefficients\" value=\"1.08 -0.05 -0.03 -0.04 1.1 -0.06 0.01 -0.09 1.08\" "
         "unit=\"rows R, G, B over the model's terms, linear light\"/>\n"
         "      <value name=\"whitePointPatches\" value=\"5\"/>\n"
         "      <value name=\"deltaE2000MeanBefore\" value=\"6.3\"/>\n"
         "      <value name=\"deltaE2000MaxBefore\" value=\"10.1\"/>\n"
         "      <value name=\"deltaE2000Mean\" value=\"1.2\"/>\n"
         "      <value name=\"deltaE2000Max\" value=\"3.1\"/>\n"
         "      <value name=\"deltaE2000MeanHeldOut\" value=\"1.4\"/>\n"
         "      <value name=\"deltaE2000MaxHeldOut\" value=\"3.5\"/>\n"
         "      <value name=\"qualityLevel\" value=\"FADGI 2023: 4 star\"/>\n"
         "      <value name=\"qualityLevel\" value=\"Metamorfoze 2019: Light\"/>\n"
         "      <value name=\"outcome\" value=\"corrected\"/>\n";
}

}  // namespace

Sample sample(const std::string& name, Outcome outcome) {
  Sample s;
  s.capture = samplecapture::make(testfiles::freshDir(name));
  std::string xml = testfiles::slurp(s.capture / "assembly-files/carrier.xml");
  s.chartFileId = fileIdOf(xml, "jpeg-exports/IMG_0001.jpg");
  std::smatch first;
  REQUIRE(std::regex_search(xml, first, std::regex("<file id=\"[^\"]+\" path=\"[^\"]*\"[^>]* sha256=\"([0-9a-f]{64})\"")));
  s.firstSha256 = first[1];

  // The libraries the header lists (the sample lists Surrogate only): the colour step links
  // OpenCV and Eigen, not OpenSSL (it writes no file).
  const std::size_t surrogate = xml.find("<software name=\"Surrogate\"");
  insertBefore(xml, xml.find("/>", surrogate) + 2,
               "\n    <software name=\"OpenCV\" version=\"4.6.0\" role=\"image processing\"/>"
               "\n    <software name=\"Eigen\" version=\"3.4.0\" role=\"linear algebra\"/>"
               "\n    <software name=\"OpenSSL\" version=\"OpenSSL 3.0.13 30 Jan 2024\" role=\"digests\"/>");

  // The step, before the fit (the plan's Colour slot comes after the lights, before the fit).
  const std::size_t fitStep = xml.rfind("<step ", xml.find("component=\"RtiFit\""));
  insertBefore(xml, fitStep,
               "<step id=\"s9\" component=\"ColourCorrection\" version=\"1\">\n"
               "      <param name=\"chart\" value=\"auto\"/>\n      <param name=\"corners\" value=\"\"/>\n"
               "      <param name=\"reference\" value=\"colorchecker-classic-2014\"/>\n"
               "      <param name=\"model\" value=\"matrix\"/>\n    </step>\n    ");
  std::string items = "      <value name=\"chart\" value=\"auto\"/>\n";
  if (outcome == Outcome::Corrected) {
    items += correctedItems(s.chartFileId);
  } else {
    items += "      <value name=\"outcome\" value=\"no ColorChecker found in jpeg-exports/IMG_0001.jpg: "
             "the images keep their colours\"/>\n"
             "      <input file=\"" + s.chartFileId + "\" kind=\"chart-search\"/>\n";
  }
  insertBefore(xml, xml.find("  </data>"),
               "    <result step=\"s9\" status=\"completed\" started=\"2026-01-02T10:00:01Z\" "
               "ended=\"2026-01-02T10:00:01Z\" seconds=\"0.4\">\n" + items + "    </result>\n");
  insertBefore(xml, xml.find("  </log>"),
               "    <entry time=\"2026-01-02T10:00:01Z\" level=\"info\" step=\"s9\">colour corrected</entry>\n");
  // The fixture is a carrier the schema accepts, as the stage writes it.
  REQUIRE_NOTHROW(surrogate::carrier::parseCarrier(xml, "colour sample carrier"));
  std::ofstream(s.capture / "assembly-files/carrier.xml", std::ios::binary) << xml;

  s.carrierXml = xml;
  s.facts = samplefacts::of(s.capture, xml);
  return s;
}

}  // namespace colourcarrier
