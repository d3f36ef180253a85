// Writing a stage's output file and recording it in the carrier (role, hash, the step that
// made it) and in the step's result.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "carrier/carrier.h"
#include "core/digest.h"
#include "core/image.h"
#include "pipeline/context.h"

namespace surrogate::stages {

// Records the already written file `relativePath` (relative to the capture) as an output of
// `step`: hashes it, identifies its PRONOM format from its bytes (formats/pronom.h), adds or
// replaces its <file> record, and adds <output kind=...>.
std::string recordOutput(pipeline::Context& ctx, const carrier::Step& step,
                         carrier::Result& result, const std::string& relativePath,
                         const std::string& role, const std::string& format,
                         const std::string& kind, const std::string& mediaType = "");

// The same with the file's digests already taken (digestFile), e.g. on another thread.
std::string recordOutput(pipeline::Context& ctx, const carrier::Step& step,
                         carrier::Result& result, const std::string& relativePath,
                         const FileDigests& digests, const std::string& role, const std::string& format,
                         const std::string& kind, const std::string& mediaType = "");

// What a writer knows of a file it has just written from bytes in memory: their size and
// SHA-256 and their PRONOM identifier, the same as digestFile and identifyPronomFile would find
// in the file, without reading it back.
struct WrittenFile {
  FileDigests digests;
  std::string puid;
};

// The same with what the writer knows of the file (writePicture's answer).
std::string recordOutput(pipeline::Context& ctx, const carrier::Step& step,
                         carrier::Result& result, const std::string& relativePath,
                         const WrittenFile& written, const std::string& role, const std::string& format,
                         const std::string& kind, const std::string& mediaType = "");

// Writes `picture` as the PNG file `relativePath` (image::encodePng, written atomically under
// the context's output folder) and hands it to ctx.settings.pictureWritten. Record it with
// recordOutput afterwards, with the answer: the encoded bytes' digest and identification, taken
// on the writing thread. Safe to call from several threads at once for different files.
// `encoded`, when given, is called once the bytes are made and `picture` is no longer read
// (before the file goes to disk and its bytes are digested): a caller that encodes a few
// pictures at a time can let go of the pixels and start the next one meanwhile.
WrittenFile writePicture(const pipeline::Context& ctx, const Image& picture, const std::string& relativePath,
                         const std::function<void()>& encoded = {});

// A file name from the carrier, checked before writing: relative, inside assembly-files/ or
// finished-files/, no ".." (a re-executed carrier from elsewhere must not write anywhere else).
std::string checkedOutputPath(const std::string& relativePath);

// The step's parameters as name/value pairs, for the option structs' fromParameters().
std::vector<std::pair<std::string, std::string>> parametersOf(const carrier::Step& step);

}  // namespace surrogate::stages
