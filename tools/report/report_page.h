// The `gearpath report` page: one self-contained XHTML document (inline CSS and SVG, no script,
// no external resource) with, for one block: the verdict, overall statistics per channel, the
// time waveform, the path contribution bars, the spectrum around each mesh frequency with
// sideband cursors, the contribution spectra with their sum against the measured one, the
// kurtograms (one colour scale) with the chosen band, the squared envelope spectra with each
// shaft's harmonics marked, the indicator table, the synchronous averages and the condition
// indicators; for a span, also the score and indicator trends against UTC time with the speed
// overlaid, and a per-block table. Times are UTC; limits appear only where they were in force.
//
// The document is well-formed XML (every text escaped, no HTML-only entity), so it parses with
// any XML parser as well as in a browser. Table cells with numbers carry the exact value in a
// data-value attribute (shortest round-trip form) next to the rounded display.
#pragma once

#include <string>

#include "tools/report/report_data.h"

namespace gearpath::tools {

std::string RenderReportHtml(const ReportData& data);

}  // namespace gearpath::tools
