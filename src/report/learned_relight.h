// Private to src/report: a learned model (fit/learned.h: rbf or bilinear, written by LearnedFit
// as finished-files/<basis>/info.json and its planes) for the relighting view, as the page's
// script relights it: the viewer's own interpolation of the basis over the light (OpenLIME's,
// as fit/learned_render.cpp computes it), then out_k = W_0k + sum_p W_(p+1)k c_p.
//
//   {"model":"learned","basis":"rbf"|"bln","width":w,"height":h,"originalWidth":W,
//    "originalHeight":H,"planes":P,"resolution":R (bln),"nodes":[x,y,z,...] (rbf: the lights),
//    "range":[P],"scale":[P],"bias":[P],"basisBytes":base64 ((P+1) x nodes x 3),
//    "coefficients":base64 (texel-interleaved: (y*w + x)*P + p)}
//
//   std::optional<std::string> json = learnedRelightFromSource(source, *infoRecord, 400, share);
#pragma once

#include <cstddef>
#include <string>

#include "fit/learned.h"
#include "report/report.h"

namespace surrogate::report {

// The copy keeps the model's resolution when its longer side is at most `maxSide` and its
// coefficients take at most `maxBytes` (0: no limit), else block averages of the coefficient
// bytes (exact in decoded units: the output is affine in each coefficient before the clamp).
std::string relightJson(const fit::LearnedModel& model, int maxSide, std::size_t maxBytes);

// The layout whose info.json the carrier records as `info` (kind learned-model), read from the
// source with the planes the carrier lists beside it. Throws Error(Input) for a malformed layout;
// nullopt when a file of it is not in the source.
std::optional<std::string> learnedRelightJson(const carrier::Carrier& c, const ReportSource& source,
                                              const carrier::FileRecord& info, int maxSide, std::size_t maxBytes);

}  // namespace surrogate::report
