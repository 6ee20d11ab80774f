#include "core/model/gear_train.h"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <numeric>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace gearpath {
namespace {

std::string Label(const char* list, std::size_t i, const std::string& name) {
  return std::string(list) + "[" + std::to_string(i) + "] (" + (name.empty() ? "unnamed" : name) +
         ")";
}

// Speed of every shaft relative to the input shaft (input = 1), propagated through the stages.
// Returns the first problem (unreachable shaft, inconsistent loop) in *why.
std::optional<std::vector<double>> RelativeSpeeds(const GearTrain& train,
                                                  const std::vector<int>& shaft_of_gear,
                                                  std::string* why) {
  const std::size_t n = train.shafts.size();
  if (n == 0) {
    *why = "shafts: at least one shaft (the input shaft) is required";
    return std::nullopt;
  }
  std::vector<double> speed(n, 0.0);
  std::vector<char> known(n, 0);
  speed[0] = 1.0;
  known[0] = 1;
  // Stage order need not follow the power flow: sweep until nothing changes (<= n sweeps).
  for (std::size_t sweep = 0; sweep < n; ++sweep) {
    bool changed = false;
    for (std::size_t s = 0; s < train.stages.size(); ++s) {
      const StageSpec& st = train.stages[s];
      const int gd = train.GearIndex(st.driver);
      const int gn = train.GearIndex(st.driven);
      const int sd = shaft_of_gear[static_cast<std::size_t>(gd)];
      const int sn = shaft_of_gear[static_cast<std::size_t>(gn)];
      const double ratio = static_cast<double>(train.gears[static_cast<std::size_t>(gd)].teeth) /
                           train.gears[static_cast<std::size_t>(gn)].teeth;
      const auto d = static_cast<std::size_t>(sd);
      const auto m = static_cast<std::size_t>(sn);
      if (known[d] && !known[m]) {
        speed[m] = speed[d] * ratio;
        known[m] = 1;
        changed = true;
      } else if (known[m] && !known[d]) {
        speed[d] = speed[m] / ratio;
        known[d] = 1;
        changed = true;
      } else if (known[d] && known[m] && std::abs(speed[m] - speed[d] * ratio) > 1e-12 * speed[d]) {
        *why = Label("stages", s, st.driver + "->" + st.driven) +
               ": tooth ratio contradicts the other stages (closed loop with inconsistent speeds)";
        return std::nullopt;
      }
    }
    if (!changed) break;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!known[i]) {
      *why = Label("shafts", i, train.shafts[i].name) +
             ": not connected to the input shaft through any stage, so its speed is unknown";
      return std::nullopt;
    }
  }
  return speed;
}

// Index of the shaft carrying every gear; requires a validated train.
std::vector<int> ShaftOfEveryGear(const GearTrain& train) {
  std::vector<int> out(train.gears.size(), -1);
  for (std::size_t s = 0; s < train.shafts.size(); ++s) {
    for (const std::string& g : train.shafts[s].gears) {
      const int gi = train.GearIndex(g);
      if (gi >= 0) out[static_cast<std::size_t>(gi)] = static_cast<int>(s);
    }
  }
  return out;
}

}  // namespace

double StandardContactRatio(int z1, int z2, double pressure_angle_deg,
                            double addendum_coefficient) {
  const double alpha = pressure_angle_deg * std::numbers::pi / 180.0;
  const double r1 = 0.5 * z1;
  const double r2 = 0.5 * z2;
  const double ra1 = r1 + addendum_coefficient;
  const double ra2 = r2 + addendum_coefficient;
  const double rb1 = r1 * std::cos(alpha);
  const double rb2 = r2 * std::cos(alpha);
  const double path = std::sqrt(ra1 * ra1 - rb1 * rb1) + std::sqrt(ra2 * ra2 - rb2 * rb2) -
                      (r1 + r2) * std::sin(alpha);
  return path / (std::numbers::pi * std::cos(alpha));
}

