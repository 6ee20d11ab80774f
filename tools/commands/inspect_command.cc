// `gearpath inspect`: what an FRF set, a recording (or a directory of them), a text export or a
// UFF file holds, with checks, as text or --json.
//
// FRF sets: shapes, frequency band and resolution, channels, paths with bearings and gears, the
// coupled DOFs; checks: finiteness, reciprocity of the coupled blocks (H_ap vs H_pa^T when both
// were measured, H_aa and H_pp symmetry), and the 2-norm condition numbers per bin of
// (H_pa - H_aa) (what Eqs. 22/24 invert) and of the decoupled matrix (what the daemon inverts),
// summarised as min / median / worst with the worst bin's frequency. Recordings: layout, block
// count, duration, time span, sequence gaps, speed range, load range, non-finite samples.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/frf/frf_set.h"
#include "core/io/frf_set_io.h"
#include "core/io/json_read.h"
#include "core/io/recording.h"
#include "core/io/text_export.h"
#include "core/io/uff58.h"
#include "daemon/machine_state_store.h"
#include "tools/commands/commands.h"
#include "tools/common/replay_input.h"

namespace gearpath::tools {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

struct InspectOptions {
  std::string input;
  bool json_output = false;
};

json FrequencyAxis(const Eigen::VectorXd& f) {
  json j{{"bins", f.size()}};
  if (f.size() == 0) return j;
  j["min_hz"] = f[0];
  j["max_hz"] = f[f.size() - 1];
  if (f.size() >= 2) {
    Eigen::VectorXd df = f.tail(f.size() - 1) - f.head(f.size() - 1);
    const double lo = df.minCoeff(), hi = df.maxCoeff();
    j["resolution_hz"] = (lo + hi) / 2;
    j["uniform"] = (hi - lo) <= 1e-9 * std::max(std::abs(hi), 1.0);
    if (!j["uniform"].get<bool>()) {
      j["resolution_min_hz"] = lo;
      j["resolution_max_hz"] = hi;
    }
  }
  return j;
}

// min / median / worst of a per-bin condition number, with the worst bin's frequency.
json ConditionSummary(const Eigen::VectorXd& f, const std::vector<Eigen::MatrixXcd>& mats) {
  std::vector<double> cond;
  double worst = -1, worst_f = 0;
  for (std::size_t k = 0; k < mats.size(); ++k) {
    Eigen::JacobiSVD<Eigen::MatrixXcd> svd(mats[k]);
    const auto& s = svd.singularValues();
    const double c = s.size() == 0         ? 0.0
                     : s[s.size() - 1] > 0 ? s[0] / s[s.size() - 1]
                                           : std::numeric_limits<double>::infinity();
    cond.push_back(c);
    if (c > worst || std::isnan(c)) {
      worst = c;
      worst_f = f[static_cast<Eigen::Index>(k)];
    }
  }
  if (cond.empty()) return nullptr;
  std::vector<double> sorted = cond;
  std::sort(sorted.begin(), sorted.end());
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json("inf"); };
  return {{"min", num(sorted.front())},
          {"median", num(sorted[sorted.size() / 2])},
          {"worst", num(worst)},
          {"worst_frequency_hz", worst_f}};
}

// max over bins of ||A - B||_F / ||B||_F, with the bin's frequency.
json MaxRelativeDifference(const Eigen::VectorXd& f, const std::vector<Eigen::MatrixXcd>& a,
                           const std::vector<Eigen::MatrixXcd>& b, bool transpose_b) {
  double worst = 0, worst_f = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const Eigen::MatrixXcd bk = transpose_b ? Eigen::MatrixXcd(b[k].transpose()) : b[k];
    const double denom = bk.norm();
    const double rel = denom > 0 ? (a[k] - bk).norm() / denom : (a[k] - bk).norm();
    if (rel > worst) {
      worst = rel;
      worst_f = f[static_cast<Eigen::Index>(k)];
    }
  }
  return {{"max_relative_difference", worst}, {"at_hz", worst_f}};
}

