// BlockPublisher: puts AccelBlocks on the DDS block topic, paced like the acquisition; with a
// load unit, AccelBlockV2s carrying each block's load (contract version 4) instead, or either
// kind block by block.
//
// Shared by the tools that feed the daemon (`gearpath sim`, `gearpath replay`). Pacing follows
// each block's t0: real time, N times faster, or as fast as the subscribers take them. The block
// topic is reliable keep-all with resource limits (idl/dds/qos.cc), so a writer that outruns
// its readers blocks in Write instead of dropping: "as fast as possible" loses nothing.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include "core/common/accel_block.h"
#include "core/common/result.h"
#include "tools/common/block_sink.h"
#include "tools/common/dds_options.h"

namespace gearpath::tools {

struct PublisherOptions {
  int domain_id = 0;
  DdsOptions dds;           // --dds-config, --dds-security
  // Empty = the default topic name of the kind load_unit chooses; a block of the other kind
  // (Publish with a load unit) always goes to its default topic.
  std::string topic;
  // Set: publish AccelBlockV2 with each block's load (AccelBlock::load) in this unit, e.g.
  // "N m" (at most 16 characters; may be empty); unset: plain AccelBlock.
  std::optional<std::string> load_unit;
  double speedup = 1.0;     // 1 = real time, N = N times faster, 0 = as fast as possible
  int min_subscribers = 1;  // wait for this many matched readers before the first block
  std::chrono::milliseconds match_timeout{10000};
  // When the daemon goes away mid-stream, hold the block and wait this long for a subscriber
  // to take it again (a restarted daemon) before giving up.
  std::chrono::seconds resume_timeout{300};
  // With speedup 0, still wait for every block's acknowledgement before Publish returns (the
  // bridge records a block as published only once a subscriber has it).
  bool acknowledge_each = false;
  // When set, the waits for a subscriber (first block, vanished daemon) give up as soon as it
  // is true, so a service stops promptly; Publish then returns an error, the block not sent.
  const std::atomic<bool>* stop = nullptr;
};

class BlockPublisher : public BlockSink {
 public:
  // Throws std::runtime_error (naming the DDS call that failed) if the endpoint cannot be made.
  explicit BlockPublisher(const PublisherOptions& options);
  ~BlockPublisher() override;
  BlockPublisher(const BlockPublisher&) = delete;
  BlockPublisher& operator=(const BlockPublisher&) = delete;

  // Waits for the subscribers (first call only), sleeps until the block is due, publishes it.
  // A subscriber that disappears later is waited for (resume_timeout), the block held.
  Status Publish(const AccelBlockView& block) override;
  // The same, as AccelBlockV2 in `load_unit` when it is set and as AccelBlock when not,
  // whatever the options say (replay: each recording as it was recorded). Both kinds share the
  // pacing; each waits for its subscribers on first use.
  Status Publish(const AccelBlockView& block, const std::optional<std::string>& load_unit);

  // Blocks until every matched reader of both kinds has acknowledged what was written, or the
  // timeout.
  Status Flush(std::chrono::milliseconds timeout) override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gearpath::tools
