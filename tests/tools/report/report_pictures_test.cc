// The analyst pictures of the report on synthetic signals with known answers: overall
// statistics of a sine, the amplitude spectrum's peak, the mesh zoom's peak and sideband
// cursors, UTC times, trends against time with limits only where learned, and one colour
// scale for both kurtograms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "tools/report/amplitude_spectrum.h"
#include "tools/report/report_page.h"
#include "tools/report/signal_charts.h"
#include "tools/report/signal_statistics.h"
#include "tools/report/trend_charts.h"
#include "tools/report/utc_time.h"

namespace gearpath::tools {
namespace {

constexpr double kPi = std::numbers::pi;

std::size_t Count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto p = text.find(needle); p != std::string::npos; p = text.find(needle, p + 1)) ++n;
  return n;
}

// The number in attribute `name` of the first element that contains `marker`.
double AttributeAfter(const std::string& text, const std::string& marker,
                      const std::string& name) {
  const auto at = text.find(marker);
  if (at == std::string::npos) return NAN;
  const auto p = text.find(name + "=\"", at);
  if (p == std::string::npos) return NAN;
  return std::strtod(text.c_str() + p + name.size() + 2, nullptr);
}

std::vector<double> Sine(double amplitude, double hz, double fs, std::size_t n,
                         double offset = 0.0) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = offset + amplitude * std::cos(2.0 * kPi * hz * static_cast<double>(i) / fs);
  }
  return x;
}

