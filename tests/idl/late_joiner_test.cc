// A subscriber that joins after the results were published still gets the current result of
// every machine (transient-local, keep-last 1 per instance), and only that.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <map>
#include <string>
#include <vector>

#include "idl/dds/gearpath_topics.h"
#include "tests/idl/loopback_test_domains.h"

namespace gearpath::dds {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

Status Publish(Writer<gearpath_SuspectedGear>& writer, const char* machine, std::uint64_t sequence,
               const char* gear) {
  Owned<gearpath_SuspectedGear> verdict;
  if (!SetString(verdict->machine_id, machine) || !SetString(verdict->gear_name, gear)) {
    return Error{"identifier too long"};
  }
  verdict->block_sequence = sequence;
  verdict->state = gearpath_SUSPECTED;
  verdict->confidence = 0.5;
  return writer.Write(*verdict);
}

// Takes whatever arrives until `window` passes with nothing new (or `deadline`).
std::vector<Owned<gearpath_SuspectedGear>> TakeAll(Reader<gearpath_SuspectedGear>& reader,
                                                   WaitSet& waitset, std::size_t expected) {
  std::vector<Owned<gearpath_SuspectedGear>> all;
  std::vector<Owned<gearpath_SuspectedGear>> batch(8);
  std::vector<SampleInfo> infos(8);
  const auto deadline = std::chrono::steady_clock::now() + seconds(10);
  while (std::chrono::steady_clock::now() < deadline) {
    std::array<dds_attach_t, 1> triggered{};
    // Once the expected samples are in, wait a little longer to catch any extra one.
    const auto wait = all.size() >= expected ? milliseconds(300) : milliseconds(1000);
    Result<std::size_t> woke = waitset.Wait(triggered, wait);
    if (!woke) break;
    if (*woke == 0 && all.size() >= expected) break;
    Result<std::size_t> n = reader.Take(batch, infos);
    if (!n) break;
    for (std::size_t i = 0; i < *n; ++i) {
      if (infos[i].valid_data) all.push_back(std::move(batch[i]));
    }
  }
  return all;
}

TEST(LateJoiner, GetsTheLastResultOfEachMachineFromATransientLocalWriter) {
  testing::LoopbackPair pair;
  Topic<gearpath_SuspectedGear> pub_topic(pair.publisher);
  Writer<gearpath_SuspectedGear> writer(pub_topic);
  ASSERT_TRUE(Publish(writer, "gearbox-1", 1, "z1"));
  ASSERT_TRUE(Publish(writer, "gearbox-2", 1, "z2"));
  ASSERT_TRUE(Publish(writer, "gearbox-1", 2, "z3"));
  ASSERT_TRUE(Publish(writer, "gearbox-1", 3, "z4"));  // the current verdict of gearbox-1

  // The subscriber joins only now.
  Topic<gearpath_SuspectedGear> sub_topic(pair.subscriber);
  Reader<gearpath_SuspectedGear> reader(sub_topic);
  ReadCondition data(reader);
  WaitSet waitset(pair.subscriber);
  waitset.Attach(data, 1);

  const std::vector<Owned<gearpath_SuspectedGear>> got = TakeAll(reader, waitset, 2);
  ASSERT_EQ(got.size(), 2U);
  std::map<std::string, std::pair<std::uint64_t, std::string>> by_machine;
  for (const Owned<gearpath_SuspectedGear>& v : got) {
    by_machine[std::string(GetString(v->machine_id))] = {v->block_sequence,
                                                         std::string(GetString(v->gear_name))};
  }
  ASSERT_EQ(by_machine.size(), 2U);
  EXPECT_EQ(by_machine["gearbox-1"].first, 3U);
  EXPECT_EQ(by_machine["gearbox-1"].second, "z4");
  EXPECT_EQ(by_machine["gearbox-2"].first, 1U);
  EXPECT_EQ(by_machine["gearbox-2"].second, "z2");
}

}  // namespace
}  // namespace gearpath::dds
