// Recorded figures: a fixed, seeded stream of blocks through BlockProcessor, every published
// number of every block compared with the figures stored in tests/data/pipeline_figures.txt.
//
// Why: the per-block numerics are rewritten for speed (issue 9: batched per-bin operators,
// fused passes, vectorised kernels). Such a rewrite may move results by rounding and by nothing
// else: this test holds every published figure to what the code computed before the rewrite.
//
// The streams (each a fresh processor, blocks in order, so learning, scoring, localisation and
// the alarm model all run):
//  - table1: the simulated Table-1 gearbox of the pipeline tests (3 x 3, 8192 samples, MWI):
//    healthy blocks through the 6-block baseline, more healthy ones, a chipped tooth on G1, a
//    healthy block, then a tooth fracture on G3;
//  - table1_tikhonov: the same gearbox with Tikhonov (noise-floor rule) through the baseline
//    and a chipped G2;
//  - reference: the issue-9 reference workload (tests/bench/reference_workload.h: 12 x 12,
//    8001-bin FRF set, 16 000 samples, MWI K = 50): a 6-block baseline of differently seeded
//    healthy blocks, healthy blocks, blocks with an impulsive input-shaft fault, a drifting
//    block, then one 65 536-sample block (a second shape, FRFs interpolated onto its grid);
//  - reference18_gcv: 18 x 12 (more channels than paths) with the GCV rule, the per-block
//    parameter choice (no precomputed operator);
//  - reference_tracked: 12 x 12 with order tracking of every average and a drifting speed.
//
// Per accepted block (the condition-indicator sets, most of the figures, on selected blocks of
// the 12-path streams and of the Tikhonov baseline): reject reason, speed, dominant path and criterion, analysis band,
// indicator channel, every path's energy, share and criterion value, the regularisation figures
// (median alpha and condition number, maximum condition number, relative residual, bin counts),
// both kurtogram bands, every shaft's envelope indicators (raw and reconstructed, harmonics,
// thresholds, enhancement), every condition-indicator set (revolutions, values, z-scores, set
// score), the block score and its limits, what the localisation stood on (BlockLocalisation:
// rate-group and mesh evidence, transfer-signature rises), and the verdict (state, gear, shaft,
// mesh, confidence, candidates).
//
// Tolerance: a figure passes when |now - stored| <= 1e-6 x max(|now|, |stored|), or
// <= 1e-9 x the largest magnitude of its named vector (small entries computed from the same sums
// as the large ones carry the large ones' absolute rounding), or both are NaN. Integers (paths,
// levels, states, gears, counts) and texts must match exactly. Why 1e-6: every figure is computed
// in double precision; reordering sums, fusing loops, vectorising or contracting to FMA changes
// a figure by a few ulps of its terms (~1e-13 relative), and the worst cancellations on the way
// (criterion excess over its healthy mean, the locked exclusive energy, log-z-scores with a 5 %
// scale floor) amplify that by at most ~1e3-1e4. Single-precision arithmetic anywhere upstream
// leaves ~1e-7 relative per operation and, through the same cancellations, 1e-4-1e-3 in the
// figures: this tolerance fails it, so a single-precision shortcut has to prove itself by other
// means (and be stated). The |H|^2 table of the path energies is single precision already
// (frf_power_table.h); it is part of what was recorded.
//
// Regenerate (only for a deliberate change of the diagnosis, e.g. a new indicator or scoring
// rule, never to absorb a difference that a speed change made):
//   GEARPATH_WRITE_FIGURES=1 ./build/tests/core/pipeline/test_pipeline
//       --gtest_filter='RecordedFiguresTest.*'  (one command line)
// writes tests/data/pipeline_figures.txt in the source tree; commit it with the change that
// moved the figures and say why in the message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/pipeline/block_processor.h"
#include "tests/bench/reference_workload.h"
#include "tests/core/pipeline/simulated_machine.h"

