// The audit as a carrier result (audit/recorded.h): every figure written is read back the same,
// so `surrogate audit` and the report print from the carrier exactly what the Audit step found.
#include <catch2/catch.hpp>

#include "audit/audit.h"
#include "audit/recorded.h"
#include "core/error.h"

using namespace surrogate;

namespace {

carrier::FileRecord file(const std::string& id, const std::string& path, const std::string& role) {
  carrier::FileRecord f;
  f.id = id;
  f.path = path;
  f.role = role;
  return f;
}

// A report with every kind of figure, two light files and a model, numbers that need all their
// digits.
audit::AuditReport sampleReport() {
  audit::AuditReport r;
  r.thresholdDegrees = 2.5;
  audit::LightComparison l;
  l.file = "assembly-files/stela.lp";
  l.thresholdDegrees = 2.5;
  l.angles = {{"IMG_0001.jpg", 0.30000000000000004, {0.1, 0.2, 0.9746794344808963}},
              {"IMG_0002.jpg", 6.125, {-0.5, 0.25, 0.82915619758885}}};
  // Surrogate's uncertainty on both lights, the prior's on one (Audit version 7).
  l.angles[0].ours = 1.25;
  l.angles[1].ours = 2.5;
  l.angles[1].priors = 0.75;
  l.aboveThreshold = {l.angles[1]};
  l.medianDegrees = 3.2125, l.p95Degrees = 5.83, l.maxDegrees = 6.125;
  l.onlyInPrior = {"jpeg-exports\\IMG_0099.JPG"};
  l.onlyInSurrogate = {"IMG_0003.jpg"};
  r.lights.push_back(l);
  audit::LightComparison other = l;
  other.file = "finished-files/old.lp";
  other.aboveThreshold.clear();
  other.onlyInPrior.clear();
  r.lights.push_back(other);

  audit::ModelCheck m;
  m.file = "finished-files/stela.ptm";
  m.lightFile = "assembly-files/stela.lp";
  m.basis = "ptm-lrgb";
  m.values = "sRGB-encoded";
  m.size = {audit::SizeRelation::Kind::UniformScale, 200, 150, 400, 300, 2};
  m.prior = {true, "", {{"IMG_0001.jpg", 10.5, 27.7, audit::Light{0.1, 0.2, 0.9746794344808963}},
                        {"IMG_0002.jpg", 12.25, 26.37, audit::Light{-0.5, 0.25, 0.82915619758885}}},
             11.4, 27.01, 27.03, 26.37, "IMG_0002.jpg"};
  m.refitPriorLights = {true, "", {{"IMG_0001.jpg", 9, 29.04, std::nullopt}, {"IMG_0002.jpg", 9.5, 28.58, std::nullopt}}, 9.25, 28.8, 28.81, 28.58, "IMG_0002.jpg"};
  m.refitSurrogateLights.note = "Surrogate has no lights of its own (a dome capture)";
  m.colour = {true, 1.058, 0.979, 12.5, 11.25, false};
  m.quantisation.clamped = true;
  m.quantisation.planes = {{"a0", 0, 0, 0, false}, {"a5", 0.001, 0.934, 0.925, true}};
  m.differences = {{"assembly-files/audit/stela-difference.png", "IMG_0002.jpg",
                    audit::Light{-0.5, 0.25, 0.82915619758885}, 25, true,
                    "prior model minus the photograph IMG_0002.jpg at its prior light (-0.500, 0.250, 0.829)"},
                   {"assembly-files/audit/stela-difference-IMG_0001.png", "IMG_0001.jpg",
                    audit::Light{0.1, 0.2, 0.9746794344808963}, 4, false,
                    "prior model minus the photograph IMG_0001.jpg at its prior light (0.100, 0.200, 0.975)"}};
  r.models.push_back(m);

  audit::Verdict v;
  v.model = m.file;
  v.lightFile = m.lightFile;
  v.dbBelowRefit = 1.79;
  v.maxDegrees = 6.125;
  v.findings = {{audit::Finding::Cause::DifferentLights, "1 of 2 prior lights differ"},
                {audit::Finding::Cause::BrokenBias, "the file's scale and bias clip coefficients: a5"}};
  v.sentence = "not reproduced: 1 of 2 prior lights differ";
  r.verdicts.push_back(v);
  audit::Verdict lightsOnly;
  lightsOnly.lightFile = other.file;
  lightsOnly.reproduced = true;
  lightsOnly.sentence = "reproduced within 0.3 degrees";
  r.verdicts.push_back(lightsOnly);
  r.notAudited = {{"finished-files/broken.rti", "the file ends before its header does"}};
  return r;
}

}  // namespace

