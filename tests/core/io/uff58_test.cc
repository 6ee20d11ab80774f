#include "core/io/uff58.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
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

class Uff58Test : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gearpath_uff58_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// A record of the given form whose values are exactly representable in single precision
// (so that binary single-precision files can be compared exactly).
Uff58Record MakeRecord(bool double_precision, bool complex_ordinate, bool even, int node) {
  Uff58Record r;
  r.id_lines[0] = "FRF node " + std::to_string(node);
  r.id_lines[2] = "22-Nov-26 00:45:00";
  r.function_type = kUffFrequencyResponse;
  r.function_id = node;
  r.response_entity = "HOUSING";
  r.response_node = node;
  r.response_direction = -2;
  r.reference_entity = "SHAFT";
  r.reference_node = 1234567;
  r.reference_direction = 3;
  r.double_precision = double_precision;
  r.complex_ordinate = complex_ordinate;
  r.even_abscissa = even;
  r.z_axis_value = 0.5;
  r.abscissa_axis = {18, 0, 0, 0, "Frequency", "Hz"};
  r.ordinate_axis = {12, 1, 0, 0, "Acceleration", "m/s^2"};
  r.denominator_axis = {13, 0, 1, 0, "Force", "N"};
  const int n = 7;  // not a multiple of the values per line, to exercise the last line
  if (even) {
    r.abscissa_start = 2.5;
    r.abscissa_increment = 0.25;
  }
  for (int i = 0; i < n; ++i) {
    const double x = 1.0 + i;
    if (!even) r.abscissa.push_back(static_cast<float>(3.0 + i * i * 0.125));
    const double re = static_cast<float>(std::sin(x) * 1e3);
    const double im = complex_ordinate ? static_cast<float>(-std::cos(x) * 1e-4) : 0.0;
    r.ordinate.push_back({re, im});
  }
  return r;
}

void ExpectSameHeader(const Uff58Record& a, const Uff58Record& b) {
  EXPECT_EQ(a.id_lines[0], b.id_lines[0]);
  EXPECT_EQ(a.id_lines[1], b.id_lines[1]);
  EXPECT_EQ(a.id_lines[2], b.id_lines[2]);
  EXPECT_EQ(a.function_type, b.function_type);
  EXPECT_EQ(a.function_id, b.function_id);
  EXPECT_EQ(a.response_entity, b.response_entity);
  EXPECT_EQ(a.response_node, b.response_node);
  EXPECT_EQ(a.response_direction, b.response_direction);
  EXPECT_EQ(a.reference_entity, b.reference_entity);
  EXPECT_EQ(a.reference_node, b.reference_node);
  EXPECT_EQ(a.reference_direction, b.reference_direction);
  EXPECT_EQ(a.double_precision, b.double_precision);
  EXPECT_EQ(a.complex_ordinate, b.complex_ordinate);
  EXPECT_EQ(a.even_abscissa, b.even_abscissa);
  EXPECT_EQ(a.abscissa_start, b.abscissa_start);
  EXPECT_EQ(a.abscissa_increment, b.abscissa_increment);
  EXPECT_EQ(a.z_axis_value, b.z_axis_value);
  EXPECT_EQ(a.abscissa_axis.specific_data_type, b.abscissa_axis.specific_data_type);
  EXPECT_EQ(a.abscissa_axis.unit_label, b.abscissa_axis.unit_label);
  EXPECT_EQ(a.ordinate_axis.label, b.ordinate_axis.label);
  EXPECT_EQ(a.ordinate_axis.length_exponent, b.ordinate_axis.length_exponent);
  EXPECT_EQ(a.denominator_axis.force_exponent, b.denominator_axis.force_exponent);
  EXPECT_EQ(a.denominator_axis.unit_label, b.denominator_axis.unit_label);
}

