// config/fastdds-profiles.xml: its loopback participant never leaves 127.0.0.1 and uses no
// multicast, as the Cyclone loopback configuration (tests/idl/config_test.cc), so the
// interoperability test keeps the project's rule that DDS in tests is loopback only.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>

namespace gearpath::testing {
namespace {

std::string ProfilesText() {
  std::ifstream in(GEARPATH_SOURCE_DIR "/config/fastdds-profiles.xml");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The XML element `<tag ...>...</tag>` whose opening tag contains `marker` (or the one that
// contains `marker` as its text, for transport descriptors).
std::string Element(const std::string& xml, const std::string& tag, const std::string& marker) {
  std::size_t from = 0;
  for (;;) {
    const std::size_t begin = xml.find("<" + tag, from);
    if (begin == std::string::npos) return "";
    const std::size_t end = xml.find("</" + tag + ">", begin);
    if (end == std::string::npos) return "";
    std::string element = xml.substr(begin, end - begin);
    if (element.find(marker) != std::string::npos) return element;
    from = end;
  }
}

TEST(FastDdsProfiles, LoopbackParticipantUsesOnly127001UnicastWithoutBuiltinTransports) {
  const std::string xml = ProfilesText();
  ASSERT_FALSE(xml.empty());
  const std::string participant = Element(xml, "participant", "profile_name=\"gearpath_loopback\"");
  const std::string transport =
      Element(xml, "transport_descriptor", "<transport_id>gearpath_udp_loopback</transport_id>");
  ASSERT_FALSE(participant.empty());
  ASSERT_FALSE(transport.empty());

  EXPECT_NE(participant.find("<useBuiltinTransports>false</useBuiltinTransports>"),
            std::string::npos);
  EXPECT_NE(participant.find("<transport_id>gearpath_udp_loopback</transport_id>"),
            std::string::npos);
  EXPECT_NE(transport.find("<type>UDPv4</type>"), std::string::npos);
  EXPECT_NE(transport.find("<interfaceWhiteList>"), std::string::npos);
  // No multicast locator list, and every address named is loopback.
  EXPECT_EQ(participant.find("ulticast"), std::string::npos);
  EXPECT_NE(participant.find("<metatrafficUnicastLocatorList>"), std::string::npos);
  EXPECT_NE(participant.find("<initialPeersList>"), std::string::npos);
  const std::regex address_re("<address>([^<]*)</address>");
  int addresses = 0;
  for (const std::string* element : {&participant, &transport}) {
    for (auto a = std::sregex_iterator(element->begin(), element->end(), address_re);
         a != std::sregex_iterator(); ++a, ++addresses) {
      EXPECT_EQ((*a)[1].str(), "127.0.0.1");
    }
  }
  EXPECT_EQ(addresses, 4);  // whitelist, default unicast, metatraffic unicast, initial peer
}

}  // namespace
}  // namespace gearpath::testing
