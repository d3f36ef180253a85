// pack --layout ocfl and verify of an OCFL object, pinned to the OCFL 1.1 specification
// (https://ocfl.io/1.1/spec/) and to an independent validator, ocfl-py's (kept unmodified in
// tests/third_party/ocfl-py, run with Debian's python3): it must accept every object pack
// writes, and reject the damaged ones verify rejects.
#include <catch2/catch.hpp>

#include <fstream>
#include <functional>
#include <map>
#include <regex>

#include <nlohmann/json.hpp>

#include "core/digest.h"
#include "e2e_support.h"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using e2e::quote;

namespace {

constexpr const char* kOcflPy = SOURCE_DIR "/tests/third_party/ocfl-py";
constexpr const char* kOcflPyImports = SOURCE_DIR "/tests/third_party/ocfl-py-imports";

// Debian's python3 (where install-deps puts python3-fsspec), else the one on the path.
std::string python() { return fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3"; }

e2e::CommandResult ocflValidate(const fs::path& object) {
  return e2e::runShell("PYTHONPATH=" + quote(kOcflPyImports) + ":" + quote(kOcflPy) + " " + python() + " " +
                       quote(fs::path(kOcflPy) / "ocfl-validate.py") + " " + quote(object));
}

bool ocflValid(const fs::path& object) {
  const e2e::CommandResult r = ocflValidate(object);
  INFO(r.output);
  REQUIRE_THAT(r.output, Contains("OCFL v1.1 Object at") && (Contains("is VALID") || Contains("is INVALID")));
  return r.exitCode == 0 && r.output.find("is VALID") != std::string::npos;
}

e2e::CommandResult pack(const fs::path& capture, const fs::path& out, long epoch, const std::string& more = "") {
  return e2e::runShell("SOURCE_DATE_EPOCH=" + std::to_string(epoch) + " " + SURROGATE_EXE + " pack " +
                       quote(capture) + " -o " + quote(out) + " --quiet " + more);
}

int verifyExit(const fs::path& package, std::string* output = nullptr) {
  const e2e::CommandResult r = e2e::surrogate("verify " + quote(package) + " --quiet");
  if (output) *output = r.output;
  return r.exitCode;
}

std::string sha512Of(const std::string& bytes) {
  surrogate::MultiDigest d({surrogate::DigestAlgorithm::Sha512});
  d.update(bytes.data(), bytes.size());
  return d.hex(surrogate::DigestAlgorithm::Sha512);
}

void write(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << bytes;
  REQUIRE(out.good());
}

nlohmann::json inventoryOf(const fs::path& object) { return nlohmann::json::parse(e2e::bytesOf(object / "inventory.json")); }

// A capture processed with a creator (the version's user), packed as v1 and v2.
struct Object {
  fs::path dir, capture, object;
};

const Object& twoVersions() {
  static Object o = [] {
    Object x;
    x.dir = e2e::freshDir("ocfl");
    x.capture = e2e::smallCapture(x.dir, 8);
    const e2e::CommandResult run =
        e2e::surrogate("run " + quote(x.capture) + " --creator \"Ann Photographer\" --no-report --quiet");
    if (run.exitCode != 0) throw std::runtime_error(run.output);
    x.object = x.dir / "object";
    for (long epoch : {1700000000L, 1700086400L}) {
      const e2e::CommandResult r = pack(x.capture, x.object, epoch, "--layout ocfl");
      if (r.exitCode != 0) throw std::runtime_error(r.output);
    }
    return x;
  }();
  return o;
}

fs::path copyOf(const fs::path& object, const std::string& name) {
  const fs::path target = e2e::freshDir(name) / "object";
  fs::copy(object, target, fs::copy_options::recursive);
  return target;
}

// Rewrites every inventory (root and each version's) with `edit` applied to its text, and
// every sidecar to match: what someone who knows OCFL would do to hide a change.
void forgeInventories(const fs::path& object, const std::function<std::string(std::string)>& edit) {
  for (const fs::path& folder : {object, object / "v1", object / "v2"}) {
    if (!fs::exists(folder / "inventory.json")) continue;
    const std::string text = edit(e2e::bytesOf(folder / "inventory.json"));
    write(folder / "inventory.json", text);
    write(folder / "inventory.json.sha512", sha512Of(text) + " inventory.json\n");
  }
}

std::string replaceAll(std::string text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// The carrier's capture identifier, read from its text here: "urn:surrogate:capture:" and the
// SHA-256 of its first file.
std::string captureIdentifierOf(const fs::path& capture) {
  const std::string carrier = e2e::bytesOf(capture / "assembly-files/carrier.xml");
  std::smatch m;
  REQUIRE(std::regex_search(carrier, m, std::regex("<file [^>]*sha256=\"([0-9a-f]{64})\"")));
  return "urn:surrogate:capture:" + m[1].str();
}

// The id an object made before issue 56 got: the SHA-256 of "<sha256>  <path>\n" of each
// evidence file of the carrier (originals, exports, sidecars, the .lp, prior work), by path.
std::string evidenceListId(const fs::path& capture) {
  const std::string carrier = e2e::bytesOf(capture / "assembly-files/carrier.xml");
  std::map<std::string, std::string> evidence;
  const std::regex file("<file [^>]*path=\"([^\"]+)\" role=\"(original|export|sidecar|lp|prior)\"[^>]*sha256=\"([0-9a-f]{64})\"");
  for (auto it = std::sregex_iterator(carrier.begin(), carrier.end(), file); it != std::sregex_iterator(); ++it)
    evidence[(*it)[1].str()] = (*it)[3].str();
  REQUIRE_FALSE(evidence.empty());
  std::string list;
  for (const auto& [path, sha256] : evidence) list += sha256 + "  " + path + "\n";
  surrogate::MultiDigest d({surrogate::DigestAlgorithm::Sha256});
  d.update(list.data(), list.size());
  return "urn:sha256:" + d.hex(surrogate::DigestAlgorithm::Sha256);
}

}  // namespace

TEST_CASE("pack --layout ocfl writes an OCFL 1.1 object holding the whole bag, that ocfl-py accepts",
          "[ocfl]") {
  const fs::path dir = e2e::freshDir("ocfl-v1");
  const fs::path capture = e2e::processedCapture(dir);
  const fs::path object = dir / "object", bag = dir / "bag";
  REQUIRE(pack(capture, object, 1700000000, "--layout ocfl").exitCode == 0);
  REQUIRE(pack(capture, bag, 1700000000).exitCode == 0);

  // The spec's object root (3.1): the declaration, the inventory and its sidecar, v1.
  CHECK(e2e::bytesOf(object / "0=ocfl_object_1.1") == "ocfl_object_1.1\n");
  const std::string inventory = e2e::bytesOf(object / "inventory.json");
  CHECK(e2e::bytesOf(object / "inventory.json.sha512") == sha512Of(inventory) + " inventory.json\n");
  CHECK(e2e::bytesOf(object / "v1" / "inventory.json") == inventory);
  const nlohmann::json inv = nlohmann::json::parse(inventory);
  CHECK(inv["type"] == "https://ocfl.io/1.1/spec/#inventory");
  CHECK(inv["digestAlgorithm"] == "sha512");
  CHECK(inv["head"] == "v1");
  CHECK(inv["versions"]["v1"]["created"] == "2023-11-14T22:13:20Z");
  CHECK_THAT(inv["versions"]["v1"]["message"].get<std::string>(), Contains("Packed by Surrogate"));

  // v1/content is the bag pack writes as a folder, byte for byte (metadata/ included), and
  // the manifest's digests are the bag's own SHA-512s.
  CHECK(e2e::snapshot(object / "v1" / "content") == e2e::snapshot(bag));
  const std::string manifest = e2e::bytesOf(bag / "manifest-sha512.txt");
  for (const auto& [digest, paths] : inv["manifest"].items()) {
    const std::string path = paths[0].get<std::string>().substr(std::string("v1/content/").size());
    if (path.rfind("data/", 0) == 0) CHECK_THAT(manifest, Contains(digest + "  " + path));
    CHECK(inv["versions"]["v1"]["state"][digest][0] == path);
  }
  CHECK(inv["manifest"].size() == e2e::snapshot(bag).size());

  CHECK(ocflValid(object));
  std::string out;
  CHECK(verifyExit(object, &out) == 0);
  CHECK_THAT(out, Contains("SOUND"));
}

TEST_CASE("pack --layout ocfl adds versions, keeping unchanged files in the earlier one", "[ocfl]") {
  const Object& o = twoVersions();
  const nlohmann::json inv = inventoryOf(o.object);
  CHECK(inv["head"] == "v2");
  CHECK(inv["versions"]["v2"]["created"] == "2023-11-15T22:13:20Z");
  CHECK(inv["versions"]["v2"]["user"]["name"] == "Ann Photographer");
  // v1 untouched: its inventory still says v1 is head, and it matches the root's v1.
  const nlohmann::json v1 = nlohmann::json::parse(e2e::bytesOf(o.object / "v1" / "inventory.json"));
  CHECK(v1["head"] == "v1");
  CHECK(v1["versions"]["v1"] == inv["versions"]["v1"]);
  // v2's content holds only files whose bytes differ from v1's (the packing time is in them);
  // the originals are served by v1's copies.
  const auto second = e2e::snapshot(o.object / "v2" / "content");
  const auto first = e2e::snapshot(o.object / "v1" / "content");
  REQUIRE(!second.empty());
  for (const auto& [path, sha] : second) {
    INFO(path);
    CHECK(path.rfind("data/original-captures/", 0) != 0);
    CHECK(first.at(path) != sha);
  }
  CHECK(second.count("bag-info.txt") == 1);
  for (const auto& [digest, paths] : inv["versions"]["v2"]["state"].items())
    for (const auto& p : paths)
      if (p.get<std::string>().rfind("data/original-captures/", 0) == 0)
        CHECK(inv["manifest"][digest][0].get<std::string>().rfind("v1/content/", 0) == 0);
  CHECK(ocflValid(o.object));
  CHECK(verifyExit(o.object) == 0);

  // The same bytes again (same SOURCE_DATE_EPOCH): no version added.
  const fs::path copy = copyOf(o.object, "ocfl-same");
  const e2e::CommandResult again = pack(o.capture, copy, 1700086400, "--layout ocfl --json");
  REQUIRE(again.exitCode == 0);
  CHECK_THAT(again.output, Contains("\"unchanged\":true"));
  CHECK(!fs::exists(copy / "v3"));
  CHECK(e2e::snapshot(copy) == e2e::snapshot(o.object));
}

TEST_CASE("pack --layout ocfl refuses another capture's object and a folder that is no object",
          "[ocfl]") {
  const Object& o = twoVersions();
  const fs::path other = copyOf(o.object, "ocfl-other");
  forgeInventories(other, [&](std::string text) {
    return replaceAll(text, inventoryOf(o.object)["id"].get<std::string>(), "urn:sha256:0123");
  });
  const auto before = e2e::snapshot(other);
  const e2e::CommandResult r = pack(o.capture, other, 1700200000, "--layout ocfl");
  CHECK(r.exitCode == 2);
  CHECK_THAT(r.output, Contains("another capture") && Contains("urn:sha256:0123"));
  CHECK(e2e::snapshot(other) == before);

  const fs::path folder = e2e::freshDir("ocfl-folder");
  write(folder / "notes.txt", "mine\n");
  const e2e::CommandResult f = pack(o.capture, folder, 1700200000, "--layout ocfl");
  CHECK(f.exitCode == 2);
  CHECK_THAT(f.output, Contains("not an OCFL object"));
  CHECK(e2e::snapshot(folder).size() == 1);

  const e2e::CommandResult force = pack(o.capture, folder, 1700200000, "--layout ocfl --force");
  CHECK(force.exitCode == 2);
  const e2e::CommandResult bad = pack(o.capture, folder, 1700200000, "--layout mets");
  CHECK(bad.exitCode == 2);
  CHECK_THAT(bad.output, Contains("--layout mets"));
}

TEST_CASE("pack --layout ocfl completes a version a killed pack put in place, and removes its leftovers",
          "[ocfl]") {
  const Object& o = twoVersions();
  // A pack killed after renaming v3 into place and replacing inventory.json, before the
  // sidecar: the root still has v2's sidecar. And a hidden temporary of a dead process.
  const fs::path full = copyOf(o.object, "ocfl-full");
  REQUIRE(pack(o.capture, full, 1700300000, "--layout ocfl").exitCode == 0);
  const fs::path killed = copyOf(o.object, "ocfl-killed");
  fs::copy(full / "v3", killed / "v3", fs::copy_options::recursive);
  fs::copy_file(full / "inventory.json", killed / "inventory.json", fs::copy_options::overwrite_existing);
  CHECK(verifyExit(killed) == 3);
  CHECK(!ocflValid(killed));
  const fs::path leftover = killed.parent_path() / ".object.part-999999-0";
  fs::create_directories(leftover / "content");
  const fs::path rootLeftover = killed / ".inventory.json.part-999999-3";
  write(rootLeftover, "{");
  std::string report;
  CHECK(verifyExit(killed, &report) == 3);
  CHECK_THAT(report, Contains(".inventory.json.part-999999-3: a file at the object's root"));
  const e2e::CommandResult r = e2e::runShell("SOURCE_DATE_EPOCH=1700400000 " + std::string(SURROGATE_EXE) + " pack " +
                                             quote(o.capture) + " -o " + quote(killed) + " --layout ocfl");
  REQUIRE(r.exitCode == 0);
  CHECK_THAT(r.output, Contains("inventory.json.sha512"));
  CHECK_THAT(r.output, Contains(".object.part-999999-0"));
  CHECK(!fs::exists(leftover));
  CHECK(!fs::exists(rootLeftover));
  CHECK(inventoryOf(killed)["head"] == "v4");
  CHECK(ocflValid(killed));
  CHECK(verifyExit(killed) == 0);

  // Killed before the root inventory was replaced: v3 is there, the root still says v2.
  const fs::path early = copyOf(o.object, "ocfl-early");
  fs::copy(full / "v3", early / "v3", fs::copy_options::recursive);
  CHECK(verifyExit(early) == 3);
  const e2e::CommandResult e = pack(o.capture, early, 1700400000, "--layout ocfl");
  REQUIRE(e.exitCode == 0);
  CHECK(inventoryOf(early)["head"] == "v4");
  CHECK(inventoryOf(early)["versions"]["v3"] == inventoryOf(full)["versions"]["v3"]);
  CHECK(ocflValid(early));
  CHECK(verifyExit(early) == 0);
}

TEST_CASE("verify never says SOUND of an OCFL object cut, flipped, forged or missing a version",
          "[ocfl]") {
  const Object& o = twoVersions();
  const nlohmann::json inv = inventoryOf(o.object);
  std::string originalDigest, originalPath;
  for (const auto& [digest, paths] : inv["manifest"].items())
    if (paths[0].get<std::string>().find("original-captures/") != std::string::npos) {
      originalDigest = digest;
      originalPath = paths[0];
      break;
    }
  REQUIRE(!originalPath.empty());

  struct Fault {
    std::string name, check;
    std::function<void(const fs::path&)> make;
    bool ocflPyRejects;  // whether the fault is one OCFL itself can see
  };
  const std::vector<Fault> faults = {
      {"a byte flipped in an original", "ocfl.fixity-sha512",
       [&](const fs::path& obj) {
         std::string b = e2e::bytesOf(obj / originalPath);
         b[b.size() / 2] = static_cast<char>(b[b.size() / 2] ^ 0x20);
         write(obj / originalPath, b);
       },
       true},
      {"an original cut short", "ocfl.fixity-sha512",
       [&](const fs::path& obj) { fs::resize_file(obj / originalPath, fs::file_size(obj / originalPath) / 2); }, true},
      {"the head version removed", "ocfl.versions", [](const fs::path& obj) { fs::remove_all(obj / "v2"); }, true},
      {"the first version removed", "ocfl.versions", [](const fs::path& obj) { fs::remove_all(obj / "v1"); }, true},
      {"the inventory edited, its sidecar not", "ocfl.sidecar",
       [](const fs::path& obj) {
         write(obj / "inventory.json", replaceAll(e2e::bytesOf(obj / "inventory.json"), "Packed by", "Made by"));
       },
       true},
      {"an inventory digest forged in the root inventory, sidecar redone", "ocfl.fixity-sha512",
       [&](const fs::path& obj) {
         const std::string text = replaceAll(e2e::bytesOf(obj / "inventory.json"), originalDigest, std::string(128, 'a'));
         write(obj / "inventory.json", text);
         write(obj / "inventory.json.sha512", sha512Of(text) + " inventory.json\n");
       },
       true},
      {"a file added to a version's content", "ocfl.complete",
       [](const fs::path& obj) { write(obj / "v2" / "content" / "extra.txt", "x\n"); }, true},
      // Every inventory and sidecar redone for a changed bag-info.txt: a valid OCFL object,
      // whose bag no longer matches its own tag manifests.
      {"bag-info.txt changed and every inventory redone to match", "bagit.tagfixity-sha512",
       [](const fs::path& obj) {
         const fs::path info = obj / "v2" / "content" / "bag-info.txt";
         const std::string before = e2e::bytesOf(info);
         const std::string after = before + "Contact-Name: someone\n";
         write(info, after);
         forgeInventories(obj, [&](std::string text) { return replaceAll(text, sha512Of(before), sha512Of(after)); });
       },
       false},
  };
  for (const Fault& f : faults) {
    SECTION(f.name) {
      const fs::path obj = copyOf(o.object, "ocfl-fault");
      f.make(obj);
      std::string out;
      const e2e::CommandResult r = e2e::surrogate("verify " + quote(obj));
      INFO(r.output);
      CHECK(r.exitCode == 3);
      CHECK_THAT(r.output, Contains("FAIL  " + f.check));
      CHECK(r.output.find("\nSOUND") == std::string::npos);
      CHECK(ocflValid(obj) == !f.ocflPyRejects);
    }
  }
}

TEST_CASE("info and report show the bag of an OCFL object's head version and name the verify command when it cannot be read",
          "[ocfl]") {
  const Object& o = twoVersions();
  const nlohmann::json inv = inventoryOf(o.object);
  const e2e::CommandResult info = e2e::surrogate("info " + quote(o.object) + " --json");
  INFO(info.output);
  REQUIRE(info.exitCode == 0);
  const nlohmann::json j = nlohmann::json::parse(info.output);
  CHECK(j["kind"] == "package");
  CHECK(j["format"] == "ocfl");
  CHECK(j["surrogatePackage"] == true);
  // Every logical file of the head state (the inventory, read here with nlohmann's JSON).
  std::size_t logical = 0;
  for (const auto& [digest, paths] : inv["versions"]["v2"]["state"].items()) logical += paths.size();
  CHECK(j["files"] == logical);
  // v2's bag-info, not v1's: packed at the second SOURCE_DATE_EPOCH.
  std::string packedAt;
  for (const auto& field : j["bagInfo"])
    if (field["label"] == "Surrogate-Packaging-Time") packedAt = field["value"];
  CHECK(packedAt == "2023-11-15T22:13:20Z");
  CHECK(j["carrier"]["creators"][0]["name"] == "Ann Photographer");
  const e2e::CommandResult text = e2e::surrogate("info " + quote(o.object));
  CHECK_THAT(text.output, Contains("Surrogate package (OCFL object, head version v2)"));
  CHECK_THAT(text.output, Contains("surrogate verify " + o.object.string()));

  const fs::path html = o.dir / "object-report.html";
  const e2e::CommandResult report = e2e::surrogate("report " + quote(o.object) + " -o " + quote(html) + " --json");
  INFO(report.output);
  REQUIRE(report.exitCode == 0);
  CHECK_THAT(nlohmann::json::parse(report.output)["source"].get<std::string>(),
             Contains("OCFL object, head version v2 " + o.object.string()));
  CHECK_THAT(e2e::bytesOf(html), Contains("Ann Photographer"));
  // Nothing written into the object.
  CHECK(e2e::snapshot(o.object) == e2e::snapshot(copyOf(o.object, "ocfl-read-only")));

  // Without its root inventory: refused, with the command that says what is wrong.
  const fs::path broken = copyOf(o.object, "ocfl-no-inventory");
  fs::remove(broken / "inventory.json");
  for (const std::string& command : {"info " + quote(broken), "report " + quote(broken) + " -o " + quote(o.dir / "x.html")}) {
    const e2e::CommandResult r = e2e::surrogate(command);
    INFO(r.output);
    CHECK(r.exitCode == 2);
    CHECK_THAT(r.output, Contains("inventory.json: missing"));
    CHECK_THAT(r.output, Contains("surrogate verify " + broken.string()));
  }
  CHECK(!fs::exists(o.dir / "x.html"));
}

// Issue 51: pack --layout ocfl onto an existing object trusted it, adding a version (exit 0)
// that reused whatever its inventory pointed at. Each of these objects is one verify refuses;
// pack must refuse it too (exit 2, the verify command named) and write nothing, no v3 above all.
TEST_CASE("pack --layout ocfl refuses an object whose paths leave it, that holds a link, or whose copy changed",
          "[ocfl]") {
  const Object& o = twoVersions();
  const nlohmann::json inv = inventoryOf(o.object);
  std::string originalPath, bagitPath;
  for (const auto& [digest, paths] : inv["manifest"].items()) {
    const std::string p = paths[0];
    if (originalPath.empty() && p.rfind("v1/content/data/original-captures/", 0) == 0) originalPath = p;
    if (p == "v1/content/bagit.txt") bagitPath = p;
  }
  REQUIRE(!originalPath.empty());
  REQUIRE(!bagitPath.empty());  // bagit.txt never changes: every version reuses v1's copy

  const std::vector<std::pair<std::string, std::function<void(const fs::path&)>>> hostile = {
      {"a manifest path out of the object, every inventory and sidecar redone",
       [&](const fs::path& obj) {
         forgeInventories(obj, [&](std::string t) { return replaceAll(t, "\"" + bagitPath + "\"", "\"../../../../etc/passwd\""); });
       }},
      {"a state path with ..",
       [](const fs::path& obj) { forgeInventories(obj, [](std::string t) { return replaceAll(t, "\"bagit.txt\"", "\"../bagit.txt\""); }); }},
      {"an absolute state path",
       [](const fs::path& obj) { forgeInventories(obj, [](std::string t) { return replaceAll(t, "\"bagit.txt\"", "\"/etc/passwd\""); }); }},
      {"v1's bagit.txt a symbolic link to /etc/passwd",
       [&](const fs::path& obj) {
         fs::remove(obj / bagitPath);
         fs::create_symlink("/etc/passwd", obj / bagitPath);
       }},
      {"v1 a symbolic link out of the object",
       [](const fs::path& obj) {
         const fs::path elsewhere = obj.parent_path() / "elsewhere-v1";
         fs::rename(obj / "v1", elsewhere);
         fs::create_symlink(elsewhere, obj / "v1");
       }},
      {"a bit flipped in v1's copy of an original",
       [&](const fs::path& obj) {
         std::string b = e2e::bytesOf(obj / originalPath);
         b[b.size() / 2] = static_cast<char>(b[b.size() / 2] ^ 0x01);
         write(obj / originalPath, b);
       }},
  };
  for (const auto& [name, make] : hostile) {
    SECTION(name) {
      const fs::path obj = copyOf(o.object, "ocfl-hostile");
      make(obj);
      const auto before = e2e::snapshot(obj);
      const e2e::CommandResult r = pack(o.capture, obj, 1700500000, "--layout ocfl");
      INFO(r.output);
      CHECK(r.exitCode == 2);
      CHECK_THAT(r.output, Contains("surrogate verify " + obj.string()));
      CHECK(!fs::exists(fs::symlink_status(obj / "v3")));
      CHECK(e2e::snapshot(obj) == before);
      CHECK(verifyExit(obj) != 0);
    }
  }
}

// Issue 56: the object's id is the capture identifier, which the bag itself holds (bag-info.txt
// and the RO-Crate), so that every package of one capture, before and after its record changes,
// is a version of one object a repository can find from the bag.
TEST_CASE("the OCFL object id is the capture identifier, the same for every pack of the capture and named in the bag",
          "[ocfl]") {
  const Object& o = twoVersions();
  const std::string captureId = captureIdentifierOf(o.capture);
  const nlohmann::json inventory = inventoryOf(o.object);
  CHECK(inventory["id"] == captureId);
  CHECK(inventoryOf(o.object / "v1")["id"] == captureId);
  CHECK(inventoryOf(o.object / "v2")["id"] == captureId);
  // In the bag: bag-info.txt and the RO-Crate's identifiers.
  CHECK_THAT(e2e::bytesOf(o.object / "v1/content/bag-info.txt"),
             Contains("Surrogate-Capture-Identifier: " + captureId + "\n"));
  CHECK_THAT(e2e::bytesOf(o.object / "v1/content/data/ro-crate-metadata.json"), Contains("\"" + captureId + "\""));

  // A changed record is a new package of the same capture: a new version of the same object.
  const fs::path copy = copyOf(o.object, "ocfl-same-capture");
  const fs::path capture = e2e::freshDir("ocfl-same-capture-cap") / "cap";
  fs::copy(o.capture, capture, fs::copy_options::recursive);
  const e2e::CommandResult retitled = e2e::surrogate("run " + quote(capture) + " --title \"Stela 12, again\" --no-report --quiet");
  REQUIRE(retitled.exitCode == 0);
  const e2e::CommandResult r = pack(capture, copy, 1700300000, "--layout ocfl --json");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK_THAT(r.output, Contains("\"objectId\":\"" + captureId + "\"") && Contains("\"version\":\"v3\""));
  CHECK(inventoryOf(copy)["id"] == captureId);
  CHECK(ocflValid(copy));
}

TEST_CASE("pack --layout ocfl adds to an object made before the id was the capture identifier, keeping its id",
          "[ocfl]") {
  const Object& o = twoVersions();
  const fs::path older = copyOf(o.object, "ocfl-older-id");
  const std::string legacy = evidenceListId(o.capture);
  forgeInventories(older, [&](std::string text) { return replaceAll(text, captureIdentifierOf(o.capture), legacy); });
  const e2e::CommandResult r = pack(o.capture, older, 1700400000, "--layout ocfl");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK(inventoryOf(older)["id"] == legacy);
  CHECK(fs::exists(older / "v3"));
  CHECK(ocflValid(older));
}
