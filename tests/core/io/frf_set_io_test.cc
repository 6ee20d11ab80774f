#include "core/io/frf_set_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/io/npy.h"
#include "tests/core/io/io_test_util.h"

namespace gearpath {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// Values with full 53-bit mantissas, so that any rounding on the way would show.
Eigen::MatrixXcd Block(Eigen::Index rows, Eigen::Index cols, double seed) {
  Eigen::MatrixXcd m(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i) {
    for (Eigen::Index j = 0; j < cols; ++j) {
      const double x = seed + 0.1 * static_cast<double>(i) + 0.01 * static_cast<double>(j);
      m(i, j) = {std::sin(x) / 3.0, -std::cos(x) * 1e-7};
    }
  }
  return m;
}

std::vector<Eigen::MatrixXcd> Blocks(const Eigen::VectorXd& f, Eigen::Index rows, Eigen::Index cols,
                                     double seed) {
  std::vector<Eigen::MatrixXcd> blocks;
  for (Eigen::Index k = 0; k < f.size(); ++k) blocks.push_back(Block(rows, cols, seed + f[k]));
  return blocks;
}

Eigen::VectorXd Frequencies() {
  Eigen::VectorXd f(4);
  f << 10.0, 20.5, 31.0, 1.0 / 0.0213;
  return f;
}

FrfSet MakeSet(bool decoupled, bool coupled) {
  FrfSet set;
  set.description = "test housing, 4 bins";
  set.paths = {{"B1x", "input shaft, drive end", "x", {"G1"}},
               {"B1y", "input shaft, drive end", "y", {"G1"}},
               {"B3z", "intermediate shaft", "z", {"G2", "G3"}}};
  set.channels = {{"A1", "x"}, {"A2", "z"}};
  const Eigen::VectorXd f = Frequencies();
  if (decoupled) {
    set.decoupling = "eq24";
    set.decoupled.frequency_hz = f;
    set.decoupled.at = Blocks(f, 2, 3, 0.3);
  }
  if (coupled) {
    CoupledSet c;
    c.active = {{"a1x", "11", "x"}, {"a1y", "11", "y"}};
    c.passive = {{"p1x", "21", "x"}, {"p1y", "21", "y"}, {"p2z", "22", "z"}};
    c.measurement = {{"m1x", "A1", "x"}};
    c.blocks.frequency_hz = f;
    c.blocks.aa = Blocks(f, 2, 2, 1.0);
    c.blocks.pa = Blocks(f, 3, 2, 2.0);
    c.blocks.pp = Blocks(f, 3, 3, 3.0);
    c.blocks.ap = Blocks(f, 2, 3, 4.0);
    c.blocks.ma = Blocks(f, 1, 2, 5.0);
    c.blocks.mp = Blocks(f, 1, 3, 6.0);
    set.coupled = std::move(c);
  }
  return set;
}

bool SameBits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         SameBytes(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double));
}

void ExpectSameBlocks(const std::vector<Eigen::MatrixXcd>& a,
                      const std::vector<Eigen::MatrixXcd>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].rows(), b[k].rows()) << what;
    ASSERT_EQ(a[k].cols(), b[k].cols()) << what;
    EXPECT_TRUE(SameBytes(a[k].data(), b[k].data(),
                          static_cast<std::size_t>(a[k].size()) * sizeof(Complex)))
        << what << " differs at bin " << k;
  }
}

void ExpectSameDofs(const std::vector<CoupledDof>& a, const std::vector<CoupledDof>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].name, b[i].name);
    EXPECT_EQ(a[i].node, b[i].node);
    EXPECT_EQ(a[i].direction, b[i].direction);
  }
}

