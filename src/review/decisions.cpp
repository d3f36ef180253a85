#include "review/decisions.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/sphere_reference.h"
#include "core/text.h"

namespace surrogate::review {

namespace {

using nlohmann::json;

[[noreturn]] void refuse(const std::string& what, const std::string& why) {
  throw Error(ErrorKind::Usage, what, "review page", why);
}

json parse(const std::string& body) {
  json j = json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) refuse("the decisions sent", "are not a JSON object");
  return j;
}

std::string text(const json& object, const char* member, const std::string& where, bool required) {
  const auto it = object.find(member);
  if (it == object.end() || it->is_null()) {
    if (required) refuse(where, std::string("needs \"") + member + "\"");
    return "";
  }
  if (!it->is_string()) refuse(where + "." + member, "must be text");
  return it->get<std::string>();
}

// Pixels: a million is beyond any frame's side, and well within what the options' numbers
// carry (a larger value, 1e308, would overflow to infinity when rounded to tenths).
constexpr double kMaxPixels = 1e6;

double pixels(const json& value, const std::string& where) {
  if (!value.is_number()) refuse(where, "must be a number");
  const double v = value.get<double>();
  if (!std::isfinite(v) || std::fabs(v) > kMaxPixels) refuse(where, "must be a number of pixels, from -1000000 to 1000000");
  return v;
}

double number(const json& object, const char* member, const std::string& where) {
  const auto it = object.find(member);
  return pixels(it == object.end() ? json() : *it, where + "." + member);
}

int index(const json& object, const char* member, const std::string& where) {
  const auto it = object.find(member);
  if (it == object.end() || !it->is_number_integer() || it->get<long long>() < 0 || it->get<long long>() > 99)
    refuse(where + "." + member, "must be a sphere number from 0");
  return static_cast<int>(it->get<long long>());
}

// The members that are lists of objects, each visited with its place for messages.
template <class Visit>
void eachOf(const json& body, const char* member, Visit visit) {
  const auto it = body.find(member);
  if (it == body.end() || it->is_null()) return;
  if (!it->is_array()) refuse(member, "must be a list");
  for (std::size_t n = 0; n < it->size(); ++n) {
    const json& item = (*it)[n];
    const std::string where = std::string(member) + "[" + std::to_string(n) + "]";
    if (!item.is_object()) refuse(where, "must be an object");
    visit(item, where);
  }
}

}  // namespace

std::string coordinateText(double value) {
  const double tenths = std::round(value * 10) / 10;
  return formatNumber(tenths == 0 ? 0.0 : tenths);  // never "-0"
}

std::string revisionOf(const std::string& applyJson) {
  return text(parse(applyJson), "revision", "the decisions sent", false);
}

std::vector<std::string> argumentsFor(const std::string& applyJson) {
  const json body = parse(applyJson);
  std::vector<std::string> out;
  auto option = [&](const std::string& name, const std::string& value) {
    out.push_back("--" + name);
    out.push_back(value);
  };
  auto reason = [&](const std::string& value) {
    if (!value.empty()) option("reason", value);
  };

  if (const std::string title = text(body, "title", "the decisions sent", false); !title.empty()) option("title", title);
  if (const auto it = body.find("creators"); it != body.end() && !it->is_null()) {
    if (!it->is_array()) refuse("creators", "must be a list");
    for (const json& c : *it) {
      if (!c.is_string()) refuse("creators", "must be a list of names");
      if (!c.get<std::string>().empty()) option("creator", c.get<std::string>());
    }
  }
  for (const char* field : {"rights", "license"}) {
    const std::string v = text(body, field, "the decisions sent", false);
    if (!v.empty()) option(field, v);
  }
  eachOf(body, "meta", [&](const json& m, const std::string& where) {
    option("meta", text(m, "key", where, true) + "=" + text(m, "value", where, true));
  });
  eachOf(body, "spheres", [&](const json& s, const std::string& where) {
    option("sphere", coordinateText(number(s, "cx", where)) + "," + coordinateText(number(s, "cy", where)) + "," +
                         coordinateText(number(s, "r", where)));
    reason(text(s, "reason", where, false));
  });
  eachOf(body, "forgetSpheres", [&](const json& s, const std::string& where) {
    // Spheres as people name them, sphere1 for the first (core/sphere_reference.h).
    option("forget-sphere", sphereReference(index(s, "sphere", where)));
    reason(text(s, "reason", where, true));
  });
  eachOf(body, "highlights", [&](const json& h, const std::string& where) {
    option("highlight", text(h, "image", where, true) + ":" + sphereReference(index(h, "sphere", where)) + "=" +
                            coordinateText(number(h, "x", where)) + "," + coordinateText(number(h, "y", where)));
    reason(text(h, "reason", where, false));
  });
  eachOf(body, "forgetHighlights", [&](const json& h, const std::string& where) {
    option("forget-highlight", text(h, "image", where, true) + ":" + sphereReference(index(h, "sphere", where)));
    reason(text(h, "reason", where, true));
  });
  // The colour chart: its corners marked on a frame, or no chart (stages/colour_chart_options.h).
  if (const auto it = body.find("chart"); it != body.end() && !it->is_null()) {
    const json& chart = *it;
    if (!chart.is_object()) refuse("chart", "must be an object");
    if (const auto none = chart.find("none"); none != chart.end() && !none->is_null()) {
      if (!none->is_boolean() || !none->get<bool>()) refuse("chart.none", "must be true (or left out)");
      if (chart.contains("image") || chart.contains("corners")) refuse("chart", "gives no chart and a chart: give one");
      option("colour-chart", "none");
    } else {
      const auto corners = chart.find("corners");
      if (corners == chart.end() || !corners->is_array() || corners->size() != 8)
        refuse("chart.corners", "must be the four corners' 8 numbers x1,y1,...,x4,y4");
      std::string spec = text(chart, "image", "chart", true) + ":";
      for (std::size_t n = 0; n < 8; ++n) {
        spec += (n ? "," : "") + coordinateText(pixels((*corners)[n], "chart.corners[" + std::to_string(n) + "]"));
      }
      option("colour-chart", spec);
    }
    reason(text(chart, "reason", "chart", false));
  }
  // The decisions that name one thing (an image, a check) and need a reason, in this order.
  struct Named {
    const char* member;  // of the page's JSON
    const char* option;  // of surrogate run
    const char* names;   // the member of each item holding the name
  };
  for (const Named& n : {Named{"exclude", "exclude", "image"}, Named{"forgetExclusions", "forget-exclusion", "image"},
                         Named{"accept", "accept", "check"}, Named{"forgetAccept", "forget-accept", "check"}})
    eachOf(body, n.member, [&](const json& item, const std::string& where) {
      option(n.option, text(item, n.names, where, true));
      reason(text(item, "reason", where, true));
    });
  return out;
}

}  // namespace surrogate::review
