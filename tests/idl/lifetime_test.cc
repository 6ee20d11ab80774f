// Children keep their parents alive: dropping the wrapper of a parent before its children
// leaves the children usable, and the entities are deleted child first when the last goes.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "idl/dds/gearpath_topics.h"
#include "tests/idl/loopback_test_domains.h"

namespace gearpath::dds {
namespace {

using std::chrono::seconds;

TEST(Lifetime, AWriterOutlivesTheWrappersOfItsTopicParticipantAndDomain) {
  std::optional<testing::LoopbackPair> pair;
  pair.emplace();
  Topic<gearpath_Status> sub_topic(pair->subscriber);
  Reader<gearpath_Status> reader(sub_topic);

  auto domain = std::make_unique<Domain>(testing::TestDomainBase() + 2,
                                         testing::TestConfig(testing::TestDomainBase()),
                                         EnvironmentConfig::kIgnore);
  auto participant = std::make_unique<Participant>(*domain);
  auto topic = std::make_unique<Topic<gearpath_Status>>(*participant);
  Writer<gearpath_Status> writer(*topic);
  const dds_entity_t domain_handle = domain->handle();
  topic.reset();
  participant.reset();
  domain.reset();

  // The domain entity still exists (the writer holds it) and the writer still publishes.
  EXPECT_GT(dds_get_parent(writer.handle()), 0);  // its (implicit) publisher
  dds_domainid_t id = 0;
  EXPECT_EQ(dds_get_domainid(domain_handle, &id), DDS_RETCODE_OK);
  ASSERT_TRUE(writer.WaitForReaders(1, seconds(10)));
  Owned<gearpath_Status> status;
  ASSERT_TRUE(SetString(status->daemon_id, "gearpathd-1"));
  status->state = gearpath_RUNNING;
  ASSERT_TRUE(writer.Write(*status));

  ReadCondition data(reader);
  WaitSet waitset(pair->subscriber);
  waitset.Attach(data, 1);
  std::array<dds_attach_t, 1> triggered{};
  Result<std::size_t> woke = waitset.Wait(triggered, seconds(10));
  ASSERT_TRUE(woke && *woke == 1U);
  std::vector<Owned<gearpath_Status>> got(1);
  std::vector<SampleInfo> infos(1);
  Result<std::size_t> n = reader.Take(got, infos);
  ASSERT_TRUE(n && *n == 1U);
  EXPECT_EQ(GetString(got[0]->daemon_id), "gearpathd-1");
  EXPECT_EQ(got[0]->state, gearpath_RUNNING);

  // Dropping the writer, the last owner, deletes it and then its topic, participant, domain.
  const dds_entity_t writer_handle = writer.handle();
  { Writer<gearpath_Status> last(std::move(writer)); }
  EXPECT_EQ(writer.handle(), 0);  // NOLINT(bugprone-use-after-move): moved-from is empty
  EXPECT_LT(dds_get_domainid(writer_handle, &id), 0);
  EXPECT_LT(dds_get_domainid(domain_handle, &id), 0);
}

TEST(Lifetime, MovingAReaderKeepsOneLiveEntity) {
  testing::LoopbackPair pair;
  Topic<gearpath_Status> topic(pair.subscriber);
  Reader<gearpath_Status> first(topic);
  const dds_entity_t handle = first.handle();
  Reader<gearpath_Status> second(std::move(first));
  EXPECT_EQ(second.handle(), handle);
  EXPECT_EQ(first.handle(), 0);  // NOLINT(bugprone-use-after-move)
  dds_domainid_t id = 0;
  EXPECT_EQ(dds_get_domainid(handle, &id), DDS_RETCODE_OK);
}

}  // namespace
}  // namespace gearpath::dds
