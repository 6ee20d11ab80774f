#include "daemon/daemon_config.h"

#include <fmt/format.h>

#include <fstream>
#include <map>
#include <set>

#include "core/io/json_read.h"
#include "daemon/config_schema.h"
#include "daemon/ip_address.h"

namespace gearpath::daemon {
namespace {

using nlohmann::json;

std::string JoinLines(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& line : lines) {
    if (!out.empty()) out += '\n';
    out += line;
  }
  return out;
}

// `"frf_set": "identity"` takes its paths from `channels`, each with the gears its sensor sits
// near; any other FRF set names its own paths, so `gears` on a channel would be ignored.
void CheckIdentityChannels(const json& m, const std::string& at,
                           const std::set<std::string>& gear_names,
                           std::vector<std::string>& errors) {
  const bool identity = m["frf_set"].get<std::string>() == kIdentityFrfSet;
  const json& channels = m["channels"];
  if (identity && channels.empty()) {
    errors.push_back(fmt::format("{}.channels: frf_set \"identity\" needs the block's channels "
                                 "listed, each with the gears its sensor sits near "
                                 "(channels[].gears)",
                                 at));
  }
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const json& c = channels[i];
    const std::string where = fmt::format("{}.channels[{}]", at, i);
    if (!identity) {
      if (c.contains("gears")) {
        errors.push_back(fmt::format("{}.gears: only used with frf_set \"identity\" (an FRF "
                                     "set names its paths' gears; override them in paths[])",
                                     where));
      }
      continue;
    }
    if (!c.contains("gears")) {
      errors.push_back(fmt::format("{}.gears: required with frf_set \"identity\" (the gears "
                                   "this sensor sits nearest to)",
                                   where));
    } else {
      const json& near = c["gears"];
      std::set<std::string> named;
      for (std::size_t g = 0; g < near.size(); ++g) {
        const auto gear = near[g].get<std::string>();
        if (!gear_names.contains(gear)) {
          errors.push_back(fmt::format("{}.gears[{}]: unknown gear \"{}\"", where, g, gear));
        } else if (!named.insert(gear).second) {
          errors.push_back(fmt::format("{}.gears[{}]: gear \"{}\" is named twice", where, g, gear));
        }
      }
    }
    if (c["frf_row"].get<long>() >= 0) {
      errors.push_back(fmt::format("{}.frf_row: must be -1 with frf_set \"identity\" (channel "
                                   "i is row i of the identity set)",
                                   where));
    }
  }
}