// Relative tolerance `tol` (0 = exact).
void ExpectSameData(const Uff58Record& a, const Uff58Record& b, double ordinate_tol,
                    double abscissa_tol) {
  ASSERT_EQ(a.ordinate.size(), b.ordinate.size());
  ASSERT_EQ(a.abscissa.size(), b.abscissa.size());
  for (std::size_t i = 0; i < a.ordinate.size(); ++i) {
    EXPECT_NEAR(a.ordinate[i].real(), b.ordinate[i].real(),
                ordinate_tol * std::abs(a.ordinate[i].real()))
        << "sample " << i;
    EXPECT_NEAR(a.ordinate[i].imag(), b.ordinate[i].imag(),
                ordinate_tol * std::abs(a.ordinate[i].imag()))
        << "sample " << i;
  }
  for (std::size_t i = 0; i < a.abscissa.size(); ++i) {
    EXPECT_NEAR(a.abscissa[i], b.abscissa[i], abscissa_tol * std::abs(a.abscissa[i]));
  }
}

TEST_F(Uff58Test, ReadsTheHandWrittenSampleFile) {
  // tests/data/uff58_hand_frf.unv was typed by hand from the dataset 58 description; it starts
  // with a units dataset (164) that the reader must skip.
  auto records = ReadUff58(fs::path(GEARPATH_TEST_DATA_DIR) / "uff58_hand_frf.unv");
  ASSERT_TRUE(records.ok()) << records.error();
  ASSERT_EQ(records->size(), 1u);
  const Uff58Record& r = records->front();
  EXPECT_EQ(r.id_lines[0], "Hand-written FRF: acceleration at node 101 +Z per force at node 7 -Y");
  EXPECT_EQ(r.function_type, 4);
  EXPECT_EQ(r.function_id, 1);
  EXPECT_EQ(r.response_node, 101);
  EXPECT_EQ(r.response_direction, 3);
  EXPECT_EQ(r.reference_node, 7);
  EXPECT_EQ(r.reference_direction, -2);
  EXPECT_EQ(r.response_entity, "NONE");
  EXPECT_TRUE(r.double_precision);
  EXPECT_TRUE(r.complex_ordinate);
  EXPECT_TRUE(r.even_abscissa);
  EXPECT_EQ(r.abscissa_start, 5.0);
  EXPECT_EQ(r.abscissa_increment, 2.5);
  EXPECT_EQ(r.AbscissaAt(3), 12.5);
  EXPECT_EQ(r.abscissa_axis.specific_data_type, 18);
  EXPECT_EQ(r.abscissa_axis.label, "Frequency");
  EXPECT_EQ(r.abscissa_axis.unit_label, "Hz");
  EXPECT_EQ(r.ordinate_axis.unit_label, "m/s^2");
  EXPECT_EQ(r.ordinate_axis.length_exponent, 1);
  EXPECT_EQ(r.denominator_axis.unit_label, "N");
  EXPECT_EQ(r.denominator_axis.force_exponent, 1);
  ASSERT_EQ(r.ordinate.size(), 4u);
  EXPECT_EQ(r.ordinate[0], C(1.5, -0.25));
  EXPECT_EQ(r.ordinate[1], C(-0.03, 40.0));
  EXPECT_EQ(r.ordinate[2], C(1.234567890123e-3, -987.6543210987));
  EXPECT_EQ(r.ordinate[3], C(0.0, 1.0));
}

TEST_F(Uff58Test, RoundTripsEveryVariantInBothEncodings) {
  for (UffEncoding encoding : {UffEncoding::kAscii, UffEncoding::kBinary}) {
    for (bool double_precision : {false, true}) {
      for (bool complex_ordinate : {false, true}) {
        for (bool even : {true, false}) {
          SCOPED_TRACE(::testing::Message()
                       << (encoding == UffEncoding::kAscii ? "ascii" : "binary")
                       << (double_precision ? " double" : " single")
                       << (complex_ordinate ? " complex" : " real")
                       << (even ? " even" : " uneven"));
          const std::vector<Uff58Record> written = {
              MakeRecord(double_precision, complex_ordinate, even, 11),
              MakeRecord(double_precision, complex_ordinate, even, 12)};
          const fs::path file = dir_ / "round.unv";
          ASSERT_TRUE(WriteUff58(file, written, encoding).ok());
          auto read = ReadUff58(file);
          ASSERT_TRUE(read.ok()) << read.error();
          ASSERT_EQ(read->size(), 2u);
          // Binary stores the values themselves; ASCII prints 6 (E13.5) or 13 (E20.12)
          // significant digits; uneven abscissae print as E13.5 in either precision.
          const bool binary = encoding == UffEncoding::kBinary;
          const double ordinate_tol = binary ? 0.0 : (double_precision ? 1e-12 : 5e-6);
          const double abscissa_tol = binary ? 0.0 : 5e-6;
          for (std::size_t k = 0; k < 2; ++k) {
            ExpectSameHeader(written[k], (*read)[k]);
            ExpectSameData(written[k], (*read)[k], ordinate_tol, abscissa_tol);
          }
        }
      }
    }
  }
}