void ExpectSameSet(const FrfSet& a, const FrfSet& b) {
  EXPECT_EQ(a.format_version, b.format_version);
  EXPECT_EQ(a.description, b.description);
  EXPECT_EQ(a.quantity, b.quantity);
  EXPECT_EQ(a.unit, b.unit);
  EXPECT_EQ(a.decoupling, b.decoupling);
  ASSERT_EQ(a.paths.size(), b.paths.size());
  for (std::size_t i = 0; i < a.paths.size(); ++i) {
    EXPECT_EQ(a.paths[i].name, b.paths[i].name);
    EXPECT_EQ(a.paths[i].bearing, b.paths[i].bearing);
    EXPECT_EQ(a.paths[i].direction, b.paths[i].direction);
    EXPECT_EQ(a.paths[i].gears, b.paths[i].gears);
  }
  ASSERT_EQ(a.channels.size(), b.channels.size());
  for (std::size_t i = 0; i < a.channels.size(); ++i) {
    EXPECT_EQ(a.channels[i].sensor, b.channels[i].sensor);
    EXPECT_EQ(a.channels[i].axis, b.channels[i].axis);
  }
  EXPECT_TRUE(SameBits(a.decoupled.frequency_hz, b.decoupled.frequency_hz));
  ExpectSameBlocks(a.decoupled.at, b.decoupled.at, "decoupled");
  ASSERT_EQ(a.coupled.has_value(), b.coupled.has_value());
  if (a.coupled) {
    ExpectSameDofs(a.coupled->active, b.coupled->active);
    ExpectSameDofs(a.coupled->passive, b.coupled->passive);
    ExpectSameDofs(a.coupled->measurement, b.coupled->measurement);
    const auto& x = a.coupled->blocks;
    const auto& y = b.coupled->blocks;
    EXPECT_TRUE(SameBits(x.frequency_hz, y.frequency_hz));
    ExpectSameBlocks(x.aa, y.aa, "aa");
    ExpectSameBlocks(x.pa, y.pa, "pa");
    ExpectSameBlocks(x.pp, y.pp, "pp");
    ExpectSameBlocks(x.ap, y.ap, "ap");
    ExpectSameBlocks(x.ma, y.ma, "ma");
    ExpectSameBlocks(x.mp, y.mp, "mp");
  }
}

class FrfSetIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gearpath_frfset_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path manifest() const { return dir_ / "manifest.json"; }

  void WriteValid(bool decoupled = true, bool coupled = true) {
    const Status st = WriteFrfSet(MakeSet(decoupled, coupled), dir_);
    ASSERT_TRUE(st.ok()) << st.error();
  }

  void EditManifest(const std::function<void(Json&)>& edit) {
    Json j;
    {
      std::ifstream in(manifest());
      j = Json::parse(in);
    }
    edit(j);
    std::ofstream(manifest()) << j.dump(2);
  }

  // Reads the set, expecting failure; returns the message.
  std::string ReadError() {
    auto set = ReadFrfSet(dir_);
    EXPECT_FALSE(set.ok()) << "the set was accepted";
    return set.ok() ? std::string() : set.error();
  }

  fs::path dir_;
};

TEST_F(FrfSetIoTest, RoundTripsDecoupledOnlySetBitForBit) {
  const FrfSet set = MakeSet(true, false);
  ASSERT_TRUE(WriteFrfSet(set, dir_).ok());
  auto read = ReadFrfSet(dir_);
  ASSERT_TRUE(read.ok()) << read.error();
  ExpectSameSet(set, *read);
  EXPECT_FALSE(fs::exists(dir_ / "H_aa.npy"));
}

TEST_F(FrfSetIoTest, RoundTripsCoupledOnlySetBitForBit) {
  FrfSet set = MakeSet(false, true);
  set.quantity = FrfQuantity::kReceptance;
  set.unit = "m/N";
  ASSERT_TRUE(WriteFrfSet(set, dir_).ok());
  auto read = ReadFrfSet(dir_);
  ASSERT_TRUE(read.ok()) << read.error();
  ExpectSameSet(set, *read);
  EXPECT_FALSE(fs::exists(dir_ / "H_decoupled.npy"));
}

