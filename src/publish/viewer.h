// Private to src/publish: the viewer written into every published model folder, index.html
// and viewer-data.js (docs/formats.md, "The viewer").
//
// A page opened from file:// may neither fetch() a file nor give WebGL an image loaded from a
// file:// address (it counts as another origin), so the page cannot read plane_N.jpg; it reads
// viewer-data.js, loaded by a <script> tag, which holds the planes (and the normals and
// albedo pictures) as data: URIs of JPEG bytes. These are the Deep Zoom level that fits in
// kViewerMaxSide texels: the model itself when it fits (the same bytes as plane_N.jpg), a
// reduced level of a larger one.
//
//   ViewerData data{infoJsonText, width, height, halvings, level, planeJpegs, normalsJpeg, albedoJpeg};
//   files.emplace_back("index.html", viewerHtml(description, "ptm-lrgb"));
//   files.emplace_back("viewer-data.js", viewerDataJs(data));
//
// The page names what it shows (the capture's title, creators, rights and licence, and the
// basis), escaped for HTML; it zooms and pans the picture (wheel, drag, pinch) and relights
// the texels on screen, texel by texel, at any zoom.
//
// The page's code is web code in web/ (viewer.html, viewer.css, shader.js and viewer_*.js, one
// concern a file; index.html for the index of several models), embedded at build time
// (publish/web_files.h); viewer.cpp only fills in the description and the data.
#pragma once

#include <string>
#include <vector>

#include "publish/web_layout.h"

namespace surrogate::publish {

// The largest side the viewer holds: a large screen's width, which keeps viewer-data.js at a
// quarter of the planes' size or less for any model larger than that.
constexpr int kViewerMaxSide = 2048;

// The viewer page of a model of `basis` (ptm-lrgb, ptm-rgb, hsh1, hsh2, hsh3): the same bytes
// for the same description and basis.
std::string viewerHtml(const WebDescription& description, const std::string& basis);

// "PTM LRGB", "PTM RGB", "HSH order 2"...; the basis itself for any other text.
std::string basisLabel(const std::string& basis);

struct ViewerData {
  std::string infoJson;           // the folder's info.json, as written
  int width = 0, height = 0;      // of the level held
  int halvings = 0;               // 0: the model's own size; k: halved k times
  int level = -1;                 // its Deep Zoom level when the planes are tiled, else -1
  std::vector<std::string> planes;  // JPEG bytes of plane 0, 1, ... at that level
  std::string normals, albedo;      // JPEG bytes, same size
};

std::string viewerDataJs(const ViewerData& data);

}  // namespace surrogate::publish
