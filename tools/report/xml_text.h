// Text for hand-written SVG/XHTML: escaping and number formatting.
//
// Every string that reaches the page (machine ids, path names, file paths, reasons) goes
// through XmlEscape, so a name like "B<1>&x" cannot break the markup; the page is then
// well-formed XML (an XHTML document whose SVG parts are inline), which the tests parse.
#pragma once

#include <string>
#include <string_view>

namespace gearpath::tools {

// & < > " ' replaced by their XML entities; control characters other than tab, newline and
// carriage return (not allowed in XML 1.0) replaced by '?'.
std::string XmlEscape(std::string_view text);

// Compact display form with `digits` significant digits ("0.0123", "1.23e+05"); "-" for NaN.
std::string DisplayNumber(double value, int digits = 4);

// Shortest text that reads back to exactly `value` (for data-value attributes).
std::string ExactNumber(double value);

}  // namespace gearpath::tools
