#include "daemon/daemon_config.h"

#include <fmt/format.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "daemon/config_schema.h"

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
    if (auto [it, fresh] = rows.emplace(row, i); !fresh) {
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
  const json& shafts = m["gear_train"]["shafts"];
  for (std::size_t i = 0; i < shafts.size(); ++i) {
    shaft_names.insert(shafts[i]["name"].get<std::string>());
    const json& on = shafts[i]["gears"];
    for (std::size_t g = 0; g < on.size(); ++g) {
      if (!gear_names.contains(on[g].get<std::string>())) {
        errors.push_back(fmt::format("{}.gear_train.shafts[{}].gears[{}]: unknown gear \"{}\"",
                                     at, i, g, on[g].get<std::string>()));
      }
    }
  }
  std::set<std::string> bearing_names;
  const json& bearings = m["gear_train"]["bearings"];
  for (std::size_t i = 0; i < bearings.size(); ++i) {
    bearing_names.insert(bearings[i]["name"].get<std::string>());
    if (!shaft_names.contains(bearings[i]["shaft"].get<std::string>())) {
      errors.push_back(fmt::format("{}.gear_train.bearings[{}].shaft: unknown shaft \"{}\"", at,
                                   i, bearings[i]["shaft"].get<std::string>()));
    }
  }
  const json& paths = m["paths"];
  for (std::size_t i = 0; i < paths.size(); ++i) {
    if (!bearing_names.contains(paths[i]["bearing"].get<std::string>())) {
      errors.push_back(fmt::format("{}.paths[{}].bearing: unknown bearing \"{}\"", at, i,
                                   paths[i]["bearing"].get<std::string>()));
    }
  }
}

}  // namespace

Result<DaemonConfig> ParseDaemonConfig(std::string_view text, std::string_view origin) {
  json raw;
  try {
    raw = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/true,
                      /*ignore_comments=*/false);
  } catch (const json::parse_error& e) {
    return Error{fmt::format("{}: not valid JSON: {}", origin, e.what())};
  }
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
  if (!errors.empty()) return Error{JoinLines(errors)};

  DaemonConfig config;
  config.origin = std::string(origin);
  config.daemon_id = c["daemon"]["id"];
  config.log_level = c["daemon"]["log_level"];
  config.status_period_s = c["daemon"]["status_period_s"];
  config.throughput_log_period_s = c["daemon"]["throughput_log_period_s"];
  config.domain_id = c["dds"]["domain_id"];
  const json& t = c["dds"]["topics"];
  config.topics = {t["accel_block"], t["dominant_path"], t["suspected_gear"],
                   t["envelope_indicators"], t["status"]};
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
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return Error{fmt::format("{}: cannot read the configuration file", path)};
  return ParseDaemonConfig(text.str(), path);
}

}  // namespace gearpath::daemon
