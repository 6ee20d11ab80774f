#include "core/io/uff58_import.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/core/io/io_test_util.h"

namespace gearpath {
namespace {

namespace fs = std::filesystem;
using C = std::complex<double>;

constexpr int kBins = 6;

// DOFs listed with roles interleaved, to check that each role keeps the caller's order.
const std::vector<UffDofAssignment> kDofs = {{"a1", 1, 1, DofRole::kActive},
                                             {"p1", 2, 1, DofRole::kPassive},
                                             {"a2", 1, 2, DofRole::kActive},
                                             {"m1", 9, 2, DofRole::kMeasurement},
                                             {"p2", 3, 3, DofRole::kPassive}};
constexpr std::size_t kA1 = 0, kP1 = 1, kA2 = 2, kM1 = 3, kP2 = 4;

// The true FRF between two DOFs (indices into kDofs), positive directions: a value that says
// which pair and which bin it belongs to.
C Truth(std::size_t response, std::size_t reference, int k) {
  return {100.0 * static_cast<double>(response + 1) + static_cast<double>(reference + 1),
          0.5 * k + static_cast<double>(response)};
}

// An FRF record of the pair, optionally measured along negative directions (so stored negated
// once per negative end, as a test system would).
Uff58Record Frf(std::size_t response, std::size_t reference, bool negative_response = false,
                bool negative_reference = false) {
  Uff58Record r;
  r.function_type = kUffFrequencyResponse;
  r.response_node = kDofs[response].node;
  r.response_direction = kDofs[response].direction * (negative_response ? -1 : 1);
  r.reference_node = kDofs[reference].node;
  r.reference_direction = kDofs[reference].direction * (negative_reference ? -1 : 1);
  r.abscissa_start = 10.0;
  r.abscissa_increment = 5.0;
  const double sign = (negative_response != negative_reference) ? -1.0 : 1.0;
  for (int k = 0; k < kBins; ++k) r.ordinate.push_back(sign * Truth(response, reference, k));
  return r;
}

// Every pair the import needs (aa, pa, pp, ma, mp), some along negative directions, plus
// records it must ignore.
std::vector<Uff58Record> MeasuredRecords() {
  std::vector<Uff58Record> records;
  const std::size_t a[] = {kA1, kA2}, p[] = {kP1, kP2};
  for (std::size_t i : a) {
    for (std::size_t j : a)
      records.push_back(Frf(i, j, i == kA2 && j == kA1, i == kA2 && j == kA1));
  }
  for (std::size_t i : p) {
    for (std::size_t j : a) records.push_back(Frf(i, j, i == kP2 && j == kA1));
  }
  for (std::size_t i : p) {
    for (std::size_t j : p) records.push_back(Frf(i, j));
  }
  for (std::size_t j : a) records.push_back(Frf(kM1, j));
  for (std::size_t j : p) records.push_back(Frf(kM1, j, false, j == kP1));
  // To be ignored: a coherence next to an FRF, a time response, an FRF of an unassigned node.
  Uff58Record coherence = Frf(kA1, kA2);
  coherence.function_type = kUffCoherence;
  records.push_back(coherence);
  Uff58Record time = Frf(kA1, kA1);
  time.function_type = kUffTimeResponse;
  time.reference_node = 0;
  time.reference_direction = 0;
  records.push_back(time);
  Uff58Record stranger = Frf(kP1, kA1);
  stranger.response_node = 77;
  records.push_back(stranger);
  return records;
}

std::size_t FindRecord(const std::vector<Uff58Record>& records, std::size_t response,
                       std::size_t reference) {
  for (std::size_t k = 0; k < records.size(); ++k) {
    if (records[k].function_type == kUffFrequencyResponse &&
        records[k].response_node == kDofs[response].node &&
        std::abs(records[k].response_direction) == kDofs[response].direction &&
        records[k].reference_node == kDofs[reference].node &&
        std::abs(records[k].reference_direction) == kDofs[reference].direction) {
      return k;
    }
  }
  ADD_FAILURE() << "no record " << response << " " << reference;
  return 0;
}

void ExpectBlock(const std::vector<Eigen::MatrixXcd>& block, const std::vector<std::size_t>& rows,
                 const std::vector<std::size_t>& cols, const char* what) {
  ASSERT_EQ(block.size(), static_cast<std::size_t>(kBins)) << what;
  for (int k = 0; k < kBins; ++k) {
    ASSERT_EQ(block[static_cast<std::size_t>(k)].rows(), static_cast<Eigen::Index>(rows.size()));
    ASSERT_EQ(block[static_cast<std::size_t>(k)].cols(), static_cast<Eigen::Index>(cols.size()));
    for (std::size_t i = 0; i < rows.size(); ++i) {
      for (std::size_t j = 0; j < cols.size(); ++j) {
        EXPECT_EQ(block[static_cast<std::size_t>(k)](static_cast<Eigen::Index>(i),
                                                     static_cast<Eigen::Index>(j)),
                  Truth(rows[i], cols[j], k))
            << what << " bin " << k << " (" << i << ", " << j << ")";
      }
    }
  }
}

TEST(ImportCoupledSet, PlacesEveryFrfInItsBlockByRoleAndUndoesNegativeDirections) {
  const auto records = MeasuredRecords();
  auto set = ImportCoupledSet(records, kDofs);
  ASSERT_TRUE(set.ok()) << set.error();
  ASSERT_EQ(set->blocks.bins(), kBins);
  EXPECT_EQ(set->blocks.frequency_hz[0], 10.0);
  EXPECT_EQ(set->blocks.frequency_hz[5], 35.0);
  ExpectBlock(set->blocks.aa, {kA1, kA2}, {kA1, kA2}, "aa");
  ExpectBlock(set->blocks.pa, {kP1, kP2}, {kA1, kA2}, "pa");
  ExpectBlock(set->blocks.pp, {kP1, kP2}, {kP1, kP2}, "pp");
  ExpectBlock(set->blocks.ma, {kM1}, {kA1, kA2}, "ma");
  ExpectBlock(set->blocks.mp, {kM1}, {kP1, kP2}, "mp");
  EXPECT_FALSE(set->blocks.has_ap());
  ASSERT_EQ(set->active.size(), 2u);
  EXPECT_EQ(set->active[1].name, "a2");
  EXPECT_EQ(set->active[1].node, "1");
  EXPECT_EQ(set->active[1].direction, "y");
  ASSERT_EQ(set->passive.size(), 2u);
  EXPECT_EQ(set->passive[1].name, "p2");
  EXPECT_EQ(set->passive[1].direction, "z");
  ASSERT_EQ(set->measurement.size(), 1u);
  EXPECT_EQ(set->measurement[0].node, "9");
}

TEST(ImportCoupledSet, FillsApWhenItWasMeasured) {
  auto records = MeasuredRecords();
  for (std::size_t i : {kA1, kA2}) {
    for (std::size_t j : {kP1, kP2}) records.push_back(Frf(i, j));
  }
  auto set = ImportCoupledSet(records, kDofs);
  ASSERT_TRUE(set.ok()) << set.error();
  ASSERT_TRUE(set->blocks.has_ap());
  ExpectBlock(set->blocks.ap, {kA1, kA2}, {kP1, kP2}, "ap");
}

TEST(ImportCoupledSet, LeavesMeasurementBlocksEmptyWithoutMeasurementDofs) {
  std::vector<UffDofAssignment> dofs = kDofs;
  dofs.erase(dofs.begin() + static_cast<std::ptrdiff_t>(kM1));
  auto set = ImportCoupledSet(MeasuredRecords(), dofs);
  ASSERT_TRUE(set.ok()) << set.error();
  EXPECT_FALSE(set->blocks.has_measurement_points());
  EXPECT_TRUE(set->measurement.empty());
}

TEST(ImportCoupledSet, RejectsMissingRequiredPairNamingBothDofs) {
  auto records = MeasuredRecords();
  records.erase(records.begin() + static_cast<std::ptrdiff_t>(FindRecord(records, kP2, kA2)));
  auto set = ImportCoupledSet(records, kDofs);
  ASSERT_FALSE(set.ok());
  EXPECT_TRUE(Contains(set.error(),
                       "missing FRF for H_pa: response p2 (node 3 +Z), reference a2 (node 1 +Y)"));
}

TEST(ImportCoupledSet, RejectsNonFrfRecordWhereAnFrfIsExpected) {
  auto records = MeasuredRecords();
  records[FindRecord(records, kM1, kP2)].function_type = kUffCrossSpectrum;
  auto set = ImportCoupledSet(records, kDofs);
  ASSERT_FALSE(set.ok());
  EXPECT_TRUE(Contains(set.error(), "missing FRF for H_mp: response m1 (node 9 +Y), reference p2"));
  EXPECT_TRUE(Contains(set.error(),
                       "has function type 3 (cross spectrum), expected 4 "
                       "(frequency response function)"));
}

TEST(ImportCoupledSet, RejectsPartlyMeasuredAp) {
  auto records = MeasuredRecords();
  records.push_back(Frf(kA1, kP2));
  auto set = ImportCoupledSet(records, kDofs);
  ASSERT_FALSE(set.ok());
  EXPECT_TRUE(Contains(set.error(), "missing FRF for H_ap (partly measured): response a1"));
}

TEST(ImportCoupledSet, RejectsRecordsOnDifferentAbscissae) {
  auto records = MeasuredRecords();
  const std::size_t k = FindRecord(records, kP1, kP1);
  records[k].abscissa_increment = 5.0001;
  auto set = ImportCoupledSet(records, kDofs);
  ASSERT_FALSE(set.ok());
  EXPECT_TRUE(
      Contains(set.error(), "abscissa mismatch: record " + std::to_string(k) +
                                " (response node 2 +X, reference node 2 +X) has 6 points from 10 "
                                "step 5.0001, record 0"));
}

TEST(ImportCoupledSet, RejectsTwoFrfsForOnePair) {
  auto records = MeasuredRecords();
  records.push_back(Frf(kP2, kA1));  // also present as -Z response
  auto set = ImportCoupledSet(records, kDofs);
  ASSERT_FALSE(set.ok());
  EXPECT_TRUE(Contains(set.error(), "two FRFs for response p2 (node 3 +Z), reference a1"));
}

TEST(ImportCoupledSet, RejectsBadAssignments) {
  std::vector<UffDofAssignment> dofs = kDofs;
  dofs[kP1].direction = 4;
  auto set = ImportCoupledSet(MeasuredRecords(), dofs);
  ASSERT_FALSE(set.ok());
  EXPECT_TRUE(Contains(set.error(), "dofs[1] (p1): direction must be 1, 2 or 3"));

  dofs = kDofs;
  dofs[kP2].node = 2;
  dofs[kP2].direction = 1;
  set = ImportCoupledSet(MeasuredRecords(), dofs);
  ASSERT_FALSE(set.ok());
  EXPECT_TRUE(Contains(set.error(), "node 2 +X is assigned twice"));

  dofs = {kDofs[kP1], kDofs[kP2]};
  set = ImportCoupledSet(MeasuredRecords(), dofs);
  ASSERT_FALSE(set.ok());
  EXPECT_TRUE(Contains(set.error(), "no DOF has the active (a) role"));
}

TEST(ImportCoupledSet, GivesTheSameBlocksAfterAUffFileRoundTrip) {
  const auto records = MeasuredRecords();
  auto direct = ImportCoupledSet(records, kDofs);
  ASSERT_TRUE(direct.ok()) << direct.error();
  const fs::path file =
      fs::temp_directory_path() / ("gearpath_uff_import_" + std::to_string(::getpid()) + ".unv");
  ASSERT_TRUE(WriteUff58(file, records, UffEncoding::kBinary).ok());
  auto read = ReadUff58(file);
  fs::remove(file);
  ASSERT_TRUE(read.ok()) << read.error();
  auto via_file = ImportCoupledSet(*read, kDofs);
  ASSERT_TRUE(via_file.ok()) << via_file.error();
  EXPECT_EQ(via_file->blocks.frequency_hz, direct->blocks.frequency_hz);
  for (int k = 0; k < kBins; ++k) {
    EXPECT_EQ(via_file->blocks.pa[static_cast<std::size_t>(k)],
              direct->blocks.pa[static_cast<std::size_t>(k)]);
    EXPECT_EQ(via_file->blocks.mp[static_cast<std::size_t>(k)],
              direct->blocks.mp[static_cast<std::size_t>(k)]);
  }
}

Uff58Record TimeRecord(int node, int direction, int samples, double dt) {
  Uff58Record r;
  r.function_type = kUffTimeResponse;
  r.id_lines[0] = "accel " + std::to_string(node);
  r.response_node = node;
  r.response_direction = direction;
  r.complex_ordinate = false;
  r.abscissa_start = 0.0;
  r.abscissa_increment = dt;
  r.ordinate_axis.unit_label = "m/s^2";
  for (int i = 0; i < samples; ++i) r.ordinate.push_back(std::sin(0.3 * i + node));
  return r;
}

TEST(ExtractTimeHistories, ReturnsChannelsOnOneSampleClockFromAUffFile) {
  const std::vector<Uff58Record> records = {TimeRecord(5, 1, 8, 1e-3), Frf(kA1, kA1),
                                            TimeRecord(6, -3, 8, 1e-3)};
  const fs::path file =
      fs::temp_directory_path() / ("gearpath_uff_time_" + std::to_string(::getpid()) + ".unv");
  ASSERT_TRUE(WriteUff58(file, records, UffEncoding::kAscii).ok());
  auto read = ReadUff58(file);
  fs::remove(file);
  ASSERT_TRUE(read.ok()) << read.error();
  auto th = ExtractTimeHistories(*read);
  ASSERT_TRUE(th.ok()) << th.error();
  EXPECT_DOUBLE_EQ(th->sample_rate_hz, 1000.0);
  EXPECT_EQ(th->start_time_s, 0.0);
  ASSERT_EQ(th->channels.size(), 2u);
  EXPECT_EQ(th->channels[1].node, 6);
  EXPECT_EQ(th->channels[1].direction, -3);
  EXPECT_EQ(th->channels[0].label, "accel 5");
  EXPECT_EQ(th->channels[0].unit, "m/s^2");
  ASSERT_EQ(th->samples.rows(), 8);
  ASSERT_EQ(th->samples.cols(), 2);
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(th->samples(i, 0), std::sin(0.3 * i + 5), 1e-12);
    EXPECT_NEAR(th->samples(i, 1), std::sin(0.3 * i + 6), 1e-12);
  }
}

TEST(ExtractTimeHistories, RejectsChannelsOfDifferentLengthOrRateAndComplexOrNoData) {
  std::vector<Uff58Record> records = {TimeRecord(5, 1, 8, 1e-3), TimeRecord(6, 1, 9, 1e-3)};
  auto th = ExtractTimeHistories(records);
  ASSERT_FALSE(th.ok());
  EXPECT_TRUE(Contains(th.error(),
                       "time base mismatch: record 1 (response node 6 +X, reference node 0 scalar) "
                       "has 9 points"));
  records[1] = TimeRecord(6, 1, 8, 2e-3);
  EXPECT_FALSE(ExtractTimeHistories(records).ok());
  records[1] = TimeRecord(6, 1, 8, 1e-3);
  records[1].complex_ordinate = true;
  th = ExtractTimeHistories(records);
  ASSERT_FALSE(th.ok());
  EXPECT_TRUE(Contains(th.error(), "time response has complex samples"));
  const std::vector<Uff58Record> frfs = {Frf(kA1, kA1)};
  th = ExtractTimeHistories(frfs);
  ASSERT_FALSE(th.ok());
  EXPECT_TRUE(Contains(th.error(), "no time response record (function type 1)"));
}

}  // namespace
}  // namespace gearpath
