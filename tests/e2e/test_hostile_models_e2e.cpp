// The hostile-input suite, models and web layouts (issue 39): a JPEG-compressed PTM or a web
// layout whose header declares far more texels than its few bytes hold is refused from that
// header by render, publish and the audit of prior work in run, and the process's peak memory
// stays under --memory (core/memory_budget.h); a web layout's files are never read through a
// symbolic link (publish/layout_files.h); publish CAPTURE reads only what lies inside the
// capture, whatever its carrier says.
//
// The bombs are made here: JPEG streams of W x H even grey (or RGB) pixels in which every 8x8
// block is two bits (a one-bit Huffman code for "DC difference 0" and one for "end of block"),
// 1/32 bit a texel, the most a baseline JPEG compresses an even image.
#include <catch2/catch.hpp>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "e2e_support.h"
#include "formats/ptm.h"

namespace fs = std::filesystem;

namespace {

void put16(std::string& out, unsigned v) {
  out += static_cast<char>(v >> 8);
  out += static_cast<char>(v & 0xFF);
}

void segment(std::string& out, unsigned marker, const std::string& body) {
  put16(out, marker);
  put16(out, static_cast<unsigned>(body.size() + 2));
  out += body;
}

// A baseline JPEG of width x height pixels, every sample 128, `components` 1 (grey) or 3.
std::string evenJpeg(unsigned width, unsigned height, unsigned components) {
  std::string out;
  put16(out, 0xFFD8);
  segment(out, 0xFFDB, std::string(1, '\0') + std::string(64, '\1'));
  std::string frame(1, '\x08');
  put16(frame, height);
  put16(frame, width);
  frame += static_cast<char>(components);
  for (unsigned c = 0; c < components; ++c) frame += std::string{static_cast<char>(c + 1), '\x11', '\0'};
  segment(out, 0xFFC0, frame);
  for (const char tableClass : {'\x00', '\x10'}) {  // DC, then AC: one code of one bit, symbol 0
    std::string table(1, tableClass);
    table += '\1';
    table += std::string(15, '\0');
    table += '\0';
    segment(out, 0xFFC4, table);
  }
  std::string scan(1, static_cast<char>(components));
  for (unsigned c = 0; c < components; ++c) scan += std::string{static_cast<char>(c + 1), '\0'};
  scan += std::string{'\0', '\x3F', '\0'};
  segment(out, 0xFFDA, scan);
  const std::uint64_t bits = 2ull * ((width + 7) / 8) * ((height + 7) / 8) * components;
  out += std::string(static_cast<std::size_t>(bits / 8), '\0');
  if (bits % 8) out += static_cast<char>((1u << (8 - bits % 8)) - 1);  // padded with one-bits
  put16(out, 0xFFD9);
  return out;
}

// A PTM_FORMAT_JPEG_LRGB file of width x height texels: nine planes, none predicted.
std::string jpegPtm(unsigned width, unsigned height) {
  const std::string plane = evenJpeg(width, height, 1);
  auto line = [](const std::string& v) {
    std::string l;
    for (int p = 0; p < 9; ++p) l += (p ? " " : "") + v;
    return l + "\n";
  };
  std::string order;
  for (int p = 0; p < 9; ++p) order += (p ? " " : "") + std::to_string(p);
  std::string out = "PTM_1.2\nPTM_FORMAT_JPEG_LRGB\n" + std::to_string(width) + "\n" + std::to_string(height) +
                    "\n1 1 1 1 1 1\n0 0 0 0 0 0\n75\n" + line("0") + line("0") + line("0") + order + "\n" +
                    line("-1") + line(std::to_string(plane.size())) + line("0");
  for (int p = 0; p < 9; ++p) out += plane;
  return out;
}

// An LRGB PTM web layout of width x height texels (info.json and three whole planes) in `dir`.
void webLayout(const fs::path& dir, unsigned width, unsigned height) {
  fs::create_directories(dir);
  std::ofstream(dir / "info.json", std::ios::binary)
      << R"({"width":)" << width << R"(,"height":)" << height
      << R"(,"type":"ptm","colorspace":"lrgb","nplanes":9,"format":"jpg","materials":[{"scale":[1,1,1,1,1,1,1,1,1],)"
      << R"("bias":[0,0,0,0,0,0,0,0,0]}]})";
  const std::string plane = evenJpeg(width, height, 3);
  for (int j = 0; j < 3; ++j) std::ofstream(dir / ("plane_" + std::to_string(j) + ".jpg"), std::ios::binary) << plane;
}

void writeBytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

struct Measured {
  int exitCode = -1;
  std::string output;
  long peakKiB = 0;  // the largest resident set of the command's processes
};

// Runs `surrogate ARGS` in a child of its own and takes the peak resident memory from wait4:
// the child's own and its waited-for descendants' (the shell's, surrogate's), none of the
// processes this test ran before.
Measured measured(const fs::path& dir, const std::string& args) {
  const fs::path log = dir / "measured.log";
  const std::string command = std::string(SURROGATE_EXE) + " " + args + " > " + e2e::quote(log) + " 2>&1";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  Measured m;
  int status = 0;
  rusage usage{};
  REQUIRE(pid > 0);
  REQUIRE(::wait4(pid, &status, 0, &usage) == pid);
  m.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  m.peakKiB = usage.ru_maxrss;
  m.output = e2e::bytesOf(log);
  return m;
}

// The budget the bombs are given: the least --memory takes.
constexpr long kBudgetKiB = 64 * 1024;

}  // namespace

