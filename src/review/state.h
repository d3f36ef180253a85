// What the review page shows of a capture, read from its carrier and its folders: the frames
// with their highlights and flags, the spheres, the lights on the hemisphere, the checks, the
// standing decisions, the description and the last run, as one JSON object; and each frame's
// preview, made in memory from the image the run decodes (never written anywhere).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace surrogate::review {

// "sha256:HEX" of the capture's carrier file as it is now, or "none" when it has none: the
// revision every state carries and every Apply names.
std::string captureRevision(const std::filesystem::path& capture);

// One frame of the capture: the image of a shot the run decodes (or would decode).
struct Frame {
  std::string name;  // the shot ("IMG_0003"), as --exclude and --highlight name it
  std::string path;  // relative to the capture
};

struct CaptureState {
  std::string revision;
  std::vector<Frame> frames;
  std::vector<std::pair<std::string, std::string>> decodeSettings;  // the recorded LibRaw settings
  int frameWidth = 0, frameHeight = 0;  // of the images the run decodes
  std::string json;  // the page's state (see state.cpp for its members)
};

// Reads the capture (names and headers, and the carrier when there is one). `who` is shown as
// the person the decisions will be recorded as made by. Throws Error(Input) for a folder that
// is not a capture or a carrier that cannot be read.
CaptureState readCaptureState(const std::filesystem::path& capture, const std::string& who, int threads);

// The frame as a JPEG whose longer side is at most `maxSide` (sRGB, for display): decoded from
// the capture's file with the recorded settings, made in memory; a camera raw frame at least
// twice `maxSide` (`frameLongSide`) is decoded at half size (LibRaw's 2x2 cells, 4x faster),
// which still gives `maxSide`. Throws Error(Input) naming the file when it cannot be decoded.
std::string framePreview(const std::filesystem::path& capture, const Frame& frame,
                         const std::vector<std::pair<std::string, std::string>>& decodeSettings, int maxSide,
                         int frameLongSide);

}  // namespace surrogate::review