std::vector<Eigen::MatrixXcd> Difference(const std::vector<Eigen::MatrixXcd>& a,
                                         const std::vector<Eigen::MatrixXcd>& b) {
  std::vector<Eigen::MatrixXcd> out;
  for (std::size_t k = 0; k < a.size(); ++k) out.push_back(a[k] - b[k]);
  return out;
}

bool AllFinite(const std::vector<Eigen::MatrixXcd>& m) {
  return std::all_of(m.begin(), m.end(), [](const Eigen::MatrixXcd& x) { return x.allFinite(); });
}

json InspectFrfSet(const FrfSet& set) {
  json j{{"kind", "frf-set"},
         {"description", set.description},
         {"quantity", FrfQuantityName(set.quantity)},
         {"unit", set.unit}};
  if (!set.decoupled.at.empty()) {
    json channels = json::array(), paths = json::array();
    for (const auto& c : set.channels) channels.push_back(c.sensor + "-" + c.axis);
    for (const auto& p : set.paths) {
      paths.push_back({{"name", p.name},
                       {"bearing", p.bearing},
                       {"direction", p.direction},
                       {"gears", p.gears}});
    }
    j["decoupled"] = {
        {"decoupling", set.decoupling},
        {"shape", {set.decoupled.bins(), set.decoupled.outputs(), set.decoupled.inputs()}},
        {"frequency", FrequencyAxis(set.decoupled.frequency_hz)},
        {"channels", channels},
        {"paths", paths},
        {"finite", AllFinite(set.decoupled.at)},
        {"condition_number", ConditionSummary(set.decoupled.frequency_hz, set.decoupled.at)}};
  }
  if (set.coupled) {
    const CoupledSet& c = *set.coupled;
    const CoupledBlocks& b = c.blocks;
    auto names = [](const std::vector<CoupledDof>& dofs) {
      json a = json::array();
      for (const auto& d : dofs) a.push_back(d.name);
      return a;
    };
    json checks;
    checks["finite"] = AllFinite(b.aa) && AllFinite(b.pa) && AllFinite(b.pp) && AllFinite(b.ap) &&
                       AllFinite(b.ma) && AllFinite(b.mp);
    checks["reciprocity_ap_pa"] = b.has_ap()
                                      ? MaxRelativeDifference(b.frequency_hz, b.ap, b.pa, true)
                                      : json("assumed (H_ap = H_pa^T, ap not measured)");
    checks["symmetry_aa"] = MaxRelativeDifference(b.frequency_hz, b.aa, b.aa, true);
    checks["symmetry_pp"] = MaxRelativeDifference(b.frequency_hz, b.pp, b.pp, true);
    std::vector<Eigen::MatrixXcd> inverted;
    if (b.pa.size() == b.aa.size() && c.active.size() == c.passive.size()) {
      inverted = Difference(b.pa, b.aa);
    }
    j["coupled"] = {
        {"dofs", {{"a", names(c.active)}, {"p", names(c.passive)}, {"m", names(c.measurement)}}},
        {"frequency", FrequencyAxis(b.frequency_hz)},
        {"blocks",
         {{"ap_measured", b.has_ap()}, {"measurement_points", b.has_measurement_points()}}},
        {"checks", checks},
        {"condition_number_pa_minus_aa",
         inverted.empty() ? json("n/a (|a| != |p|)") : ConditionSummary(b.frequency_hz, inverted)}};
  }
  return j;
}

std::string UtcTime(std::int64_t ns) {
  const std::time_t s = static_cast<std::time_t>(ns / 1000000000);
  std::tm tm{};
  gmtime_r(&s, &tm);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &tm);
  char frac[16];
  std::snprintf(frac, sizeof frac, ".%03lldZ", static_cast<long long>((ns % 1000000000) / 1000000));
  return std::string(buf) + frac;
}

