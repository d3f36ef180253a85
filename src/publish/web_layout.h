// The web layout of a relightable model: the folder that OpenLIME's RTI layer and Relight's
// web viewer read (docs/formats.md, "The web layout"): an info.json naming the basis, the
// size, the colour space and, per coefficient, the scale and bias that turn a plane's byte
// into the coefficient, plus the coefficient planes as JPEG images, three coefficients per
// image (plane_0.jpg, plane_1.jpg, ...).
//
//   PTM LRGB  "ptm"/"lrgb", 9 planes:  plane_0 = colour, plane_1 = (1, u, v), plane_2 = (u^2, uv, v^2)
//   PTM RGB   "ptm"/"rgb", 18 planes:  plane_j = term j of (1, u, v, u^2, uv, v^2) for R, G, B
//   HSH       "hsh"/"rgb", 12 or 27:   plane_j = HSH term j for R, G, B
//   coefficient = (byte / 255 - bias) * scale; the viewer's value, 0..1, is display sRGB
//
// The bytes are the model's own bytes (moved between planes, never re-quantised); only the
// JPEG compression changes them. Rows are top-first, as the model's image; the light is the
// model's (x right, y up). The folder is written under a temporary name beside the final one
// and renamed into place when complete, so an interrupted publish never leaves a folder that
// looks finished.
//
//   PublishOptions options;  options.quality = 90;
//   std::vector<PublishedModel> done = publish("finished-files/stela.ptm", "web/stela", options);
//   // web/stela/info.json, web/stela/plane_0.jpg ...
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/memory_budget.h"

#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace surrogate::carrier {
struct Header;
struct Carrier;
}

