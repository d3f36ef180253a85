// Private to src/meta: process-wide Exiv2 set-up, done once before the first use.
//
//   - warnings and errors are not printed (Exiv2 writes them to stderr by default);
//   - BMFF (CR3, HEIF) reading is switched on where this Exiv2 was built with it;
//   - the XMP toolkit is initialised with a lock, which Exiv2 requires before XMP is parsed
//     from several threads.
//   - every use of Exiv2 holds one process-wide lock: measured with Exiv2 0.27.6, four threads
//     reading the same files at once sometimes got an empty XMP packet (BMFF packets are
//     re-parsed and Exiv2's XMP namespace registry is shared), so results depended on timing.
//     Metadata is a small part of ingest (hashing, which runs in parallel, dominates).
#pragma once

#include <mutex>

namespace surrogate::meta {

void ensureExiv2Ready();

// The lock every Exiv2 call in src/meta holds.
std::mutex& exiv2Mutex();

}  // namespace surrogate::meta
