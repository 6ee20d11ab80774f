// sim_publisher: publishes the simulated Table-1 gearbox (core/simulation) as AccelBlocks on a
// loopback DDS domain, for trying gearpathd by hand and for demos: first healthy blocks (for
// the daemon to learn its baseline), then blocks with a gear fault. Loopback only (the
// project's Cyclone configuration, CYCLONEDDS_URI ignored).
//
//   sim_publisher --machine table1 --healthy 20 --faulty 10 --fault fracture --gear G1
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <thread>

#include "core/model/gear_train.h"
#include "core/model/lumped_gearbox_model.h"
#include "core/simulation/gearbox_simulator.h"
#include "idl/dds/gearpath_topics.h"
#include "tests/integration/wire_block.h"

int main(int argc, char** argv) {
  using namespace gearpath;
  CLI::App app{"Publish the simulated Table-1 gearbox as AccelBlocks (loopback DDS)"};
  std::string machine = "table1";
  std::string fault = "fracture";
  std::string gear = "G1";
  int healthy = 20;
  int faulty = 10;
  int domain = 0;
  double period_s = 0.2;
  double noise = 0.05;
  app.add_option("--machine", machine, "Machine id")->capture_default_str();
  app.add_option("--fault", fault, "none, chipped, wear or fracture")->capture_default_str();
  app.add_option("--gear", gear, "Faulty gear (G1..G4)")->capture_default_str();
  app.add_option("--healthy", healthy, "Healthy blocks first")->capture_default_str();
  app.add_option("--faulty", faulty, "Then faulty blocks")->capture_default_str();
  app.add_option("--domain", domain, "DDS domain id")->capture_default_str();
  app.add_option("--period", period_s, "Seconds between blocks")->capture_default_str();
  app.add_option("--noise", noise, "Noise std relative to the signal RMS")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  const auto type = ParseFaultType(fault);
  if (!type) {
    std::fprintf(stderr, "unknown fault type %s\n", fault.c_str());
    return 2;
  }
  auto model = LumpedGearboxModel::Create(Table1Parameters());
  if (!model) {
    std::fprintf(stderr, "%s\n", model.error().c_str());
    return 1;
  }
  auto make = [&](FaultType t, std::uint64_t seed) {
    SimulatorConfig c;
    c.machine_id = machine;
    c.fault.type = t;
    c.fault.gear = gear;
    c.noise_relative = noise;
    c.seed = seed;
    c.include_housing_channel = false;  // p1..p3: the rows of builtin:table1
    return GearboxSimulator::Create(model.value(), GearTrain::Table1(), c);
  };
  auto good = make(FaultType::kNone, 7);
  auto bad = make(*type, 21);
  if (!good || !bad) {
    std::fprintf(stderr, "%s\n", (!good ? good.error() : bad.error()).c_str());
    return 1;
  }
  dds::Domain dds_domain(domain, dds::kLoopbackConfigXml, dds::EnvironmentConfig::kIgnore);
  dds::Participant participant(dds_domain);
  dds::Topic<gearpath_AccelBlock> topic(participant);
  dds::Writer<gearpath_AccelBlock> writer(topic);
  if (!writer.WaitForReaders(1, std::chrono::seconds(30)).ok()) {
    std::fprintf(stderr, "no AccelBlock subscriber (is gearpathd running on domain %d?)\n",
                 domain);
    return 1;
  }
  AccelBlock block;
  dds::Owned<gearpath_AccelBlock> sample;
  std::uint64_t seq = 1;
  for (int i = 0; i < healthy + faulty; ++i) {
    (i < healthy ? good.value() : bad.value()).NextBlock(block);
    block.sequence = seq++;
    block.t0_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                      std::chrono::system_clock::now().time_since_epoch())
                      .count();
    if (!testing::ToWire(block, sample)) return 1;
    if (Status st = writer.Write(*sample); !st) {
      std::fprintf(stderr, "%s\n", st.error().c_str());
      return 1;
    }
    std::fprintf(stderr, "block %llu (%s)\n", static_cast<unsigned long long>(block.sequence),
                 i < healthy ? "healthy" : fault.c_str());
    std::this_thread::sleep_for(std::chrono::duration<double>(period_s));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let reliable delivery finish
  return 0;
}
