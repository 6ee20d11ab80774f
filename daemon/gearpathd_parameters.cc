// The declaration of every gearpathd configuration parameter (see config_schema.h). This is the
// single source of truth: validation, defaults and docs/configuration.md all come from here.
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
                 bool min_exclusive = false) {
  ParamSpec s;
  s.name = std::move(name);
  s.meaning = std::move(meaning);
  s.kind = ParamKind::kNumber;
  s.min = min;
  s.max = max;
  s.min_exclusive = min_exclusive;
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
constexpr std::size_t kMaxMachines = 64;
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
              1.0, 86400.0, 60.0)});
}

ParamSpec DdsSection() {
  return Object(
      "dds", "DDS domain and topic names (docs/topics.md).",
      {Integer("domain_id", "DDS domain id.", 0, 232, 0),
       Object("topics", "Topic names; every daemon and client on a domain must agree on them.",
              {String("accel_block", "Input: blocks of housing accelerations.",
                      "gearpath_AccelBlock", 1, 256),
               String("dominant_path", "Output: the dominant transfer path per block.",
                      "gearpath_DominantPath", 1, 256),
               String("suspected_gear", "Output: the suspected gear per block.",
                      "gearpath_SuspectedGear", 1, 256),
               String("envelope_indicators", "Output: envelope fault indicators per block.",
                      "gearpath_EnvelopeIndicators", 1, 256),
               String("status", "Output: daemon status, periodically.", "gearpath_Status", 1,
                      256)})});
}

ParamSpec ChannelSpec() {
  return Object(
      "channel", "One block channel.",
      {String("sensor", "Sensor id as carried by the AccelBlock channel, e.g. `A4`.", nullptr, 1,
              kMaxIdLength),
       Enum("axis", "Sensor axis as carried by the AccelBlock channel.", {"x", "y", "z"},
            nullptr),
       Integer("frf_row", "Row (response channel) of the decoupled FRF matrix it measures.", 0,
               1023, nullptr)});
}

ParamSpec GearTrainSection() {
  return Object(
      "gear_train",
      "Shafts, gears, meshes and bearings of the gearbox (core/model/gear_train.h). Shaft rates "
      "follow from the input shaft speed and the tooth counts.",
      {Array("shafts", "Shafts from input to output; the first is the input shaft.",
             Object("shaft", "One shaft.",
                    {String("name", "Shaft name, e.g. `input`.", nullptr, 1, kMaxIdLength),
                     Array("gears", "Names of the gears keyed to this shaft.",
                           String("gear", "Gear name.", nullptr, 1, kMaxIdLength), 1, 8)}),
             1, 16),
       Array("gears", "Gears.",
             Object("gear", "One gear.",
                    {String("name", "Gear name, e.g. `G1`.", nullptr, 1, kMaxIdLength),
                     Integer("teeth", "Tooth count.", 3, 1000, nullptr)}),
             2, 64),
       Array("stages", "Gear meshes (stages), input side first.",
             Object("stage", "One mesh; power flows from driver to driven.",
                    {String("driver", "Driving gear.", nullptr, 1, kMaxIdLength),
                     String("driven", "Driven gear.", nullptr, 1, kMaxIdLength)}),
             1, 16),
       Array("bearings", "Bearings (seats); each supports one shaft.",
             Object("bearing", "One bearing.",
                    {String("name", "Bearing name, e.g. `B1`.", nullptr, 1, kMaxIdLength),
                     String("shaft", "Name of the shaft it supports.", nullptr, 1,
                            kMaxIdLength)}),
             1, 64),
       Number("pressure_angle_deg", "Pressure angle of the (standard involute) gears, degrees.",
              5.0, 45.0, 20.0),
       Number("addendum_coefficient", "Addendum coefficient of the gears.", 0.5, 2.0, 1.0)});
}

ParamSpec PathSpec() {
  return Object("path", "One transfer path.",
                {String("name", "Path name as in the FRF set, e.g. `F4`.", nullptr, 1,
                        kMaxIdLength),
                 String("bearing", "Name of the gear_train bearing whose force it is.", nullptr,
                        1, kMaxIdLength)});
}