TEST_F(Uff58Test, ReadsMixedAsciiAndBinaryRecordsInOneFile) {
  const std::vector<Uff58Record> one = {MakeRecord(true, true, true, 1)};
  const std::vector<Uff58Record> two = {MakeRecord(false, false, false, 2)};
  ASSERT_TRUE(WriteUff58(dir_ / "a.unv", one, UffEncoding::kAscii).ok());
  ASSERT_TRUE(WriteUff58(dir_ / "b.unv", two, UffEncoding::kBinary).ok());
  WriteFileBytes(dir_ / "ab.unv", ReadFileBytes(dir_ / "b.unv") + ReadFileBytes(dir_ / "a.unv") +
                                      ReadFileBytes(dir_ / "b.unv"));
  auto read = ReadUff58(dir_ / "ab.unv");
  ASSERT_TRUE(read.ok()) << read.error();
  ASSERT_EQ(read->size(), 3u);
  EXPECT_EQ((*read)[0].response_node, 2);
  EXPECT_EQ((*read)[1].response_node, 1);
  EXPECT_EQ((*read)[2].ordinate, two[0].ordinate);
}

TEST_F(Uff58Test, ReadsBigEndianBinaryData) {
  Uff58Record r = MakeRecord(true, true, true, 5);
  const std::vector<Uff58Record> records = {r};
  ASSERT_TRUE(WriteUff58(dir_ / "le.unv", records, UffEncoding::kBinary).ok());
  std::string bytes = ReadFileBytes(dir_ / "le.unv");
  // Line 2 is the 58b header: set the byte-ordering flag (columns 8-13) to 2, MSB first.
  const std::size_t header = bytes.find('\n') + 1;
  bytes.replace(header + 7, 6, "     2");
  // Data starts after 13 lines; reverse each 8-byte value.
  std::size_t data = 0;
  for (int line = 0; line < 13; ++line) data = bytes.find('\n', data) + 1;
  for (std::size_t i = 0; i < 2 * r.ordinate.size(); ++i) {
    std::reverse(bytes.begin() + static_cast<std::ptrdiff_t>(data + 8 * i),
                 bytes.begin() + static_cast<std::ptrdiff_t>(data + 8 * i + 8));
  }
  WriteFileBytes(dir_ / "be.unv", bytes);
  auto read = ReadUff58(dir_ / "be.unv");
  ASSERT_TRUE(read.ok()) << read.error();
  EXPECT_EQ(read->front().ordinate, r.ordinate);
}

TEST_F(Uff58Test, ReadsFreeFormatDataWithFortranExponents) {
  const std::string text =
      "    -1\n    58\nfree\nNONE\nNONE\nNONE\nNONE\n"
      "1 0 0 0 NONE 3 1 NONE 4 -1\n"
      "         2         3         1  0.00000E+00  1.00000E-03  0.00000E+00\n"
      "        17    0    0    0 Time                 s\n"
      "        12    1    0    0 Acceleration         m/s^2\n"
      "         0    0    0    0 NONE                 NONE\n"
      "         0    0    0    0 NONE                 NONE\n"
      "  1.0D+00 -2.5d-01\n 3.0\n    -1\n";
  auto read = ParseUff58(text, "free.unv");
  ASSERT_TRUE(read.ok()) << read.error();
  const auto& r = read->front();
  EXPECT_EQ(r.function_type, kUffTimeResponse);
  EXPECT_EQ(r.response_node, 3);
  EXPECT_EQ(r.reference_direction, -1);
  EXPECT_EQ(r.ordinate, (std::vector<C>{{1.0, 0}, {-0.25, 0}, {3.0, 0}}));
}

