#include "core/frf/identity_frf_set.h"

#include <fmt/format.h>

#include <cmath>
#include <set>
#include <utility>

namespace gearpath {
namespace {

Status CheckChannels(const std::vector<ResponseChannel>& channels) {
  if (channels.empty())
    return Error{"channels: empty (the identity set needs one path per channel)"};
  std::set<std::pair<std::string, std::string>> seen;
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const ResponseChannel& c = channels[i];
    if (c.sensor.empty()) return Error{fmt::format("channels[{}].sensor: empty", i)};
    if (c.axis != "x" && c.axis != "y" && c.axis != "z") {
      return Error{fmt::format("channels[{}].axis: expected x, y or z, got \"{}\"", i, c.axis)};
    }
    if (!seen.emplace(c.sensor, c.axis).second) {
      return Error{
          fmt::format("channels[{}]: sensor {} axis {} is listed twice", i, c.sensor, c.axis)};
    }
  }
  return Status::Ok();
}

Status CheckGears(const std::vector<std::vector<std::string>>& gears, std::size_t channels) {
  if (gears.size() != channels) {
    return Error{
        fmt::format("gears_per_channel: {} entries for {} channels (one list per "
                    "channel)",
                    gears.size(), channels)};
  }
  for (std::size_t i = 0; i < gears.size(); ++i) {
    if (gears[i].empty()) {
      return Error{
          fmt::format("gears_per_channel[{}]: no gear named (each sensor needs the "
                      "gears it sits near)",
                      i)};
    }
    std::set<std::string> seen;
    for (std::size_t g = 0; g < gears[i].size(); ++g) {
      if (gears[i][g].empty()) return Error{fmt::format("gears_per_channel[{}][{}]: empty", i, g)};
      if (!seen.insert(gears[i][g]).second) {
        return Error{fmt::format("gears_per_channel[{}][{}]: gear \"{}\" is named twice", i, g,
                                 gears[i][g])};
      }
    }
  }
  return Status::Ok();
}

Status CheckGrid(const Eigen::VectorXd& f) {
  if (f.size() == 0) return Error{"frequency_hz: empty"};
  for (Eigen::Index k = 0; k < f.size(); ++k) {
    if (!std::isfinite(f[k]) || f[k] < 0.0) {
      return Error{fmt::format("frequency_hz[{}]: {} is not a finite frequency >= 0", k, f[k])};
    }
    if (k > 0 && !(f[k] > f[k - 1])) {
      return Error{
          fmt::format("frequency_hz[{}]: {} Hz does not exceed the previous {} Hz (the "
                      "grid must increase strictly)",
                      k, f[k], f[k - 1])};
    }
  }
  return Status::Ok();
}

}  // namespace

Result<FrfSet> MakeIdentityFrfSet(const std::vector<ResponseChannel>& channels,
                                  const std::vector<std::vector<std::string>>& gears_per_channel,
                                  const Eigen::VectorXd& frequency_hz) {
  if (Status st = CheckChannels(channels); !st) return Error{st.error()};
  if (Status st = CheckGears(gears_per_channel, channels.size()); !st) return Error{st.error()};
  if (Status st = CheckGrid(frequency_hz); !st) return Error{st.error()};

  FrfSet set;
  set.description =
      "identity: every sensor channel is its own transfer path (monitoring before the FRFs are "
      "measured)";
  // The "force" of a path is the response itself, so H is dimensionless.
  set.unit = "1";
  set.decoupling = kIdentityDecoupling;
  set.channels = channels;
  for (std::size_t i = 0; i < channels.size(); ++i) {
    TransferPath p;
    p.name = channels[i].sensor + "/" + channels[i].axis;
    p.bearing = "sensor " + channels[i].sensor + " (identity path, no FRF measured)";
    p.direction = channels[i].axis;
    p.gears = gears_per_channel[i];
    set.paths.push_back(std::move(p));
  }
  const auto n = static_cast<Eigen::Index>(channels.size());
  set.decoupled.frequency_hz = frequency_hz;
  set.decoupled.at.assign(static_cast<std::size_t>(frequency_hz.size()),
                          Eigen::MatrixXcd::Identity(n, n));
  return set;
}

}  // namespace gearpath
