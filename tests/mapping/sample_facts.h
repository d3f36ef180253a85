// The package facts the mapping tests derive metadata with, for a capture folder as `surrogate
// pack` would record them: the package id from the carrier's SHA-256, a fixed packaging time and
// agent, and every file of the folder as data/PATH with its size and digests, in path order.
//   mapping::PackageFacts f = samplefacts::of(capture, carrierXml);
#pragma once

#include <filesystem>
#include <string>

#include "mapping/mapping.h"

namespace samplefacts {

surrogate::mapping::PackageFacts of(const std::filesystem::path& capture, const std::string& carrierXml);

}  // namespace samplefacts