TEST_F(FrfSetIoTest, RoundTripsSetWithBothPartsBitForBit) {
  const FrfSet set = MakeSet(true, true);
  ASSERT_TRUE(WriteFrfSet(set, dir_).ok());
  auto read = ReadFrfSet(dir_);
  ASSERT_TRUE(read.ok()) << read.error();
  ExpectSameSet(set, *read);
}

TEST_F(FrfSetIoTest, RoundTripsCoupledSetWithoutApAndWithoutMeasurementPoints) {
  FrfSet set = MakeSet(false, true);
  set.coupled->blocks.ap.clear();
  set.coupled->blocks.ma.clear();
  set.coupled->blocks.mp.clear();
  set.coupled->measurement.clear();
  ASSERT_TRUE(WriteFrfSet(set, dir_).ok());
  auto read = ReadFrfSet(dir_);
  ASSERT_TRUE(read.ok()) << read.error();
  ExpectSameSet(set, *read);
  EXPECT_FALSE(read->coupled->blocks.has_ap());
  EXPECT_FALSE(read->coupled->blocks.has_measurement_points());
}

TEST_F(FrfSetIoTest, WritesArraysThatMatchTheDocumentedLayout) {
  const FrfSet set = MakeSet(true, false);
  ASSERT_TRUE(WriteFrfSet(set, dir_).ok());
  // Element [k, i, j] of H_decoupled.npy is H(channel i, path j) at frequency k (C order).
  auto h = ReadNpy<std::complex<double>>(dir_ / "H_decoupled.npy");
  ASSERT_TRUE(h.ok()) << h.error();
  EXPECT_EQ(h->shape, (std::vector<std::size_t>{4, 2, 3}));
  EXPECT_EQ(h->data[2 * 6 + 1 * 3 + 2], set.decoupled.at[2](1, 2));
  Json j;
  std::ifstream(manifest()) >> j;
  EXPECT_EQ(j["format"], "gearpath-frf-set");
  EXPECT_EQ(j["format_version"], 1);
  EXPECT_EQ(j["paths"][2]["gears"][1], "G3");
}

TEST_F(FrfSetIoTest, RejectsDirectoryWithoutManifest) {
  fs::create_directories(dir_);
  const std::string e = ReadError();
  EXPECT_TRUE(Contains(e, manifest().string()));
  EXPECT_TRUE(Contains(e, "missing manifest"));
}

TEST_F(FrfSetIoTest, RejectsInvalidJson) {
  WriteValid();
  std::ofstream(manifest()) << "{\"format\": ";
  EXPECT_TRUE(Contains(ReadError(), "manifest.json: not valid JSON"));
}

TEST_F(FrfSetIoTest, RejectsANumberThatOverflowsADoubleNamingTheLine) {
  WriteValid();
  std::string text = ReadFileBytes(manifest());
  const auto at = text.find("\"format_version\": 1");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 19, "\"format_version\": 1e999");
  WriteFileBytes(manifest(), text);
  const std::string e = ReadError();
  EXPECT_TRUE(Contains(e, manifest().string() + ": not valid JSON: line 3, column"));
  EXPECT_TRUE(Contains(e, "number overflow parsing '1e999' (too large for a double)"));
}