json InspectRecording(const Recording& r, const fs::path& dir) {
  json channels = json::array();
  for (const auto& c : r.layout.channels) {
    channels.push_back({{"sensor", c.sensor},
                        {"axis", AxisName(c.axis)},
                        {"unit", c.unit},
                        {"sensitivity_mv_per_unit", c.sensitivity}});
  }
  json j{{"kind", "recording"},
         {"path", dir.string()},
         {"machine_id", r.layout.machine_id},
         {"sample_rate_hz", r.layout.sample_rate_hz},
         {"samples_per_channel", r.layout.samples_per_channel},
         {"channels", channels},
         {"blocks", r.block_count()},
         {"shape", {r.block_count(), r.layout.channels.size(), r.layout.samples_per_channel}}};
  const double block_s = r.layout.samples_per_channel / r.layout.sample_rate_hz;
  j["duration_s"] = static_cast<double>(r.block_count()) * block_s;
  if (!r.blocks.empty()) {
    j["t0_first_utc"] = UtcTime(r.blocks.front().t0_ns);
    j["t0_last_utc"] = UtcTime(r.blocks.back().t0_ns);
    j["sequence_first"] = r.blocks.front().sequence;
    j["sequence_last"] = r.blocks.back().sequence;
    std::uint64_t gaps = 0, missing = 0;
    double smin = r.blocks[0].speed_hz, smax = smin;
    for (std::size_t i = 1; i < r.block_count(); ++i) {
      const std::uint64_t d = r.blocks[i].sequence - r.blocks[i - 1].sequence;
      if (d != 1) {
        ++gaps;
        if (d > 1 && d < (1ull << 63)) missing += d - 1;
      }
      smin = std::min(smin, r.blocks[i].speed_hz);
      smax = std::max(smax, r.blocks[i].speed_hz);
    }
    j["sequence_gaps"] = gaps;
    j["missing_blocks"] = missing;
    j["speed_hz"] = {{"min", smin}, {"max", smax}};
    if (r.carries_load()) {
      const auto [lo, hi] = std::minmax_element(
          r.blocks.begin(), r.blocks.end(),
          [](const RecordedBlockInfo& a, const RecordedBlockInfo& b) { return a.load < b.load; });
      j["load"] = {{"min", lo->load}, {"max", hi->load}, {"unit", r.layout.load_unit}};
    }
  }
  std::size_t non_finite = 0;
  for (float v : r.samples) non_finite += std::isfinite(v) ? 0 : 1;
  j["checks"] = {{"non_finite_samples", non_finite}};
  return j;
}

json InspectContinuous(const ContinuousAcquisition& a, const std::string& kind) {
  json channels = json::array();
  for (std::size_t c = 0; c < a.channels.size(); ++c) {
    channels.push_back({{"column", a.column_names[c]},
                        {"sensor", a.channels[c].sensor},
                        {"axis", AxisName(a.channels[c].axis)},
                        {"unit", a.channels[c].unit}});
  }
  return {{"kind", kind},
          {"sample_rate_hz", a.sample_rate_hz},
          {"samples_per_channel", a.samples_per_channel},
          {"duration_s", static_cast<double>(a.samples_per_channel) / a.sample_rate_hz},
          {"channels", channels}};
}

json InspectUff(const std::vector<Uff58Record>& records) {
  json list = json::array();
  for (const auto& r : records) {
    list.push_back(
        {{"function", UffFunctionTypeName(r.function_type)},
         {"response", std::to_string(r.response_node) + UffDirectionName(r.response_direction)},
         {"reference", std::to_string(r.reference_node) + UffDirectionName(r.reference_direction)},
         {"points", r.ordinate.size()},
         {"abscissa_min", r.AbscissaAt(0)},
         {"abscissa_max", r.ordinate.empty() ? 0.0 : r.AbscissaAt(r.ordinate.size() - 1)}});
  }
  return {{"kind", "uff58"}, {"records", list}};
}