TEST_F(Uff58Test, ReadsTouchingFixedWidthFields) {
  // E13.5 fields with 3-digit exponents fill their 13 columns, so values touch.
  const std::string text =
      "    -1\n    58\nx\nNONE\nNONE\nNONE\nNONE\n"
      "    1         0    0         0       NONE         3   1       NONE         0   0\n"
      "         2         2         1  0.00000E+00  1.00000E-03  0.00000E+00\n"
      "        17    0    0    0 Time                 s\n"
      "        12    1    0    0 Acceleration         m/s^2\n"
      "         0    0    0    0 NONE                 NONE\n"
      "         0    0    0    0 NONE                 NONE\n"
      "-1.00000E-100-2.50000E+100\n    -1\n";
  auto read = ParseUff58(text, "touch.unv");
  ASSERT_TRUE(read.ok()) << read.error();
  EXPECT_EQ(read->front().ordinate[0].real(), -1e-100);
  EXPECT_EQ(read->front().ordinate[1].real(), -2.5e100);
}

// The hand-written sample with its data section edited by `edit`.
std::string HandSample(const std::string& from, const std::string& to) {
  std::string text = ReadFileBytes(fs::path(GEARPATH_TEST_DATA_DIR) / "uff58_hand_frf.unv");
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST_F(Uff58Test, RejectsTruncatedAsciiDataNamingFileLineAndCounts) {
  const std::string text = HandSample(
      "  1.234567890123E-03 -9.876543210987E+02  0.000000000000E+00  1.000000000000E+00\n", "");
  auto read = ParseUff58(text, "cut.unv");
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(Contains(read.error(), "cut.unv:21:"));
  EXPECT_TRUE(Contains(read.error(), "truncated data: expected 8 values, got 4"));
}

TEST_F(Uff58Test, RejectsUnsupportedOrdinateDataType) {
  const std::string text =
      HandSample("         6         4         1", "         3         4         1");
  auto read = ParseUff58(text, "t.unv");
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(
      Contains(read.error(), "t.unv:15: record 7: ordinate data type '3' is not supported"));
}

TEST_F(Uff58Test, RejectsGarbageInTheData) {
  const std::string text = HandSample("  1.500000000000E+00", "  1.5000000000x0E+00");
  auto read = ParseUff58(text, "g.unv");
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(Contains(read.error(), "g.unv:20: record 12: cannot read a number"));
}

TEST_F(Uff58Test, RejectsMoreDataThanAnnounced) {
  const std::string text = HandSample("  1.000000000000E+00\n", "  1.000000000000E+00\n  7.0\n");
  auto read = ParseUff58(text, "m.unv");
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(Contains(read.error(), "more data than the 8 values record 7 announces"));
}

TEST_F(Uff58Test, RejectsBinaryRecordsWhoseByteCountDisagrees) {
  const std::vector<Uff58Record> records = {MakeRecord(true, true, true, 5)};
  ASSERT_TRUE(WriteUff58(dir_ / "b.unv", records, UffEncoding::kBinary).ok());
  const std::string bytes = ReadFileBytes(dir_ / "b.unv");
  // 7 complex doubles = 112 bytes; announce 120.
  std::string wrong = bytes;
  wrong.replace(wrong.find("         112"), 12, "         120");
  auto read = ParseUff58(wrong, "b.unv");
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(Contains(read.error(),
                       "b.unv:2: dataset 58b: header announces 120 data bytes but "
                       "record 7 (7 points, data type 6) needs 112"));
  // Cut the file inside the binary data.
  auto cut = ParseUff58(bytes.substr(0, bytes.size() - 60), "b.unv");
  ASSERT_FALSE(cut.ok());
  EXPECT_TRUE(Contains(cut.error(), "truncated binary data: expected 112 bytes, got"));
}

TEST_F(Uff58Test, RejectsNonIeeeBinaryAndMissingDelimiters) {
  const std::vector<Uff58Record> records = {MakeRecord(true, false, true, 5)};
  ASSERT_TRUE(WriteUff58(dir_ / "b.unv", records, UffEncoding::kBinary).ok());
  std::string bytes = ReadFileBytes(dir_ / "b.unv");
  const std::size_t header = bytes.find('\n') + 1;
  bytes.replace(header + 13, 6, "     1");  // DEC VMS floating point
  auto read = ParseUff58(bytes, "vms.unv");
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(Contains(read.error(), "floating-point format '1' is not supported"));

  auto no_delimiter = ParseUff58("    58\n", "x.unv");
  ASSERT_FALSE(no_delimiter.ok());
  EXPECT_TRUE(Contains(no_delimiter.error(), "x.unv:1: expected a dataset delimiter"));
}

TEST_F(Uff58Test, RejectsEveryTruncationOfAValidFileWithoutCrashing) {
  const std::vector<Uff58Record> records = {MakeRecord(true, true, false, 1),
                                            MakeRecord(false, false, true, 2)};
  for (UffEncoding encoding : {UffEncoding::kAscii, UffEncoding::kBinary}) {
    ASSERT_TRUE(WriteUff58(dir_ / "t.unv", records, encoding).ok());
    const std::string bytes = ReadFileBytes(dir_ / "t.unv");
    std::size_t accepted = 0;
    // Up to the final newline, which a reader does not need.
    for (std::size_t cut = 0; cut + 1 < bytes.size(); ++cut) {
      auto read = ParseUff58(std::string_view(bytes).substr(0, cut), "t.unv");
      // A prefix parses only if it ends on a record boundary, and then with fewer records.
      if (read.ok()) {
        ++accepted;
        EXPECT_LT(read->size(), 2u) << "cut at " << cut;
      } else {
        EXPECT_TRUE(Contains(read.error(), "t.unv:")) << "cut at " << cut;
      }
    }
    EXPECT_GE(accepted, 2u);  // the empty prefix and the first record alone
  }
}

TEST_F(Uff58Test, RejectsPointCountBeyondTheFileBeforeAllocating) {
  const std::string text =
      HandSample("         6         4         1", "         62000000000         1");
  auto read = ParseUff58(text, "big.unv");
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(Contains(read.error(), "big.unv:15: record 7 announces 2000000000 points"));
}

TEST_F(Uff58Test, RejectsMissingFile) {
  auto read = ReadUff58(dir_ / "absent.unv");
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(Contains(read.error(), "absent.unv: cannot open file"));
}

TEST_F(Uff58Test, WriterRejectsInconsistentRecords) {
  Uff58Record r = MakeRecord(true, true, false, 1);
  r.abscissa.pop_back();
  std::vector<Uff58Record> records = {r};
  Status st = WriteUff58(dir_ / "w.unv", records, UffEncoding::kAscii);
  ASSERT_FALSE(st.ok());
  EXPECT_TRUE(
      Contains(st.error(), "record 0: uneven abscissa has 6 values for 7 ordinate samples"));
  records[0] = MakeRecord(true, false, true, 1);
  records[0].ordinate[2] = {1.0, 2.0};
  st = WriteUff58(dir_ / "w.unv", records, UffEncoding::kAscii);
  ASSERT_FALSE(st.ok());
  EXPECT_TRUE(Contains(st.error(), "real ordinate has a nonzero imaginary part at sample 2"));
}

TEST_F(Uff58Test, NamesFunctionTypesAndDirections) {
  EXPECT_EQ(UffFunctionTypeName(1), "time response");
  EXPECT_EQ(UffFunctionTypeName(4), "frequency response function");
  EXPECT_EQ(UffDirectionName(-2), "-Y");
  EXPECT_EQ(UffDirectionName(6), "+RZ");
  EXPECT_EQ(UffDirectionName(0), "scalar");
}

}  // namespace
}  // namespace gearpath