namespace gearpath {
namespace {
using namespace gearpath::testing;

constexpr double kRelativeTolerance = 1e-6;
constexpr double kVectorScaleTolerance = 1e-9;
constexpr const char* kFiguresFile = GEARPATH_TEST_DATA_DIR "/pipeline_figures.txt";

// One named figure: numbers, or a text.
struct Figure {
  std::string key;
  std::vector<double> values;
  bool is_text = false;
  std::string text;
};

class Recorder {
 public:
  explicit Recorder(std::string prefix) : prefix_(std::move(prefix)) {}
  void Values(const std::string& name, std::vector<double> v) {
    figures_.push_back({prefix_ + name, std::move(v), false, {}});
  }
  void Value(const std::string& name, double v) { Values(name, {v}); }
  void Text(const std::string& name, std::string_view t) {
    Figure f;
    f.key = prefix_ + name;
    f.is_text = true;
    f.text = t.empty() ? "-" : std::string(t);
    figures_.push_back(std::move(f));
  }
  void SetPrefix(std::string prefix) { prefix_ = std::move(prefix); }
  std::vector<Figure>& figures() { return figures_; }

 private:
  std::string prefix_;
  std::vector<Figure> figures_;
};

void RecordBand(Recorder& r, const std::string& name, const BlockEnvelopeBand& b) {
  r.Values(name, {b.centre_hz, b.width_hz, static_cast<double>(b.level), b.kurtosis,
                  b.significant ? 1.0 : 0.0});
}

void RecordResult(Recorder& r, const ProcessOutcome& o, const BlockResult& res,
                  bool condition_sets) {
  r.Value("reason", static_cast<double>(o.reason));
  if (!o.accepted()) return;
  r.Values("speed", {res.speed_hz, static_cast<double>(res.speed_source)});
  r.Values("dominant", {static_cast<double>(res.dominant_path),
                        static_cast<double>(res.criterion), res.analysis_band_lo_hz,
                        res.analysis_band_hi_hz, static_cast<double>(res.indicator_channel)});
  r.Text("dominant_name", res.dominant_path_name);
  std::vector<double> energy, share, criterion;
  for (const BlockPathShare& p : res.paths) {
    energy.push_back(p.energy);
    share.push_back(p.share);
    criterion.push_back(p.criterion);
  }
  r.Values("path_energy", energy);
  r.Values("path_share", share);
  r.Values("path_criterion", criterion);
  const BlockRegularisation& g = res.regularisation;
  r.Values("regularisation", {g.alpha_median, g.condition_median, g.condition_max,
                              g.relative_residual, static_cast<double>(g.bins_used),
                              static_cast<double>(g.bins_outside_frf)});
  RecordBand(r, "raw_band", res.raw_band);
  RecordBand(r, "rec_band", res.reconstructed_band);
  for (const BlockShaftIndicator& s : res.shafts) {
    const std::string at = "shaft_" + std::string(s.shaft) + "_";
    r.Values(at + "envelope", {s.characteristic_hz, s.raw, s.reconstructed, s.enhancement_percent,
                               s.raw_threshold, s.reconstructed_threshold});
    r.Values(at + "raw_harmonics", {s.raw_harmonics.begin(), s.raw_harmonics.end()});
    r.Values(at + "rec_harmonics",
             {s.reconstructed_harmonics.begin(), s.reconstructed_harmonics.end()});
  }
  for (const BlockConditionIndicators& c : res.condition) {
    if (!condition_sets) break;
    const std::string at = "ci_" + std::string(ToString(c.source)) + "_" + std::string(c.signal) +
                           "@" + std::string(c.shaft) + "_";
    r.Values(at + "set", {c.shaft_hz, static_cast<double>(c.revolutions), c.score});
    r.Values(at + "value", {c.value.begin(), c.value.end()});
    r.Values(at + "z", {c.z.begin(), c.z.end()});
  }
  const BlockScore& sc = res.score;
  r.Values("score", {sc.limit_z, sc.clear_level, sc.score, static_cast<double>(sc.exceed_count),
                     static_cast<double>(sc.window),
                     static_cast<double>(sc.baseline_blocks_learned),
                     static_cast<double>(sc.baseline_blocks_needed)});
  r.Text("score_by", std::string(sc.indicator) + "@" + std::string(sc.signal) + "@" +
                         std::string(sc.shaft));
  // What the localisation stood on (BlockLocalisation): the rate groups' evidence, the chosen
  // group's mesh evidence and every transfer signature's rise (from the measured channels and
  // the identified forces).
  const BlockLocalisation& loc = res.localisation;
  r.Values("localisation", {static_cast<double>(loc.group), static_cast<double>(loc.group_count),
                            static_cast<double>(loc.mesh_count)});
  r.Values("localisation_shaft_evidence",
           {loc.shaft_evidence.begin(), loc.shaft_evidence.end()});
  r.Values("localisation_shaft_evidence_accumulated",
           {loc.shaft_evidence_accumulated.begin(), loc.shaft_evidence_accumulated.end()});
  r.Values("localisation_mesh_evidence", {loc.mesh_evidence.begin(), loc.mesh_evidence.end()});
  std::vector<double> signatures;
  for (const auto& group : loc.signature_excess) {
    for (const auto& mesh : group) signatures.insert(signatures.end(), mesh.begin(), mesh.end());
  }
  r.Values("localisation_signature_excess", signatures);
  const GearVerdict& v = res.verdict;
  r.Values("verdict", {static_cast<double>(v.state), static_cast<double>(v.gear),
                       static_cast<double>(v.shaft), v.characteristic_hz, v.confidence,
                       static_cast<double>(v.mesh)});
  std::string candidates;
  for (std::string_view c : v.candidate_names) candidates += (candidates.empty() ? "" : ",") + std::string(c);
  r.Text("verdict_candidates", candidates);
}

// Runs `blocks` through `p`, recording each under "<stream>/<block index>/".
class Stream {
 public:
  Stream(Recorder& r, std::string name, BlockProcessor& p) : r_(r), name_(std::move(name)), p_(p) {}
  // condition_sets: record this block's condition-indicator sets too (they are most of the
  // figures, so the 12-path streams record them on a few blocks only).
  void Feed(AccelBlock& block, bool condition_sets = true) {
    block.sequence = ++sequence_;
    const ProcessOutcome o = p_.Process(block.view(), result_);
    EXPECT_TRUE(o.accepted()) << name_ << " block " << index_ << ": " << o.message.view();
    r_.SetPrefix(name_ + "/" + std::to_string(index_++) + "/");
    RecordResult(r_, o, result_, condition_sets);
  }

