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

#include <unistd.h>

#include <string>

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

}  // namespace gearpath::dds::testing
