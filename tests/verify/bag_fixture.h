// Test support for the verifier: making bags and archives, including broken and hostile ones,
// with libarchive (never by hand).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace verify_test {

// A fresh empty folder under the system's temporary folder.
std::filesystem::path freshDir(const std::string& name);

void writeText(const std::filesystem::path& path, const std::string& text);
std::string readText(const std::filesystem::path& path);

// A tiny capture (two "originals" of a few bytes and a valid carrier listing them), for
// checks that do not need a real pipeline run.
std::filesystem::path tinyCapture(const std::filesystem::path& dir);

// Makes a BagIt bag at `bag` holding `capture` as data/, as `surrogate pack` would: manifests
// (sha256, sha512), bagit.txt, bag-info.txt (the computed labels, the carrier's metadata and
// External-Description, Surrogate-Package-Identifier = urn:sha256 of the carrier,
// Surrogate-Packaging-Time), metadata/crm.rdf and metadata/mets.xml derived from the carrier
// with the bundled stylesheets, schemas and tables copied to metadata/ (when the mapping
// library is built; placeholders otherwise) and tagmanifests.
void makeBag(const std::filesystem::path& capture, const std::filesystem::path& bag);

// Rewrites the bag's manifests, bag-info.txt, metadata and tagmanifests for its current
// content (after a test changed files "consistently"): what a forger who redoes every
// derivable file would do. The bag's Bag-Software-Agent and packaging time are kept. With
// `keepRoCrate`, data/ro-crate-metadata.json is left as it is (a forger who changed it).
// `mappingEdition` (src/mapping/mapping.h): 1 writes the metadata as packages made before
// issue 56 held it.
void rehashBag(const std::filesystem::path& bag, bool keepRoCrate = false, int mappingEdition = 2);

// A manifest path as RFC 8493 writes it: CR, LF and % percent-encoded.
std::string escapedPath(const std::string& path);

// Only the tagmanifests (after a test changed a tag file or a manifest "consistently").
void rehashTagManifests(const std::filesystem::path& bag);

// One entry of a hand-made archive.
struct Entry {
  enum Type { File, Directory, Symlink, Hardlink, Fifo, CharDevice };
  Entry() = default;
  Entry(Type t, std::string n, std::string c = "", std::string link = "")
      : type(t), name(std::move(n)), content(std::move(c)), linkTarget(std::move(link)) {}
  Type type = File;
  std::string name;
  std::string content;
  std::string linkTarget;                  // symlinks and hard links
  std::optional<std::int64_t> claimedSize; // a header size other than content.size() (tar)
};

// Writes `entries` into `archive` (format by extension: .tar or .zip) with libarchive.
void writeArchive(const std::filesystem::path& archive, const std::vector<Entry>& entries);

// Packs the directory `dir` into `archive` (.tar or .zip), entries under `prefix` ("" for the
// bag's files at the archive's top, or e.g. "stela/").
void archiveDirectory(const std::filesystem::path& dir, const std::filesystem::path& archive,
                      const std::string& prefix);

// Where the entries of an uncompressed tar begin (each header block, pax headers included, in
// order), and last the offset of its end-of-archive marker. Only for well-formed archives.
std::vector<std::uint64_t> tarEntryOffsets(const std::string& tar);

// Where the local headers of a zip's entries begin (from its central directory, in order),
// then the central directory's offset and the end record's offset.
std::vector<std::uint64_t> zipEntryOffsets(const std::string& zip);

// The bag's files (regular files, relative '/' paths) in the order an archive writer writes
// them: byte order of their paths (bag-info.txt, bagit.txt, data/..., manifest-*, metadata/...,
// tagmanifest-*), as `surrogate pack` writes.
std::vector<std::string> filesInWriteOrder(const std::filesystem::path& bag);

}  // namespace verify_test