// Rules that span several keys of one machine.
void CheckMachine(const json& m, const std::string& at, std::vector<std::string>& errors) {
  const json& acq = m["acquisition"];
  if (acq["min_samples_per_channel"].get<long>() > acq["max_samples_per_channel"].get<long>()) {
    errors.push_back(fmt::format(
        "{}.acquisition.min_samples_per_channel: {} exceeds max_samples_per_channel {}", at,
        acq["min_samples_per_channel"].get<long>(), acq["max_samples_per_channel"].get<long>()));
  }
  std::map<long, std::size_t> rows;
  std::map<std::string, std::size_t> sensors;
  const json& channels = m["channels"];
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const long row = channels[i]["frf_row"].get<long>();
    if (row < 0) {
      // matched by sensor and axis when the machine is built
    } else if (auto [it, fresh] = rows.emplace(row, i); !fresh) {
      errors.push_back(fmt::format("{}.channels[{}].frf_row: row {} is already mapped by "
                                   "channels[{}]",
                                   at, i, row, it->second));
    }
    const std::string name = channels[i]["sensor"].get<std::string>() + "/" +
                             channels[i]["axis"].get<std::string>();
    if (auto [it, fresh] = sensors.emplace(name, i); !fresh) {
      errors.push_back(fmt::format("{}.channels[{}]: sensor axis {} is already listed by "
                                   "channels[{}]",
                                   at, i, name, it->second));
    }
  }
  const std::string source = m["frf_set"].get<std::string>();
  if (source.starts_with(kBuiltinPrefix) && source != "builtin:table1") {
    errors.push_back(fmt::format("{}.frf_set: unknown built-in FRF set \"{}\" (known: "
                                 "builtin:table1)",
                                 at, source));
  }
  std::set<std::string> gear_names;
  const json& gears = m["gear_train"]["gears"];
  for (std::size_t i = 0; i < gears.size(); ++i) {
    if (!gear_names.insert(gears[i]["name"].get<std::string>()).second) {
      errors.push_back(fmt::format("{}.gear_train.gears[{}].name: duplicate gear \"{}\"", at, i,
                                   gears[i]["name"].get<std::string>()));
    }
  }
  CheckIdentityChannels(m, at, gear_names, errors);
  const json& stages = m["gear_train"]["stages"];
  for (std::size_t i = 0; i < stages.size(); ++i) {
    for (const char* end : {"driver", "driven"}) {
      const auto name = stages[i][end].get<std::string>();
      if (!gear_names.contains(name)) {
        errors.push_back(
            fmt::format("{}.gear_train.stages[{}].{}: unknown gear \"{}\"", at, i, end, name));
      }
    }
  }
  std::set<std::string> shaft_names;
  std::map<std::string, std::string> shaft_of_gear;
  const json& shafts = m["gear_train"]["shafts"];
  for (std::size_t i = 0; i < shafts.size(); ++i) {
    const auto shaft = shafts[i]["name"].get<std::string>();
    if (!shaft_names.insert(shaft).second) {
      errors.push_back(
          fmt::format("{}.gear_train.shafts[{}].name: duplicate shaft \"{}\"", at, i, shaft));
    }
    const json& on = shafts[i]["gears"];
    for (std::size_t g = 0; g < on.size(); ++g) {
      const auto gear = on[g].get<std::string>();
      if (!gear_names.contains(gear)) {
        errors.push_back(fmt::format("{}.gear_train.shafts[{}].gears[{}]: unknown gear \"{}\"",
                                     at, i, g, gear));
      } else if (auto [it, fresh] = shaft_of_gear.emplace(gear, shaft); !fresh) {
        errors.push_back(fmt::format("{}.gear_train.shafts[{}].gears[{}]: gear \"{}\" is "
                                     "already on shaft \"{}\"",
                                     at, i, g, gear, it->second));
      }
    }
  }
  for (std::size_t i = 0; i < gears.size(); ++i) {
    const auto gear = gears[i]["name"].get<std::string>();
    if (!shaft_of_gear.contains(gear)) {
      errors.push_back(fmt::format("{}.gear_train.gears[{}]: gear \"{}\" is on no shaft (list "
                                   "it in gear_train.shafts[].gears)",
                                   at, i, gear));
    }
  }
  const json& paths = m["paths"];
  std::set<std::string> path_names;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    if (!path_names.insert(paths[i]["name"].get<std::string>()).second) {
      errors.push_back(fmt::format("{}.paths[{}].name: duplicate path \"{}\"", at, i,
                                   paths[i]["name"].get<std::string>()));
    }
    const json& near = paths[i]["gears"];
    for (std::size_t g = 0; g < near.size(); ++g) {
      if (!gear_names.contains(near[g].get<std::string>())) {
        errors.push_back(fmt::format("{}.paths[{}].gears[{}]: unknown gear \"{}\"", at, i, g,
                                     near[g].get<std::string>()));
      }
    }
  }
}

}  // namespace

