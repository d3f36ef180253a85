// Private to src/archive: bag-info.txt as writeBag writes it (bag.cpp), from the payload's sizes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "archive/bag.h"

namespace surrogate::archive {

// bag-info.txt of a payload of `total` bytes in `files` files: the computed labels
// (Bag-Software-Agent, Bagging-Date, Bag-Size, Payload-Oxum), then the caller's (BagInput::info,
// refused with Error(Usage) when bagInfoLabelProblem says so), then the packer's own
// (BagInput::ownInfo, only their form checked), then the holder's (BagInput::holderInfo,
// checked as the caller's, a value with a line break refused). A value's line breaks become
// continuation lines.
std::string bagInfoText(const BagInput& input, std::uint64_t total, std::size_t files);

}  // namespace surrogate::archive
