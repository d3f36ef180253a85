#include <catch2/catch.hpp>

#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "formats/lp.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"
#include "formats/summary.h"

using namespace surrogate;
using namespace surrogate::formats;
namespace fs = std::filesystem;

TEST_CASE("summary: describes .ptm, .rti and .lp files, and reports truncation") {
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-summary";
  fs::remove_all(dir);
  fs::create_directories(dir);

  PtmFile p;
  p.width = 4;
  p.height = 3;
  p.scale = {1, 1, 1, 1, 1, 0.5};
  p.coefficients.assign(p.texels() * 6, 1);
  p.rgb.assign(p.texels() * 3, 2);
  writePtm(dir / "a.ptm", p);
  FileSummary s = summarize(dir / "a.ptm");
  CHECK(s.kind == "ptm");
  CHECK(s.basis == "ptm-lrgb");
  CHECK(s.width == 4);
  CHECK(s.height == 3);
  CHECK(s.scale.back() == 0.5);
  CHECK(s.trailingBytes == 0);
  CHECK_THAT(s.toText(), Catch::Contains(": PTM model ptm-lrgb, 4x3\n  PRONOM:    Polynomial Texture Map (fmt/519)\n"));
  CHECK_THAT(s.toJson(), Catch::Contains("\"basis\":\"ptm-lrgb\""));

  HshFile h;
  h.width = 2;
  h.height = 2;
  h.terms = 9;
  h.scale.assign(9, 0.25f);
  h.bias.assign(9, 0.0f);
  h.coefficients.assign(h.texels() * 27, 3);
  writeRti(dir / "a.rti", h);
  s = summarize(dir / "a.rti");
  CHECK(s.kind == "rti");
  CHECK(s.basis == "hsh3");
  CHECK(s.version == "HSH1.2");
  CHECK(s.scale.size() == 9);

  writeLp(dir / "a.lp", {{"a.jpg", 0, 0, 1}, {"b.jpg", 1, 0, 1}});
  s = summarize(dir / "a.lp");
  CHECK(s.lightCount == 2);
  CHECK(s.maxElevationDegrees == Approx(90));
  CHECK(s.minElevationDegrees == Approx(45));
  CHECK_THAT(s.toJson(), Catch::Contains("\"lights\":2"));

  const std::string bytes = readFile(dir / "a.ptm", "t");
  writeFileAtomically(dir / "cut.ptm", bytes.substr(0, bytes.size() - 1));
  CHECK_THROWS_AS(summarize(dir / "cut.ptm"), Error);
  writeFileAtomically(dir / "x.ptm", "hello");
  CHECK_THROWS_AS(summarize(dir / "x.ptm"), Error);
  fs::remove_all(dir);
}