TEST_CASE("an audit recorded in a carrier result reads back with every figure the same") {
  carrier::Carrier c;
  c.files = {file("f1", "jpeg-exports/IMG_0001.jpg", "original"), file("f2", "jpeg-exports/IMG_0002.jpg", "original"),
             file("f3", "jpeg-exports/IMG_0003.jpg", "original"), file("f4", "assembly-files/stela.lp", "prior"),
             file("f5", "finished-files/old.lp", "prior"), file("f6", "finished-files/stela.ptm", "prior"),
             file("f7", "finished-files/broken.rti", "prior")};
  audit::RecordedIds ids;
  for (const auto& f : c.files) {
    if (f.role == "prior") ids.priorFiles[f.path] = f.id;
    else ids.photographs[f.path.substr(f.path.rfind('/') + 1)] = f.id;
  }
  carrier::Result result;
  result.step = "s9";
  const audit::AuditReport report = sampleReport();
  audit::recordAudit(report, ids, result);
  const audit::AuditReport back = audit::recordedAudit(c, result);
  CHECK(audit::auditJson(back) == audit::auditJson(report));
  CHECK(audit::auditLines(back) == audit::auditLines(report));
  // Exact doubles, beyond what the JSON's rounding shows.
  CHECK(back.lights.at(0).angles.at(0).degrees == 0.30000000000000004);
  CHECK(back.lights.at(0).angles.at(1).prior[2] == 0.82915619758885);
  CHECK(back.lights.at(0).angles.at(0).ours == 1.25);
  CHECK_FALSE(back.lights.at(0).angles.at(0).priors.has_value());
  CHECK(back.lights.at(0).aboveThreshold.at(0).ours == 2.5);
  CHECK(back.lights.at(0).aboveThreshold.at(0).priors == 0.75);
  CHECK(back.models.at(0).prior.images.at(1).rmse == 12.25);
  CHECK(back.models.at(0).colour.rmseAfter == 11.25);
  CHECK(back.models.at(0).size.kind == audit::SizeRelation::Kind::UniformScale);
  // Each photograph's prior light, and each difference picture's photograph, light and scale.
  CHECK(back.models.at(0).prior.images.at(1).light == audit::Light{-0.5, 0.25, 0.82915619758885});
  CHECK_FALSE(back.models.at(0).refitPriorLights.images.at(0).light.has_value());
  REQUIRE(back.models.at(0).differences.size() == 2);
  const audit::DifferenceImage& named = back.models.at(0).differences.at(1);
  CHECK(named.file == "assembly-files/audit/stela-difference-IMG_0001.png");
  CHECK(named.image == "IMG_0001.jpg");
  CHECK(named.light == audit::Light{0.1, 0.2, 0.9746794344808963});
  CHECK(named.fullScale == 4);
  CHECK_FALSE(named.worst);
  CHECK(back.models.at(0).differences.at(0).worst);
}

TEST_CASE("an audit recorded before Audit version 5 reads back with its one difference image") {
  carrier::Carrier c;
  c.files = {file("f1", "jpeg-exports/IMG_0001.jpg", "original"), file("f6", "finished-files/stela.ptm", "prior")};
  carrier::Result result;
  result.add("input").set("file", "f1").set("kind", "image");
  result.add("input").set("file", "f6").set("kind", "prior-model");
  result.add("imageValue").set("image", "f6").set("name", "prior psnr").set("value", "30.5");
  result.add("imageValue").set("image", "f1").set("name", "prior psnr").set("value", "30.5");
  result.add("imageValue").set("image", "f1").set("name", "prior rmse").set("value", "7.6");
  result.add("imageValue").set("image", "f6").set("name", "differenceImage").set("value", "assembly-files/audit/stela-difference.png");
  result.add("imageValue").set("image", "f6").set("name", "difference").set("value", "prior model minus the photograph, 128 = no difference");
  const audit::AuditReport back = audit::recordedAudit(c, result);
  REQUIRE(back.models.size() == 1);
  const audit::ModelCheck& m = back.models[0];
  REQUIRE(m.differences.size() == 1);
  CHECK(m.differences[0].file == "assembly-files/audit/stela-difference.png");
  CHECK(m.differences[0].description == "prior model minus the photograph, 128 = no difference");
  CHECK(m.differences[0].fullScale == 0);
  CHECK_FALSE(m.differences[0].light.has_value());
  REQUIRE(m.prior.images.size() == 1);
  CHECK_FALSE(m.prior.images[0].light.has_value());
  CHECK(audit::auditJson(back).find("\"differenceImage\":\"assembly-files/audit/stela-difference.png\"") !=
        std::string::npos);
}

TEST_CASE("a recorded audit figure that is not a number is an input error naming it") {
  carrier::Carrier c;
  c.files = {file("f4", "assembly-files/stela.lp", "prior")};
  carrier::Result result;
  result.add("input").set("file", "f4").set("kind", "prior-lp");
  result.add("imageValue").set("image", "f4").set("name", "medianDegrees").set("value", "about two");
  REQUIRE_THROWS_AS(audit::recordedAudit(c, result), Error);
  try {
    audit::recordedAudit(c, result);
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("medianDegrees") != std::string::npos);
  }
}