Result<DaemonConfig> ParseDaemonConfig(std::string_view text, std::string_view origin) {
  // Bounded, exception-free parse (core/io/json_read.h): 1e999 or a value nested 50 000 deep
  // is an error naming the line, never an abort, at start-up and on SIGHUP alike.
  Result<json> parsed = ParseJson<json>(text, origin);
  if (!parsed) return Error{parsed.error()};
  const json& raw = parsed.value();
  auto applied = ApplySchema(DaemonConfigSchema(), raw);
  if (!applied) return Error{applied.error()};
  const json& c = applied.value();

  std::vector<std::string> errors;
  std::map<std::string, std::size_t> ids;
  const json& machines = c["machines"];
  for (std::size_t i = 0; i < machines.size(); ++i) {
    const std::string at = fmt::format("machines[{}]", i);
    const auto id = machines[i]["id"].get<std::string>();
    if (auto [it, fresh] = ids.emplace(id, i); !fresh) {
      errors.push_back(fmt::format("{}.id: duplicate machine id \"{}\" (also machines[{}].id)",
                                   at, id, it->second));
    }
    CheckMachine(machines[i], at, errors);
  }
  const json& security = c["dds"]["security"];  // all six files or none
  bool secured = false;
  for (const auto& file : security) secured = secured || !file.get<std::string>().empty();
  for (const auto& [key, file] : security.items()) {
    if (secured && file.get<std::string>().empty()) {
      errors.push_back(fmt::format("dds.security.{}: required when any dds.security file is "
                                   "given (DDS Security needs all six)",
                                   key));
    }
  }
  if (c["standby"]["primary"] == c["daemon"]["id"]) {
    errors.push_back("standby.primary: a daemon cannot stand by for itself (daemon.id is the "
                     "same)");
  }
  const json& metrics = c["metrics"];
  const auto metrics_address = metrics["address"].get<std::string>();
  if (!IsNumericAddress(metrics_address)) {
    errors.push_back(fmt::format("metrics.address: expected a numeric IPv4 or IPv6 address "
                                 "(e.g. 127.0.0.1 or ::1), got \"{}\"",
                                 metrics_address));
  } else if (!IsLoopbackAddress(metrics_address) && !metrics["allow_remote"].get<bool>()) {
    errors.push_back(fmt::format("metrics.address: \"{}\" is not a loopback address; the "
                                 "endpoint has no TLS and no authentication, so set "
                                 "metrics.allow_remote to true to serve it beyond this host",
                                 metrics_address));
  }
  if (!errors.empty()) return Error{JoinLines(errors)};

  DaemonConfig config;
  config.origin = std::string(origin);
  config.daemon_id = c["daemon"]["id"];
  config.log_level = c["daemon"]["log_level"];
  config.status_period_s = c["daemon"]["status_period_s"];
  config.throughput_log_period_s = c["daemon"]["throughput_log_period_s"];
  config.workers = c["daemon"]["workers"];
  config.queue_blocks = c["daemon"]["queue_blocks"];
  config.state_directory = c["state"]["directory"];
  config.state_save_period_s = c["state"]["save_period_s"];
  config.standby_primary = c["standby"]["primary"];
  config.takeover_after_s = c["standby"]["takeover_after_s"];
  if (config.takeover_after_s == 0.0) config.takeover_after_s = 1.5 * config.status_period_s;
  config.domain_id = c["dds"]["domain_id"];
  const json& t = c["dds"]["topics"];
  config.topics = {t["accel_block"],    t["accel_block_v2"],      t["dominant_path"],
                   t["suspected_gear"], t["envelope_indicators"], t["condition_indicators"],
                   t["status"],         t["machine_health"]};
  config.dds_config_file = c["dds"]["config"];
  config.dds_security = {security["identity_ca"],    security["identity_certificate"],
                         security["identity_private_key"], security["permissions_ca"],
                         security["governance"],     security["permissions"]};
  config.metrics = {metrics["enabled"], metrics_address, metrics["port"],
                    metrics["allow_remote"]};
  for (std::size_t i = 0; i < machines.size(); ++i) {
    config.machines.push_back({fmt::format("machines[{}]", i), machines[i]["id"],
                               machines[i]["frf_set"], machines[i]});
  }
  config.normalized = c;
  return config;
}

Result<DaemonConfig> LoadDaemonConfigFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{fmt::format("{}: cannot open the configuration file", path)};
  in.close();
  Result<std::string> text = ReadTextFile(path, kMaxJsonFileBytes);
  if (!text) return Error{fmt::format("{} (cannot read the configuration file)", text.error())};
  return ParseDaemonConfig(*text, path);
}

}  // namespace gearpath::daemon
