// The pictures of `gearpath report`, as standalone inline SVG fragments written by hand (no
// script, no external font or stylesheet, so a page opens the same offline and in ten years).
//
// Every drawn element that a test or a reader may want to find carries a class and data-*
// attributes: one rect.path-bar per transfer path (data-path, data-share), rect.kurtogram-cell
// per kurtogram band and one rect.chosen-band around the band the envelope used, one
// line.harmonic-marker per shaft harmonic (data-shaft, data-harmonic, data-hz), and one
// circle.harmonic-reading per value the indicator summed. All text is XML-escaped.
#pragma once

#include <string>
#include <vector>

#include "tools/report/report_data.h"

namespace gearpath::tools {

// Bar chart of the paths' contribution-energy shares (percent), the dominant path highlighted.
std::string PathBarsSvg(const std::vector<ReportPath>& paths, int dominant_path);

// Kurtogram heat map: rows = levels (0 at the top), columns = frequency 0..Nyquist, colour =
// spectral kurtosis from 0 to `sk_max` (values below 0 drawn as 0, above as sk_max), colour-
// scale legend, chosen band outlined. Maps shown side by side get the same sk_max.
std::string KurtogramSvg(const ReportKurtogram& map, double sk_max);

// Squared envelope spectrum from 0 to `max_hz` on a y axis 0..`y_max`, with a dashed vertical
// marker at each shaft's first five harmonics and a dot at each harmonic amplitude the indicator
// read (raw or reconstructed harmonics of ReportShaft, by `reconstructed`).
std::string SesSvg(const ReportSes& ses, const std::vector<ReportShaft>& shafts, double max_hz,
                   double y_max, bool reconstructed);

// The trends over a span are in trend_charts.h; the signal pictures in signal_charts.h.

}  // namespace gearpath::tools
