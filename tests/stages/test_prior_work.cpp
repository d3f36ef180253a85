// Prior work (stages/prior_work.h): which files of the output folders are prior work, what a
// prior file says of its making, and the refusal of a plan that would write over one.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <fstream>

#include "core/error.h"
#include "stages/audit_stage.h"
#include "run/plan.h"
#include "stages/prior_work.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("surrogate-stages-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

carrier::Carrier recordedWith(const std::string& path, const std::string& role) {
  carrier::Carrier c;
  carrier::FileRecord f;
  f.path = path;
  f.role = role;
  c.putFile(f);
  return c;
}

fs::path written(const fs::path& dir, const std::string& name, const std::string& bytes) {
  std::ofstream(dir / name, std::ios::binary) << bytes;
  return dir / name;
}

}  // namespace

TEST_CASE("which files of the output folders are prior work follows the carrier", "[stages][prior]") {
  const std::vector<std::string> planned = {"finished-files/ptm-lrgb.ptm", "assembly-files/highlights-sphere*.png"};
  // Never processed: everything is prior work.
  CHECK(stages::isPriorWork("finished-files/ptm-lrgb.ptm", nullptr, planned));
  CHECK(stages::isPriorWork("assembly-files/x.lp", nullptr, planned));
  // Recorded: as recorded.
  const carrier::Carrier prior = recordedWith("finished-files/ptm-lrgb.ptm", "prior");
  CHECK(stages::isPriorWork("finished-files/ptm-lrgb.ptm", &prior, planned));
  const carrier::Carrier ours = recordedWith("finished-files/old.rti", "result");
  CHECK_FALSE(stages::isPriorWork("finished-files/old.rti", &ours, planned));
  // Not recorded: prior work unless the run writes there.
  CHECK(stages::isPriorWork("finished-files/new.ptm", &ours, planned));
  CHECK_FALSE(stages::isPriorWork("finished-files/ptm-lrgb.ptm", &ours, planned));
  CHECK_FALSE(stages::isPriorWork("assembly-files/highlights-sphere2.png", &ours, planned));
  CHECK(stages::isPriorWork("assembly-files/highlights-sphere2.jpg", &ours, planned));
}

TEST_CASE("the planned outputs name every file a default run writes", "[stages][prior]") {
  run::RunRequest request;
  const fs::path dir = freshDir("prior-plan");
  const std::vector<std::string> planned = stages::plannedOutputs(run::planRun(dir, request));
  // What a default run writes (docs/user-guide.md, "The capture folder").
  for (const char* path : {"assembly-files/carrier.xml", "assembly-files/lights.lp", "assembly-files/spheres.png",
                           "assembly-files/highlights-sphere1.png", "finished-files/ptm-lrgb.ptm",
                           "finished-files/hsh2.rti", "finished-files/normals.png", "finished-files/albedo.png",
                           "finished-files/preview-raking.png", "finished-files/preview-top.png",
                           "finished-files/preview-specular.png", "finished-files/report.html"}) {
    INFO(path);
    CHECK(stages::isPlannedOutput(path, planned));
  }
  CHECK_FALSE(stages::isPlannedOutput("finished-files/ptm-rgb.ptm", planned));
  CHECK_FALSE(stages::isPlannedOutput("finished-files/rtibuilder/ptm-lrgb.ptm", planned));
}

TEST_CASE("a plan over prior work is refused naming the file but a leftover is not", "[stages][prior]") {
  const std::vector<std::string> planned = {"finished-files/ptm-lrgb.ptm"};
  try {
    stages::refuseOutputsOverPriorWork({"assembly-files/a.lp", "finished-files/ptm-lrgb.ptm"}, nullptr, planned);
    FAIL("not refused");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Usage);
    CHECK(e.file() == "finished-files/ptm-lrgb.ptm");
    CHECK_THAT(e.message(), Catch::Contains("finished-files/prior/"));
  }
  const carrier::Carrier ours = recordedWith("finished-files/hsh2.rti", "result");
  CHECK_NOTHROW(stages::refuseOutputsOverPriorWork({"finished-files/ptm-lrgb.ptm"}, &ours, planned));
}

