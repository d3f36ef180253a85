// The published viewer's pages filled in: the page (web/viewer.html with its style and scripts,
// embedded at build time as publish/web_files.h) gets the description, escaped here, and the
// elevations photographed; the model's data go to viewer-data.js, one JavaScript assignment of
// one object (publish/viewer.h). The index of several models (web/index.html) gets their list.
#include "publish/viewer.h"

#include <cstdio>
#include <utility>

#include "core/base64.h"
#include "core/text.h"
#include "publish/web_files.h"

namespace surrogate::publish {

namespace {
std::string jpegUri(const std::string& bytes) { return "\"data:image/jpeg;base64," + base64(bytes) + "\""; }

// A folder name as a relative URL's path segment: every byte but the unreserved ones of RFC
// 3986 percent-encoded (a folder named after a file may hold spaces, '#', '?' or '%').
std::string segment(const std::string& name) {
  static const char* const hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : name) {
    if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '.' ||
        c == '_' || c == '~') {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

// Only a web address becomes a link: any other scheme (javascript:, data:, file:) stays text.
bool isWebAddress(const std::string& text) {
  auto startsWith = [&](const char* p) { return text.compare(0, std::char_traits<char>::length(p), p) == 0; };
  return (startsWith("https://") || startsWith("http://")) && text.find_first_of(" \t\r\n\"<>") == std::string::npos;
}

std::string shownTitle(const WebDescription& d) { return d.title.empty() ? "Relightable model" : d.title; }

// The page's head of description: title, creators with roles, rights, licence and, when
// given, the model's basis. Elements without text are left out.
std::string aboutHtml(const WebDescription& d, const std::string& basis) {
  std::string out = "<h1 id=\"title\">" + escapeHtml(shownTitle(d)) + "</h1>\n";
  if (!d.creators.empty()) {
    out += "<p id=\"creators\">By ";
    for (std::size_t i = 0; i < d.creators.size(); ++i) {
      if (i) out += "; ";
      out += "<span class=\"creator\">" + escapeHtml(d.creators[i].first);
      if (!d.creators[i].second.empty()) out += " (" + escapeHtml(d.creators[i].second) + ")";
      out += "</span>";
    }
    out += "</p>\n";
  }
  if (!d.rights.empty()) out += "<p id=\"rights\">Rights: " + escapeHtml(d.rights) + "</p>\n";
  if (!d.license.empty()) {
    out += "<p id=\"license\">Licence: ";
    out += isWebAddress(d.license) ? "<a href=\"" + escapeHtml(d.license) + "\" rel=\"license\">" + escapeHtml(d.license) + "</a>"
                                   : escapeHtml(d.license);
    out += "</p>\n";
  }
  if (!basis.empty())
    out += "<p id=\"basis\">Model: " + escapeHtml(basisLabel(basis)) + " (" + escapeHtml(basis) + ")</p>\n";
  return out;
}

// A web file as the page holds it: without the comment it opens with ("<!-- ... -->\n" for HTML,
// "/* ... */\n" for CSS), which says what the file is to whoever edits it. A script keeps its
// comments: it is what ESLint checked.
std::string withoutOpeningComment(const char* file, const std::string& open, const std::string& close) {
  const std::string text = file;
  if (text.compare(0, open.size(), open) != 0) return text;
  return text.substr(text.find(close) + close.size());
}

// The template with each of its markers replaced by its value, in one pass: the values (a
// description may hold anything, even a marker) are never searched for markers themselves.
std::string filled(const std::string& page, const std::vector<std::pair<std::string, std::string>>& values) {
  std::string out;
  std::size_t from = 0;
  for (;;) {
    std::size_t at = std::string::npos;
    const std::pair<std::string, std::string>* first = nullptr;
    for (const auto& v : values) {
      const std::size_t found = page.find(v.first, from);
      if (found < at) at = found, first = &v;
    }
    if (!first) break;
    out.append(page, from, at - from).append(first->second);
    from = at + first->first.size();
  }
  return out.append(page, from);
}

std::string degrees(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v + 0.0);
  return buf;
}

// The disc's holder's attribute giving the elevations photographed (web/viewer_geometry.js's
// photographedRange reads it), or nothing when they are not known.
std::string photographedAttribute(const WebDescription& d) {
  if (!d.lightElevationsDeg) return "";
  return " data-photographed=\"" + degrees(d.lightElevationsDeg->first) + "," + degrees(d.lightElevationsDeg->second) +
         "\"";
}
}  // namespace

std::string basisLabel(const std::string& basis) {
  if (basis == "ptm-lrgb") return "PTM LRGB";
  if (basis == "ptm-rgb") return "PTM RGB";
  if (basis.size() == 4 && basis.compare(0, 3, "hsh") == 0 && basis[3] >= '1' && basis[3] <= '3')
    return std::string("HSH order ") + basis[3];
  if (basis == "rbf") return "RBF (learned)";
  if (basis == "bln") return "Bilinear (learned)";
  return basis;
}

std::string viewerHtml(const WebDescription& description, const std::string& basis) {
  return filled(withoutOpeningComment(kViewerPage, "<!--", "-->\n"),
                {{"@STYLE@", withoutOpeningComment(kViewerStyle, "/*", "*/\n")},
                 {"@ERRORS_SCRIPT@", kErrorsScript},
                 {"@GEOMETRY_SCRIPT@", kGeometryScript},
                 {"@RELIGHTING_SCRIPT@", kRelightingScript},
                 {"@SHADER_SCRIPT@", kShaderScript},
                 {"@WEBGL_SCRIPT@", kWebglScript},
                 {"@DISC_SCRIPT@", kDiscScript},
                 {"@GESTURES_SCRIPT@", kGesturesScript},
                 {"@UI_SCRIPT@", kUiScript},
                 {"@TITLE@", escapeHtml(shownTitle(description) + " (" + basisLabel(basis) + ")")},
                 {"@ABOUT@", aboutHtml(description, basis)},
                 {"@PHOTOGRAPHED@", photographedAttribute(description)}});
}

std::string webIndexHtml(const WebDescription& description, const std::vector<IndexedModel>& models) {
  std::string list;
  for (const IndexedModel& m : models) {
    // A learned basis has no page of its own: this viewer draws PTM and HSH only; its folder
    // is what OpenLIME's RTI layer or relight's viewer reads.
    const bool learned = m.basis == "rbf" || m.basis == "bln";
    list += "<li><a href=\"" + segment(m.folder) + (learned ? "/info.json" : "/index.html") + "\">" +
            escapeHtml(basisLabel(m.basis)) + "</a> (" + escapeHtml(m.basis) + "), in " + escapeHtml(m.folder) + "/" +
            (learned ? " (for OpenLIME or relight's viewer)" : "") + "</li>\n";
  }
  return filled(withoutOpeningComment(kIndexPage, "<!--", "-->\n"), {{"@TITLE@", escapeHtml(shownTitle(description))},
                                                                      {"@ABOUT@", aboutHtml(description, "")},
                                                                      {"@MODELS@", list}});
}

std::string viewerDataJs(const ViewerData& d) {
  std::string js =
      "// Written by Surrogate's publish for index.html: the planes of info.json at the size the viewer\n"
      "// shows, the normals and the albedo, as data: URIs of JPEG images (a page opened from file://\n"
      "// cannot read the plane files themselves).\n"
      "window.surrogateViewerData = {\n\"info\": " + d.infoJson + ",\n\"width\": " + std::to_string(d.width) +
      ", \"height\": " + std::to_string(d.height) + ", \"halvings\": " + std::to_string(d.halvings) +
      ", \"level\": " + std::to_string(d.level) + ",\n\"planes\": [";
  for (std::size_t j = 0; j < d.planes.size(); ++j) js += (j ? ",\n" : "\n") + jpegUri(d.planes[j]);
  js += "],\n\"normals\": " + jpegUri(d.normals) + ",\n\"albedo\": " + jpegUri(d.albedo) + "\n};\n";
  return js;
}

}  // namespace surrogate::publish
