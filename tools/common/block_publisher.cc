#include "tools/common/block_publisher.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <thread>
#include <type_traits>

#include "idl/dds/accel_block_wire.h"
#include "idl/dds/domain.h"
#include "idl/dds/gearpath_topics.h"
#include "idl/dds/topic.h"

namespace gearpath::tools {

namespace {

// One block topic and its writer: AccelBlock, or AccelBlockV2 (with the load).
template <typename Wire>
struct BlockEndpoint {
  BlockEndpoint(const dds::Participant& participant, const std::string& name)
      : topic(participant, name.empty() ? std::string(dds::TopicTraits<Wire>::kName) : name),
        writer(topic) {}
  dds::Topic<Wire> topic;
  dds::Writer<Wire> writer;
  dds::Owned<Wire> sample;
  bool matched = false;  // the wait for the first subscribers is done
};

}  // namespace

struct BlockPublisher::Impl {
  explicit Impl(const PublisherOptions& o)
      : options(o),
        domain(o.domain_id, ToolDomainConfig(o.dds)),
        participant(domain, ToolSecurityFiles(o.dds)) {
    // The kind the options name is made now (so it is discovered early); the other one when a
    // block first needs it, on its default topic.
    if (o.load_unit) {
      Endpoint(with_load);
    } else {
      Endpoint(plain);
    }
  }

  template <typename Wire>
  BlockEndpoint<Wire>& Endpoint(std::optional<BlockEndpoint<Wire>>& e) {
    if (!e) {
      const bool named =
          std::is_same_v<Wire, gearpath_AccelBlockV2> == options.load_unit.has_value();
      e.emplace(participant, named ? options.topic : std::string());
    }
    return *e;
  }

