// Private to src/archive: a bag's payload, checked, then streamed into the output with its two
// digests (bag_payload.cpp), and the rule of the paths the bag writer takes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "archive/bag.h"

namespace surrogate::archive {

class Sink;  // bag_output.h

// The bytes read at once from a payload file or a derived tag file.
inline constexpr std::size_t kBufferSize = 1 << 20;

// A payload file as checked: its source and its size when checked (it must not change after).
struct PayloadFile {
  const PayloadSource* in;
  std::uint64_t size;
};

// True for a relative '/'-separated path with no empty, "." or ".." part and no NUL: the rule
// of payload and tag file paths alike.
bool safeRelative(const std::string& path);

// The payload: checked (paths under data/, each once: else Error(Internal); sources that are
// regular files, by lstat, never following a link: else Error(Input)), sorted by bag path,
// sized; `total` receives the sum of the sizes.
std::vector<PayloadFile> checkedPayload(const BagInput& input, std::uint64_t& total);

// Every payload file into the sink, in order, each read once for the output and both digests
// (on worker threads beside the write when the machine has two cores or more). Throws
// Error(Input) for a file that cannot be read or changes size, PayloadChanged for one whose
// SHA-256 is not the expected one.
std::vector<PayloadDigest> streamPayload(const BagInput& input, const std::vector<PayloadFile>& files,
                                         std::uint64_t total, Sink& sink);

}  // namespace surrogate::archive
