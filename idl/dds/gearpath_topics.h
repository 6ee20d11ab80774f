// The gearpath topics: TopicTraits for the idlc types of idl/gearpath.idl, binding each to its
// topic name and QoS class (docs/topics.md is the reference for both).
//
// Names follow "gearpath/<Type>". Include this header (it includes every other header of the
// layer) to use Topic<gearpath_AccelBlock> and friends.
#pragma once

#include <dds/dds.h>

#include <string_view>

#include "idl/dds/domain.h"
#include "idl/dds/qos.h"
#include "idl/dds/sequence.h"
#include "idl/dds/topic.h"
#include "idl/dds/waitset.h"
#include "idl/gearpath.h"

namespace gearpath::dds {

#define GEARPATH_DDS_TOPIC(type, topic_class)                                              \
  template <>                                                                            \
  struct TopicTraits<gearpath_##type> {                                                  \
    static const dds_topic_descriptor_t& Descriptor() noexcept { return gearpath_##type##_desc; } \
    static constexpr std::string_view kName = "gearpath/" #type;                        \
    static constexpr TopicClass kClass = topic_class;                                    \
  }

GEARPATH_DDS_TOPIC(AccelBlock, TopicClass::kBlockStream);
GEARPATH_DDS_TOPIC(DominantPath, TopicClass::kLatestResult);
GEARPATH_DDS_TOPIC(SuspectedGear, TopicClass::kLatestResult);
GEARPATH_DDS_TOPIC(EnvelopeIndicators, TopicClass::kLatestResult);
GEARPATH_DDS_TOPIC(Status, TopicClass::kStatus);

#undef GEARPATH_DDS_TOPIC

}  // namespace gearpath::dds