int GearTrain::GearIndex(const std::string& name) const {
  for (std::size_t i = 0; i < gears.size(); ++i) {
    if (gears[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

int GearTrain::ShaftIndex(const std::string& name) const {
  for (std::size_t i = 0; i < shafts.size(); ++i) {
    if (shafts[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

int GearTrain::ShaftOfGear(const std::string& name) const {
  for (std::size_t s = 0; s < shafts.size(); ++s) {
    for (const std::string& g : shafts[s].gears) {
      if (g == name) return static_cast<int>(s);
    }
  }
  return -1;
}

std::vector<std::string> GearTrain::GearsNearBearing(int bearing) const {
  if (bearing < 0 || static_cast<std::size_t>(bearing) >= bearings.size()) return {};
  const int s = ShaftIndex(bearings[static_cast<std::size_t>(bearing)].shaft);
  if (s < 0) return {};
  return shafts[static_cast<std::size_t>(s)].gears;
}

bool GearTrain::IsValid(std::string* why) const {
  std::string local;
  std::string& msg = why != nullptr ? *why : local;
  msg.clear();
  if (shafts.empty()) {
    msg = "shafts: at least one shaft (the input shaft) is required";
    return false;
  }
  if (gears.size() < 2) {
    msg = "gears: at least two gears are required, got " + std::to_string(gears.size());
    return false;
  }
  if (stages.empty()) {
    msg = "stages: at least one stage is required";
    return false;
  }
  if (!(pressure_angle_deg > 0.0 && pressure_angle_deg < 45.0)) {
    msg =
        "pressure_angle_deg: must be in (0, 45) degrees, got " + std::to_string(pressure_angle_deg);
    return false;
  }
  if (!(addendum_coefficient > 0.0 && addendum_coefficient <= 2.0)) {
    msg = "addendum_coefficient: must be in (0, 2], got " + std::to_string(addendum_coefficient);
    return false;
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < shafts.size(); ++i) {
    if (shafts[i].name.empty()) {
      msg = Label("shafts", i, "") + ": name must not be empty";
      return false;
    }
    if (!names.insert(shafts[i].name).second) {
      msg = Label("shafts", i, shafts[i].name) + ": duplicate shaft name";
      return false;
    }
  }
  names.clear();
  for (std::size_t i = 0; i < gears.size(); ++i) {
    if (gears[i].name.empty()) {
      msg = Label("gears", i, "") + ": name must not be empty";
      return false;
    }
    if (!names.insert(gears[i].name).second) {
      msg = Label("gears", i, gears[i].name) + ": duplicate gear name";
      return false;
    }
    if (gears[i].teeth < 1) {
      msg = Label("gears", i, gears[i].name) + ": teeth must be >= 1, got " +
            std::to_string(gears[i].teeth);
      return false;
    }
  }
  // Every gear sits on exactly one shaft.
  std::vector<int> shaft_of_gear(gears.size(), -1);
  for (std::size_t s = 0; s < shafts.size(); ++s) {
    for (const std::string& g : shafts[s].gears) {
      const int gi = GearIndex(g);
      if (gi < 0) {
        msg = Label("shafts", s, shafts[s].name) + ": unknown gear '" + g + "'";
        return false;
      }
      int& owner = shaft_of_gear[static_cast<std::size_t>(gi)];
      if (owner >= 0) {
        msg = Label("gears", static_cast<std::size_t>(gi), g) + ": on two shafts, '" +
              shafts[static_cast<std::size_t>(owner)].name + "' and '" + shafts[s].name + "'";
        if (owner == static_cast<int>(s)) {
          msg = Label("shafts", s, shafts[s].name) + ": lists gear '" + g + "' twice";
        }
        return false;
      }
      owner = static_cast<int>(s);
    }
  }
  for (std::size_t i = 0; i < gears.size(); ++i) {
    if (shaft_of_gear[i] < 0) {
      msg = Label("gears", i, gears[i].name) + ": on no shaft";
      return false;
    }
  }
  // Every gear meshes in exactly one stage; the two gears of a stage are on different shafts.
  std::vector<int> stage_of_gear(gears.size(), -1);
  for (std::size_t s = 0; s < stages.size(); ++s) {
    const StageSpec& st = stages[s];
    const std::string label = Label("stages", s, st.driver + "->" + st.driven);
    for (const std::string* g : {&st.driver, &st.driven}) {
      const int gi = GearIndex(*g);
      if (gi < 0) {
        msg = label + ": unknown gear '" + *g + "'";
        return false;
      }
      int& owner = stage_of_gear[static_cast<std::size_t>(gi)];
      if (owner >= 0) {
        msg = Label("gears", static_cast<std::size_t>(gi), *g) + ": meshes in two stages (" +
              std::to_string(owner) + " and " + std::to_string(s) +
              "); idler gears are not supported";
        return false;
      }
      owner = static_cast<int>(s);
    }
    if (shaft_of_gear[static_cast<std::size_t>(GearIndex(st.driver))] ==
        shaft_of_gear[static_cast<std::size_t>(GearIndex(st.driven))]) {
      msg = label + ": driver and driven gear are on the same shaft";
      return false;
    }
  }
  for (std::size_t i = 0; i < gears.size(); ++i) {
    if (stage_of_gear[i] < 0) {
      msg = Label("gears", i, gears[i].name) + ": meshes in no stage";
      return false;
    }
  }
  names.clear();
  for (std::size_t b = 0; b < bearings.size(); ++b) {
    if (bearings[b].name.empty()) {
      msg = Label("bearings", b, "") + ": name must not be empty";
      return false;
    }
    if (!names.insert(bearings[b].name).second) {
      msg = Label("bearings", b, bearings[b].name) + ": duplicate bearing name";
      return false;
    }
    if (ShaftIndex(bearings[b].shaft) < 0) {
      msg = Label("bearings", b, bearings[b].name) + ": unknown shaft '" + bearings[b].shaft + "'";
      return false;
    }
  }
  return RelativeSpeeds(*this, shaft_of_gear, &msg).has_value();
}

Status GearTrain::Validate() const {
  std::string why;
  if (IsValid(&why)) return Status::Ok();
  return Error{"gear train: " + why};
}

Result<TrainKinematics> GearTrain::Kinematics(double input_hz) const {
  if (Status st = Validate(); !st) return Error{st.error()};
  if (!(input_hz > 0.0) || !std::isfinite(input_hz)) {
    return Error{"gear train: input speed must be a finite positive frequency in Hz, got " +
                 std::to_string(input_hz)};
  }
  const std::vector<int> shaft_of_gear = ShaftOfEveryGear(*this);
  std::string why;
  const std::optional<std::vector<double>> rel = RelativeSpeeds(*this, shaft_of_gear, &why);
  TrainKinematics k;
  k.input_hz = input_hz;
  for (std::size_t s = 0; s < shafts.size(); ++s) {
    k.shafts.push_back({shafts[s].name, input_hz * (*rel)[s]});
  }
  for (const StageSpec& st : stages) {
    const GearSpec& d = gears[static_cast<std::size_t>(GearIndex(st.driver))];
    const GearSpec& n = gears[static_cast<std::size_t>(GearIndex(st.driven))];
    const int sd = shaft_of_gear[static_cast<std::size_t>(GearIndex(st.driver))];
    k.meshes.push_back(
        {st.driver, st.driven, d.teeth * k.shafts[static_cast<std::size_t>(sd)].rotation_hz,
         StandardContactRatio(d.teeth, n.teeth, pressure_angle_deg, addendum_coefficient)});
  }
  for (std::size_t g = 0; g < gears.size(); ++g) {
    GearKinematics gk;
    gk.name = gears[g].name;
    gk.teeth = gears[g].teeth;
    gk.shaft = shaft_of_gear[g];
    for (std::size_t s = 0; s < stages.size(); ++s) {
      if (stages[s].driver == gk.name || stages[s].driven == gk.name)
        gk.stage = static_cast<int>(s);
    }
    gk.characteristic_hz = k.shafts[static_cast<std::size_t>(gk.shaft)].rotation_hz;
    k.gears.push_back(gk);
  }
  return k;
}

Result<std::int64_t> GearTrain::InputRevolutionsPerCommonPeriod() const {
  if (Status st = Validate(); !st) return Error{st.error()};
  constexpr std::int64_t kLimit = 1'000'000'000;
  const std::vector<int> shaft_of_gear = ShaftOfEveryGear(*this);
  // Speed of every shaft relative to the input as a reduced fraction num/den.
  std::vector<std::int64_t> num(shafts.size(), 0);
  std::vector<std::int64_t> den(shafts.size(), 0);
  if (num.empty() || den.empty()) return Error{"gear train: no shafts"};
  num[0] = 1;
  den[0] = 1;
  bool changed = true;
  while (changed) {
    changed = false;
    for (const StageSpec& st : stages) {
      const auto gd = static_cast<std::size_t>(GearIndex(st.driver));
      const auto gn = static_cast<std::size_t>(GearIndex(st.driven));
      const auto d = static_cast<std::size_t>(shaft_of_gear[gd]);
      const auto n = static_cast<std::size_t>(shaft_of_gear[gn]);
      std::int64_t zd = gears[gd].teeth;
      std::int64_t zn = gears[gn].teeth;
      std::size_t from = d;
      std::size_t to = n;
      if (den[d] == 0 && den[n] != 0) {  // propagate against the power flow
        std::swap(from, to);
        std::swap(zd, zn);
      }
      if (den[from] == 0 || den[to] != 0) continue;
      std::int64_t p = num[from] * zd;
      std::int64_t q = den[from] * zn;
      const std::int64_t g = std::gcd(p, q);
      p /= g;
      q /= g;
      if (q > kLimit || p > kLimit) {
        return Error{"gear train: shaft '" + shafts[to].name +
                     "' has no common period with the input shaft below 10^9 revolutions"};
      }
      num[to] = p;
      den[to] = q;
      changed = true;
    }
  }
  std::int64_t revolutions = 1;
  for (std::size_t s = 0; s < shafts.size(); ++s) {
    revolutions = std::lcm(revolutions, den[s]);
    if (revolutions > kLimit) {
      return Error{"gear train: the shafts have no common period below 10^9 input revolutions"};
    }
  }
  return revolutions;
}

GearTrain GearTrain::Table1() {
  GearTrain t;
  t.shafts = {{"input", {"G1"}}, {"intermediate", {"G2", "G3"}}, {"output", {"G4"}}};
  t.gears = {{"G1", 28}, {"G2", 40}, {"G3", 34}, {"G4", 34}};
  t.stages = {{"G1", "G2"}, {"G3", "G4"}};
  t.bearings = {{"B1", "input"}, {"B2", "intermediate"}, {"B3", "output"}};
  return t;
}

}  // namespace gearpath