TEST_F(FrfSetIoTest, RejectsAHundredThousandNestedLevelsWithoutOverflowingTheStack) {
  WriteValid();
  WriteFileBytes(manifest(), "{\"format\": \"gearpath-frf-set\", \"description\": " +
                                 std::string(100'000, '[') + std::string(100'000, ']') + "}");
  const std::string e = ReadError();
  EXPECT_TRUE(Contains(e, manifest().string() + ": not valid JSON: line 1, column 110: nested "
                                                "deeper than 64 levels"));
}

TEST_F(FrfSetIoTest, RefusesToWriteANameThatIsNotUtf8) {
  FrfSet set = MakeSet(true, false);
  set.description = "bad \xFF byte";
  const Status st = WriteFrfSet(set, dir_);
  ASSERT_FALSE(st.ok());
  EXPECT_TRUE(Contains(st.error(), "invalid UTF-8 byte at index 4: 0xFF"));
  EXPECT_FALSE(fs::exists(manifest()));  // no manifest, so no half set that loads
}

TEST_F(FrfSetIoTest, RejectsMissingArrayFileNamingItAndTheKey) {
  WriteValid();
  fs::remove(dir_ / "H_pp.npy");
  const std::string e = ReadError();
  EXPECT_TRUE(Contains(e, (dir_ / "H_pp.npy").string() + ": missing array file"));
  EXPECT_TRUE(Contains(e, "coupled.blocks.pp"));
}

TEST_F(FrfSetIoTest, RejectsWrongDtype) {
  WriteValid();
  const std::vector<float> f = {10, 20, 30, 40};
  ASSERT_TRUE(WriteNpy<float>(dir_ / "frequency_hz.npy", f, {4}).ok());
  const std::string e = ReadError();
  EXPECT_TRUE(Contains(e, "frequency_hz.npy: unsupported dtype '<f4' (expected float64"));
}

TEST_F(FrfSetIoTest, RejectsWrongShapeSayingExpectedAndGot) {
  WriteValid();
  const std::vector<std::complex<double>> h(4 * 3 * 2);
  ASSERT_TRUE(WriteNpy<std::complex<double>>(dir_ / "H_decoupled.npy", h, {4, 3, 2}).ok());
  const std::string e = ReadError();
  EXPECT_TRUE(Contains(e,
                       "H_decoupled.npy: shape (4, 3, 2) does not match the manifest: "
                       "expected (4, 2, 3) (n_freq, n_channels, n_paths)"));
}

TEST_F(FrfSetIoTest, RejectsPathCountThatDisagreesWithArrayColumns) {
  WriteValid();
  EditManifest([](Json& j) { j["paths"].erase(2); });
  const std::string e = ReadError();
  EXPECT_TRUE(Contains(e, "H_decoupled.npy: shape (4, 2, 3)"));
  EXPECT_TRUE(Contains(e, "expected (4, 2, 2)"));
}

TEST_F(FrfSetIoTest, RejectsNonFiniteValueNamingArrayIndexAndFrequency) {
  FrfSet set = MakeSet(true, true);
  WriteValid();
  // Overwrite H_pa with a NaN at bin 2, row 1, column 0.
  std::vector<std::complex<double>> pa;
  for (const auto& m : set.coupled->blocks.pa) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      for (Eigen::Index j = 0; j < m.cols(); ++j) pa.push_back(m(i, j));
    }
  }
  pa[2 * 6 + 1 * 2 + 0] = {1.0, std::numeric_limits<double>::quiet_NaN()};
  ASSERT_TRUE(WriteNpy<std::complex<double>>(dir_ / "H_pa.npy", pa, {4, 3, 2}).ok());
  const std::string e = ReadError();
  EXPECT_TRUE(Contains(e, "H_pa.npy: non-finite value at index [2, 1, 0] (frequency 31 Hz)"));
}

TEST_F(FrfSetIoTest, RejectsNonIncreasingFrequencyAxisNamingTheIndex) {
  WriteValid();
  const std::vector<double> f = {10, 20.5, 20.5, 40};
  ASSERT_TRUE(WriteNpy<double>(dir_ / "frequency_hz.npy", f, {4}).ok());
  const std::string e = ReadError();
  EXPECT_TRUE(
      Contains(e, "frequency_hz.npy: not strictly increasing at index 2 (20.5 Hz after 20.5 Hz)"));
}

TEST_F(FrfSetIoTest, RejectsNonFiniteFrequency) {
  WriteValid();
  const std::vector<double> f = {10, 20.5, std::numeric_limits<double>::infinity(), 40};
  ASSERT_TRUE(WriteNpy<double>(dir_ / "frequency_hz.npy", f, {4}).ok());
  EXPECT_TRUE(Contains(ReadError(), "frequency_hz.npy: non-finite value inf at index 2"));
}