// A gearpathd machine state file (docs/state.md): what the daemon will resume for the machine
// at its next start, so that an operator can check the epoch and the alarm before restarting.
json InspectMachineState(const daemon::SavedMachine& m) {
  const LearnedState& l = m.learned;
  json j;
  j["kind"] = "machine-state";
  j["machine_id"] = m.machine_id;
  j["saved_at"] = UtcTime(m.saved_at_ns);
  j["baseline_epoch"] = l.baseline_epoch ? json(*l.baseline_epoch) : json("(not recorded)");
  j["fingerprint"] = fmt::format("{:016x}", l.fingerprint);
  j["baseline"] = {{"learning", l.learning},
                   {"blocks_learned", l.indicator_baseline.count},
                   {"blocks_needed", l.indicator_baseline.blocks},
                   {"indicators", l.indicator_baseline.indicators}};
  j["verdict_state"] = std::string(ToString(l.alarm.state));
  j["blocks_in_state"] = l.alarm.blocks_in_state;
  // [0, 0]: saved before the range was kept, or blocks without it; every value is judged.
  const auto range = [](double lo, double hi) {
    return lo == 0.0 && hi == 0.0 ? json("every") : json::array({lo, hi});
  };
  const auto load_range = [&range](const LearnedBand& b) {
    return b.baseline_load_partial ? json("every (not every baseline block carried a load)")
                                   : range(b.baseline_load_lo, b.baseline_load_hi);
  };
  j["speed_range_hz"] = range(l.baseline_speed_lo_hz, l.baseline_speed_hi_hz);
  j["load_range"] = load_range(l);
  // Every operating band (docs/diagnosis.md section 10), the one in use first.
  json bands = json::array();
  const auto band = [&](const LearnedBand& b, bool in_use) {
    bands.push_back({{"id", b.band_id},
                     {"in_use", in_use},
                     {"learning", b.indicator_baseline.count < b.indicator_baseline.blocks},
                     {"blocks_learned", b.indicator_baseline.count},
                     {"speed_range_hz", range(b.baseline_speed_lo_hz, b.baseline_speed_hi_hz)},
                     {"load_range", load_range(b)}});
  };
  band(l, true);
  for (const LearnedBand& b : l.parked_bands) band(b, false);
  j["operating_bands"] = std::move(bands);
  j["order_tracking"] = l.order_tracking_mode < 0    ? "not decided"
                        : l.order_tracking_mode == 0 ? "constant speed"
                                                     : "tracked";
  const daemon::MachineCounters& c = m.counters;
  json not_judged = json::object();
  for (std::size_t i = 1; i < c.not_judged.size(); ++i) {
    if (c.not_judged[i] > 0) {
      not_judged[std::string(ToString(static_cast<NotJudgedCause>(i)))] = c.not_judged[i];
    }
  }
  j["blocks"] = {{"received", c.received},
                 {"processed", c.processed},
                 {"rejected", c.rejected},
                 {"lost", c.lost},
                 {"not_judged", not_judged}};
  return j;
}

// gearpathd names its state files <machine>.state.json (MachineStateStore::PathOf); the reader
// then checks the format itself, so the file is read once.
bool IsMachineStateFile(const fs::path& path) {
  return path.filename().string().ends_with(".state.json");
}

void PrintJsonAsText(const json& j, int indent) {
  const std::string pad(static_cast<std::size_t>(indent) * 2, ' ');
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it->is_object()) {
      std::printf("%s%s:\n", pad.c_str(), it.key().c_str());
      PrintJsonAsText(*it, indent + 1);
    } else if (it->is_array() && !it->empty() && it->front().is_object()) {
      std::printf("%s%s: (%zu)\n", pad.c_str(), it.key().c_str(), it->size());
      for (const auto& e : *it) {
        std::string line;
        for (auto f = e.begin(); f != e.end(); ++f) {
          line += (line.empty() ? "" : ", ") + f.key() + " " +
                  (f->is_string() ? f->get<std::string>() : f->dump());
        }
        std::printf("%s  - %s\n", pad.c_str(), line.c_str());
      }
    } else {
      std::printf("%s%s: %s\n", pad.c_str(), it.key().c_str(),
                  it->is_string() ? it->get<std::string>().c_str() : it->dump().c_str());
    }
  }
}

