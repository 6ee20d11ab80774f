// ReportData: everything `gearpath report` draws for one block (and, optionally, the indicator
// trend over a span of blocks), as plain values copied out of the pipeline.
//
// Why a separate plain struct: the page renderer (report_page.h) then depends on nothing but
// this header, so it can be tested on hand-made data, and the command stays the only place that
// talks to the BlockProcessor. Frequencies in Hz, shares in [0, 1], indicators dimensionless
// (sums of normalised squared-envelope-spectrum amplitudes, core/dsp/envelope_spectrum.h).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace gearpath::tools {

inline constexpr std::size_t kReportHarmonics = 5;  // seed Sec. 4.3: first five harmonics

struct ReportPath {
  std::string name;     // e.g. "B1x"
  std::string bearing;  // e.g. "B1, input shaft"
  double share = 0.0;   // energy share in [0, 1]
  double energy = 0.0;
  double criterion = 0.0;
};

// One kurtogram map: rows of the 1/3-binary tree (core/dsp/kurtogram.h), band 0 = lowest.
struct ReportKurtogram {
  std::string title;
  double nyquist_hz = 0.0;
  std::vector<double> row_level;          // Antoni's display level per row (0, 1, 1.6, ...)
  std::vector<std::vector<double>> rows;  // spectral kurtosis per band
  int chosen_row = -1;                    // -1: no band chosen
  int chosen_index = -1;
  bool significant = false;
  double low_hz = 0.0;  // the band used for the envelope
  double high_hz = 0.0;
  double kurtosis = 0.0;
};

struct ReportShaft {
  std::string name;
  double rate_hz = 0.0;
  double raw = 0.0;
  double reconstructed = 0.0;
  double enhancement_percent = 0.0;
  double raw_threshold = 0.0;  // 0 while the baseline is being learned
  double reconstructed_threshold = 0.0;
  std::array<double, kReportHarmonics> raw_harmonics{};
  std::array<double, kReportHarmonics> reconstructed_harmonics{};
};

// Squared envelope spectrum of one signal (bins at k * bin_hz).
struct ReportSes {
  std::string title;
  double bin_hz = 0.0;
  std::vector<double> values;
  double band_low_hz = 0.0;  // the envelope band it was demodulated from
  double band_high_hz = 0.0;
};

struct ReportTrendPoint {
  std::size_t block_index = 0;
  std::uint64_t sequence = 0;
  std::string dominant_path;
  std::string state;  // "learning", "no_fault", "suspected", "alarm"
  std::string gear;
  std::vector<double> raw;                      // per shaft
  std::vector<double> reconstructed;            // per shaft
  std::vector<double> reconstructed_threshold;  // per shaft (0 while learning: not drawn)
  std::int64_t t0_ns = 0;  // first sample, ns since the Unix epoch (UTC)
  double speed_hz = 0.0;   // input-shaft speed used for the block
  double score = 0.0;      // block score, in units of the limit (BlockScore::score)
  double limit_z = 0.0;    // 0 while learning: no score bands drawn there
  double clear_level = 0.0;
};

// Overall statistics of one time signal (tools/report/signal_statistics.h).
struct ReportSignalStatistics {
  std::string signal;  // e.g. "p1 x", or "reconstructed (B1x at p1 x)"
  std::string unit;    // e.g. "m/s^2"
  double rms = 0.0;
  double peak = 0.0;
  double crest_factor = 0.0;
  double kurtosis = 0.0;
};

// A time signal of the block: samples at sample_rate_hz from the block's t0.
struct ReportWaveform {
  std::string title;
  std::string unit;
  double sample_rate_hz = 0.0;
  std::vector<double> samples;
};

// One-sided amplitude spectrum (tools/report/amplitude_spectrum.h): bin k at k * bin_hz.
struct ReportSpectrum {
  std::string title;
  std::string unit;
  double bin_hz = 0.0;
  std::vector<double> amplitude;
};

