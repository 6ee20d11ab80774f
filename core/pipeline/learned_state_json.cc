#include "core/pipeline/learned_state_json.h"

#include <fmt/format.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

namespace gearpath {
namespace {

using nlohmann::json;

json Mean(const std::vector<double>& mean, int blocks) {
  return json{{"blocks", blocks}, {"mean", mean}};
}

// nlohmann converts a float to int with a plain cast (undefined for 1e300): demand an
// integer that fits.
int Int(const json& parent, const char* key) {
  const json& v = parent.at(key);
  if (!v.is_number_integer()) throw std::invalid_argument(std::string(key) + ": not an integer");
  const auto x = v.get<std::int64_t>();
  if ((v.is_number_unsigned() && v.get<std::uint64_t>() > INT32_MAX) || x < INT32_MIN ||
      x > INT32_MAX) {
    throw std::out_of_range(std::string(key) + ": out of range");
  }
  return static_cast<int>(x);
}

std::vector<int> Ints(const json& parent, const char* key) {
  const json& v = parent.at(key);
  if (!v.is_array()) throw std::invalid_argument(std::string(key) + ": not an array");
  std::vector<int> out;
  for (const json& e : v) {
    if (!e.is_number_integer() || e.get<std::int64_t>() < INT32_MIN ||
        e.get<std::int64_t>() > INT32_MAX) {
      throw std::invalid_argument(std::string(key) + ": entries must be integers");
    }
    out.push_back(static_cast<int>(e.get<std::int64_t>()));
  }
  return out;
}

FaultState ParseFaultState(const std::string& name) {
  for (FaultState s :
       {FaultState::kLearning, FaultState::kNoFault, FaultState::kSuspected, FaultState::kAlarm}) {
    if (ToString(s) == name) return s;
  }
  throw std::invalid_argument("alarm.state: unknown fault state \"" + name + "\"");
}

// An optional [low, high] pair; left as it is when absent.
Status ReadRange(const json& parent, const char* key, double& lo, double& hi) {
  if (!parent.contains(key)) return Status::Ok();
  const auto range = parent.at(key).get<std::vector<double>>();
  if (range.size() != 2) {
    return Error{std::string("learned state: ") + key + ": expected [low, high], got " +
                 std::to_string(range.size()) + " values"};
  }
  lo = range[0];
  hi = range[1];
  return Status::Ok();
}

// One band's fields from `j` (BandToJson); throws on a missing key or a wrong type.
Status BandFromJson(const json& j, LearnedBand& s) {
  // Absent in states written before operating bands: the first band.
  s.band_id = j.contains("operating_band_id") ? Int(j, "operating_band_id") : 0;
  if (s.band_id < 0) return Error{"learned state: operating_band_id: negative"};
  const json& b = j.at("indicator_baseline");
  RobustBaselineState& r = s.indicator_baseline;
  r.blocks = Int(b, "blocks");
  r.indicators = Int(b, "indicators");
  r.count = Int(b, "count");
  r.skipped = Int(b, "skipped");
  r.relative_floor = b.at("relative_floor").get<double>();
  r.absolute_floor = b.at("absolute_floor").get<double>();
  r.log_value_floor = b.at("log_value_floor").get<double>();
  r.median = b.at("median").get<std::vector<double>>();
  r.scale = b.at("scale").get<std::vector<double>>();
  r.log_transform = b.at("log_transform").get<std::vector<bool>>();
  r.samples = b.at("samples").get<std::vector<double>>();
  const json& rv = j.at("residual_variance_healthy");
  s.residual_variance_healthy = rv.at("mean").get<std::vector<double>>();
  s.residual_variance_blocks = Int(rv, "blocks");
  const json& ch = j.at("criterion_healthy");
  s.criterion_healthy = ch.at("mean").get<std::vector<double>>();
  s.criterion_blocks = Int(ch, "blocks");
  // Absent in states written before them: [0, 0], every speed and every load judged.
  if (Status st = ReadRange(j, "baseline_speed_hz", s.baseline_speed_lo_hz, s.baseline_speed_hi_hz);
      !st) {
    return st;
  }
  if (Status st = ReadRange(j, "baseline_load", s.baseline_load_lo, s.baseline_load_hi); !st) {
    return st;
  }
  if (j.contains("baseline_load_partial")) {
    s.baseline_load_partial = j.at("baseline_load_partial").get<bool>();
  }
  return Status::Ok();
}

// One band's fields, into `j` (the state's top level for the band in use, as states saved
// before operating bands had them; an entry of "operating_bands" for a parked one).
void BandToJson(const LearnedBand& s, json& j) {
  const RobustBaselineState& b = s.indicator_baseline;
  j["operating_band_id"] = s.band_id;
  j["indicator_baseline"] = {
      {"blocks", b.blocks},
      {"indicators", b.indicators},
      {"count", b.count},
      {"skipped", b.skipped},
      {"relative_floor", b.relative_floor},
      {"absolute_floor", b.absolute_floor},
      {"log_value_floor", b.log_value_floor},
      {"median", b.median},
      {"scale", b.scale},
      {"log_transform", b.log_transform},
      {"samples", b.samples},
  };
  j["residual_variance_healthy"] = Mean(s.residual_variance_healthy, s.residual_variance_blocks);
  j["criterion_healthy"] = Mean(s.criterion_healthy, s.criterion_blocks);
  j["baseline_speed_hz"] = {s.baseline_speed_lo_hz, s.baseline_speed_hi_hz};
  j["baseline_load"] = {s.baseline_load_lo, s.baseline_load_hi};
  j["baseline_load_partial"] = s.baseline_load_partial;
}

}  // namespace

json ToJson(const LearnedState& s) {
  json j;
  j["fingerprint"] = fmt::format("{:016x}", s.fingerprint);
  j["learning"] = s.learning;
  BandToJson(s, j);
  if (s.envelope_baseline) {
    const HealthyBaselineState& e = *s.envelope_baseline;
    j["envelope_baseline"] = {{"blocks", e.options.blocks},
                              {"k_sigma", e.options.k_sigma},
                              {"min_margin", e.options.min_margin},
                              {"floor", e.options.floor},
                              {"count", e.count},
                              {"mean", e.mean},
                              {"m2", e.m2}};
  } else {
    j["envelope_baseline"] = nullptr;
  }
  const AlarmModelState& a = s.alarm;
  j["alarm"] = {{"n", a.options.n},
                {"suspect_k", a.options.suspect_k},
                {"alarm_k", a.options.alarm_k},
                {"clear_level", a.options.clear_level},
                {"clear_blocks", a.options.clear_blocks},
                {"state", std::string(ToString(a.state))},
                {"exceed_bits", a.exceed_bits},
                {"quiet_run", a.quiet_run},
                {"blocks_in_state", a.blocks_in_state},
                {"votes", a.votes}};
  j["group_excess_sum"] = s.group_excess_sum;
  j["mesh_evidence_sum"] = s.mesh_evidence_sum;
  j["order_tracking_mode"] = s.order_tracking_mode;
  json parked = json::array();
  for (const LearnedBand& band : s.parked_bands) {
    json e;
    BandToJson(band, e);
    parked.push_back(std::move(e));
  }
  j["operating_bands"] = std::move(parked);
  if (s.baseline_epoch) j["baseline_epoch"] = *s.baseline_epoch;
  return j;
}

Result<LearnedState> LearnedStateFromJson(const json& j) {
  try {
    LearnedState s;
    const std::string fp = j.at("fingerprint").get<std::string>();
    char* end = nullptr;
    s.fingerprint = std::strtoull(fp.c_str(), &end, 16);
    if (fp.size() != 16 || end != fp.c_str() + fp.size()) {
      return Error{"fingerprint: expected 16 hex digits, got \"" + fp + "\""};
    }
    s.learning = j.at("learning").get<bool>();
    if (Status st = BandFromJson(j, s); !st) return Error{st.error()};
    if (const json& e = j.at("envelope_baseline"); !e.is_null()) {
      HealthyBaselineState h;
      h.options.blocks = Int(e, "blocks");
      h.options.k_sigma = e.at("k_sigma").get<double>();
      h.options.min_margin = e.at("min_margin").get<double>();
      h.options.floor = e.at("floor").get<double>();
      h.count = Int(e, "count");
      h.mean = e.at("mean").get<std::vector<double>>();
      h.m2 = e.at("m2").get<std::vector<double>>();
      s.envelope_baseline = std::move(h);
    }
    const json& a = j.at("alarm");
    s.alarm.options.n = Int(a, "n");
    s.alarm.options.suspect_k = Int(a, "suspect_k");
    s.alarm.options.alarm_k = Int(a, "alarm_k");
    s.alarm.options.clear_level = a.at("clear_level").get<double>();
    s.alarm.options.clear_blocks = Int(a, "clear_blocks");
    s.alarm.state = ParseFaultState(a.at("state").get<std::string>());
    if (!a.at("exceed_bits").is_number_unsigned()) {
      return Error{"learned state: alarm.exceed_bits: not an unsigned integer"};
    }
    s.alarm.exceed_bits = a.at("exceed_bits").get<std::uint64_t>();
    s.alarm.quiet_run = Int(a, "quiet_run");
    s.alarm.blocks_in_state = Int(a, "blocks_in_state");
    s.alarm.votes = Ints(a, "votes");
    s.group_excess_sum = j.at("group_excess_sum").get<std::vector<double>>();
    // Absent in states written before the mesh evidence accumulated: it starts from zero.
    if (j.contains("mesh_evidence_sum")) {
      s.mesh_evidence_sum = j.at("mesh_evidence_sum").get<std::vector<double>>();
    }
    // Absent in states written before order tracking existed: those machines averaged at
    // constant speed.
    s.order_tracking_mode = j.contains("order_tracking_mode") ? Int(j, "order_tracking_mode") : 0;
    if (s.order_tracking_mode < -1 || s.order_tracking_mode > 1) {
      return Error{"learned state: order_tracking_mode: " + std::to_string(s.order_tracking_mode) +
                   " is not -1, 0 or 1"};
    }
    // Absent in states written before operating bands: the band in use is the only one.
    if (j.contains("operating_bands")) {
      const json& bands = j.at("operating_bands");
      if (!bands.is_array()) return Error{"learned state: operating_bands: not an array"};
      for (const json& e : bands) {
        LearnedBand band;
        if (Status st = BandFromJson(e, band); !st) {
          return Error{st.error() + " (in operating_bands)"};
        }
        s.parked_bands.push_back(std::move(band));
      }
    }
    // Absent in states written before it was recorded.
    if (j.contains("baseline_epoch")) {
      if (!j.at("baseline_epoch").is_string()) {
        return Error{"learned state: baseline_epoch: expected text, got " +
                     std::string(j.at("baseline_epoch").type_name())};
      }
      std::string epoch = j.at("baseline_epoch").get<std::string>();
      if (Status st = ValidateBaselineEpoch(epoch); !st) {
        return Error{"learned state: baseline_epoch " + st.error()};
      }
      s.baseline_epoch = std::move(epoch);
    }
    return s;
  } catch (const std::exception& e) {
    // nlohmann names the missing key or the type it found ("type must be number, but is
    // string"); out_of_range for ints too large for their field lands here as well.
    return Error{std::string("learned state: ") + e.what()};
  }
}

}  // namespace gearpath