TEST_F(FrfSetIoTest, RejectsUnknownFormat) {
  WriteValid();
  EditManifest([](Json& j) { j["format"] = "other-format"; });
  EXPECT_TRUE(Contains(
      ReadError(), "manifest.json: format: expected \"gearpath-frf-set\", got \"other-format\""));
}

TEST_F(FrfSetIoTest, RejectsUnknownFormatVersion) {
  WriteValid();
  EditManifest([](Json& j) { j["format_version"] = 2; });
  EXPECT_TRUE(Contains(ReadError(), "manifest.json: format_version 2 is not supported"));
}

TEST_F(FrfSetIoTest, RejectsMissingKeyNamingItsPath) {
  WriteValid();
  EditManifest([](Json& j) { j["paths"][2].erase("direction"); });
  EXPECT_TRUE(Contains(ReadError(), "manifest.json: missing key \"paths[2].direction\""));
}

TEST_F(FrfSetIoTest, RejectsMistypedKeysNamingPathAndTypes) {
  WriteValid();
  EditManifest([](Json& j) { j["paths"][1]["gears"] = "G1"; });
  EXPECT_TRUE(Contains(ReadError(), "key \"paths[1].gears\" must be an array, got string"));
  WriteValid();
  EditManifest([](Json& j) { j["format_version"] = "1"; });
  EXPECT_TRUE(Contains(ReadError(), "key \"format_version\" must be an integer, got string"));
  WriteValid();
  EditManifest([](Json& j) { j["coupled"]["dofs"]["p"][1]["node"] = 21; });
  EXPECT_TRUE(Contains(ReadError(), "key \"coupled.dofs.p[1].node\" must be a string, got number"));
}

TEST_F(FrfSetIoTest, RejectsUnknownQuantity) {
  WriteValid();
  EditManifest([](Json& j) { j["quantity"] = "inertance"; });
  EXPECT_TRUE(Contains(ReadError(), "manifest.json: quantity: unknown value \"inertance\""));
}

TEST_F(FrfSetIoTest, RejectsUnitThatDoesNotMatchTheQuantity) {
  WriteValid();
  EditManifest([](Json& j) { j["unit"] = "mm/s^2/N"; });
  EXPECT_TRUE(Contains(ReadError(),
                       "unit \"mm/s^2/N\" does not match quantity \"accelerance\" "
                       "(expected \"m/s^2/N\")"));
}

TEST_F(FrfSetIoTest, RejectsSetWithNeitherDecoupledNorCoupled) {
  WriteValid();
  EditManifest([](Json& j) {
    j.erase("decoupled");
    j.erase("coupled");
  });
  EXPECT_TRUE(Contains(ReadError(), "neither \"decoupled\" nor \"coupled\" is present"));
}

TEST_F(FrfSetIoTest, RejectsBadDirectionAndDuplicatePathNames) {
  WriteValid();
  EditManifest([](Json& j) { j["paths"][0]["direction"] = "w"; });
  EXPECT_TRUE(Contains(ReadError(), "paths[0].direction must be \"x\", \"y\" or \"z\", got \"w\""));
  WriteValid();
  EditManifest([](Json& j) { j["paths"][2]["name"] = "B1x"; });
  EXPECT_TRUE(Contains(ReadError(), "paths[2].name \"B1x\" is used by another path"));
}

TEST_F(FrfSetIoTest, RejectsUnknownDecouplingLabel) {
  WriteValid();
  EditManifest([](Json& j) { j["decoupling"] = "eq23"; });
  EXPECT_TRUE(Contains(ReadError(),
                       "decoupling must be \"eq22\", \"eq24\", \"physical\" or "
                       "\"model\", got \"eq23\""));
}

TEST_F(FrfSetIoTest, RejectsArrayFileNamesThatLeaveTheSetDirectory) {
  WriteValid();
  EditManifest([](Json& j) { j["decoupled"]["file"] = "../H.npy"; });
  EXPECT_TRUE(
      Contains(ReadError(), "key \"decoupled.file\" must name a file inside the set directory"));
}

