#include "core/diagnosis/train_layout.h"

#include <cmath>
#include <string>

#include "core/model/gear_train.h"

namespace gearpath {

TrainLayout TrainLayout::Table1() {
  TrainLayout t;
  t.shafts = {{"input"}, {"intermediate"}, {"output"}};
  t.gears = {{"G1", 28, 0}, {"G2", 40, 1}, {"G3", 34, 1}, {"G4", 34, 2}};
  t.meshes = {{0, 1}, {2, 3}};
  t.input_shaft = 0;
  return t;
}

Result<std::vector<double>> ShaftRateRatios(const TrainLayout& layout) {
  const int shafts = static_cast<int>(layout.shafts.size());
  const int gears = static_cast<int>(layout.gears.size());
  if (shafts == 0) return Error{"train layout has no shafts"};
  if (layout.input_shaft < 0 || layout.input_shaft >= shafts) {
    return Error{"train layout: input_shaft " + std::to_string(layout.input_shaft) +
                 " is not a shaft index (0.." + std::to_string(shafts - 1) + ")"};
  }
  for (int s = 0; s < shafts; ++s) {
    if (layout.shafts[s].name.empty()) {
      return Error{"train layout: shaft " + std::to_string(s) + " has no name"};
    }
  }
  for (int g = 0; g < gears; ++g) {
    const TrainGear& gear = layout.gears[g];
    if (gear.name.empty()) return Error{"train layout: gear " + std::to_string(g) + " has no name"};
    if (gear.teeth <= 0) {
      return Error{"train layout: gear '" + gear.name + "' has " + std::to_string(gear.teeth) +
                   " teeth (must be > 0)"};
    }
    if (gear.shaft < 0 || gear.shaft >= shafts) {
      return Error{"train layout: gear '" + gear.name + "' is on shaft " +
                   std::to_string(gear.shaft) + ", not a shaft index"};
    }
    for (int h = 0; h < g; ++h) {
      if (layout.gears[h].name == gear.name) {
        return Error{"train layout: gear name '" + gear.name + "' is used twice"};
      }
    }
  }
  for (std::size_t m = 0; m < layout.meshes.size(); ++m) {
    const TrainMesh& mesh = layout.meshes[m];
    if (mesh.gear_a < 0 || mesh.gear_a >= gears || mesh.gear_b < 0 || mesh.gear_b >= gears) {
      return Error{"train layout: mesh " + std::to_string(m) + " names gear indices " +
                   std::to_string(mesh.gear_a) + " and " + std::to_string(mesh.gear_b) +
                   ", not both gear indices"};
    }
    if (layout.gears[mesh.gear_a].shaft == layout.gears[mesh.gear_b].shaft) {
      return Error{"train layout: mesh " + std::to_string(m) + " joins gears '" +
                   layout.gears[mesh.gear_a].name + "' and '" + layout.gears[mesh.gear_b].name +
                   "' on the same shaft"};
    }
  }
  // Propagate rates from the input shaft through the meshes (rigid shafts, no slip).
  std::vector<double> ratio(shafts, 0.0);
  ratio[layout.input_shaft] = 1.0;
  bool changed = true;
  while (changed) {
    changed = false;
    for (std::size_t m = 0; m < layout.meshes.size(); ++m) {
      const TrainGear& a = layout.gears[layout.meshes[m].gear_a];
      const TrainGear& b = layout.gears[layout.meshes[m].gear_b];
      for (int dir = 0; dir < 2; ++dir) {
        const TrainGear& from = dir == 0 ? a : b;
        const TrainGear& to = dir == 0 ? b : a;
        if (ratio[from.shaft] == 0.0) continue;
        const double r = ratio[from.shaft] * from.teeth / to.teeth;
        if (ratio[to.shaft] == 0.0) {
          ratio[to.shaft] = r;
          changed = true;
        } else if (std::abs(ratio[to.shaft] - r) > 1e-9 * r) {
          return Error{"train layout: mesh " + std::to_string(m) + " ('" + from.name + "'-'" +
                       to.name + "') gives shaft '" + layout.shafts[to.shaft].name +
                       "' a rate inconsistent with another path through the train"};
        }
      }
    }
  }
  for (int s = 0; s < shafts; ++s) {
    if (ratio[s] == 0.0) {
      return Error{"train layout: shaft '" + layout.shafts[s].name +
                   "' is not connected to the input shaft through any mesh"};
    }
  }
  return ratio;
}

Result<TrainLayout> TrainLayoutFromGearTrain(const GearTrain& train) {
  if (auto st = train.Validate(); !st) return Error{st.error()};
  TrainLayout t;
  for (const ShaftSpec& s : train.shafts) t.shafts.push_back({s.name});
  for (const GearSpec& g : train.gears) {
    t.gears.push_back({g.name, g.teeth, train.ShaftOfGear(g.name)});
  }
  for (const StageSpec& st : train.stages) {
    t.meshes.push_back({train.GearIndex(st.driver), train.GearIndex(st.driven)});
  }
  t.input_shaft = 0;
  return t;
}

}  // namespace gearpath
