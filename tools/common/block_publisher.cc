#include "tools/common/block_publisher.h"

#include <thread>

#include "idl/dds/accel_block_wire.h"
#include "idl/dds/domain.h"
#include "idl/dds/gearpath_topics.h"
#include "idl/dds/topic.h"

namespace gearpath::tools {

struct BlockPublisher::Impl {
  explicit Impl(const PublisherOptions& o)
      : options(o),
        domain(o.domain_id, ToolDomainConfig(o.dds)),
        participant(domain, ToolSecurityFiles(o.dds)),
        topic(participant, o.topic.empty()
                               ? std::string(dds::TopicTraits<gearpath_AccelBlock>::kName)
                               : o.topic),
        writer(topic) {}

  PublisherOptions options;
  dds::Domain domain;
  dds::Participant participant;
  dds::Topic<gearpath_AccelBlock> topic;
  dds::Writer<gearpath_AccelBlock> writer;
  dds::Owned<gearpath_AccelBlock> sample;
  bool started = false;
  std::int64_t first_t0_ns = 0;
  std::chrono::steady_clock::time_point first_wall;
};

BlockPublisher::BlockPublisher(const PublisherOptions& options)
    : impl_(std::make_unique<Impl>(options)) {}

BlockPublisher::~BlockPublisher() = default;

Status BlockPublisher::Publish(const AccelBlockView& block) {
  Impl& s = *impl_;
  if (!s.started) {
    if (s.options.min_subscribers > 0) {
      Status matched = s.writer.WaitForReaders(
          static_cast<std::uint32_t>(s.options.min_subscribers), s.options.match_timeout);
      if (!matched) return Error{"no daemon subscribed to the block topic: " + matched.error()};
    }
    s.started = true;
    s.first_t0_ns = block.t0_ns;
    s.first_wall = std::chrono::steady_clock::now();
  } else if (s.options.speedup > 0) {
    const double offset_s = static_cast<double>(block.t0_ns - s.first_t0_ns) * 1e-9;
    std::this_thread::sleep_until(
        s.first_wall + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(offset_s / s.options.speedup)));
  }
  Status filled = dds::FillWireBlock(block, *s.sample);
  if (!filled) return Error{"block " + std::to_string(block.sequence) + ": " + filled.error()};
  return s.writer.Write(*s.sample);
}

Status BlockPublisher::Flush(std::chrono::milliseconds timeout) {
  const dds_return_t rc =
      dds_wait_for_acks(impl_->writer.handle(), DDS_MSECS(timeout.count()));
  if (rc < 0) return Error{dds::DdsErrorMessage("dds_wait_for_acks", rc)};
  return Status::Ok();
}

}  // namespace gearpath::tools
