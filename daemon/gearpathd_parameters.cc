// The declaration of every gearpathd configuration parameter (see config_schema.h). This is the
// single source of truth: validation, defaults and docs/configuration.md all come from here.
#include "core/pipeline/learned_state.h"  // kMaxBaselineEpochBytes, kMaxOperatingBands
#include "daemon/config_schema.h"

namespace gearpath::daemon {
namespace {

using nlohmann::json;

ParamSpec Object(std::string name, std::string meaning, std::vector<ParamSpec> fields) {
  ParamSpec s;
  s.name = std::move(name);
  s.meaning = std::move(meaning);
  s.kind = ParamKind::kObject;
  s.fields = std::move(fields);
  return s;
}

ParamSpec Array(std::string name, std::string meaning, ParamSpec element, std::size_t min_items,
                std::size_t max_items, json fallback = nullptr) {
  ParamSpec s;
  s.name = std::move(name);
  s.meaning = std::move(meaning);
  s.kind = ParamKind::kArray;
  s.element.push_back(std::move(element));
  s.min_size = min_items;
  s.max_size = max_items;
  s.default_value = std::move(fallback);
  s.required = s.default_value.is_null();
  return s;
}

// A string; `fallback` null means required.
ParamSpec String(std::string name, std::string meaning, json fallback, std::size_t min_len = 0,
                 std::size_t max_len = 4096) {
  ParamSpec s;
  s.name = std::move(name);
  s.meaning = std::move(meaning);
  s.kind = ParamKind::kString;
  s.default_value = std::move(fallback);
  s.required = s.default_value.is_null();
  s.min_size = min_len;
  s.max_size = max_len;
  return s;
}

ParamSpec Enum(std::string name, std::string meaning, std::vector<std::string> choices,
               json fallback) {
  ParamSpec s;
  s.name = std::move(name);
  s.meaning = std::move(meaning);
  s.kind = ParamKind::kEnum;
  s.choices = std::move(choices);
  s.default_value = std::move(fallback);
  s.required = s.default_value.is_null();
  return s;
}

ParamSpec Integer(std::string name, std::string meaning, double min, double max, json fallback) {
  ParamSpec s;
  s.name = std::move(name);
  s.meaning = std::move(meaning);
  s.kind = ParamKind::kInteger;
  s.min = min;
  s.max = max;
  s.default_value = std::move(fallback);
  s.required = s.default_value.is_null();
  return s;
}

// A real number in (min, max] when min_exclusive, else [min, max].
ParamSpec Number(std::string name, std::string meaning, double min, double max, json fallback,
                 bool min_exclusive = false, bool max_exclusive = false) {
  ParamSpec s;
  s.name = std::move(name);
  s.meaning = std::move(meaning);
  s.kind = ParamKind::kNumber;
  s.min = min;
  s.max = max;
  s.min_exclusive = min_exclusive;
  s.max_exclusive = max_exclusive;
  s.default_value = std::move(fallback);
  s.required = s.default_value.is_null();
  return s;
}

ParamSpec Boolean(std::string name, std::string meaning, bool fallback) {
  ParamSpec s;
  s.name = std::move(name);
  s.meaning = std::move(meaning);
  s.kind = ParamKind::kBoolean;
  s.default_value = fallback;
  return s;
}

constexpr std::size_t kMaxIdLength = 64;  // machine ids are DDS keys: keep them short
// A sanity bound, not a design limit: a daemon serves as many machines as its cores keep up
// with (Status.machines carries the first 64, MachineHealth every one). 4096 catches a
// generated configuration gone wrong before it builds thousands of processors.
constexpr std::size_t kMaxMachines = 4096;
constexpr std::size_t kMaxChannels = 32;  // IDL MAX_CHANNELS

ParamSpec DaemonSection() {
  return Object(
      "daemon", "This daemon process.",
      {String("id", "Daemon id, reported on the Status topic (tells several daemons apart).",
              "gearpathd", 1, kMaxIdLength),
       Enum("log_level", "spdlog level; `--log-level` overrides it.",
            {"trace", "debug", "info", "warn", "error", "critical", "off"}, "info"),
       Number("status_period_s", "Period of the Status topic, seconds.", 0.1, 3600.0, 1.0),
       Number("throughput_log_period_s", "Period of the throughput summary in the log, seconds.",
              1.0, 86400.0, 60.0),
       Integer("workers",
               "Processing threads: machines are processed in parallel, each machine's blocks "
               "one at a time in arrival order. 0: one per hardware thread. Read at start-up "
               "(a reload keeps the running pool).",
               0, 256, 0),
       Integer("queue_blocks",
               "Blocks queued per machine while its previous block is processed; when a "
               "machine's queue is full the DDS reader waits for room, so DDS flow control "
               "slows the writers and nothing is lost (docs/topics.md). Read at start-up.",
               1, 1024, 32)});
}

ParamSpec MetricsSection() {
  return Object(
      "metrics",
      "Prometheus metrics over HTTP (GET /metrics; every metric in docs/deployment.md). No TLS "
      "and no authentication: keep it on loopback, or put a reverse proxy in front.",
      {Boolean("enabled", "Serve the metrics endpoint.", false),
       String("address",
              "Numeric IPv4 or IPv6 address to listen on. A non-loopback address (e.g. "
              "`0.0.0.0`) is refused unless `allow_remote` is true.",
              "127.0.0.1", 1, 64),
       Integer("port", "TCP port; 0: a free port chosen at start (the log names it).", 0, 65535,
               9469),
       Boolean("allow_remote",
               "Allow a non-loopback `address`: anyone who reaches it reads every machine's "
               "counters and verdict states.",
               false)});
}

ParamSpec StandbySection() {
  return Object(
      "standby",
      "Hot standby (docs/deployment.md): this daemon processes every block of its machines "
      "(so its baselines stay learned) but publishes results only while the primary daemon "
      "is silent.",
      {String("primary",
              "Daemon id of the primary this daemon backs up. Empty: this daemon is a primary "
              "and always publishes.",
              "", 0, kMaxIdLength),
       Number("takeover_after_s",
              "Publish once the primary's Status has been missing this long (or at once when "
              "it says STOPPING); stop again when its Status returns. 0: 1.5 x "
              "daemon.status_period_s (both daemons should share the status period).",
              0.0, 3600.0, 0.0)});
}

ParamSpec StateSection() {
  return Object(
      "state",
      "What each machine has learned (healthy baseline, alarm state) and its counters, kept "
      "across restarts and reloads (docs/state.md).",
      {String("directory",
              "Directory of the per-machine state files; written only by this daemon. Empty: "
              "`$STATE_DIRECTORY` when systemd sets it (`StateDirectory=`), else nothing is "
              "kept and a restart relearns every baseline (a warning says so).",
              "", 0, 4096),
       Number("save_period_s",
              "A machine's state is saved when its verdict state changes, when its baseline "
              "is learned, at stop, and at most this many seconds after any other change.",
              1.0, 86400.0, 30.0)});
}

ParamSpec DdsSection() {
  return Object(
      "dds", "DDS domain, network configuration, security and topic names (docs/topics.md).",
      {Integer("domain_id", "DDS domain id.", 0, 232, 0),
       String("config",
              "Cyclone DDS XML configuration file of a deployment (docs/deployment.md); it "
              "alone decides interfaces, peers and ports, replacing the embedded loopback "
              "configuration and `CYCLONEDDS_URI`. Empty: `CYCLONEDDS_URI` if set, else the "
              "embedded loopback configuration (127.0.0.1, multicast off).",
              "", 0, 4096),
       Object("security",
              "DDS Security (docs/deployment.md): all six files, or none (no security). "
              "tools/make-security-fixtures.sh makes a test set.",
              {String("identity_ca", "PEM certificate of the CA that signs identities.", "", 0,
                      4096),
               String("identity_certificate", "PEM certificate of this daemon.", "", 0, 4096),
               String("identity_private_key", "PEM private key of this daemon (unencrypted).",
                      "", 0, 4096),
               String("permissions_ca",
                      "PEM certificate of the CA that signs governance and permissions.", "", 0,
                      4096),
               String("governance", "Signed governance document (S/MIME, .p7s).", "", 0, 4096),
               String("permissions", "Signed permissions of this daemon (S/MIME, .p7s).", "", 0,
                      4096)}),
       Object("topics", "Topic names; every daemon and client on a domain must agree on them.",
              {String("accel_block", "Input: blocks of housing accelerations.",
                      "gearpath/AccelBlock", 1, 256),
               String("accel_block_v2",
                      "Input: the same blocks with the machine's operating load (AccelBlockV2; "
                      "version 4 of the contract). Empty: not read (e.g. DDS permissions that "
                      "do not grant it).",
                      "gearpath/AccelBlockV2", 0, 256),
               String("dominant_path", "Output: the dominant transfer path per block.",
                      "gearpath/DominantPath", 1, 256),
               String("suspected_gear", "Output: the suspected gear per block.",
                      "gearpath/SuspectedGear", 1, 256),
               String("envelope_indicators", "Output: envelope fault indicators per block.",
                      "gearpath/EnvelopeIndicators", 1, 256),
               String("condition_indicators",
                      "Output: every condition indicator, its z-score and the block score per "
                      "block.",
                      "gearpath/ConditionIndicators", 1, 256),
               String("status",
                      "Output: daemon status, periodically (with the first 64 machines).",
                      "gearpath/Status", 1, 256),
               String("machine_health",
                      "Output: every machine's counters and state, one instance per daemon "
                      "and machine, each status period.",
                      "gearpath/MachineHealth", 1, 256)})});
}

ParamSpec ChannelSpec() {
  // Optional and absent by default: only an identity FRF set uses it, and there it is required.
  ParamSpec gears = Array(
      "gears",
      "With `\"frf_set\": \"identity\"` (and only then; required there): the gears this sensor "
      "sits nearest to, which localise a fault by mesh as an FRF path's gears do.",
      String("gear", "Gear name.", nullptr, 1, kMaxIdLength), 1, 8);
  gears.required = false;
  return Object(
      "channel", "One block channel, in block order.",
      {String("sensor", "Sensor id as carried by the AccelBlock channel, e.g. `A4`.", nullptr, 1,
              kMaxIdLength),
       Enum("axis", "Sensor axis as carried by the AccelBlock channel.", {"x", "y", "z"},
            nullptr),
       Integer("frf_row",
               "Row (response channel) of the decoupled FRF matrix it measures (-1: the row "
               "with the same sensor and axis; must stay -1 with an identity FRF set).",
               -1, 1023, -1),
       std::move(gears)});
}

ParamSpec GearTrainSection() {
  return Object(
      "gear_train",
      "Shafts, gears and meshes of the gearbox (core/diagnosis/train_layout.h). Shaft rates "
      "follow from the input shaft speed and the tooth counts.",
      {Array("shafts", "Shafts from input to output; the first is the input shaft.",
             Object("shaft", "One shaft.",
                    {String("name", "Shaft name, e.g. `input`.", nullptr, 1, kMaxIdLength),
                     Array("gears", "Names of the gears keyed to this shaft.",
                           String("gear", "Gear name.", nullptr, 1, kMaxIdLength), 1, 8)}),
             1, 16),
       Array("gears", "Gears.",
             Object("gear", "One gear.",
                    {String("name", "Gear name, e.g. `G1`; FRF set paths name their gears so.",
                            nullptr, 1, kMaxIdLength),
                     Integer("teeth", "Tooth count.", 3, 1000, nullptr)}),
             2, 64),
       Array("stages", "Gear meshes (stages), input side first.",
             Object("stage", "One mesh; power flows from driver to driven.",
                    {String("driver", "Driving gear (nearer the input).", nullptr, 1,
                            kMaxIdLength),
                     String("driven", "Driven gear.", nullptr, 1, kMaxIdLength)}),
             1, 16)});
}

ParamSpec PathSpec() {
  return Object(
      "path", "One transfer path.",
      {String("name", "Path name as in the FRF set, e.g. `B2y`.", nullptr, 1, kMaxIdLength),
       Array("gears", "Gears nearest to the bearing this path's force acts in.",
             String("gear", "Gear name.", nullptr, 1, kMaxIdLength), 1, 8)});
}

ParamSpec AnalysisSection() {
  return Object(
      "analysis", "How each block is analysed (core/pipeline/block_processor.h).",
      {Object("inverse", "Bearing-force identification (seed Eqs. 27-28, 40-43).",
              {Enum("method",
                    "mwi: Maximumly Weighted Iteration; tikhonov: Tikhonov regularisation; "
                    "least_squares: unregularised (baseline).",
                    {"mwi", "tikhonov", "least_squares"}, "mwi"),
               Enum("alpha_rule",
                    "How the regularisation parameter is chosen per bin "
                    "(core/inverse/regularisation_rule.h): noise_floor (filter singular "
                    "components below relative_noise * sigma_max; precomputed), fixed (alpha; "
                    "precomputed), discrepancy (Morozov, from noise_rms; per block), gcv (per "
                    "block where well posed, else noise_floor).",
                    {"noise_floor", "fixed", "discrepancy", "gcv"}, "noise_floor"),
               Number("alpha", "Regularisation parameter (MWI alpha, Tikhonov lambda) when "
                      "alpha_rule is fixed.",
                      0.0, 1e12, 1e-3, true),
               Number("relative_noise",
                      "Relative noise level eta of the FRFs (noise_floor and the gcv fallback).",
                      0.0, 1.0, 1e-3, true, /*max_exclusive=*/true),
               Number("noise_rms",
                      "Per-channel noise RMS of the responses, m/s^2 (discrepancy rule).", 0.0,
                      1e6, 1e-3, true),
               Number("discrepancy_factor", "Safety factor tau of the discrepancy rule.", 1.0,
                      100.0, 1.0),
               Integer("iterations", "MWI iteration count K (seed Algorithm 1).", 1, 1000, 10)}),
       Object("speed",
              "Input-shaft speed: its search when the block carries none, its variation "
              "within a block.",
              {Number("search_lo_hz",
                      "Lower end of the mesh-frequency speed search, Hz (0: 0.8 x nominal).",
                      0.0, 10000.0, 0.0),
               Number("search_hi_hz",
                      "Upper end of the mesh-frequency speed search, Hz (0: 1.2 x nominal).",
                      0.0, 10000.0, 0.0),
               Boolean("order_tracking",
                       "Track the speed's variation within each block from the mesh tones (the "
                       "median of the first mesh harmonics' warps) and average the shafts at the "
                       "tracked angle; a machine whose first block gains nothing from it stays "
                       "at constant speed (off: constant speed per block; docs/diagnosis.md).",
                       true),
               Boolean("localisation_tracking",
                       "With order_tracking off: track the speed within each block for the "
                       "shaft localisation only (the exclusive residual that names the shaft); "
                       "every scored indicator stays at constant speed (docs/diagnosis.md).",
                       true)}),
       Object("condition",
              "The time-synchronous averages behind the gear condition indicators.",
              {Boolean("transient_gate",
                       "Take the short transients that no shaft explains (broadband bursts, "
                       "knocks) out of each measured channel before its averages: an average "
                       "keeps 1/R of a burst in one revolution, which the peak indicators read "
                       "as a fault (docs/diagnosis.md).",
                       true)}),
       Object("dominant_path", "How the dominant transfer path is chosen.",
              {Enum("criterion",
                    "sideband_energy: energy at mesh-harmonic sidebands; band_energy: energy in "
                    "the analysis band; indicator: largest envelope fault indicator.",
                    {"sideband_energy", "band_energy", "indicator"}, "sideband_energy"),
               Number("band_lo_hz", "Analysis band lower edge, Hz (0 and 0: the FRF range).",
                      0.0, 1e6, 0.0),
               Number("band_hi_hz", "Analysis band upper edge, Hz (0 and 0: the FRF range).",
                      0.0, 1e6, 0.0),
               Integer("sideband_orders", "Sidebands k = 1..n around each mesh harmonic.", 1, 50,
                       6),
               Integer("indicator_channel",
                       "FRF row whose raw and reconstructed signals give the indicators (-1: "
                       "where the dominant path contributes most).",
                       -1, 1023, -1)}),
       Object("envelope", "Band selection (fast kurtogram) and envelope analysis.",
              {Integer("kurtogram_max_level",
                       "Deepest kurtogram level (band width fs / 2^(level+1)).", 1, 12, 6),
               Number("min_band_width_hz",
                      "Narrowest envelope band, Hz (0: 2 x 5 harmonics x highest shaft rate).",
                      0.0, 1e6, 0.0),
               Boolean("remove_mesh_tones",
                       "Remove the mesh harmonics (deterministic tones) before the kurtogram "
                       "(off: removing the tones but not their healthy sidebands raised healthy "
                       "indicators 4-10x on the simulated gearbox; docs/diagnosis.md).",
                       false),
               Number("harmonic_tolerance",
                      "Relative tolerance on harmonic positions (speed drift).", 0.0, 0.5, 0.02)}),
       Object("baseline",
              "The machine's healthy baseline, learned from its first accepted blocks (assumed "
              "healthy): every condition indicator's median and robust scale (Qn, or MAD "
              "beyond 256 blocks), judged with a z limit "
              "from a target false-alarm rate (docs/diagnosis.md).",
              {Integer("learning_blocks",
                       "Healthy blocks to learn the baseline from (a median and a robust scale need "
                       "three; the scale is Qn from 10 to 256 blocks, else the MAD).",
                       3, 100000, 20),
               Number("false_alarm_rate",
                      "Target rate of healthy blocks in which any scored indicator exceeds its "
                      "limit (the alarm model's persistence lowers the rate of flagged blocks "
                      "far below it).",
                      0.0, 0.5, 0.01, true),
               Number("scale_floor",
                      "Relative floor of every indicator's healthy spread, as a change of the "
                      "signal's amplitude (0.05: an amplitude, or an energy or NA4 that goes with "
                      "its square or fourth power, never counts a change of the signal's level "
                      "under 5 % as large).",
                      0.0, 1.0, 0.05),
               Boolean("tail_guard",
                       "Widen each indicator's healthy spread so that the worst baseline block "
                       "scores at most z = 3, about half the limit (indicators that are "
                       "heavy-tailed when healthy, e.g. high moments under broadband bursts).",
                       true),
               Number("speed_tolerance",
                      "A block is judged only when its input speed lies within the speeds the "
                      "baseline was learned at, widened by this fraction either way (the speed "
                      "reading's jitter); outside, the state is held and the reason says so (the "
                      "baseline holds the response at the speeds it saw: a healthy machine "
                      "learned at one constant speed can exceed its limits 0.01 % away). 1 "
                      "judges every speed.",
                      0.0, 1.0, 2e-5),
               Number("load_tolerance",
                      "When every baseline block carried a load (AccelBlockV2.load), a block "
                      "that carries one is judged only within the loads the baseline was "
                      "learned at, widened by this fraction either way; outside, the state is "
                      "held and the reason says so (amplitudes and energies grow with the load: "
                      "a healthy machine learned at one load exceeds its limits 20 % above it). "
                      "1 judges every load; blocks without a load are always judged.",
                      0.0, 1.0, 0.1),
               Integer("operating_bands",
                       "How many healthy baselines, each at its own band of input speed and "
                       "load, the machine may learn. 1: one baseline, and a block outside its "
                       "speeds or loads (speed_tolerance, load_tolerance) is not judged. More: "
                       "such a block is judged against the band learned at its speed and load; "
                       "when none was and no fault is suspected, a new band "
                       "learns there from the blocks that stay at that operating point (the "
                       "state holds meanwhile). A band learned while a fault develops takes it "
                       "for healthy: raise it where the operating points recur.",
                       1, kMaxOperatingBands, 1),
               String("epoch",
                      "A label of the healthy baseline, e.g. the date of the last "
                      "maintenance. Changing it and reloading (SIGHUP) makes this machine "
                      "forget its baseline and learn a new one from its next blocks; the other "
                      "machines keep theirs. Empty: no label (states saved before it are kept).",
                      "", 0, kMaxBaselineEpochBytes),
               Number("k_sigma",
                      "Published envelope-indicator thresholds = mean + k_sigma x standard "
                      "deviation.",
                      0.0, 100.0, 4.0, true),
               Array("raw_thresholds",
                     "Per-shaft thresholds of the raw envelope indicator, shaft order (empty: "
                     "learn).",
                     Number("threshold", "Threshold.", 0.0, 1e30, nullptr, true), 0, 16,
                     json::array()),
               Array("reconstructed_thresholds",
                     "Per-shaft thresholds of the reconstructed envelope indicator (empty: "
                     "learn).",
                     Number("threshold", "Threshold.", 0.0, 1e30, nullptr, true), 0, 16,
                     json::array())}),
       Object("alarm",
              "Persistence, hysteresis and clear delay between the per-block score and the "
              "published state (core/diagnosis/alarm_model.h).",
              {Integer("window", "Blocks the persistence rule looks back over.", 1, 64, 5),
               Integer("suspect_blocks", "Exceeding blocks in the window for `suspected`.", 1,
                       64, 2),
               Integer("alarm_blocks", "Exceeding blocks in the window for `alarm`.", 1, 64, 3),
               Number("clear_level",
                      "Once raised, a block still counts as exceeding down to this fraction of "
                      "the limit (hysteresis).",
                      0.0, 1.0, 0.7, true),
               Integer("clear_blocks", "Consecutive blocks under clear_level that clear it.", 1,
                       1000, 3),
               Number("mesh_separation",
                      "A mesh is named alone when its transfer-signature evidence leads the "
                      "next mesh's by this factor (1: the leading mesh whenever any evidence "
                      "rose); otherwise the close meshes' gears are candidates.",
                      1.0, 100.0, 1.0)})});
}

ParamSpec MachineSpec() {
  return Object(
      "machine", "One gearbox this daemon watches.",
      {String("id", "Machine id: the DDS key of its blocks and results.", nullptr, 1,
              kMaxIdLength),
       String("description", "Free text for people.", ""),
       String("frf_set",
              "Decoupled FRF set: a directory in the format of docs/frf_format.md, "
              "`builtin:table1` (the seed's Table-1 gearbox, computed through Eq. 22 at start), "
              "or `identity` (no FRFs yet: every channel is its own path, see \"Monitoring "
              "before the hammer test\"; `./identity` names a directory).",
              nullptr, 1),
       Number("nominal_speed_hz",
              "Input shaft speed used when a block carries none (speed_hz = 0), Hz.", 0.0,
              10000.0, nullptr, true),
       Object("acquisition", "What blocks of this machine must look like.",
              {Number("sample_rate_hz", "Expected sample rate, Hz.", 0.0, 1e7, nullptr, true),
               Number("sample_rate_tolerance", "Accepted relative deviation of the sample rate.",
                      0.0, 0.1, 1e-4),
               Integer("min_samples_per_channel", "Shortest accepted block, samples per channel.",
                       16, 65536, 1024),
               Integer("max_samples_per_channel",
                       "Longest accepted block, samples per channel (IDL bound 65536).", 16,
                       65536, 65536),
               Array("prepare_samples_per_channel",
                     "Block lengths configured at start-up and on reload, before READY (FFT "
                     "plans, the FRF set on the block's bin grid, the per-bin inverse "
                     "operators), in parallel across machines. A length not listed is "
                     "configured by its first block, which then waits for it.",
                     Integer("samples", "Samples per channel.", 16, 65536, nullptr), 0, 4,
                     json::array())}),
       Array("channels",
             "The block's channels in order, each mapped to an FRF row. Empty: the FRF set's "
             "response channels, in their order.",
             ChannelSpec(), 0, kMaxChannels, json::array()),
       GearTrainSection(),
       Array("paths",
             "Transfer path (FRF column) -> nearest gears, overriding the gears the FRF set "
             "names for that path. Empty: the FRF set's.",
             PathSpec(), 0, 64, json::array()),
       AnalysisSection()});
}

}  // namespace

const ParamSpec& DaemonConfigSchema() {
  static const ParamSpec schema = Object(
      "", "gearpathd configuration",
      {DaemonSection(), StateSection(), StandbySection(), DdsSection(), MetricsSection(),
       Array("machines",
             "The gearboxes this daemon watches; blocks of other machines are ignored. No "
             "fixed cap (4096 is a sanity bound): Status lists the first 64, MachineHealth "
             "every one.",
             MachineSpec(), 1, kMaxMachines)});
  return schema;
}

}  // namespace gearpath::daemon
