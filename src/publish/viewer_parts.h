// Private to src/publish: parts of the published viewer's page (viewer.cpp) in files of their
// own, put into the page where it names them (@DISC@, @DISC_STYLE@, @DISC_SCRIPT@, @SHADER_SCRIPT@).
//
// The light disc (viewer_disc.cpp) shows the light's direction with its azimuths and elevation
// rings labelled, shades the elevations the capture's lights were photographed at, and says in
// words when the chosen light is outside them. The shaders (web/shader.js) relight the texels.
#pragma once

#include <string>

#include "publish/web_files.h"
#include "publish/web_layout.h"

namespace surrogate::publish {

// The disc's markup: the canvas in a holder that carries the photographed elevations
// (data-photographed="LOWEST,HIGHEST", absent when unknown), the readout and the notes.
std::string discHtml(const WebDescription& description);

// CSS rules of the disc, for the page's <style>.
extern const char* const kDiscStyle;

// Functions for the page's script, in its scope (after `degree`): fixed(value, digits),
// discRadius(pad), labelDisc(pad), drawDisc(pad, angles) and describeLight(pad, angles, light).
extern const char* const kDiscScript;

// The script's vertexSource and fragmentSource, GLSL ES 3.0 as JavaScript strings: web/shader.js,
// kShaderScript in the generated publish/web_files.h.

}  // namespace surrogate::publish