TEST_CASE("a JPEG-compressed PTM declaring more than --memory is refused from its header, under the budget") {
  const fs::path dir = e2e::freshDir("hostile-ptm-bomb");
  // 4000 x 4000 texels in nine planes of 63 KB: 144 MB once decoded, and as much again for
  // the model, in a file of 560 KB.
  const fs::path bomb = dir / "bomb.ptm";
  writeBytes(bomb, jpegPtm(4000, 4000));
  REQUIRE(fs::file_size(bomb) < 600 * 1024);
  for (const std::string& command : {"render " + e2e::quote(bomb) + " --light 0,0,1 -o " + e2e::quote(dir / "r.png"),
                                     "publish " + e2e::quote(bomb) + " -o " + e2e::quote(dir / "web")}) {
    const Measured m = measured(dir, command + " --memory 64M");
    INFO(command << "\n" << m.output << "peak " << m.peakKiB << " KiB");
    CHECK(m.exitCode == 1);
    CHECK(m.output.find(bomb.string()) != std::string::npos);
    CHECK(m.output.find("4000x4000 texels") != std::string::npos);
    CHECK(m.output.find("--memory") != std::string::npos);
    CHECK(m.peakKiB < kBudgetKiB);
  }
  CHECK_FALSE(fs::exists(dir / "r.png"));
  CHECK_FALSE(fs::exists(dir / "web"));
  // The same file under a budget that holds it decodes: every texel of every plane is 128.
  const Measured fits = measured(dir, "render " + e2e::quote(bomb) + " --light 0,0,1 -o " +
                                          e2e::quote(dir / "r.png") + " --memory 1G");
  INFO(fits.output);
  CHECK(fits.exitCode == 0);
}

TEST_CASE("parsePtm refuses a JPEG-PTM bomb from its header and decodes an honest one within the budget") {
  const std::string bomb = jpegPtm(4000, 4000);
  const auto* data = reinterpret_cast<const std::uint8_t*>(bomb.data());
  try {
    surrogate::formats::parsePtm(data, bomb.size(), "bomb.ptm", nullptr, {64ull << 20, 0});
    FAIL("a PTM declaring 4000x4000 texels was read within 64 MB");
  } catch (const surrogate::Error& e) {
    CHECK(e.kind() == surrogate::ErrorKind::Input);
    CHECK(e.file() == "bomb.ptm");
    CHECK(e.message().find("budget of 64M") != std::string::npos);
  }
  // What the caller holds beside the model counts: 64x64 texels fit 64 MB, not with a
  // gigabyte a texel beside them.
  const std::string small = jpegPtm(64, 64);
  const auto* smallData = reinterpret_cast<const std::uint8_t*>(small.data());
  const surrogate::formats::PtmFile ptm =
      surrogate::formats::parsePtm(smallData, small.size(), "small.ptm", nullptr, {64ull << 20, 0});
  CHECK(ptm.width == 64);
  CHECK(ptm.coefficients == std::vector<std::uint8_t>(64 * 64 * 6, 128));
  CHECK(ptm.rgb == std::vector<std::uint8_t>(64 * 64 * 3, 128));
  CHECK_THROWS_AS(surrogate::formats::parsePtm(smallData, small.size(), "small.ptm", nullptr, {64ull << 20, 1ull << 30}),
                  surrogate::Error);
}

