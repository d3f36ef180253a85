// Private to src/formats: the JPEG-compressed PTM variants (PTM_FORMAT_JPEG_LRGB and
// PTM_FORMAT_JPEG_RGB), read into the same PtmFile as the raw formats.
//
// After the bias line such a file holds eight more text lines: the compression parameter, then
// one value per plane for transforms, motion x, motion y, decoding order, reference plane, JPEG
// size and side-information size. The payload is, plane after plane in plane order, the
// plane's greyscale JPEG then its side information. Decoding, in the decoding order:
//
//     plane = JPEG                                   (no reference)
//     plane = (JPEG + r - 128) mod 256               (reference plane r, already final;
//                                                     255 - r when the transform inverts it)
//     plane[index] = value                           (each 5-byte side-information entry:
//                                                     a big-endian 32-bit index, a byte)
//
// JPEG rows and side-information indices run from the bottom image row up, as the raw
// payload does. docs/formats.md, "JPEG-compressed PTMs", is the full statement.
//
//   HeaderCursor cur(...);  ...parse up to the biases...
//   parseJpegPlaneTable(cur, 9, &header);       // fills header.jpegPlanes
//   PtmFile ptm = decodeJpegPtm(header, payload, available, "object.ptm");
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "formats/ptm.h"
#include "formats/text_parse.h"

namespace surrogate::formats {

// Reads the eight table lines for `planes` planes (9 or 18) into header->jpegPlanes and
// header->report.jpegQuality, and sets header->payloadBytes. Throws Error(Input) through
// `cur` for any line that is missing or malformed, and for a table that cannot be decoded.
void parseJpegPlaneTable(HeaderCursor& cur, int planes, PtmHeader* header);

// Decodes the payload described by `header` (`available` bytes at `payload`, at least
// header.payloadBytes). Throws Error(Input) naming `name` and the plane at fault.
PtmFile decodeJpegPtm(const PtmHeader& header, const std::uint8_t* payload,
                      std::size_t available, const std::string& name);

}  // namespace surrogate::formats
