// The report's trends over a span of blocks, against clock time (UTC) with the input speed
// overlaid on a right-hand axis. Limits are drawn only over the blocks where they were in
// force (learned or configured): a baseline still being learned has none, and a line at 0
// would read as "everything is over the limit".
//
// Elements: polyline.trend-reconstructed / .trend-raw / .trend-threshold (data-shaft),
// polyline.trend-speed, polyline.trend-score, rect.score-band-alert / .score-band-alarm,
// circle.trend-state (data-state, data-t0-ns).
#pragma once

#include <string>
#include <vector>

#include "tools/report/report_data.h"

namespace gearpath::tools {

// Reconstructed (solid), raw (dotted) and reconstructed threshold (dashed, learned blocks only)
// per shaft, against time; speed (grey) on the right axis.
std::string TrendSvg(const std::vector<ReportTrendPoint>& trend,
                     const std::vector<std::string>& shaft_names);

// Block score in units of the limit against time, one dot per block coloured by state, over
// the alert band (clear level .. limit: an alarm holds but does not rise) and the alarm band
// (over the limit), both only where the limit was in force; speed on the right axis.
std::string ScoreTrendSvg(const std::vector<ReportTrendPoint>& trend);

}  // namespace gearpath::tools
