// Colour-accuracy levels of imaging guidelines. See quality_levels.h.
//
// FADGI 2023: Federal Agencies Digital Guidelines Initiative, "Technical Guidelines for
//   Digitizing Cultural Heritage Materials", 3rd edition (May 2023), performance levels for
//   reflective originals: colour accuracy as CIEDE2000, mean and 90th percentile over the
//   target's patches:
//                    4 star   3 star   2 star   1 star
//     mean            2.0      3.5      5.0      6.5
//     90th pct.       4        7        10       13
//   Transcribed from the FADGI / ISO 19264-1 / Metamorfoze comparison table at
//   https://skandalski.pl/tabela-fadgi-iso-metamorfoze/ (FADGI 2023 columns); the FADGI PDF itself
//   (digitizationguidelines.gov) was not at hand. The table writes "<"; the limits are taken as
//   inclusive here (<=), as our specification states them.
// Metamorfoze 2.0: Metamorfoze Preservation Imaging Guidelines, version 2.0 (draft, June 2023),
//   as announced at https://preservationimaging.com/version-2/: colour accuracy by CIEDE2000
//   with S_L = 1 (CIE 1976 is no longer used),
//     Metamorfoze Full   mean <= 3, max <= 7
//     Metamorfoze Light  mean <= 4, max <= 14
//   Metamorfoze Extra Light sets no colour-accuracy limit there, so it is not listed.
#include "colour/quality_levels.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace surrogate::colour {
namespace {

struct Stats {
  double mean = 0, max = 0, p90 = 0;
};

Stats stats(std::vector<double> v) {
  Stats s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  s.max = v.back();
  const double rank = 0.9 * static_cast<double>(v.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(rank));
  const size_t above = std::min(below + 1, v.size() - 1);
  s.p90 = v[below] + (rank - static_cast<double>(below)) * (v[above] - v[below]);
  return s;
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", v);
  return text;
}

}  // namespace

ChartFigures chartFigures(const std::vector<double>& deltaE2000s) {
  const Stats s = stats(deltaE2000s);
  ChartFigures f;
  f.mean = s.mean;
  f.max = s.max;
  f.p90 = s.p90;
  f.patches = static_cast<int>(deltaE2000s.size());
  return f;
}

ChartFigures chartFigures(const std::vector<double>& deltaE2000s,
                          const std::vector<double>& deltaE2000UnitSLs) {
  ChartFigures f = chartFigures(deltaE2000s);
  const Stats s = stats(deltaE2000UnitSLs);
  f.meanUnitSL = s.mean;
  f.maxUnitSL = s.max;
  f.unitSL = !deltaE2000UnitSLs.empty();
  return f;
}

std::vector<LevelVerdict> qualityLevels(const ChartFigures& figures) {
  std::vector<LevelVerdict> out;
  struct Fadgi {
    const char* level;
    double mean, p90;
  };
  for (const Fadgi& l : {Fadgi{"4 star", 2.0, 4.0}, Fadgi{"3 star", 3.5, 7.0},
                         Fadgi{"2 star", 5.0, 10.0}, Fadgi{"1 star", 6.5, 13.0}})
    out.push_back({"FADGI 2023", l.level,
                   "mean dE2000 <= " + number(l.mean) + ", 90th percentile <= " + number(l.p90) +
                       " (FADGI Technical Guidelines, 3rd edition, 2023)",
                   figures.patches > 0 && figures.mean <= l.mean && figures.p90 <= l.p90});

  const double mean = figures.unitSL ? figures.meanUnitSL : figures.mean;
  const double max = figures.unitSL ? figures.maxUnitSL : figures.max;
  const std::string how = figures.unitSL
                              ? ""
                              : "; judged here on standard dE2000, which is never larger";
  struct Metamorfoze {
    const char* level;
    double mean, max;
  };
  for (const Metamorfoze& l : {Metamorfoze{"Full", 3.0, 7.0}, Metamorfoze{"Light", 4.0, 14.0}})
    out.push_back({"Metamorfoze 2.0", l.level,
                   "mean dE2000 (S_L = 1) <= " + number(l.mean) + ", max <= " + number(l.max) +
                       " (Metamorfoze Preservation Imaging Guidelines 2.0, 2023" + how + ")",
                   figures.patches > 0 && mean <= l.mean && max <= l.max});
  return out;
}

std::string bestLevel(const std::vector<LevelVerdict>& verdicts, const std::string& guideline) {
  // Verdicts are listed best first within a guideline: the first met is the best.
  for (const LevelVerdict& v : verdicts)
    if (v.guideline == guideline && v.met) return v.level;
  return "";
}

}  // namespace surrogate::colour