TEST_F(FrfSetIoTest, RejectsMeasurementBlocksGivenWithoutTheirPair) {
  WriteValid();
  EditManifest([](Json& j) { j["coupled"]["blocks"].erase("mp"); });
  EXPECT_TRUE(
      Contains(ReadError(), "coupled.blocks.ma and coupled.blocks.mp must be given together"));
}

TEST_F(FrfSetIoTest, WriterRefusesSetTheReaderWouldReject) {
  FrfSet set = MakeSet(true, false);
  set.decoupled.at[3](0, 1) = {std::numeric_limits<double>::infinity(), 0.0};
  Status st = WriteFrfSet(set, dir_);
  ASSERT_FALSE(st.ok());
  EXPECT_TRUE(Contains(st.error(), "decoupled: non-finite value at [3, 0, 1]"));
  EXPECT_FALSE(fs::exists(manifest()));

  FrfSet mismatched = MakeSet(true, true);
  mismatched.coupled->blocks.frequency_hz[1] += 1e-9;
  st = WriteFrfSet(mismatched, dir_);
  ASSERT_FALSE(st.ok());
  EXPECT_TRUE(Contains(st.error(), "share one frequency axis"));

  FrfSet wrong_shape = MakeSet(false, true);
  wrong_shape.coupled->blocks.pa[0] = Eigen::MatrixXcd::Zero(2, 2);
  st = WriteFrfSet(wrong_shape, dir_);
  ASSERT_FALSE(st.ok());
  EXPECT_TRUE(Contains(st.error(), "coupled.blocks.pa at bin 0 is 2 x 2, expected 3 x 2"));
}

// Reads the set that the Python snippet of docs/frf_format.md writes (ctest entry
// io_frf_set_written_by_python sets GEARPATH_PYTHON_FRF_SET); the snippet fills
// H[k, i, j] = (i + 1 + 1j * (j + 1)) * f[k] with f = linspace(10, 100, 4).
TEST(FrfSetFromPython, ReadsTheSetWrittenByTheDocumentedPythonSnippet) {
  const char* dir = std::getenv("GEARPATH_PYTHON_FRF_SET");
  if (dir == nullptr) GTEST_SKIP() << "run through ctest entry io_frf_set_written_by_python";
  auto set = ReadFrfSet(dir);
  ASSERT_TRUE(set.ok()) << set.error();
  ASSERT_EQ(set->decoupled.bins(), 4);
  ASSERT_EQ(set->channels.size(), 2u);
  ASSERT_EQ(set->paths.size(), 3u);
  for (Eigen::Index k = 0; k < 4; ++k) {
    const double f = 10.0 + 30.0 * static_cast<double>(k);
    EXPECT_DOUBLE_EQ(set->decoupled.frequency_hz[k], f);
    for (Eigen::Index i = 0; i < 2; ++i) {
      for (Eigen::Index j = 0; j < 3; ++j) {
        const Complex expected =
            Complex(static_cast<double>(i + 1), static_cast<double>(j + 1)) * f;
        EXPECT_EQ(set->decoupled.at[static_cast<std::size_t>(k)](i, j), expected);
      }
    }
  }
  EXPECT_EQ(set->paths[2].gears, (std::vector<std::string>{"G2", "G3"}));
  EXPECT_EQ(set->decoupling, "eq24");
}

// Writes MakeSet(true, true) for the Python reader of docs/frf_format.md (same ctest entry, which
// sets GEARPATH_FRF_SET_FOR_PYTHON and checks H_pa[2, 1, 0] = sin(x) / 3 - 1e-7 j cos(x) with
// x = 2 + f[2] + 0.1 there).
TEST(FrfSetForPython, WritesASetForTheDocumentedPythonReader) {
  const char* dir = std::getenv("GEARPATH_FRF_SET_FOR_PYTHON");
  if (dir == nullptr) GTEST_SKIP() << "run through ctest entry io_frf_set_written_by_python";
  const Status st = WriteFrfSet(MakeSet(true, true), dir);
  ASSERT_TRUE(st.ok()) << st.error();
}

}  // namespace
}  // namespace gearpath
