// The report renderer on hand-made data: escaping, well-formedness whatever the names, and the
// geometry rules (one marker per harmonic inside the plotted range, chosen band outlined).
#include "tools/report/report_page.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "tools/report/report_charts.h"
#include "tools/report/xml_text.h"

namespace gearpath::tools {
namespace {

std::size_t Count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto p = text.find(needle); p != std::string::npos; p = text.find(needle, p + 1)) ++n;
  return n;
}

ReportData HostileData() {
  ReportData d;
  d.machine_id = "m<1>&\"quoted\" 'x'";
  d.recording = "/tmp/a&b<c>";
  d.frf_source = "builtin:table1";
  d.paths = {{"B<1>x", "B1 & co", 0.7, 2.0, 1.0}, {"B2x", "\"B2\"", 0.3, 1.0, 0.5}};
  d.dominant_path = 0;
  d.indicator_channel = "p1 x";
  d.kurtogram_raw.title = "raw <k>";
  d.kurtogram_raw.nyquist_hz = 4000.0;
  d.kurtogram_raw.row_level = {0.0, 1.0};
  d.kurtogram_raw.rows = {{0.5}, {3.0, -1.0}};
  d.kurtogram_raw.chosen_row = 1;
  d.kurtogram_raw.chosen_index = 0;
  d.kurtogram_raw.significant = true;
  d.kurtogram_raw.low_hz = 0.0;
  d.kurtogram_raw.high_hz = 2000.0;
  d.kurtogram_reconstructed = d.kurtogram_raw;
  d.ses_raw.title = "ses & raw";
  d.ses_raw.bin_hz = 1.0;
  d.ses_raw.values.assign(100, 0.1);
  d.ses_reconstructed = d.ses_raw;
  ReportShaft a;
  a.name = "in<put>";
  a.rate_hz = 10.0;
  ReportShaft b;
  b.name = "out&put";
  b.rate_hz = 7.0;
  d.shafts = {a, b};
  d.state = "alarm";
  d.gear = "G<1>";
  d.shaft = a.name;
  d.reason = "because x < y & y > z";
  d.trend = {{0, 1, "B<1>x", "learning", "", {0.1, 0.2}, {0.3, 0.4}, {0.0, 0.0}},
             {1, 2, "B<1>x", "alarm", "G<1>", {0.1, 0.2}, {0.9, 0.4}, {0.5, 0.5}}};
  d.baseline_learned = 20;
  d.baseline_needed = 20;
  d.score = {6.0, 0.7, 1.5, "fm<4>", "B<1>x", "in<put>", 3, 5};
  d.condition = {{"measured", "p<1>/x", "in<put>", 0, 10.0, 20, 0.5, {{"fm<4>", 3.0, 2.0}}},
                 {"force", "B<1>x", "in<put>", 0, 10.0, 20, 1.5, {{"fm<4>", 9.0, -9.0}}},
                 {"measured", "p<1>/x", "out&put", 1, 7.0, 14, 0.1, {{"sideband_G1-G2", 1.0,
                                                                       0.5}}}};
  return d;
}

TEST(ReportPageTest, ConditionTablesShowEachIndicatorsValueAndZAndMarkZOverTheLimit) {
  const std::string html = RenderReportHtml(HostileData());
  // One table per rate group, one row per signal.
  EXPECT_EQ(Count(html, "<table class=\"condition\""), 2u);
  EXPECT_NE(html.find("data-group=\"1\""), std::string::npos);
  EXPECT_EQ(Count(html, "<tr data-signal="), 3u);
  // The limit in force and the block score.
  EXPECT_NE(html.find("1.5 of the limit (z 9)"), std::string::npos);
  EXPECT_NE(html.find("|z| 6 (from the false-alarm rate)"), std::string::npos);
  EXPECT_NE(html.find("3 of the last 5 blocks"), std::string::npos);
  // |z| = 9 > 6 is red (value, z and the set score 1.5 > 1); z = 2 is not.
  EXPECT_NE(html.find("<td data-value=\"-9\" class=\"over\">"), std::string::npos);
  EXPECT_NE(html.find("<td data-value=\"9\" class=\"over\">"), std::string::npos);
  EXPECT_NE(html.find("<td data-value=\"2\">"), std::string::npos);
}

TEST(ReportPageTest, ConditionIndicatorsAreNotJudgedWhileTheBaselineIsLearned) {
  ReportData d = HostileData();
  d.score.limit_z = 0.0;
  d.baseline_learned = 7;
  const std::string html = RenderReportHtml(d);
  EXPECT_EQ(Count(html, "<table class=\"condition\""), 0u);
  EXPECT_NE(html.find("(7 of 20 blocks)"), std::string::npos);
}

