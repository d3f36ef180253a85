// Private to src/meta: finding an XMP packet's stored bytes by packet scanning.
//
// XMP packets are wrapped so that they can be found in any file without knowing its format
// (XMP specification part 1, "packet scanning"):
//
//   <?xpacket begin="..." id="W5M0MpCehiHzreSzNTczkc9d"?> ... <?xpacket end="w"?>
//
// Exiv2 0.27 keeps the stored packet for most formats, but for BMFF files (CR3, HEIF) it only
// parses it; its re-serialisation differs from the stored bytes. This recovers them.
#pragma once

#include <string>
#include <vector>

namespace surrogate::meta {

// Every complete xpacket-wrapped packet in `bytes`, in file order.
std::vector<std::string> scanXmpPackets(const std::string& bytes);

}  // namespace surrogate::meta