TEST_CASE("a JPEG-PTM bomb left in a capture as prior work is not audited, and run stays under --memory") {
  const fs::path dir = e2e::freshDir("hostile-prior-bomb");
  const fs::path capture = e2e::smallCapture(dir, 8);
  fs::create_directories(capture / "finished-files");
  // 8000 x 8000 texels: 576 MB of planes and as much of model, more than the whole budget.
  writeBytes(capture / "finished-files" / "prior.ptm", jpegPtm(8000, 8000));
  const long budgetKiB = 256 * 1024;
  const Measured m = measured(dir, "run " + e2e::quote(capture) + " --no-report --quiet --memory 256M");
  INFO(m.output << "peak " << m.peakKiB << " KiB");
  CHECK(m.exitCode == 0);
  CHECK(m.peakKiB < budgetKiB);
  // The audit says why in the carrier's log, naming the file and the budget.
  const std::string carrier = e2e::bytesOf(capture / "assembly-files" / "carrier.xml");
  CHECK(carrier.find("finished-files/prior.ptm is not audited") != std::string::npos);
  CHECK(carrier.find("8000x8000 texels") != std::string::npos);
  CHECK(carrier.find("--memory") != std::string::npos);
}

TEST_CASE("a web layout declaring more than --memory, or planes too small for their size, is refused before decoding") {
  const fs::path dir = e2e::freshDir("hostile-web-bomb");
  SECTION("planes of 4000x4000 texels under --memory 64M") {
    webLayout(dir / "web", 4000, 4000);
    const Measured m =
        measured(dir, "render " + e2e::quote(dir / "web") + " --light 0,0,1 -o " + e2e::quote(dir / "r.png") + " --memory 64M");
    INFO(m.output << "peak " << m.peakKiB << " KiB");
    CHECK(m.exitCode == 1);
    CHECK(m.output.find((dir / "web" / "info.json").string()) != std::string::npos);
    CHECK(m.output.find("--memory") != std::string::npos);
    CHECK(m.peakKiB < kBudgetKiB);
  }
  SECTION("a plane whose bytes cannot hold its 4000x4000 texels") {
    webLayout(dir / "web", 4000, 4000);
    std::string plane = evenJpeg(4000, 4000, 3);
    plane.resize(plane.size() / 100);  // its header, and a hundredth of its blocks
    writeBytes(dir / "web" / "plane_0.jpg", plane);
    const Measured m =
        measured(dir, "render " + e2e::quote(dir / "web") + " --light 0,0,1 -o " + e2e::quote(dir / "r.png") + " --memory 1G");
    INFO(m.output << "peak " << m.peakKiB << " KiB");
    CHECK(m.exitCode == 1);
    CHECK(m.output.find((dir / "web" / "plane_0.jpg").string()) != std::string::npos);
    CHECK(m.output.find("any JPEG of that size needs") != std::string::npos);
    // Refused from its header: the plane's 48 MB of pixels were never allocated.
    CHECK(m.peakKiB < 40 * 1024);
  }
}