 private:
  Recorder& r_;
  std::string name_;
  BlockProcessor& p_;
  BlockResult result_;
  std::uint64_t sequence_ = 0;
  int index_ = 0;
};

void FeedSimulated(Stream& s, GearboxSimulator sim, int count, bool condition_sets = true) {
  AccelBlock block;
  for (int i = 0; i < count; ++i) {
    sim.NextBlock(block);
    s.Feed(block, condition_sets || i + 1 == count);
  }
}

void Table1Stream(Recorder& r) {
  const Machine& m = Table1Machine();
  auto p = BlockProcessor::Create(MakeSetup(m));
  ASSERT_TRUE(p.ok()) << p.error();
  Stream s(r, "table1", p.value());
  FeedSimulated(s, MakeSimulator(m, FaultType::kNone, "", 7), kBaselineBlocks, false);
  FeedSimulated(s, MakeSimulator(m, FaultType::kNone, "", 11), 2);
  FeedSimulated(s, MakeSimulator(m, FaultType::kChippedTooth, "G1", 21), 4);
  FeedSimulated(s, MakeSimulator(m, FaultType::kNone, "", 41), 1);
  FeedSimulated(s, MakeSimulator(m, FaultType::kToothFracture, "G3", 31), 3);
}

void Table1TikhonovStream(Recorder& r) {
  const Machine& m = Table1Machine();
  MachineSetup setup = MakeSetup(m);
  setup.options.identification.method = InverseMethod::kTikhonov;
  auto p = BlockProcessor::Create(setup);
  ASSERT_TRUE(p.ok()) << p.error();
  Stream s(r, "table1_tikhonov", p.value());
  FeedSimulated(s, MakeSimulator(m, FaultType::kNone, "", 7), kBaselineBlocks, false);
  FeedSimulated(s, MakeSimulator(m, FaultType::kChippedTooth, "G2", 21), 3);
}

void ReferenceStream(Recorder& r) {
  MachineSetup setup = reference::ReferenceSetup(12, 0);
  setup.options.baseline_blocks = 6;
  const FrfSet set = setup.frf_set;
  auto p = BlockProcessor::Create(std::move(setup));
  ASSERT_TRUE(p.ok()) << p.error();
  Stream s(r, "reference", p.value());
  reference::BlockVariant v;
  // Condition-indicator sets on the last baseline block, the first scored one, the second
  // faulty block, the drifting block and the long one.
  for (std::uint64_t seed = 101; seed <= 108; ++seed) {  // 6 baseline + 2 healthy
    v.noise_seed = seed;
    AccelBlock b = reference::ReferenceBlock(set, 16000, v);
    s.Feed(b, seed == 106 || seed == 107);
  }
  v.impulse_amplitude = 0.6;
  for (std::uint64_t seed = 109; seed <= 111; ++seed) {
    v.noise_seed = seed;
    AccelBlock b = reference::ReferenceBlock(set, 16000, v);
    s.Feed(b, seed == 110);
  }
  v.impulse_amplitude = 0.0;
  v.drift = true;
  v.noise_seed = 112;
  AccelBlock drift = reference::ReferenceBlock(set, 16000, v);
  s.Feed(drift);
  v.drift = false;
  v.noise_seed = 113;
  AccelBlock long_block = reference::ReferenceBlock(set, 65536, v);
  s.Feed(long_block);
}

void Reference18GcvStream(Recorder& r) {
  MachineSetup setup = reference::ReferenceSetup(18, 0);
  setup.options.baseline_blocks = 6;
  setup.options.identification.regularisation.rule = RegularisationRule::kGcv;
  const FrfSet set = setup.frf_set;
  auto p = BlockProcessor::Create(std::move(setup));
  ASSERT_TRUE(p.ok()) << p.error();
  Stream s(r, "reference18_gcv", p.value());
  reference::BlockVariant v;
  for (std::uint64_t seed = 201; seed <= 203; ++seed) {
    v.noise_seed = seed;
    v.impulse_amplitude = seed == 203 ? 0.6 : 0.0;
    AccelBlock b = reference::ReferenceBlock(set, 16000, v);
    s.Feed(b, seed == 203);
  }
}

void ReferenceTrackedStream(Recorder& r) {
  MachineSetup setup = reference::ReferenceSetup(12, 1);
  setup.options.baseline_blocks = 6;
  const FrfSet set = setup.frf_set;
  auto p = BlockProcessor::Create(std::move(setup));
  ASSERT_TRUE(p.ok()) << p.error();
  Stream s(r, "reference_tracked", p.value());
  reference::BlockVariant v;
  v.drift = true;
  for (std::uint64_t seed = 301; seed <= 302; ++seed) {
    v.noise_seed = seed;
    AccelBlock b = reference::ReferenceBlock(set, 16000, v);
    s.Feed(b, seed == 302);  // the first block decides the tracking, the second is tracked
  }
}

std::vector<Figure> RunAllStreams() {
  Recorder r("");
  Table1Stream(r);
  Table1TikhonovStream(r);
  ReferenceStream(r);
  Reference18GcvStream(r);
  ReferenceTrackedStream(r);
  return std::move(r.figures());
}

// File format: one figure per line, "v <key> <n> <values...>" or "t <key> <text>"; '#' comments.
void WriteFigures(const std::vector<Figure>& figures, const std::string& path) {
  std::ofstream out(path);
  ASSERT_TRUE(out) << "cannot write " << path;
  out << "# Recorded per-block figures of BlockProcessor (tests/core/pipeline/"
         "recorded_figures_test.cc).\n"
         "# Regenerate only for a deliberate diagnosis change:\n"
         "#   GEARPATH_WRITE_FIGURES=1 ./build/tests/core/pipeline/test_pipeline "
         "--gtest_filter='RecordedFiguresTest.*'\n";
  char buffer[64];
  for (const Figure& f : figures) {
    if (f.is_text) {
      out << "t " << f.key << ' ' << f.text << '\n';
      continue;
    }
    out << "v " << f.key << ' ' << f.values.size();
    for (double v : f.values) {
      std::snprintf(buffer, sizeof buffer, " %.10g", v);
      out << buffer;
    }
    out << '\n';
  }
}

std::vector<Figure> ReadFigures(const std::string& path) {
  std::vector<Figure> figures;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::string kind;
    Figure f;
    s >> kind >> f.key;
    if (kind == "t") {
      f.is_text = true;
      s >> std::ws;
      std::getline(s, f.text);
    } else {
      std::size_t n = 0;
      s >> n;
      f.values.resize(n);
      for (double& v : f.values) {
        std::string token;  // "nan" and "inf" as printf writes them
        s >> token;
        v = std::strtod(token.c_str(), nullptr);
      }
    }
    figures.push_back(std::move(f));
  }
  return figures;
}

bool Close(double now, double stored, double vector_scale) {
  if (std::isnan(now) || std::isnan(stored)) return std::isnan(now) && std::isnan(stored);
  if (now == stored) return true;  // also equal infinities
  const double diff = std::abs(now - stored);
  return diff <= kRelativeTolerance * std::max(std::abs(now), std::abs(stored)) ||
         diff <= kVectorScaleTolerance * vector_scale;
}

TEST(RecordedFiguresTest, EveryPublishedFigureMatchesTheRecordedStream) {
  const std::vector<Figure> now = RunAllStreams();
  if (std::getenv("GEARPATH_WRITE_FIGURES") != nullptr) {
    WriteFigures(now, kFiguresFile);
    GTEST_SKIP() << "wrote " << now.size() << " figures to " << kFiguresFile;
  }
  const std::vector<Figure> stored = ReadFigures(kFiguresFile);
  ASSERT_FALSE(stored.empty()) << "no recorded figures in " << kFiguresFile;
  ASSERT_EQ(now.size(), stored.size())
      << "the streams publish another set of figures than was recorded: a deliberate diagnosis "
         "change regenerates them (see the file's header)";
  int reported = 0;
  int failures = 0;
  double largest = 0.0;  // largest relative difference of a figure that is not 0 in both
  std::string largest_at;
  for (std::size_t i = 0; i < now.size(); ++i) {
    const Figure& a = now[i];
    const Figure& b = stored[i];
    ASSERT_EQ(a.key, b.key) << "figure " << i;
    if (a.is_text || b.is_text) {
      ASSERT_EQ(a.is_text, b.is_text) << a.key;
      if (a.text != b.text) {
        ++failures;
        if (reported++ < 40) ADD_FAILURE() << a.key << ": '" << a.text << "', recorded '" << b.text << "'";
      }
      continue;
    }
    ASSERT_EQ(a.values.size(), b.values.size()) << a.key;
    double scale = 0.0;
    for (double v : b.values) {
      if (std::isfinite(v)) scale = std::max(scale, std::abs(v));
    }
    for (std::size_t j = 0; j < a.values.size(); ++j) {
      const double relative = std::abs(a.values[j] - b.values[j]) /
                              std::max(std::abs(a.values[j]), std::abs(b.values[j]));
      if (std::isfinite(relative) && relative > largest) {
        largest = relative;
        largest_at = a.key + "[" + std::to_string(j) + "]";
      }
      if (Close(a.values[j], b.values[j], scale)) continue;
      ++failures;
      if (reported++ < 40) {
        ADD_FAILURE() << a.key << "[" << j << "]: " << a.values[j] << ", recorded " << b.values[j]
                      << " (relative difference "
                      << std::abs(a.values[j] - b.values[j]) / std::abs(b.values[j]) << ")";
      }
    }
  }
  std::printf("largest relative difference from the recording: %.3g at %s\n", largest,
              largest_at.empty() ? "-" : largest_at.c_str());
  EXPECT_EQ(failures, 0) << failures << " figures differ from the recording (first 40 shown)";
}

}  // namespace
}  // namespace gearpath
