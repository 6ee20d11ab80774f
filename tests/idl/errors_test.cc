// Failures of the DDS layer say which dds_* call failed and Cyclone's reason.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "idl/dds/gearpath_topics.h"
#include "tests/idl/loopback_test_domains.h"

namespace gearpath::dds {
namespace {

using ::testing::HasSubstr;

template <typename F>
std::string ErrorOf(F&& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(Errors, CreatingATopicOnADeletedParticipantNamesDdsCreateTopicAndTheTopic) {
  testing::LoopbackPair pair;
  ASSERT_EQ(dds_delete(pair.publisher.handle()), DDS_RETCODE_OK);
  const std::string message = ErrorOf([&] { Topic<gearpath_DominantPath> topic(pair.publisher); });
  EXPECT_THAT(message, HasSubstr("dds_create_topic(\"gearpath/DominantPath\") failed: "));
  // Cyclone's reason, from dds_strretcode, follows.
  EXPECT_THAT(message, HasSubstr(dds_strretcode(DDS_RETCODE_BAD_PARAMETER)));
}

TEST(Errors, AHistoryDeeperThanThePerInstanceLimitNamesDdsCreateReader) {
  testing::LoopbackPair pair;
  Topic<gearpath_AccelBlock> topic(pair.subscriber);
  Qos inconsistent = ReaderQos(TopicClass::kBlockStream);
  inconsistent.KeepLast(32).ResourceLimits(64, 4, 16);  // depth 32 > 16 per instance
  const std::string message =
      ErrorOf([&] { Reader<gearpath_AccelBlock> reader(topic, inconsistent); });
  EXPECT_THAT(message, HasSubstr("dds_create_reader(\"gearpath/AccelBlock\") failed: "));
  EXPECT_THAT(message, HasSubstr(dds_strretcode(DDS_RETCODE_INCONSISTENT_POLICY)));
}

TEST(Errors, ASecondDomainWithTheSameIdNamesDdsCreateDomainAndTheId) {
  testing::LoopbackPair pair;
  const dds_domainid_t id = pair.domain_a.id();
  const std::string message =
      ErrorOf([&] { Domain again(id, testing::TestConfig(id), EnvironmentConfig::kIgnore); });
  EXPECT_THAT(message, HasSubstr("dds_create_domain(" + std::to_string(id) + ") failed: "));
}

TEST(Errors, MalformedConfigurationNamesDdsCreateDomain) {
  const dds_domainid_t id = testing::TestDomainBase();
  const std::string message = ErrorOf([&] {
    Domain bad(id,
               "<CycloneDDS><Domain><General><AllowMulticast>sometimes</AllowMulticast>"
               "</General></Domain></CycloneDDS>",
               EnvironmentConfig::kIgnore);
  });
  EXPECT_THAT(message, HasSubstr("dds_create_domain(" + std::to_string(id) + ") failed: "));
}

TEST(Errors, DdsErrorMessageNamesTheCallAndCycloneReason) {
  EXPECT_EQ(DdsErrorMessage("dds_take(\"x\")", DDS_RETCODE_TIMEOUT),
            std::string("dds_take(\"x\") failed: ") + dds_strretcode(DDS_RETCODE_TIMEOUT) + " (" +
                std::to_string(DDS_RETCODE_TIMEOUT) + ")");
}

}  // namespace
}  // namespace gearpath::dds