// One gear mesh at this block's speed; shaft_a / shaft_b index ReportData::shafts.
struct ReportMesh {
  std::string name;  // e.g. "G1-G2"
  double mesh_hz = 0.0;
  std::size_t shaft_a = 0;  // the driver's shaft
  std::size_t shaft_b = 0;  // the driven gear's shaft
};

// One revolution of a shaft's time-synchronous average (core/dsp/synchronous_average.h).
struct ReportSynchronousAverage {
  std::string shaft;
  double shaft_hz = 0.0;
  int revolutions = 0;
  std::vector<double> raw;            // measured indicator channel
  std::vector<double> reconstructed;  // dominant-path contribution at that channel
};

// Condition indicators of one signal at one shaft rate (BlockConditionIndicators).
struct ReportIndicatorValue {
  std::string name;  // e.g. "fm4", "sideband_G1-G2"
  double value = 0.0;
  double z = 0.0;  // robust z-score against the healthy baseline (0 while learning)
};

struct ReportIndicatorSet {
  std::string source;  // "measured", "contribution", "force"
  std::string signal;  // channel "A1/x" or path name
  std::string shaft;   // first shaft of the rate group
  std::size_t group = 0;  // rate group (sets of one group share their indicator names)
  double shaft_hz = 0.0;
  int revolutions = 0;
  double score = 0.0;  // largest directional z / limit over the set
  std::vector<ReportIndicatorValue> values;
};

// The block's anomaly score and the limits in force (BlockScore).
struct ReportScore {
  double limit_z = 0.0;  // 0 while learning
  double clear_level = 0.0;
  double score = 0.0;  // largest z / limit_z
  std::string indicator;
  std::string signal;
  std::string shaft;
  int exceed_count = 0;
  int window = 0;
};

struct ReportData {
  // Where it comes from.
  std::string machine_id;
  std::string recording;
  std::string frf_source;
  std::size_t block_index = 0;
  std::size_t block_count = 0;  // blocks in the recording
  std::uint64_t sequence = 0;
  std::int64_t t0_ns = 0;
  double sample_rate_hz = 0.0;
  std::uint32_t samples_per_channel = 0;
  double speed_hz = 0.0;
  std::string speed_source;
  int baseline_learned = 0;
  int baseline_needed = 0;
  std::size_t rejected_blocks = 0;  // blocks before this one the pipeline rejected

  // Paths.
  std::vector<ReportPath> paths;
  int dominant_path = -1;
  std::string indicator_channel;  // e.g. "p1 x"

  // Envelope analysis.
  ReportKurtogram kurtogram_raw;
  ReportKurtogram kurtogram_reconstructed;
  ReportSes ses_raw;
  ReportSes ses_reconstructed;
  std::vector<ReportShaft> shafts;

  // Time-domain view of the block: statistics of every measured channel (and the
  // reconstructed signal), waveforms of the indicator channel and its reconstruction.
  std::vector<ReportSignalStatistics> statistics;
  std::vector<ReportWaveform> waveforms;
  std::vector<ReportSynchronousAverage> synchronous_averages;

  // Spectra at the indicator channel: measured, each path's contribution, their sum.
  ReportSpectrum measured_spectrum;
  std::vector<ReportSpectrum> path_spectra;  // ReportData::paths order
  ReportSpectrum contribution_sum;
  std::vector<ReportSpectrum> force_spectra;  // identified bearing forces, paths order (N)
  double analysis_band_lo_hz = 0.0;
  double analysis_band_hi_hz = 0.0;
  std::vector<ReportMesh> meshes;
  int sideband_orders = 6;  // k = 1..sideband_orders cursors around each mesh frequency

  // Condition indicators and the block score (shown once the baseline is learned).
  ReportScore score;
  std::vector<ReportIndicatorSet> condition;

  // Verdict.
  std::string state;
  std::string gear;
  std::string shaft;
  double confidence = 0.0;
  std::vector<std::string> candidates;
  std::string reason;

  // Indicator trend over a span (empty for a single block).
  std::vector<ReportTrendPoint> trend;
};

}  // namespace gearpath::tools
