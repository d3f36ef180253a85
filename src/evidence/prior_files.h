// Private to src/evidence: reading PRIOR's files without changing anything of them, their
// access times included (O_NOATIME where allowed), and copying them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "carrier/carrier.h"

namespace surrogate::evidence {

// Every regular file under `root` as a '/'-separated relative path, sorted, less what is never
// evidence (evidence.h): .surrogate/ and superseded-files/ at the top, system files anywhere,
// interrupted writes in assembly-files/ and finished-files/. Error(Input) naming a symbolic
// link, a special file or a folder that cannot be read.
std::vector<std::string> listFiles(const std::filesystem::path& root);

// Whether `folder` holds a regular file at its top (not in a subfolder), read as listFiles
// reads; false when it cannot be opened as a folder.
bool holdsFile(const std::filesystem::path& folder);

// The whole of a small file (PRIOR's carrier), read without touching its access time.
std::string readSmallFile(const std::filesystem::path& file);

// The file's size and SHA-256, read once.
carrier::AuditedSource::Item hashFile(const std::filesystem::path& root, const std::string& relative);

// Copies `root`/`relative` to `destination`/`relative` (created; never over an existing file),
// hashing the bytes as they pass, flushed to disk and with the source's modification time.
// Error(Input) when the source changes size while it is copied.
carrier::AuditedSource::Item copyFile(const std::filesystem::path& root, const std::string& relative,
                                      const std::filesystem::path& destination);

}  // namespace surrogate::evidence
