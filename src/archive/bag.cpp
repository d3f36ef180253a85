// writeBag: the order of a bag's entries and its all-or-nothing output. Each part is a file of
// its own, since each changes for its own reasons: bag-info.txt and its dates (bag_info.cpp),
// the payload read once for the output and both digests (bag_payload.cpp), the manifests and
// other tag files (bag_tag_files.cpp), and the folder, .tar or .zip they go into
// (bag_output.cpp).
#include "archive/bag.h"

#include <algorithm>
#include <chrono>
#include <memory>

#include "archive/bag_info.h"
#include "archive/bag_output.h"
#include "archive/bag_payload.h"
#include "archive/bag_tag_files.h"
#include "core/atomic_file.h"

namespace surrogate::archive {

namespace fs = std::filesystem;

BagResult writeBag(const BagInput& input, const fs::path& out) {
  const auto started = std::chrono::steady_clock::now();
  const BagFormat format = bagFormatFor(out);
  const std::int64_t epoch = input.epoch.value_or(sourceDateEpoch());

  std::uint64_t total = 0;
  const std::vector<PayloadFile> sources = checkedPayload(input, total);
  // bag-info.txt and bagit.txt need only the sizes: they come first, as the sorted order wants.
  const std::string info = bagInfoText(input, total, sources.size());
  const std::string bagit = "BagIt-Version: 1.0\nTag-File-Character-Encoding: UTF-8\n";

  // The output, under a temporary name until complete; first the partial outputs of packs to
  // the same name that were killed.
  checkOutput(out, input.replace);
  std::vector<std::string> removedLeftovers = removeStaleParts(out);
  AtomicFile target(out);
  std::unique_ptr<Sink> sink = openSink(format, target.tempPath(), out, epoch);

  std::vector<PayloadDigest> tagDigests;
  tagDigests.push_back(putTagFile(*sink, {"bag-info.txt", info, {}}));
  tagDigests.push_back(putTagFile(*sink, {"bagit.txt", bagit, {}}));

  BagResult result;
  result.path = out;
  result.format = format;
  result.removedLeftovers = std::move(removedLeftovers);
  result.payloadBytes = total;
  result.payloadFiles = sources.size();
  result.payload = streamPayload(input, sources, total, *sink);

  // Manifests and the caller's tag files, in path order; then the tag manifests.
  for (const TagFile& t : sortedTagFiles(input, result.payload))
    tagDigests.push_back(putTagFile(*sink, t));
  std::sort(tagDigests.begin(), tagDigests.end(),
            [](const PayloadDigest& a, const PayloadDigest& b) { return a.bagPath < b.bagPath; });
  for (const PayloadDigest& d : tagDigests) result.tagFiles.push_back(d.bagPath);
  putTag(*sink, "tagmanifest-sha256.txt", manifestText(tagDigests, DigestAlgorithm::Sha256));
  putTag(*sink, "tagmanifest-sha512.txt", manifestText(tagDigests, DigestAlgorithm::Sha512));
  result.tagFiles.push_back("tagmanifest-sha256.txt");
  result.tagFiles.push_back("tagmanifest-sha512.txt");
  sink->close();
  sink.reset();
  if (input.replace)
    target.commit();
  else
    target.commitWithoutReplacing();
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace surrogate::archive