TEST(XmlEscapeTest, EscapesTheFiveXmlSpecialCharacters) {
  EXPECT_EQ(XmlEscape("a<b>&\"c\"'d'"), "a&lt;b&gt;&amp;&quot;c&quot;&#39;d&#39;");
  EXPECT_EQ(XmlEscape("plain text"), "plain text");
  EXPECT_EQ(XmlEscape(""), "");
  EXPECT_EQ(XmlEscape(std::string("a\x01"
                                  "b\tc")),
            "a?b\tc");
}

TEST(XmlEscapeTest, ExactNumberReadsBackBitForBit) {
  for (const double v : {0.1, 1.0 / 3.0, 6.02214076e23, -2.5e-300, 0.0}) {
    EXPECT_EQ(std::strtod(ExactNumber(v).c_str(), nullptr), v);
  }
}

TEST(ReportPageTest, NoNameCanInjectMarkup) {
  const std::string html = RenderReportHtml(HostileData());
  EXPECT_EQ(html.find("B<1>x"), std::string::npos);
  EXPECT_EQ(html.find("G<1>"), std::string::npos);
  EXPECT_EQ(html.find("x < y"), std::string::npos);
  EXPECT_NE(html.find("B&lt;1&gt;x"), std::string::npos);
  EXPECT_NE(html.find("because x &lt; y &amp; y &gt; z"), std::string::npos);
}

TEST(ReportPageTest, PageWithHostileNamesIsWellFormedXml) {
  if (std::system("python3 -c 'import xml.dom.minidom' 2>/dev/null") != 0) {
    GTEST_SKIP() << "python3 with xml.dom.minidom not available";
  }
  const auto file = std::filesystem::temp_directory_path() /
                    ("gearpath_report_page_" + std::to_string(getpid()) + ".html");
  {
    std::ofstream out(file);
    out << RenderReportHtml(HostileData());
  }
  const std::string cmd =
      "python3 -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' " +
      file.string();
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  std::filesystem::remove(file);
}

TEST(SesSvgTest, MarksEveryHarmonicInsideTheRangeAndNoneBeyond) {
  ReportSes ses;
  ses.bin_hz = 1.0;
  ses.values.assign(200, 0.0);
  ReportShaft fast;
  fast.name = "fast";
  fast.rate_hz = 10.0;
  ReportShaft slow;
  slow.name = "slow";
  slow.rate_hz = 7.0;
  // Up to 45 Hz: fast shows 1..4 (50 Hz is beyond), slow 1..5 (35 Hz).
  const std::string svg = SesSvg(ses, {fast, slow}, 45.0, 1.0, false);
  EXPECT_EQ(Count(svg, "class=\"harmonic-marker\" data-shaft=\"fast\""), 4u);
  EXPECT_EQ(Count(svg, "class=\"harmonic-marker\" data-shaft=\"slow\""), 5u);
  EXPECT_EQ(Count(svg, "data-hz=\"50\""), 0u);
  EXPECT_EQ(Count(svg, "data-hz=\"35\""), 1u);
}

TEST(KurtogramSvgTest, DrawsOneCellPerBandAndOutlinesTheChosenBand) {
  ReportKurtogram k;
  k.nyquist_hz = 4000.0;
  k.row_level = {0.0, 1.0, 1.6};
  k.rows = {{0.1}, {0.2, 0.3}, {0.4, 5.0, 0.6}};
  k.chosen_row = 2;
  k.chosen_index = 1;
  k.significant = true;
  k.low_hz = 4000.0 / 3.0;
  k.high_hz = 8000.0 / 3.0;
  const std::string svg = KurtogramSvg(k, 5.0);
  EXPECT_EQ(Count(svg, "class=\"kurtogram-cell\""), 6u);
  EXPECT_EQ(Count(svg, "class=\"chosen-band\""), 1u);
  EXPECT_EQ(Count(svg, "stroke-dasharray=\"6 4\""), 0u) << "a significant band is drawn solid";
  k.significant = false;
  EXPECT_EQ(Count(KurtogramSvg(k, 5.0), "stroke-dasharray=\"6 4\""), 1u);
}

TEST(PathBarsSvgTest, BarHeightsAreProportionalToTheShares) {
  const std::string svg = PathBarsSvg({{"A", "a", 0.25, 1.0, 0.0}, {"B", "b", 0.75, 3.0, 0.0}}, 1);
  EXPECT_EQ(Count(svg, "<rect class=\"path-bar"), 2u);
  EXPECT_EQ(Count(svg, "<rect class=\"path-bar dominant\" data-path=\"B\""), 1u);
  // Plot height 320 - 40 - 55 = 225 px: 25 % -> 56.25 px, 75 % -> 168.75 px.
  EXPECT_NE(svg.find("height=\"56.2\""), std::string::npos);
  EXPECT_NE(svg.find("height=\"168.8\""), std::string::npos);
}

}  // namespace
}  // namespace gearpath::tools
