#include "core/io/npy.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <complex>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "tests/core/io/io_test_util.h"

namespace gearpath {
namespace {

namespace fs = std::filesystem;

class NpyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gearpath_npy_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Writes a .npy file byte by byte, as the NumPy format documentation describes it.
  fs::path WriteRaw(const std::string& name, int major, const std::string& dict,
                    const std::string& data, const char* magic = "\x93NUMPY") {
    const std::size_t length_bytes = major == 1 ? 2 : 4;
    std::string header = dict;
    const std::size_t unpadded = 6 + 2 + length_bytes + header.size() + 1;
    header += std::string((64 - unpadded % 64) % 64, ' ') + "\n";
    std::string bytes(magic, 6);
    bytes += static_cast<char>(major);
    bytes += '\0';
    for (std::size_t i = 0; i < length_bytes; ++i) {
      bytes += static_cast<char>((header.size() >> (8 * i)) & 0xff);
    }
    bytes += header + data;
    const fs::path file = dir_ / name;
    WriteFileBytes(file, bytes);
    return file;
  }

  template <typename T>
  static std::string Bytes(const std::vector<T>& values) {
    return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }

  fs::path dir_;
};

template <typename T>
void ExpectRoundTrip(const fs::path& file, const std::vector<T>& values,
                     const std::vector<std::size_t>& shape) {
  ASSERT_TRUE(WriteNpy<T>(file, values, shape).ok());
  auto read = ReadNpy<T>(file);
  ASSERT_TRUE(read.ok()) << read.error();
  EXPECT_EQ(read->shape, shape);
  ASSERT_EQ(read->data.size(), values.size());
  EXPECT_TRUE(SameBytes(read->data.data(), values.data(), values.size() * sizeof(T)));
}

TEST_F(NpyTest, RoundTripsEveryDtypeBitForBit) {
  const double tiny = std::numeric_limits<double>::denorm_min();
  ExpectRoundTrip<std::complex<double>>(
      dir_ / "c16.npy", {{1.0, -2.0}, {0.1, 1e-300}, {tiny, -0.0}, {3, 4}, {5, 6}, {-7.25, 8.5}},
      {2, 3});
  ExpectRoundTrip<double>(dir_ / "f8.npy", {0.1, 0.2, 0.30000000000000004, -1e308}, {4});
  ExpectRoundTrip<float>(dir_ / "f4.npy", {0.1f, -3.5f, 1e-38f, 7.0f, 8.0f, 9.0f, 10.f, 11.f},
                         {2, 2, 2});
  ExpectRoundTrip<std::int16_t>(dir_ / "i2.npy", {-32768, 0, 32767}, {3, 1});
  ExpectRoundTrip<std::int32_t>(dir_ / "i4.npy", {std::numeric_limits<std::int32_t>::min(), 1},
                                {1, 2});
}

TEST_F(NpyTest, RoundTripsZeroDimensionalAndEmptyArrays) {
  ExpectRoundTrip<double>(dir_ / "scalar.npy", {42.0}, {});
  ExpectRoundTrip<double>(dir_ / "empty.npy", {}, {0, 3});
}

TEST_F(NpyTest, WritesHeaderThatNumpyDocumentsWithDataAlignedTo64Bytes) {
  const std::vector<double> values = {1.5, 2.5};
  ASSERT_TRUE(WriteNpy<double>(dir_ / "a.npy", values, {2}).ok());
  const std::string bytes = ReadFileBytes(dir_ / "a.npy");
  ASSERT_GE(bytes.size(), 10u);
  EXPECT_EQ(bytes.substr(0, 6), std::string("\x93NUMPY"));
  EXPECT_EQ(bytes[6], 1);
  EXPECT_EQ(bytes[7], 0);
  const std::size_t header_length =
      static_cast<unsigned char>(bytes[8]) | (static_cast<unsigned char>(bytes[9]) << 8);
  EXPECT_EQ((10 + header_length) % 64, 0u);
  const std::string dict = bytes.substr(10, header_length);
  EXPECT_TRUE(Contains(dict, "'descr': '<f8'"));
  EXPECT_TRUE(Contains(dict, "'fortran_order': False"));
  EXPECT_TRUE(Contains(dict, "'shape': (2,)"));
  EXPECT_EQ(dict.back(), '\n');
  EXPECT_EQ(bytes.size(), 10 + header_length + 2 * sizeof(double));
}

TEST_F(NpyTest, ReadsFileBuiltFromHandWrittenHeaderBytes) {
  const std::vector<double> values = {1, 2, 3, 4, 5, 6};
  const auto file = WriteRaw(
      "hand.npy", 1, "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", Bytes(values));
  auto read = ReadNpy<double>(file);
  ASSERT_TRUE(read.ok()) << read.error();
  EXPECT_EQ(read->shape, (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(read->data, values);
}

TEST_F(NpyTest, ReadsVersion2And3HeadersAndDoubleQuotedKeys) {
  const std::vector<std::int32_t> values = {7, -8, 9};
  for (int major : {2, 3}) {
    const auto file =
        WriteRaw("v" + std::to_string(major) + ".npy", major,
                 "{\"descr\": \"<i4\", \"fortran_order\": False, \"shape\": (3,)}", Bytes(values));
    auto read = ReadNpy<std::int32_t>(file);
    ASSERT_TRUE(read.ok()) << read.error();
    EXPECT_EQ(read->data, values);
    auto header = ReadNpyHeader(file);
    ASSERT_TRUE(header.ok());
    EXPECT_EQ(header->major_version, major);
  }
}

TEST_F(NpyTest, ReordersFortranOrderDataIntoCOrder) {
  // A 2x3 matrix a[i][j] = 10 i + j, stored column by column (Fortran order).
  const std::vector<double> fortran = {0, 10, 1, 11, 2, 12};
  const auto file = WriteRaw(
      "f.npy", 1, "{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }", Bytes(fortran));
  auto read = ReadNpy<double>(file);
  ASSERT_TRUE(read.ok()) << read.error();
  EXPECT_EQ(read->data, (std::vector<double>{0, 1, 2, 10, 11, 12}));
}

TEST_F(NpyTest, RejectsBadMagicNamingTheFile) {
  const auto file =
      WriteRaw("bad.npy", 1, "{'descr': '<f8', 'fortran_order': False, 'shape': (1,), }",
               Bytes(std::vector<double>{1.0}), "\x93NUMPZ");
  auto read = ReadNpy<double>(file);
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(Contains(read.error(), file.string()));
  EXPECT_TRUE(Contains(read.error(), "bad magic"));
}

TEST_F(NpyTest, RejectsUnsupportedDtypeSayingWhichWasExpected) {
  const auto file =
      WriteRaw("f8.npy", 1, "{'descr': '<f8', 'fortran_order': False, 'shape': (1,), }",
               Bytes(std::vector<double>{1.0}));
  auto read = ReadNpy<std::complex<double>>(file);
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(Contains(read.error(), file.string()));
  EXPECT_TRUE(Contains(read.error(), "unsupported dtype '<f8' (expected complex128"));
}

TEST_F(NpyTest, RejectsBigEndianData) {
  const auto file =
      WriteRaw("be.npy", 1, "{'descr': '>f8', 'fortran_order': False, 'shape': (1,), }",
               Bytes(std::vector<double>{1.0}));
  auto read = ReadNpy<double>(file);
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(Contains(read.error(), "unsupported dtype '>f8' (expected float64"));
}

TEST_F(NpyTest, RejectsTruncatedDataStatingExpectedAndActualBytes) {
  const auto file =
      WriteRaw("short.npy", 1, "{'descr': '<c16', 'fortran_order': False, 'shape': (2, 3), }",
               std::string(90, '\0'));
  auto read = ReadNpy<std::complex<double>>(file);
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(Contains(read.error(), file.string()));
  EXPECT_TRUE(Contains(read.error(), "truncated data: expected 96 bytes"));
  EXPECT_TRUE(Contains(read.error(), "got 90"));
}

TEST_F(NpyTest, RejectsTrailingBytesAfterTheData) {
  const auto file =
      WriteRaw("long.npy", 1, "{'descr': '<f8', 'fortran_order': False, 'shape': (1,), }",
               std::string(9, '\0'));
  auto read = ReadNpy<double>(file);
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(Contains(read.error(), "1 trailing bytes"));
}

TEST_F(NpyTest, RejectsUnknownVersionAndMalformedHeaderDicts) {
  const std::string data = Bytes(std::vector<double>{1.0});
  auto v4 = ReadNpy<double>(
      WriteRaw("v4.npy", 4, "{'descr': '<f8', 'fortran_order': False, 'shape': (1,), }", data));
  ASSERT_FALSE(v4.ok());
  EXPECT_TRUE(Contains(v4.error(), "unsupported .npy version 4.0"));

  auto no_shape =
      ReadNpy<double>(WriteRaw("ns.npy", 1, "{'descr': '<f8', 'fortran_order': False, }", data));
  ASSERT_FALSE(no_shape.ok());
  EXPECT_TRUE(Contains(no_shape.error(), "lacks 'shape'"));

  auto bad_order = ReadNpy<double>(
      WriteRaw("bo.npy", 1, "{'descr': '<f8', 'fortran_order': maybe, 'shape': (1,), }", data));
  ASSERT_FALSE(bad_order.ok());
  EXPECT_TRUE(Contains(bad_order.error(), "'fortran_order' must be True or False"));

  auto bad_shape = ReadNpy<double>(
      WriteRaw("bs.npy", 1, "{'descr': '<f8', 'fortran_order': False, 'shape': (-1,), }", data));
  ASSERT_FALSE(bad_shape.ok());
  EXPECT_TRUE(Contains(bad_shape.error(), "'shape' must be a tuple of integers"));
}

TEST_F(NpyTest, RejectsEveryTruncationOfAValidFile) {
  const std::vector<std::complex<double>> values = {{1, 2}, {3, 4}, {5, 6}};
  ASSERT_TRUE(WriteNpy<std::complex<double>>(dir_ / "full.npy", values, {3}).ok());
  const std::string bytes = ReadFileBytes(dir_ / "full.npy");
  for (std::size_t cut = 0; cut < bytes.size(); ++cut) {
    WriteFileBytes(dir_ / "cut.npy", bytes.substr(0, cut));
    auto read = ReadNpy<std::complex<double>>(dir_ / "cut.npy");
    ASSERT_FALSE(read.ok()) << "cut at " << cut;
    EXPECT_TRUE(Contains(read.error(), "cut.npy: ")) << read.error();
  }
}

TEST_F(NpyTest, RejectsMissingFile) {
  auto read = ReadNpy<double>(dir_ / "absent.npy");
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(Contains(read.error(), "absent.npy"));
  EXPECT_TRUE(Contains(read.error(), "cannot open"));
}

TEST_F(NpyTest, RefusesToWriteDataThatDoesNotFillTheShape) {
  const std::vector<double> values = {1, 2, 3};
  const Status status = WriteNpy<double>(dir_ / "x.npy", values, {2, 2});
  ASSERT_FALSE(status.ok());
  EXPECT_TRUE(Contains(status.error(), "holds 4 elements but 3 were given"));
}

}  // namespace
}  // namespace gearpath