TEST_CASE("a web layout's plane, tile or info.json that is a symbolic link is refused, its target never shown") {
  const fs::path dir = e2e::freshDir("hostile-web-links");
  // What a link could expose: its first bytes would be quoted by libjpeg ("starts with 0x53 0x45").
  writeBytes(dir / "secret.txt", "SECRET: not for the terminal\n");
  const fs::path web = dir / "web";
  webLayout(web, 64, 48);
  const auto render = [&](const fs::path& layout) {
    return e2e::surrogate("render " + e2e::quote(layout) + " --light 0,0,1 -o " + e2e::quote(dir / "r.png"));
  };
  REQUIRE(render(web).exitCode == 0);
  SECTION("a plane") {
    fs::remove(web / "plane_1.jpg");
    fs::create_symlink(dir / "secret.txt", web / "plane_1.jpg");
    const e2e::CommandResult r = render(web);
    INFO(r.output);
    CHECK(r.exitCode == 1);
    CHECK(r.output.find((web / "plane_1.jpg").string() + ": is a symbolic link") != std::string::npos);
    CHECK(r.output.find("0x53") == std::string::npos);
    CHECK(r.output.find("SECRET") == std::string::npos);
    CHECK(r.output.find("secret.txt") == std::string::npos);
  }
  SECTION("info.json, for render and info") {
    fs::rename(web / "info.json", dir / "real-info.json");
    fs::create_symlink(dir / "real-info.json", web / "info.json");
    for (const e2e::CommandResult& r : {render(web), e2e::surrogate("info " + e2e::quote(web / "info.json"))}) {
      INFO(r.output);
      CHECK(r.exitCode == 1);
      CHECK(r.output.find((web / "info.json").string() + ": is a symbolic link") != std::string::npos);
    }
  }
  SECTION("a Deep Zoom tile and a tile folder") {
    const fs::path ptm = dir / "small.ptm";
    writeBytes(ptm, jpegPtm(64, 48));
    REQUIRE(e2e::surrogate("publish " + e2e::quote(ptm) + " -o " + e2e::quote(dir / "tiled") +
                           " --tiles deepzoom --tile-size 16").exitCode == 0);
    const fs::path level = dir / "tiled" / "plane_0_files" / "2";
    REQUIRE(fs::is_regular_file(level / "0_0.jpg"));
    REQUIRE(render(dir / "tiled").exitCode == 0);
    fs::remove(level / "0_0.jpg");
    fs::create_symlink(dir / "secret.txt", level / "0_0.jpg");
    e2e::CommandResult r = render(dir / "tiled");
    INFO(r.output);
    CHECK(r.exitCode == 1);
    CHECK(r.output.find((level / "0_0.jpg").string() + ": is a symbolic link") != std::string::npos);
    CHECK(r.output.find("SECRET") == std::string::npos);
    // The level folder itself a link to a copy of it.
    fs::remove(level / "0_0.jpg");
    fs::rename(level, dir / "level-copy");
    fs::create_symlink(dir / "level-copy", level);
    r = render(dir / "tiled");
    INFO(r.output);
    CHECK(r.exitCode == 1);
    CHECK(r.output.find(level.string() + ": is a symbolic link") != std::string::npos);
  }
}

TEST_CASE("publish CAPTURE reads only results inside the capture, whatever its carrier says") {
  const fs::path dir = e2e::freshDir("hostile-publish-paths");
  const fs::path capture = e2e::smallCapture(dir, 8);
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --quiet --no-report --basis ptm-lrgb").exitCode == 0);
  const fs::path carrierFile = capture / "assembly-files" / "carrier.xml";
  const std::string carrier = e2e::bytesOf(carrierFile);
  const std::string recorded = "finished-files/ptm-lrgb.ptm";
  REQUIRE(carrier.find("\"" + recorded + "\"") != std::string::npos);
  REQUIRE(e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(dir / "web")).exitCode == 0);
  // A copy outside the capture, with the digest the carrier records.
  fs::create_directories(dir / "outside");
  fs::copy_file(capture / recorded, dir / "outside" / "ptm-lrgb.ptm");
  const auto publishWith = [&](const std::string& path, const std::string& out) {
    std::string edited = carrier;
    edited.replace(edited.find("\"" + recorded + "\""), recorded.size() + 2, "\"" + path + "\"");
    writeBytes(carrierFile, edited);
    return e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(dir / out));
  };
  int n = 0;
  for (const std::string& path : {std::string("finished-files/../../outside/ptm-lrgb.ptm"),
                                  std::string("finished-files/./ptm-lrgb.ptm")}) {
    const e2e::CommandResult r = publishWith(path, "web" + std::to_string(++n));
    INFO(path << "\n" << r.output);
    CHECK(r.exitCode == 1);
    CHECK(r.output.find(carrierFile.string()) != std::string::npos);
    CHECK(r.output.find(path) != std::string::npos);
    CHECK_FALSE(fs::exists(dir / ("web" + std::to_string(n))));
  }
  // An absolute path is no result in finished-files/: nothing is published.
  const e2e::CommandResult absolute = publishWith((dir / "outside" / "ptm-lrgb.ptm").string(), "web-absolute");
  INFO(absolute.output);
  CHECK(absolute.exitCode == 1);
  CHECK_FALSE(fs::exists(dir / "web-absolute"));
  // finished-files/ptm-lrgb.ptm a link to the copy outside: the same bytes, not the capture's.
  fs::remove(capture / recorded);
  fs::create_symlink(dir / "outside" / "ptm-lrgb.ptm", capture / recorded);
  const e2e::CommandResult r = publishWith(recorded, "web-link");
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK(r.output.find("is a symbolic link") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "web-link"));
}
