// Test helper: two Cyclone domains in one process that talk to each other over UDP on
// 127.0.0.1, isolated from every other process on the machine.
//
// Cyclone delivers locally (without the network) between participants of one domain, so a
// same-domain test would never touch a socket. Two domains with different local ids but the
// same Discovery/ExternalDomainId appear as one domain on the wire, so a writer on one and a
// reader on the other exercise discovery and transport through the loopback config. A
// per-process Discovery/Tag keeps concurrently running test processes (and anything else on
// the machine) from discovering each other. The environment is ignored (kIgnore) so the tests
// stay on loopback whatever CYCLONEDDS_URI says.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <string>
#include <vector>

#include "idl/dds/gearpath_topics.h"
#include "idl/dds/topic.h"
#include "idl/dds/waitset.h"

namespace gearpath::dds::testing {

inline dds_domainid_t TestDomainBase() {
  // Ports of domain d start at 7400 + 250 d; keep d + 1 below 232 so they stay below 65536.
  return static_cast<dds_domainid_t>(1 + 2 * (getpid() % 100));
}

inline std::string TestConfig(dds_domainid_t external_id) {
  std::string config(kLoopbackConfigXml);
  config += ",<CycloneDDS><Domain Id=\"any\"><Discovery><ExternalDomainId>" +
            std::to_string(external_id) + "</ExternalDomainId><Tag>gearpath-test-" +
            std::to_string(getpid()) + "</Tag></Discovery></Domain></CycloneDDS>";
  return config;
}

// domain_a and domain_b are one domain on the wire (the network path is always used between
// them); a participant on each is the usual publisher/subscriber pair.
struct LoopbackPair {
  LoopbackPair()
      : domain_a(TestDomainBase(), TestConfig(TestDomainBase()), EnvironmentConfig::kIgnore),
        domain_b(TestDomainBase() + 1, TestConfig(TestDomainBase()), EnvironmentConfig::kIgnore),
        publisher(domain_a),
        subscriber(domain_b) {}

  Domain domain_a;
  Domain domain_b;
  Participant publisher;
  Participant subscriber;
};

// A writer on the publishing instance and a reader on the subscribing one, with a WaitSet that
// wakes with token 1 when the reader has data. Members are public so tests attach more.
template <typename T>
struct LoopbackLink {
  explicit LoopbackLink(const LoopbackPair& pair)
      : pub_topic(pair.publisher),
        sub_topic(pair.subscriber),
        writer(pub_topic),
        reader(sub_topic),
        data(reader),
        waitset(pair.subscriber) {
    waitset.Attach(data, 1);
  }

  Topic<T> pub_topic;
  Topic<T> sub_topic;
  Writer<T> writer;
  Reader<T> reader;
  ReadCondition data;
  WaitSet waitset;
};

// The data representations a writer of T offers. Cyclone 0.10 picks them from the type when
// the QoS does not say: {XCDR1, XCDR2} for a type that is final throughout, {XCDR2} alone for
// an @appendable one (contract version 1, which Fast DDS 2.x could not read); its writer
// encodes in the first one offered.
template <typename T>
std::vector<dds_data_representation_id_t> OfferedRepresentations(const Participant& p) {
  Topic<T> topic(p);
  Writer<T> writer(topic);
  dds_qos_t* qos = dds_create_qos();
  std::vector<dds_data_representation_id_t> out;
  if (dds_get_qos(writer.handle(), qos) == DDS_RETCODE_OK) {
    uint32_t n = 0;
    dds_data_representation_id_t* values = nullptr;
    if (dds_qget_data_representation(qos, &n, &values)) {
      out.assign(values, values + n);
      dds_free(values);
    }
  }
  dds_delete_qos(qos);
  return out;
}

template <typename T>
void ExpectWrittenInXcdr1(const Participant& p) {
  const auto offered = OfferedRepresentations<T>(p);
  ASSERT_FALSE(offered.empty()) << TopicTraits<T>::kName;
  EXPECT_EQ(offered.front(), DDS_DATA_REPRESENTATION_XCDR1) << TopicTraits<T>::kName;
}

// Waits up to `timeout` for `reader` (attached to `waitset`) to hold samples and takes them;
// the number taken, 0 at the deadline.
template <typename T>
std::size_t TakeWithin(Reader<T>& reader, WaitSet& waitset, std::vector<Owned<T>>& samples,
                       std::vector<SampleInfo>& infos, std::chrono::seconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    std::array<dds_attach_t, 1> triggered{};
    if (!waitset.Wait(triggered, std::chrono::seconds(1))) return 0;
    Result<std::size_t> n = reader.Take(samples, infos);
    if (!n) {
      ADD_FAILURE() << n.error();
      return 0;
    }
    if (*n > 0) return *n;
  }
  return 0;
}

}  // namespace gearpath::dds::testing