TEST(SignalStatisticsTest, SineHasRmsAOverRootTwoCrestRootTwoAndKurtosisOneAndAHalf) {
  // 50 whole periods of 160 samples, on a DC offset the statistics must ignore.
  const std::vector<double> x = Sine(3.0, 50.0, 8000.0, 8000, 0.7);
  const SignalStatistics st = ComputeSignalStatistics(x);
  EXPECT_NEAR(st.rms, 3.0 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(st.peak, 3.0, 1e-12);
  EXPECT_NEAR(st.crest_factor, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(st.kurtosis, 1.5, 1e-12);
}

TEST(SignalStatisticsTest, ASingleImpactRaisesCrestFactorAndKurtosis) {
  std::vector<double> x(1000, 0.0);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = (i % 2 == 0) ? 1.0 : -1.0;  // square: 1, 1
  SignalStatistics square = ComputeSignalStatistics(x);
  EXPECT_NEAR(square.crest_factor, 1.0, 1e-12);
  EXPECT_NEAR(square.kurtosis, 1.0, 1e-12);
  x[500] = 20.0;
  const SignalStatistics impact = ComputeSignalStatistics(x);
  EXPECT_GT(impact.crest_factor, 10.0);
  EXPECT_GT(impact.kurtosis, 50.0);  // 1 before the impact, 3 for Gaussian noise
  EXPECT_EQ(ComputeSignalStatistics(std::vector<double>(10, 2.0)).kurtosis, 0.0);
}

TEST(AmplitudeSpectrumTest, ASineOnABinReadsItsAmplitudeAtItsFrequency) {
  const double fs = 8000.0;
  const std::size_t n = 8192;
  const double hz = 287.0 * fs / static_cast<double>(n);  // bin 287
  auto sp = HannAmplitudeSpectrum(Sine(0.5, hz, fs, n), fs);
  ASSERT_TRUE(sp.ok()) << sp.error();
  EXPECT_DOUBLE_EQ(sp->bin_hz, fs / static_cast<double>(n));
  EXPECT_NEAR(sp->amplitude[287], 0.5, 1e-12);
  EXPECT_NEAR(sp->amplitude[286], 0.25, 1e-12);  // Hann: half on each neighbour
  EXPECT_LT(sp->amplitude[290], 1e-12);
  // Between two bins the window loses at most its scalloping (1.42 dB).
  auto off = HannAmplitudeSpectrum(Sine(0.5, hz + 0.5 * sp->bin_hz, fs, n), fs);
  ASSERT_TRUE(off.ok());
  EXPECT_GT(std::max(off->amplitude[287], off->amplitude[288]), 0.5 * 0.84);
  EXPECT_FALSE(HannAmplitudeSpectrum(std::vector<double>{1.0, 2.0}, fs).ok());
}

// Table-1-like kinematics: input 10 Hz, intermediate 7 Hz; mesh G1 (28 teeth) - G2 at 280 Hz.
std::vector<ReportShaft> TwoShafts() {
  ReportShaft input;
  input.name = "input";
  input.rate_hz = 10.0;
  ReportShaft inter;
  inter.name = "intermediate";
  inter.rate_hz = 7.0;
  return {input, inter};
}

TEST(MeshZoomSvgTest, PeakIsAtTheSinesFrequencyAndSidebandCursorsAtMeshPlusMinusKShaftRates) {
  const double fs = 8000.0;
  const std::size_t n = 8192;
  // A 281.3 Hz tone (off-bin) and a smaller one 10 Hz above; the largest bin is the tone's.
  std::vector<double> x = Sine(1.0, 281.3, fs, n);
  const std::vector<double> side = Sine(0.1, 291.3, fs, n);
  for (std::size_t i = 0; i < n; ++i) x[i] += side[i];
  auto sp = HannAmplitudeSpectrum(x, fs);
  ASSERT_TRUE(sp.ok());
  ReportSpectrum spectrum{"measured p1 x", "m/s^2", sp->bin_hz, sp->amplitude};
  const ReportMesh mesh{"G1-G2", 280.0, 0, 1};
  const std::string svg = MeshZoomSvg(spectrum, mesh, TwoShafts(), 6);
  const double peak_hz = AttributeAfter(svg, "class=\"spectrum-peak\"", "data-hz");
  EXPECT_NEAR(peak_hz, 281.3, sp->bin_hz / 2.0 + 1e-9);
  EXPECT_NEAR(AttributeAfter(svg, "class=\"spectrum-peak\"", "data-value"), 1.0, 0.16);
  EXPECT_EQ(Count(svg, "class=\"mesh-cursor\" data-hz=\"280\""), 1u);
  // k = -6..6 without 0 for each of the two shafts.
  EXPECT_EQ(Count(svg, "class=\"sideband-cursor\" data-shaft=\"input\""), 12u);
  EXPECT_EQ(Count(svg, "class=\"sideband-cursor\" data-shaft=\"intermediate\""), 12u);
  EXPECT_EQ(Count(svg, "data-shaft=\"input\" data-order=\"-1\" data-hz=\"270\""), 1u);
  EXPECT_EQ(Count(svg, "data-shaft=\"input\" data-order=\"6\" data-hz=\"340\""), 1u);
  EXPECT_EQ(Count(svg, "data-shaft=\"intermediate\" data-order=\"1\" data-hz=\"287\""), 1u);
  EXPECT_EQ(Count(svg, "data-shaft=\"intermediate\" data-order=\"-3\" data-hz=\"259\""), 1u);
  EXPECT_EQ(Count(svg, "data-order=\"7\""), 0u);
  EXPECT_NE(svg.find("amplitude (dB re 1 m/s^2)"), std::string::npos);
  EXPECT_NE(svg.find(">frequency (Hz)<"), std::string::npos);
}

TEST(UtcTimeTest, FormatsNanosecondsSinceTheEpochAsIso8601Utc) {
  EXPECT_EQ(FormatUtc(0), "1970-01-01T00:00:00.000Z");
  EXPECT_EQ(FormatUtc(7'168'000'000), "1970-01-01T00:00:07.168Z");
  EXPECT_EQ(FormatUtc(1'700'000'000'123'456'789), "2023-11-14T22:13:20.123Z");
  EXPECT_EQ(FormatUtc(951'782'400'000'000'000), "2000-02-29T00:00:00.000Z");  // leap day
  EXPECT_EQ(FormatUtc(-1), "1969-12-31T23:59:59.999Z");
  EXPECT_EQ(FormatUtcClock(1'700'000'000'123'456'789), "22:13:20");
}

ReportTrendPoint Point(std::size_t block, std::int64_t t0_ns, double recon, double threshold,
                       double limit_z, const std::string& state) {
  ReportTrendPoint p;
  p.block_index = block;
  p.sequence = block;
  p.state = state;
  p.raw = {0.5 * recon};
  p.reconstructed = {recon};
  p.reconstructed_threshold = {threshold};
  p.t0_ns = t0_ns;
  p.speed_hz = 10.0 + 0.1 * static_cast<double>(block);
  p.score = limit_z > 0.0 ? 0.5 : 0.0;
  p.limit_z = limit_z;
  p.clear_level = 0.7;
  return p;
}

// The x coordinates of the first polyline of class `css`.
std::vector<double> PolylineXs(const std::string& svg, const std::string& css) {
  std::vector<double> xs;
  const auto at = svg.find("<polyline class=\"" + css + "\"");
  if (at == std::string::npos) return xs;
  const auto p = svg.find("points=\"", at) + 8;
  const auto end = svg.find('"', p);
  const char* c = svg.c_str() + p;
  while (c < svg.c_str() + end) {
    char* next = nullptr;
    const double x = std::strtod(c, &next);
    if (next == c) break;
    xs.push_back(x);
    c = next + 1;                                   // the comma
    std::strtod(c, &next);                          // the y
    c = next;
    while (*c == ' ') ++c;
  }
  return xs;
}

TEST(TrendChartsTest, PointsArePlacedByTimeNotByBlockIndex) {
  const std::int64_t t = 1'700'000'000'000'000'000;
  const std::vector<ReportTrendPoint> trend = {Point(0, t, 1.0, 2.0, 6.0, "no_fault"),
                                               Point(1, t + 1'000'000'000, 1.1, 2.0, 6.0,
                                                     "no_fault"),
                                               Point(2, t + 10'000'000'000, 1.2, 2.0, 6.0,
                                                     "no_fault")};
  const std::string svg = TrendSvg(trend, {"input"});
  const std::vector<double> xs = PolylineXs(svg, "trend-reconstructed");
  ASSERT_EQ(xs.size(), 3u);
  EXPECT_NEAR((xs[2] - xs[1]) / (xs[1] - xs[0]), 9.0, 0.05);
  EXPECT_NE(svg.find("first block at 2023-11-14T22:13:20.000Z"), std::string::npos);
  EXPECT_NE(svg.find(">22:13:20<"), std::string::npos);  // clock-time ticks
  EXPECT_EQ(PolylineXs(svg, "trend-speed").size(), 3u);
  EXPECT_NE(svg.find("input speed (Hz)"), std::string::npos);
}

TEST(TrendChartsTest, LimitsAndBandsAreDrawnOnlyWhereLearned) {
  const std::int64_t s = 1'000'000'000;
  std::vector<ReportTrendPoint> learning = {Point(0, 0, 1.0, 0.0, 0.0, "learning"),
                                            Point(1, s, 1.0, 0.0, 0.0, "learning")};
  EXPECT_EQ(Count(TrendSvg(learning, {"input"}), "trend-threshold"), 0u);
  const std::string score_learning = ScoreTrendSvg(learning);
  EXPECT_EQ(Count(score_learning, "score-band"), 0u);
  EXPECT_EQ(Count(score_learning, "score-limit"), 0u);
  EXPECT_EQ(Count(score_learning, "trend-score"), 0u);
  // Learned from block 2 on: the threshold line has the learned blocks only, the bands start
  // at block 2.
  learning.push_back(Point(2, 2 * s, 1.0, 3.0, 6.0, "no_fault"));
  learning.push_back(Point(3, 3 * s, 1.0, 3.0, 6.0, "no_fault"));
  EXPECT_EQ(PolylineXs(TrendSvg(learning, {"input"}), "trend-threshold").size(), 2u);
  const std::string score = ScoreTrendSvg(learning);
  EXPECT_EQ(Count(score, "<rect class=\"score-band-alert\" data-from=\"2\" data-to=\"3\""), 1u);
  EXPECT_EQ(Count(score, "<rect class=\"score-band-alarm\" data-from=\"2\" data-to=\"3\""), 1u);
  EXPECT_EQ(PolylineXs(score, "trend-score").size(), 2u);
}

ReportData PageData() {
  ReportData d;
  d.machine_id = "m";
  d.t0_ns = 1'700'000'000'123'456'789;
  d.kurtogram_raw.title = "raw";
  d.kurtogram_raw.nyquist_hz = 4000.0;
  d.kurtogram_raw.row_level = {0.0, 1.0};
  d.kurtogram_raw.rows = {{0.5}, {3.0, 1.0}};
  d.kurtogram_reconstructed = d.kurtogram_raw;
  d.kurtogram_reconstructed.title = "reconstructed";
  d.kurtogram_reconstructed.rows = {{2.0}, {12.0, 1.0}};
  ReportShaft a;
  a.name = "input";
  a.rate_hz = 10.0;
  d.shafts = {a, a};
  d.shafts[1].name = "output";
  d.state = "learning";
  d.statistics = {{"p1 x", "m/s^2", 0.4, 1.5, 3.0, 4.5}};
  d.waveforms = {{"Measured, p1 x", "m/s^2", 8000.0, Sine(1.0, 50.0, 8000.0, 800)}};
  return d;
}

TEST(ReportPageTest, T0IsShownAsUtcTime) {
  const std::string html = RenderReportHtml(PageData());
  EXPECT_NE(html.find(">2023-11-14T22:13:20.123Z<"), std::string::npos);
  EXPECT_EQ(html.find("1700000000123456789 ns"), std::string::npos);
}

TEST(ReportPageTest, NoThresholdIsShownWhileTheBaselineIsLearned) {
  ReportData d = PageData();
  std::string html = RenderReportHtml(d);
  EXPECT_EQ(Count(html, "<td class=\"not-learned\">"), 4u);  // raw and reconstructed, 2 shafts
  EXPECT_EQ(Count(html, "trend-threshold"), 0u);
  d.shafts[0].raw_threshold = 0.25;
  d.shafts[0].reconstructed_threshold = 0.5;
  d.shafts[1].raw_threshold = 0.25;
  d.shafts[1].reconstructed_threshold = 0.5;
  html = RenderReportHtml(d);
  EXPECT_EQ(Count(html, "<td class=\"not-learned\">"), 0u);
  EXPECT_EQ(Count(html, "<td data-value=\"0.5\">"), 2u);
}

TEST(ReportPageTest, BothKurtogramsShareOneColourScale) {
  const std::string html = RenderReportHtml(PageData());
  EXPECT_EQ(Count(html, "class=\"sk-scale-max\" data-value=\"12\""), 2u);
  // SK 1 has the same colour in both maps.
  const auto fill_of = [&](std::size_t from) {
    const auto at = html.find("data-sk=\"1\"", from);
    const auto f = html.find("fill=\"", at);
    return std::make_pair(at, html.substr(f, 14));
  };
  const auto first = fill_of(0);
  const auto second = fill_of(first.first + 1);
  ASSERT_NE(second.first, std::string::npos);
  EXPECT_EQ(first.second, second.second);
}

TEST(ReportPageTest, StatisticsAndWaveformAreOnThePageWithUnits) {
  const std::string html = RenderReportHtml(PageData());
  EXPECT_NE(html.find("<tr data-statistics=\"p1 x\"><td class=\"name\">p1 x</td><td "
                      "class=\"name\">m/s^2</td><td data-value=\"0.4\">"),
            std::string::npos);
  EXPECT_EQ(Count(html, "<path class=\"waveform\" data-samples=\"800\""), 1u);
  EXPECT_NE(html.find("time from the block&#39;s t0 (ms)"), std::string::npos);
  EXPECT_NE(html.find("acceleration (m/s^2)"), std::string::npos);
}

TEST(ContributionSpectraSvgTest, DrawsEveryPathTheirSumAndTheMeasuredSpectrum) {
  ReportSpectrum sp{"p1 x", "m/s^2", 1.0, std::vector<double>(100, 0.01)};
  const std::string svg = ContributionSpectraSvg(sp, {sp, sp, sp}, {"B1x", "B2x", "B3x"}, sp,
                                                 0.0, 99.0);
  EXPECT_EQ(Count(svg, "<path class=\"spectrum-line\""), 5u);
  EXPECT_EQ(Count(svg, "data-series=\"sum of contributions\""), 1u);
  EXPECT_EQ(Count(svg, "data-series=\"measured\""), 1u);
  EXPECT_EQ(Count(svg, "data-series=\"B2x\""), 1u);
}

TEST(ForceSpectraSvgTest, MarksEachPathsLargestForceLineAtItsFrequency) {
  const double fs = 8000.0;
  const std::size_t n = 8192;
  auto a = HannAmplitudeSpectrum(Sine(20.0, 300.0, fs, n), fs);
  auto b = HannAmplitudeSpectrum(Sine(5.0, 1200.0, fs, n), fs);
  ASSERT_TRUE(a.ok() && b.ok());
  const std::vector<ReportSpectrum> forces = {{"force B1x", "N", a->bin_hz, a->amplitude},
                                              {"force B2x", "N", b->bin_hz, b->amplitude}};
  const std::string svg = ForceSpectraSvg(forces, {"B1x", "B2x"}, 100.0, 2000.0);
  EXPECT_EQ(Count(svg, "class=\"spectrum-line force-line\""), 2u);
  EXPECT_NEAR(AttributeAfter(svg, "class=\"force-peak\" data-path=\"B1x\"", "data-hz"), 300.0,
              a->bin_hz / 2.0);
  EXPECT_NEAR(AttributeAfter(svg, "class=\"force-peak\" data-path=\"B2x\"", "data-hz"), 1200.0,
              b->bin_hz / 2.0);
  EXPECT_NEAR(AttributeAfter(svg, "class=\"force-peak\" data-path=\"B1x\"", "data-value"), 20.0,
              20.0 * 0.16);
  EXPECT_NE(svg.find("force amplitude (dB re 1 N)"), std::string::npos);
  // Outside the range nothing is marked: a line at 300 Hz is not in 500..2000 Hz.
  const std::string high = ForceSpectraSvg(forces, {"B1x", "B2x"}, 500.0, 2000.0);
  EXPECT_GE(AttributeAfter(high, "class=\"force-peak\" data-path=\"B1x\"", "data-hz"), 500.0);
}

}  // namespace
}  // namespace gearpath::tools
