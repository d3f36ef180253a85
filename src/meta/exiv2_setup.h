// Private to src/meta: process-wide Exiv2 set-up, done once before the first use.
//
//   - warnings and errors are not printed (Exiv2 writes them to stderr by default);
//   - BMFF (CR3, HEIF) reading is switched on where this Exiv2 was built with it;
//   - the XMP toolkit is initialised with a lock, which Exiv2 requires before XMP is parsed
//     from several threads.
#pragma once

namespace surrogate::meta {

void ensureExiv2Ready();

}  // namespace surrogate::meta