TEST_CASE("a prior file says what made it only where its bytes say so", "[stages][prior]") {
  const fs::path dir = freshDir("prior-describe");
  const stages::PriorFile lp = stages::describePriorFile(
      written(dir, "a.lp", "2\r\njpeg-exports\\000.JPG 0 0 1\r\n\r\njpeg-exports\\001.JPG 0.6 0 0.8\r\n"), "assembly-files/a.lp");
  CHECK(lp.kind == "lp");
  CHECK(lp.madeBy.empty());
  CHECK(lp.format == "LP");
  CHECK(lp.warning.empty());

  const stages::PriorFile rgb = stages::describePriorFile(
      written(dir, "b.ptm", "PTM_1.2\nPTM_FORMAT_RGB\n1\n1\n1 1 1 1 1 1\n0 0 0 0 0 0\n" + std::string(18, 'a')),
      "finished-files/b.ptm");
  CHECK(rgb.kind == "rti");
  CHECK(rgb.madeBy == "PTM_1.2 PTM_FORMAT_RGB");
  CHECK(rgb.format == "PTM_FORMAT_RGB");

  // Named .ptm but not one: prior work all the same, with nothing said of its maker.
  const stages::PriorFile broken =
      stages::describePriorFile(written(dir, "c.ptm", "PTM_1.2\nPTM_FORMAT_LRGB\n"), "finished-files/c.ptm");
  CHECK(broken.kind == "rti");
  CHECK(broken.madeBy.empty());
  CHECK_THAT(broken.warning, Catch::Contains("finished-files/c.ptm"));

  const stages::PriorFile log = stages::describePriorFile(
      written(dir, "d.xml", "<?xml version=\"1.0\"?><rti:Log xmlns:rti=\"urn:x\" tool=\"relight\" version=\"1.0\"/>"),
      "assembly-files/d.xml");
  CHECK(log.kind == "log");
  CHECK(log.madeBy == "rti:Log tool=\"relight\" version=\"1.0\"");

  const stages::PriorFile entity = stages::describePriorFile(
      written(dir, "e.xml", "<!DOCTYPE x [<!ENTITY a \"b\">]><x>&a;</x>"), "assembly-files/e.xml");
  CHECK(entity.kind == "log");
  CHECK(entity.madeBy.empty());
  CHECK_FALSE(entity.warning.empty());

  CHECK(stages::describePriorFile(written(dir, "notes.TXT", "hello"), "finished-files/notes.TXT").kind == "other");
}

TEST_CASE("the audit's differenceImages parameter names photographs by file or shot name", "[stages][prior]") {
  const std::vector<std::string> photos = {"jpeg-exports/IMG_0001.jpg", "jpeg-exports/IMG_0002.jpg",
                                           "jpeg-exports/IMG_0003.jpg", "jpeg-exports/IMG_0004.jpg",
                                           "jpeg-exports/IMG_0005.jpg"};
  CHECK(stages::photographsNamed({"IMG_0003.jpg", "IMG_0001"}, photos) == std::vector<int>{2, 0});
  CHECK(stages::photographsNamed({"IMG_0003.jpg", "IMG_0003"}, photos) == std::vector<int>{2});  // once each
  const auto options = stages::AuditStageOptions::fromParameters({{"differenceImages", "IMG_0002.jpg, IMG_0005"}});
  CHECK(options.differenceImages == std::vector<std::string>{"IMG_0002.jpg", "IMG_0005"});
  CHECK(options.toParameters().back() == std::pair<std::string, std::string>{"differenceImages", "IMG_0002.jpg,IMG_0005"});
  CHECK(stages::AuditStageOptions::fromParameters({{"differenceImages", ""}}).differenceImages.empty());
  CHECK_THROWS_AS(stages::AuditStageOptions::fromParameters({{"differenceImages", "IMG_0002.jpg,,IMG_0003.jpg"}}), Error);
  try {
    stages::photographsNamed({"IMG_0002.jpg", "NOPE.jpg"}, photos);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Usage);
    CHECK(e.exitCode() == 2);
    CHECK(e.file() == "NOPE.jpg");
    CHECK(e.message().find("(IMG_0001.jpg, IMG_0002.jpg, IMG_0003.jpg, IMG_0004.jpg, ... (5 in all))") != std::string::npos);
  }
}