ParamSpec AnalysisSection() {
  return Object(
      "analysis", "How each block is analysed.",
      {Object("inverse", "Bearing-force identification (seed Eqs. 27-28, 40-43).",
              {Enum("method",
                    "mwi: Maximumly Weighted Iteration; tikhonov: Tikhonov regularisation; "
                    "least_squares: unregularised (baseline).",
                    {"mwi", "tikhonov", "least_squares"}, "mwi"),
               Enum("alpha_rule",
                    "How the regularisation parameter is chosen per bin "
                    "(core/inverse/regularisation_rule.h): noise_floor (filter singular "
                    "components below relative_noise * sigma_max), fixed (alpha), discrepancy "
                    "(Morozov, needs noise_rms), gcv (where well posed, else noise_floor).",
                    {"noise_floor", "fixed", "discrepancy", "gcv"}, "noise_floor"),
               Number("alpha", "Regularisation parameter when alpha_rule is fixed.", 0.0, 1e12,
                      1e-3, true),
               Number("relative_noise",
                      "Relative noise level eta of the FRFs (noise_floor and the gcv fallback).",
                      0.0, 1.0, 1e-3, true),
               Number("noise_rms",
                      "Per-channel noise RMS of the responses, m/s^2 (discrepancy rule).", 0.0,
                      1e6, 1e-3, true),
               Number("discrepancy_factor", "Safety factor tau >= 1 of the discrepancy rule.",
                      1.0, 100.0, 1.0),
               Integer("iterations", "MWI iteration count K.", 1, 1000, 10)}),
       Object("kurtogram", "Band selection by spectral kurtosis (fast kurtogram).",
              {Integer("max_level", "Deepest kurtogram level (band width fs / 2^(level+1)).", 1,
                       12, 6),
               Boolean("prewhiten", "Remove deterministic (mesh) tones before the kurtogram.",
                       true)}),
       Object("indicators", "Envelope fault indicators.",
              {Integer("harmonics", "Harmonics of a shaft rate summed into an indicator.", 1, 20,
                       5)}),
       Object("baseline",
              "Healthy-baseline learning: indicators are judged against the machine's own "
              "first blocks.",
              {Integer("learning_blocks",
                       "Blocks averaged into the healthy baseline before any verdict (0: "
                       "judge against zero).",
                       0, 100000, 0),
               Number("threshold_ratio",
                      "An indicator above this multiple of its baseline counts as a fault.", 1.0,
                      1000.0, 2.0, true)})});
}

ParamSpec MachineSpec() {
  return Object(
      "machine", "One gearbox this daemon watches.",
      {String("id", "Machine id: the DDS key of its blocks and results.", nullptr, 1,
              kMaxIdLength),
       String("description", "Free text for people.", ""),
       String("frf_set",
              "Decoupled FRF set: a directory in the format of docs/frf_format.md, or "
              "`builtin:table1` (the seed's Table-1 gearbox, computed through Eq. 22 at start).",
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
                       65536, 65536)}),
       Array("channels",
             "Block channel -> FRF row. Empty: match block channels to the FRF set's response "
             "channels by sensor and axis.",
             ChannelSpec(), 0, kMaxChannels, json::array()),
       GearTrainSection(),
       Array("paths",
             "Transfer path (FRF column) -> bearing. Empty: take the bearing named by the FRF "
             "set's path entries.",
             PathSpec(), 0, 64, json::array()),
       AnalysisSection()});
}

}  // namespace

const ParamSpec& DaemonConfigSchema() {
  static const ParamSpec schema = Object(
      "", "gearpathd configuration",
      {DaemonSection(), DdsSection(),
       Array("machines", "The gearboxes this daemon watches; blocks of other machines are ignored.",
             MachineSpec(), 1, kMaxMachines)});
  return schema;
}

}  // namespace gearpath::daemon
