// Options as people type them: an unknown option, long or one-letter, is named as typed with the
// option it most likely meant; a mistyped command gets the nearest command; a value left out is
// named as typed; the carrier records -o as -o (never --o).
#include <catch2/catch.hpp>

#include <filesystem>
#include <regex>

#include "e2e_support.h"

namespace fs = std::filesystem;
using Catch::Contains;

TEST_CASE("an unknown one-letter option is named as typed with the long option it stands for", "[cli][options]") {
  const struct {
    std::string command, said;
  } cases[] = {
      {"verify X.zip -q", "surrogate verify: unknown option \"-q\": did you mean --quiet?"},
      {"audit PRIOR -q", "surrogate audit: unknown option \"-q\": did you mean --quiet?"},
      {"run -v CAP", "surrogate run: unknown option \"-v\": did you mean --verbose?"},
      {"run CAP --titel Stela", "surrogate run: unknown option \"--titel\": did you mean --title?"},
      {"verify X.zip -quiet", "surrogate verify: unknown option \"-quiet\": did you mean --quiet?"},
      {"render -x", "surrogate render: unknown option \"-x\" (see --help)"},
  };
  for (const auto& c : cases) {
    const e2e::CommandResult r = e2e::surrogate(c.command);
    INFO(c.command << "\n" << r.output);
    CHECK(r.exitCode == 2);
    CHECK_THAT(r.output, Contains(c.said));
    CHECK(r.output.find("give exactly one") == std::string::npos);
    CHECK(r.output.find("give the folder") == std::string::npos);
  }
  // After --, a name beginning with a dash is a file: missing input (1), not an option.
  const e2e::CommandResult file = e2e::surrogate("info -- -q");
  INFO(file.output);
  CHECK(file.exitCode == 1);
  CHECK_THAT(file.output, Contains("-q: does not exist"));
}

TEST_CASE("a command mistyped by a letter or two is suggested, a far one is not", "[cli][options]") {
  const e2e::CommandResult rn = e2e::surrogate("rn");
  CHECK(rn.exitCode == 2);
  CHECK_THAT(rn.output, Contains("unknown command \"rn\"; did you mean run?"));
  const e2e::CommandResult far = e2e::surrogate("xy");
  CHECK(far.exitCode == 2);
  CHECK(far.output.find("did you mean") == std::string::npos);
}

TEST_CASE("a value left out is named as typed and the carrier records -o as typed", "[cli][options]") {
  const fs::path work = e2e::freshDir("cli-options-o");
  const fs::path capture = e2e::smallCapture(work);
  const e2e::CommandResult missing = e2e::surrogate("pack " + e2e::quote(capture) + " -o");
  INFO(missing.output);
  CHECK(missing.exitCode == 2);
  CHECK_THAT(missing.output, Contains("surrogate pack: -o: needs a value"));
  CHECK(missing.output.find("--o") == std::string::npos);

  const fs::path package = work / "small.zip";
  const e2e::CommandResult pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(package) + " --quiet");
  INFO(pack.output);
  REQUIRE(pack.exitCode == 0);
  const std::string carrier = e2e::bytesOf(capture / "assembly-files" / "carrier.xml");
  // The option and its value, one <arg> each, as typed.
  CHECK(std::regex_search(carrier, std::regex("<arg>-o</arg>\\s*<arg>" + package.filename().string() + "</arg>|"
                                              "<arg>-o</arg>\\s*<arg>[^<]*/small\\.zip</arg>")));
  CHECK(carrier.find("<arg>--o</arg>") == std::string::npos);
}
