#include "image/export_decoder.h"

#include <optional>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "image/jpeg_structure.h"
#include "image/png_structure.h"
#include "image/tiff_structure.h"

namespace surrogate::image {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "image decode";

// The structure check on the file's bytes (JPEG, PNG) or the file itself (TIFF: libtiff reads
// only the directories and the strip tables).
ImageProbe checkStructure(const fs::path& path, SourceKind kind, const std::uint8_t* data, std::size_t size) {
  ImageProbe probe;
  probe.kind = kind;
  std::string problem;
  switch (kind) {
    case SourceKind::Jpeg: {
      const JpegStructure s =
          data ? readJpegStructure(data, size) : readJpegStructure(path);
      probe.width = s.width;
      probe.height = s.height;
      problem = s.problem;
      break;
    }
    case SourceKind::Png: {
      const PngStructure s =
          data ? readPngStructure(data, size) : readPngStructure(path);
      probe.width = s.width;
      probe.height = s.height;
      problem = s.problem;
      break;
    }
    case SourceKind::Tiff: {
      const TiffStructure s = readTiffStructure(path);
      probe.width = s.width;
      probe.height = s.height;
      problem = tiffProblem(s);
      break;
    }
    case SourceKind::CameraRaw:
      throw Error(ErrorKind::Internal, path.string(), kStep, "camera raw files are LibRaw's to check");
  }
  if (!problem.empty()) throwInputError(path.string(), kStep, problem);
  if (probe.width <= 0 || probe.height <= 0)
    throwInputError(path.string(), kStep, "the image declares no size (0 pixels wide or high)");
  return probe;
}

const char* libraryOf(SourceKind kind) {
  return kind == SourceKind::Jpeg ? "libjpeg" : kind == SourceKind::Png ? "libpng" : "libtiff";
}

// A JPEG or PNG held in memory: its structure checked and its declared size against
// options.maxPixels before the decoder allocates anything; the decoder's messages go to
// `messages`, for the caller to settle.
DecodedPixels decodeHeldBytes(const fs::path& path, SourceKind kind, const std::uint8_t* data, std::size_t size,
                              const DecodeOptions& options, DecoderMessages& messages) {
  const ImageProbe probe = checkStructure(path, kind, data, size);
  checkDeclaredSize(path, static_cast<std::uint64_t>(probe.width), static_cast<std::uint64_t>(probe.height), options);
  return kind == SourceKind::Jpeg ? decodeJpeg(path, data, size, options, messages)
                                  : decodePng(path, data, size, options, messages);
}

}  // namespace

ImageProbe checkExportStructure(const fs::path& path, SourceKind kind) {
  return checkStructure(path, kind, nullptr, 0);
}

DecodedPixels decodeExport(const fs::path& path, SourceKind kind, DecodeReport* report,
                           const DecodeOptions& options) {
  DecoderMessages messages(libraryOf(kind));
  DecodedPixels im;
  if (kind == SourceKind::Tiff) {
    const ImageProbe probe = checkStructure(path, kind, nullptr, 0);
    checkDeclaredSize(path, static_cast<std::uint64_t>(probe.width), static_cast<std::uint64_t>(probe.height), options);
    im = decodeTiff(path, options, messages);
  } else {
    const std::string bytes = readFile(path, kStep);
    im = decodeHeldBytes(path, kind, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), options,
                         messages);
  }
  if (report) {
    *report = DecodeReport{};
    report->decoder = kind == SourceKind::Jpeg ? libjpegName() + " " + libjpegVersion()
                      : kind == SourceKind::Png ? "libpng " + libpngVersion()
                                                : "libtiff " + libtiffVersion();
  }
  settle(messages, path, options, report);
  return im;
}

DecodedPixels decodePicture(const std::uint8_t* data, std::size_t size, const std::string& name,
                            std::uint64_t maxPixels) {
  const std::optional<SourceKind> kind = jpegOrPngBySignature(data, size);
  if (!kind) throwInputError(name, kStep, "is not a PNG or JPEG picture");
  DecodeOptions options;
  options.maxPixels = maxPixels;
  DecoderMessages messages(libraryOf(*kind));
  DecodedPixels im = decodeHeldBytes(name, *kind, data, size, options, messages);
  settle(messages, name, options, nullptr);
  return im;
}

}  // namespace surrogate::image