int RunInspect(const InspectOptions& opt) {
  const fs::path path(opt.input);
  json report;
  auto fail = [&](const std::string& why) {
    std::fprintf(stderr, "gearpath inspect: %s\n", why.c_str());
    return kExitBadInput;
  };
  if (!fs::exists(path)) return fail(opt.input + ": no such file or directory");
  if (fs::is_directory(path)) {
    std::string format;
    if (fs::exists(path / "manifest.json")) {
      // Bounded parse (core/io/json_read.h): deep nesting or 1e999 is an error, not a crash.
      // A recording's manifest lists every block, hence the recording-sized limit.
      Result<json> manifest =
          ReadJsonFile<json>(path / "manifest.json", {kMaxJsonDepth, std::size_t{1} << 30});
      if (!manifest) return fail(manifest.error());
      if (manifest->is_object()) {
        const auto it = manifest->find("format");
        if (it != manifest->end() && it->is_string()) format = it->get<std::string>();
      }
    }
    if (format == kFrfSetFormatName) {
      Result<FrfSet> set = ReadFrfSet(path);
      if (!set) return fail(set.error());
      report = InspectFrfSet(*set);
    } else if (format == kRecordingFormatName) {
      Result<Recording> r = ReadRecording(path);
      if (!r) return fail(r.error());
      report = InspectRecording(*r, path);
    } else if (!format.empty()) {
      return fail((path / "manifest.json").string() + ": unknown format \"" + format +
                  "\" (expected \"" + kFrfSetFormatName + "\" or \"" + kRecordingFormatName +
                  "\")");
    } else {
      json list = json::array();
      std::vector<fs::path> dirs;
      for (const auto& e : fs::directory_iterator(path)) {
        if (e.is_directory() && IsRecordingDirectory(e.path())) dirs.push_back(e.path());
      }
      std::sort(dirs.begin(), dirs.end());
      for (const fs::path& d : dirs) {
        Result<Recording> r = ReadRecording(d);
        if (!r) return fail(r.error());
        list.push_back(InspectRecording(*r, d));
      }
      if (list.empty()) {
        return fail(opt.input +
                    ": neither an FRF set, a recording nor a directory of recordings "
                    "(no manifest.json)");
      }
      report = {{"kind", "recordings"}, {"recordings", list}};
    }
  } else if (IsMachineStateFile(path)) {
    Result<daemon::SavedMachine> state = daemon::ReadSavedMachine(path.string());
    if (!state) return fail(state.error());
    report = InspectMachineState(*state);
  } else if (GuessReplayFormat(path) == ReplayFormat::kUff58) {
    Result<std::vector<Uff58Record>> records = ReadUff58(path);
    if (!records) return fail(records.error());
    report = InspectUff(*records);
  } else {
    Result<TextExport> text = ReadTextExport(path);
    if (!text) return fail(text.error());
    report = InspectContinuous(text->acquisition, "text-export");
    const TextExportLayout& l = text->layout;
    report["layout"] = {{"separator", l.separator == '\t' ? "tab" : std::string(1, l.separator)},
                        {"decimal_comma", l.decimal_comma},
                        {"time_column", l.time_column},
                        {"units_row", l.units_row},
                        {"first_data_line", l.first_data_line},
                        {"sample_rate_from", l.sample_rate_from}};
  }
  if (opt.json_output) {
    Result<std::string> text = DumpJson(report, 2, "gearpath inspect");
    if (!text) {
      // Readers refuse non-UTF-8 names; should one slip through, show it rather than abort,
      // and say what was done.
      std::fprintf(stderr, "gearpath inspect: note: %s; invalid bytes shown as U+FFFD\n",
                   text.error().c_str());
      text = report.dump(2, ' ', false, json::error_handler_t::replace);
    }
    std::printf("%s\n", text->c_str());
  } else {
    PrintJsonAsText(report, 0);
  }
  return kExitOk;
}

}  // namespace

void AddInspectCommand(CLI::App& app, int& exit_code) {
  auto opt = std::make_shared<InspectOptions>();
  CLI::App* cmd = app.add_subcommand(
      "inspect",
      "Show what an FRF set, a recording, a text export, a UFF file or a gearpathd machine "
      "state file holds, with checks (finiteness, reciprocity, condition numbers)");
  cmd->add_option("input", opt->input,
                  "FRF set or recording directory, text export, .unv/.uff, <machine>.state.json")
      ->required();
  cmd->add_flag("--json", opt->json_output, "Machine-readable JSON");
  cmd->callback([opt, &exit_code] {
    try {
      exit_code = RunInspect(*opt);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gearpath inspect: %s\n", e.what());
      exit_code = kExitFailure;
    }
  });
}

}  // namespace gearpath::tools