  PublisherOptions options;
  dds::Domain domain;
  dds::Participant participant;
  std::optional<BlockEndpoint<gearpath_AccelBlock>> plain;
  std::optional<BlockEndpoint<gearpath_AccelBlockV2>> with_load;
  bool started = false;
  std::int64_t first_t0_ns = 0;
  std::chrono::steady_clock::time_point first_wall;
};

namespace {

// Waits (in slices, so that a stop request is seen) until the endpoint has its subscribers.
template <typename Impl, typename Endpoint>
Status WaitForSubscribers(const Impl& s, Endpoint& e) {
  if (e.matched || s.options.min_subscribers <= 0) {
    e.matched = true;
    return Status::Ok();
  }
  const auto deadline = std::chrono::steady_clock::now() + s.options.match_timeout;
  for (;;) {
    const auto left = std::max(std::chrono::steady_clock::duration::zero(),
                               deadline - std::chrono::steady_clock::now());
    Status matched = e.writer.WaitForReaders(
        static_cast<std::uint32_t>(s.options.min_subscribers),
        std::min<std::chrono::steady_clock::duration>(left, std::chrono::milliseconds(200)));
    if (matched) break;
    if (s.options.stop && s.options.stop->load()) {
      return Error{"stopped while waiting for a daemon to subscribe"};
    }
    if (left == std::chrono::steady_clock::duration::zero()) {
      return Error{"no daemon subscribed to the block topic " + std::string(e.topic.name()) + ": " +
                   matched.error()};
    }
  }
  e.matched = true;
  return Status::Ok();
}

// The daemon may go away under us (killed, restarted, upgraded). While it is still matched but
// no longer acknowledges, Write times out; once its lease has expired nobody is matched and a
// write would go nowhere. Either way the block is held and retried until a subscriber takes it
// again, for at most resume_timeout; pacing then restarts from this block (no burst).
template <typename Impl, typename Endpoint>
Status WriteOrWait(Impl& s, Endpoint& e, const AccelBlockView& block) {
  const auto give_up = std::chrono::steady_clock::now() + s.options.resume_timeout;
  bool waited = false;
  auto note = [&](const char* why) {
    if (waited) return;
    waited = true;
    std::fprintf(stderr, "gearpath: block %llu: %s; waiting up to %lld s for a subscriber\n",
                 static_cast<unsigned long long>(block.sequence), why,
                 static_cast<long long>(s.options.resume_timeout.count()));
  };
  const auto min = static_cast<std::uint32_t>(std::max(0, s.options.min_subscribers));
  for (;;) {
    Result<std::uint32_t> matched = e.writer.MatchedReaders();
    if (!matched) return Error{matched.error()};
    std::string last_error;
    if (*matched < min) {
      note("no daemon subscribed any more");
    } else if (Status written = e.writer.Write(*e.sample); !written) {
      // Cyclone's "Timeout": a matched reader did not acknowledge within max_blocking_time.
      if (written.error().find("Timeout") == std::string::npos) return written;
      last_error = written.error();
      note("a subscriber stopped acknowledging (daemon gone or stalled)");
    } else if (s.options.speedup <= 0 && !s.options.acknowledge_each) {
      break;  // --fast: flow control alone, for throughput
    } else {
      // Paced (real-time or N x) streams also wait for the acknowledgement: a daemon killed
      // after matching would otherwise swallow every block until its lease expires. A block
      // written again after a crash is at worst rejected by the daemon as a duplicate.
      const dds_return_t rc = dds_wait_for_acks(e.writer.handle(), DDS_SECS(5));
      Result<std::uint32_t> after = e.writer.MatchedReaders();
      if (rc == DDS_RETCODE_TIMEOUT) {
        note("not acknowledged within 5 s (daemon gone or stalled)");
      } else if (after && *after < min) {
        note("no daemon subscribed any more");  // acknowledged by nobody: the reader left
      } else {
        break;
      }
    }
    if (std::chrono::steady_clock::now() >= give_up) {
      return Error{"block " + std::to_string(block.sequence) + ": no subscriber took it within " +
                   std::to_string(s.options.resume_timeout.count()) + " s" +
                   (last_error.empty() ? std::string() : " (" + last_error + ")")};
    }
    if (s.options.stop && s.options.stop->load()) {
      return Error{"block " + std::to_string(block.sequence) +
                   ": stopped while waiting for a subscriber to take it"};
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  if (waited) {
    std::fprintf(stderr, "gearpath: block %llu taken again; publishing resumed\n",
                 static_cast<unsigned long long>(block.sequence));
    s.first_t0_ns = block.t0_ns;
    s.first_wall = std::chrono::steady_clock::now();
  }
  return Status::Ok();
}

// Waits for the endpoint's subscribers (first use), sleeps until the block is due, fills the
// endpoint's sample with `fill` and writes it.
template <typename Impl, typename Endpoint, typename Fill>
Status Send(Impl& s, Endpoint& e, const AccelBlockView& block, Fill fill) {
  if (Status st = WaitForSubscribers(s, e); !st) return st;
  if (!s.started) {
    s.started = true;
    s.first_t0_ns = block.t0_ns;
    s.first_wall = std::chrono::steady_clock::now();
  } else if (s.options.speedup > 0) {
    const double offset_s = static_cast<double>(block.t0_ns - s.first_t0_ns) * 1e-9;
    std::this_thread::sleep_until(s.first_wall +
                                  std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                      std::chrono::duration<double>(offset_s / s.options.speedup)));
  }
  Status filled = fill(*e.sample);
  if (!filled) return Error{"block " + std::to_string(block.sequence) + ": " + filled.error()};
  return WriteOrWait(s, e, block);
}

}  // namespace

BlockPublisher::BlockPublisher(const PublisherOptions& options)
    : impl_(std::make_unique<Impl>(options)) {}

BlockPublisher::~BlockPublisher() = default;

Status BlockPublisher::Publish(const AccelBlockView& block) {
  return Publish(block, impl_->options.load_unit);
}

Status BlockPublisher::Publish(const AccelBlockView& block,
                               const std::optional<std::string>& load_unit) {
  Impl& s = *impl_;
  if (load_unit) {
    return Send(s, s.Endpoint(s.with_load), block, [&](gearpath_AccelBlockV2& wire) {
      return dds::FillWireBlock(block, *load_unit, wire);
    });
  }
  return Send(s, s.Endpoint(s.plain), block,
              [&](gearpath_AccelBlock& wire) { return dds::FillWireBlock(block, wire); });
}

Status BlockPublisher::Flush(std::chrono::milliseconds timeout) {
  auto flush = [&](auto& e) -> Status {
    if (!e) return Status::Ok();
    const dds_return_t rc = dds_wait_for_acks(e->writer.handle(), DDS_MSECS(timeout.count()));
    if (rc < 0) return Error{dds::DdsErrorMessage("dds_wait_for_acks", rc)};
    return Status::Ok();
  };
  if (Status st = flush(impl_->plain); !st) return st;
  return flush(impl_->with_load);
}

}  // namespace gearpath::tools
