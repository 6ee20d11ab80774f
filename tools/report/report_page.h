// The `gearpath report` page: one self-contained XHTML document (inline CSS and SVG, no script,
// no external resource) with, for one block: the verdict, the path contribution bars, the
// kurtograms of the raw and the reconstructed signal with the chosen band, their squared
// envelope spectra with each shaft's harmonics marked, and the indicator table; for a span,
// also the indicator trend and a per-block table.
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