namespace surrogate::publish {

// How the planes are stored: whole images (plane_N.jpg), Deep Zoom tiles (plane_N.dzi and
// plane_N_files/), or tiles only for a model with a side over kAutoTileSide.
enum class TileLayout { Auto, None, DeepZoom };

// A side beyond which `auto` tiles: about twice a large screen's width; below it a viewer
// loads the whole plane at once without trouble.
constexpr int kAutoTileSide = 4096;

// What the pages of a web copy say about the capture (carrier::Header's title, creators,
// rights and licence); all empty for a lone model file. Any text: the pages escape it.
struct WebDescription {
  std::string title;
  std::vector<std::pair<std::string, std::string>> creators;  // name, role
  std::string rights;
  std::string license;  // a URI is shown as a link when it is http:// or https://
  // The elevations of the photographed lights in degrees, lowest and highest, when known (the
  // carrier's last light estimation): the viewer's disc shades them and says when the chosen
  // light is outside them, where the relighting is extrapolated. A lone model file has none.
  std::optional<std::pair<double, double>> lightElevationsDeg;
};

// The description of a capture from its carrier's header.
WebDescription webDescriptionOf(const carrier::Header& header);
// The same with the photographed lights' elevations the carrier records (web_description.cpp).
WebDescription webDescriptionOf(const carrier::Carrier& carrier);

struct PublishOptions {
  // JPEG quality 1..100 of the planes: lower gives smaller files and a larger error in the
  // relit image (docs/formats.md, "The web layout", has the measured figures).
  int quality = 95;
  // Learned layouts only (learned_layout.h): one quality per JPEG plane, nplanes / 3 of them,
  // so that planes of little energy can be compressed harder; empty = `quality` for all.
  // info.json's "quality" is then the highest used.
  std::vector<int> planeQualities;
  // Learned layouts: when > 0 (and planeQualities is empty), the JPEG planes go from `quality`
  // (the first, the planes of most energy) to this (the last) in equal steps, rounded: the later
  // planes carry little of the image and lose little to a harder compression (docs/formats.md).
  int lastQuality = 0;
  // Tiles let a web viewer load only the part and the resolution on screen, at the cost of
  // many small files and a third more bytes (the reduced levels).
  TileLayout tiles = TileLayout::Auto;
  // Side of a Deep Zoom tile in texels, 16..4096: larger tiles mean fewer files and requests,
  // smaller ones less data loaded beyond the screen's edge.
  int tileSize = 256;
  // Worker threads for the tiles, normals and albedo (0 = all cores). Not a setting of the
  // result: the bytes written are the same at any count.
  int threads = 0;
  // --memory: a model whose reading and publishing would take more (a copy of the model and
  // kPublishBytesPerTexel a texel beside it) is refused from its header, before it is decoded
  // (core/memory_budget.h). Not a setting of the result either.
  std::uint64_t memoryBudget = kDefaultMemoryBudget;
  // Shown by index.html (viewer.h); publish() of a capture fills it from the carrier.
  WebDescription description;
};

// What publishing holds beside the model: its planes as images (a copy of the model's size)
// and, per texel, their JPEG streams, the normals and albedo and the viewer's copies: 9 bytes
// measured with /usr/bin/time on a 12000x12000 LRGB PTM of even planes (3.8 GB at the peak),
// 12 with a margin. Planes of pure noise compress far less (2000x2000 HSH of 9 terms filled
// with random bytes: 94 bytes a texel beside the model): the check is about headers that
// declare what their file cannot hold, not an exact account.
inline constexpr std::uint64_t kPublishBytesPerTexel = 12;

// Surrogate's name of a published model's basis: "ptm-lrgb", "ptm-rgb", "hsh1", "hsh2", "hsh3".
struct PublishedModel;
std::string basisOf(const PublishedModel& model);

// The page of a folder of published models (index.html beside their folders): the description,
// each model's basis and a link to FOLDER/index.html, in the order given; same bytes for the
// same arguments. `basis` as basisOf gives it.
struct IndexedModel {
  std::string folder;  // the model folder's name
  std::string basis;
};
std::string webIndexHtml(const WebDescription& description, const std::vector<IndexedModel>& models);

// "auto", "none", "deepzoom" (the command line's and the carrier's spelling).
const char* tileLayoutName(TileLayout tiles);
// Throws Error(Usage) naming "--tiles" for any other name.
TileLayout parseTileLayout(const std::string& name);

// What one published model holds.
struct PublishedModel {
  std::string source;      // the .ptm or .rti, as given (a capture: relative to it)
  std::string folder;      // the folder written, relative to the output folder ("" = itself)
  std::string type;        // "ptm" or "hsh"
  std::string colorspace;  // "lrgb" or "rgb"
  int width = 0, height = 0;
  int nplanes = 0;         // coefficients per texel (the JPEGs hold three each)
  std::string tiles;       // "deepzoom" when the planes are tiled, "" for whole images
  int levels = 1;          // Deep Zoom levels (1 when not tiled)
  std::vector<std::string> files;  // info.json, the planes (or .dzi and tiles), index.html,
                                   // viewer-data.js; relative to `folder`
};

// The info.json and the planes of one model, in memory: name -> bytes, info.json first.
struct WebLayoutFiles {
  PublishedModel model;
  std::vector<std::pair<std::string, std::string>> files;
};

// Throws Error(Usage) naming "--quality" for a quality outside 1..100, "--tile-size" for a tile
// size outside 16..4096. Computes the normals and albedo the viewer shows (fit/normals.h).
WebLayoutFiles webLayoutOf(const formats::PtmFile& ptm, const PublishOptions& options);
// Throws Error(Input) for 16 terms (order 4): the web viewers evaluate HSH up to order 3.
WebLayoutFiles webLayoutOf(const formats::HshFile& hsh, const PublishOptions& options);

// The layout of a model file as Surrogate reads it (a .ptm of any variant or an HSH .rti, told
// by its first bytes), in memory; what `surrogate run --publish` records (stages/web_copy_stage.h).
// Throws Error(Input) naming the file for any other file.
WebLayoutFiles webLayoutOfFile(const std::filesystem::path& file, const PublishOptions& options);

// Publishes `source` into the folder `out`, which must not exist or be empty:
//   a .ptm (raw or JPEG-compressed) or an HSH .rti: `out` holds its layout;
//   a capture folder: each PTM or HSH result its carrier records in finished-files/, in a
//   subfolder of `out` named after the file (finished-files/stela-hsh.rti -> out/stela-hsh/),
//   and out/index.html linking them; the pages show the carrier's title, creators, rights
//   and licence (options.description is replaced by them).
// Throws Error(Input) for a source that is neither, or a capture with no such result, and
// Error(Usage) naming `out` when it is a file or a folder that is not empty.
// First removes the hidden partial folders that killed publishes left beside `out` (those whose
// process no longer runs); `removedLeftovers`, when given, receives one sentence for each.
std::vector<PublishedModel> publish(const std::filesystem::path& source, const std::filesystem::path& out,
                                    const PublishOptions& options,
                                    std::vector<std::string>* removedLeftovers = nullptr);

// Writes `layout`'s files (webLayoutOf's, any kind) into the folder `out` as publish() writes a
// model: `out` must not exist or be empty, the files go into a hidden partial folder beside it
// renamed into place when complete, and killed publishes' leftovers are removed first. Throws
// Error(Usage) naming `out` when it is a file or a folder that is not empty.
void writeWebLayoutFolder(const WebLayoutFiles& layout, const std::filesystem::path& out);

// What a web layout's info.json says (any writer's, Surrogate's or relight's), checked against
// the plane files beside it, for `surrogate info DIR/info.json`.
struct WebLayoutSummary {
  std::string type, colorspace;  // as info.json names them
  int width = 0, height = 0;
  int nplanes = 0;               // coefficients per texel
  int quality = -1;              // -1 when info.json does not say
  std::string format;            // the planes' extension ("jpg")
  std::string basis;             // Surrogate's name: "ptm-lrgb", "ptm-rgb", "hsh2", "hsh3", and
                                 // "rbf", "bln" (learned, "mrgb"); "" else
  int resolution = 0;            // bilinear: the grid's side; else 0
  int nodes = 0;                 // learned: the basis's nodes (rbf: lights; bilinear: resolution^2)
  std::vector<std::string> planes;         // the plane files the layout names, in order
  std::vector<std::string> missingPlanes;  // those not beside info.json, in no form
  std::string tiles;             // "deepzoom" or "tarzoom" when planes are tiled; "" else
  std::uint64_t bytes = 0;       // info.json and the untiled planes present
};

// Throws Error(Input) naming the file when it is not JSON or lacks a member the viewers need
// (width, height, type, colorspace, nplanes, materials with scale and bias of nplanes values).
WebLayoutSummary describeWebLayout(const std::filesystem::path& infoJson);

}  // namespace surrogate::publish
