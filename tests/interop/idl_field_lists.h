// The fields of every struct of idl/gearpath.idl, in IDL order, as X-macro lists.
//
// The interoperability test turns a sample into JSON twice, once from the Fast DDS type
// (fastddsgen: accessor methods) and once from the Cyclone type (idlc: C members), and compares
// the two field by field. Both conversions expand these lists, so they cannot disagree on a name
// or forget a field on one side only; a test checks the lists against the IDL itself
// (idl_field_lists_test.cc). Dependency-free: the Fast DDS client and the Cyclone side both
// include it.
#pragma once

// clang-format off
#define GEARPATH_FIELDS_ChannelInfo(F) F(sensor_id) F(axis) F(unit) F(sensitivity_mv_per_unit)

#define GEARPATH_FIELDS_AccelBlock(F)                                                  \
  F(machine_id) F(sequence_number) F(t0_ns) F(sample_rate_hz) F(speed_hz)             \
  F(speed_source) F(channels) F(samples_per_channel) F(samples)

#define GEARPATH_FIELDS_AccelBlockV2(F)                                                \
  GEARPATH_FIELDS_AccelBlock(F) F(load) F(load_unit)

#define GEARPATH_FIELDS_PathShare(F) F(name) F(share) F(criterion)

#define GEARPATH_FIELDS_DominantPath(F)                                                \
  F(machine_id) F(block_sequence) F(block_t0_ns) F(path_index) F(path_name) F(paths)   \
  F(band_lo_hz) F(band_hi_hz) F(criterion)

#define GEARPATH_FIELDS_SuspectedGear(F)                                               \
  F(machine_id) F(block_sequence) F(block_t0_ns) F(gear_name) F(shaft_name)            \
  F(characteristic_frequency_hz) F(confidence) F(state) F(candidates) F(reason)

#define GEARPATH_FIELDS_KurtogramBand(F)                                               \
  F(centre_hz) F(width_hz) F(level) F(kurtosis) F(significant)

#define GEARPATH_FIELDS_ShaftIndicator(F)                                              \
  F(shaft_name) F(characteristic_frequency_hz) F(raw_indicator)                        \
  F(reconstructed_indicator) F(enhancement_percent) F(raw_threshold)                   \
  F(reconstructed_threshold) F(raw_harmonics) F(reconstructed_harmonics)

#define GEARPATH_FIELDS_EnvelopeIndicators(F)                                          \
  F(machine_id) F(block_sequence) F(block_t0_ns) F(band) F(shafts) F(speed_hz)         \
  F(speed_source)

#define GEARPATH_FIELDS_IndicatorValue(F) F(name) F(value) F(z)

#define GEARPATH_FIELDS_IndicatorSet(F)                                                \
  F(source) F(signal) F(shaft) F(shaft_hz) F(revolutions) F(score) F(values)

#define GEARPATH_FIELDS_ConditionIndicators(F)                                         \
  F(machine_id) F(block_sequence) F(block_t0_ns) F(limit_z) F(clear_level) F(score)    \
  F(top_indicator) F(top_signal) F(top_shaft) F(exceed_count) F(window)                \
  F(baseline_blocks_learned) F(baseline_blocks_needed) F(sets) F(sets_omitted)         \
  F(values_omitted)

#define GEARPATH_FIELDS_MachineStatus(F)                                               \
  F(machine_id) F(blocks_received) F(blocks_processed) F(blocks_rejected)              \
  F(last_rejection_reason) F(last_alpha) F(last_condition_number)                      \
  F(last_relative_residual) F(latency_last_ms) F(latency_max_ms)

#define GEARPATH_FIELDS_Status(F) F(daemon_id) F(state) F(timestamp_ns) F(uptime_s) F(machines)

#define GEARPATH_FIELDS_MachineHealth(F)                                               \
  F(daemon_id) F(machine_id) F(daemon_state) F(timestamp_ns) F(machine_index)          \
  F(machine_count) F(fault_state) F(publishing_results) F(last_block_sequence)         \
  F(last_block_t0_ns) F(blocks_received) F(blocks_processed) F(blocks_rejected)        \
  F(blocks_lost) F(last_rejection_reason) F(last_alpha) F(last_condition_number)       \
  F(last_relative_residual) F(latency_last_ms) F(latency_max_ms)

// Every struct of the IDL, for the check against the IDL text.
#define GEARPATH_IDL_STRUCTS(S)                                                        \
  S(ChannelInfo) S(AccelBlock) S(AccelBlockV2) S(PathShare) S(DominantPath)           \
  S(SuspectedGear) S(KurtogramBand) S(ShaftIndicator) S(EnvelopeIndicators)            \
  S(IndicatorValue) S(IndicatorSet) S(ConditionIndicators) S(MachineStatus) S(Status)  \
  S(MachineHealth)
// clang-format on
