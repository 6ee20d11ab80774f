#include "core/io/text_export.h"

#include <gtest/gtest.h>

#include "tests/core/io/io_test_util.h"

namespace gearpath {
namespace {

TEST(TextExport, ReadsDecimalCommaWithSemicolonsAndAUnitsRow) {
  const std::string text =
      "DH8303 export\n"
      "Sample rate: 2,56 kHz\n"
      "A1-X;A1-Y;A2-Z\n"
      "m/s^2;m/s^2;g\n"
      "0,0123;0,0456;-1,5\n"
      "1,25;-2,5e-3;2\n";
  Result<TextExport> r = ParseTextExport(text, "export.txt");
  ASSERT_TRUE(r.ok()) << r.error();
  const TextExport& e = *r;
  EXPECT_EQ(e.layout.separator, ';');
  EXPECT_TRUE(e.layout.decimal_comma);
  EXPECT_TRUE(e.layout.units_row);
  EXPECT_FALSE(e.layout.time_column);
  EXPECT_EQ(e.layout.first_data_line, 5u);
  EXPECT_DOUBLE_EQ(e.acquisition.sample_rate_hz, 2560.0);
  ASSERT_EQ(e.acquisition.channels.size(), 3u);
  EXPECT_EQ(e.acquisition.channels[0].sensor, "A1");
  EXPECT_EQ(e.acquisition.channels[1].axis, Axis::kY);
  EXPECT_EQ(e.acquisition.channels[2].sensor, "A2");
  EXPECT_EQ(e.acquisition.channels[2].axis, Axis::kZ);
  ASSERT_EQ(e.acquisition.samples_per_channel, 2u);
  EXPECT_EQ(e.acquisition.channel(0)[0], 0.0123f);
  EXPECT_EQ(e.acquisition.channel(0)[1], 1.25f);
  EXPECT_EQ(e.acquisition.channel(1)[0], 0.0456f);
  EXPECT_EQ(e.acquisition.channel(1)[1], -2.5e-3f);
  // g is converted to m/s^2 with standard gravity.
  EXPECT_EQ(e.acquisition.channels[2].unit, "m/s^2");
  EXPECT_EQ(e.acquisition.channel(2)[0], static_cast<float>(-1.5 * 9.80665));
}

TEST(TextExport, RejectsANonUtf8ChannelNameNamingLineAndColumn) {
  // "Gehäuse" saved as Latin-1: the channel name would break every JSON report and recording.
  const std::string text =
      "Sample rate: 2560 Hz\n"
      "A1-X;Geh\xE4use-Z\n"
      "0,1;0,2\n"
      "0,3;0,4\n";
  Result<TextExport> r = ParseTextExport(text, "export.txt");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error(),
            "export.txt: line 2, column 2: the channel name is not valid UTF-8 (invalid UTF-8 "
            "byte at index 4: 0x75); save the export as UTF-8, e.g. with iconv -f latin1 -t "
            "utf-8");
}

TEST(TextExport, RejectsANonUtf8UnitNamingLineAndColumn) {
  const std::string text =
      "Sample rate: 2560 Hz\n"
      "A1-X;A1-Y\n"
      "m/s^2;\xB5m/s^2\n"
      "0,1;0,2\n"
      "0,3;0,4\n";
  Result<TextExport> r = ParseTextExport(text, "export.txt");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(Contains(r.error(), "export.txt: line 3, column 2: the unit is not valid UTF-8"));
}

TEST(TextExport, AcceptsUtf8ChannelNames) {
  const std::string text =
      "Sample rate: 2560 Hz\n"
      "A1-X;Geh\xC3\xA4use-Z\n"
      "0,1;0,2\n"
      "0,3;0,4\n";
  Result<TextExport> r = ParseTextExport(text, "export.txt");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r->acquisition.channels[1].sensor, "Geh\xC3\xA4use");
}

TEST(TextExport, ReadsCommaSeparatedWithATimeColumnAndUnitsInTheNames) {
  const std::string text =
      "Time [s],A1-X [m/s^2],A3_z [m/s^2]\r\n"
      "0.000,1.0,-1.0\r\n"
      "0.001,2.0,-2.0\r\n"
      "0.002,3.0,-3.0\r\n";
  Result<TextExport> r = ParseTextExport(text, "export.csv");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r->layout.separator, ',');
  EXPECT_FALSE(r->layout.decimal_comma);
  EXPECT_TRUE(r->layout.time_column);
  EXPECT_EQ(r->layout.sample_rate_from, "time column");
  EXPECT_NEAR(r->acquisition.sample_rate_hz, 1000.0, 1e-9);
  ASSERT_EQ(r->acquisition.channels.size(), 2u);
  EXPECT_EQ(r->acquisition.channels[1].sensor, "A3");
  EXPECT_EQ(r->acquisition.channels[1].axis, Axis::kZ);
  EXPECT_EQ(r->acquisition.channels[1].unit, "m/s^2");
  EXPECT_EQ(r->acquisition.channel(1)[2], -3.0f);
}

TEST(TextExport, ReadsTabSeparatedWithDecimalCommaAndATimeColumnNamedT) {
  const std::string text =
      "Fs\t100 Hz\n"
      "t\tA1 X\tA1 Y\n"
      "s\tm/s²\tm/s²\n"
      "0,00\t0,5\t-0,25\n"
      "0,01\t0,75\t-0,125\n";
  Result<TextExport> r = ParseTextExport(text, "export.tsv");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r->layout.separator, '\t');
  EXPECT_TRUE(r->layout.decimal_comma);
  EXPECT_TRUE(r->layout.time_column);
  EXPECT_TRUE(r->layout.units_row);
  EXPECT_EQ(r->layout.sample_rate_from, "header and time column");
  EXPECT_DOUBLE_EQ(r->acquisition.sample_rate_hz, 100.0);
  ASSERT_EQ(r->acquisition.channels.size(), 2u);
  EXPECT_EQ(r->acquisition.channels[0].unit, "m/s^2");
  EXPECT_EQ(r->acquisition.channel(0)[1], 0.75f);
  EXPECT_EQ(r->acquisition.channel(1)[1], -0.125f);
}

TEST(TextExport, KeepsAFirstColumnThatIsNotNamedAsTimeAsAChannel) {
  const std::string text = "Sampling frequency = 50\nA1-X A2-X\n1 4\n2 5\n3 6\n";
  Result<TextExport> r = ParseTextExport(text, "spaces.txt");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r->layout.separator, ' ');
  EXPECT_FALSE(r->layout.time_column);
  EXPECT_EQ(r->acquisition.channels.size(), 2u);
  EXPECT_DOUBLE_EQ(r->acquisition.sample_rate_hz, 50.0);
}

TEST(TextExport, RejectsATimeColumnThatGoesBackwardsNamingTheLine) {
  const std::string text = "Time;A1-X\n0,0;1\n0,2;2\n0,1;3\n";
  Result<TextExport> r = ParseTextExport(text, "bad.txt");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(Contains(r.error(), "does not increase strictly at data row 3 (line 4)"));
}

TEST(TextExport, RejectsHeaderRateThatDisagreesWithTheTimeColumn) {
  const std::string text = "Sample rate: 200 Hz\nTime,A1-X\n0.0,1\n0.01,2\n";
  Result<TextExport> r = ParseTextExport(text, "bad.txt");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(Contains(r.error(), "disagrees with the time column"));
}

TEST(TextExport, RejectsAFileWithoutSampleRate) {
  Result<TextExport> r = ParseTextExport("A1-X;A2-X\n1;2\n", "norate.txt");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(Contains(r.error(), "norate.txt: no sample rate"));
}

TEST(TextExport, RejectsAFileWithoutNumericData) {
  Result<TextExport> r = ParseTextExport("just some words\n", "words.txt");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(Contains(r.error(), "no data rows were found"));
}

TEST(TextExport, RejectsDataWithoutNamesRow) {
  Result<TextExport> r = ParseTextExport("Sample rate: 10\n1;2\n3;4\n", "nonames.txt");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(Contains(r.error(), "no names row with 2 columns"));
}

TEST(TextExport, ReportsAMissingFile) {
  Result<TextExport> r = ReadTextExport("/nonexistent/gearpath/export.txt");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(Contains(r.error(), "/nonexistent/gearpath/export.txt: cannot open"));
}

TEST(TextExport, SplitsTheUsualChannelNameSpellings) {
  std::string sensor;
  Axis axis;
  ASSERT_TRUE(SplitChannelName("A12-Y", &sensor, &axis));
  EXPECT_EQ(sensor, "A12");
  EXPECT_EQ(axis, Axis::kY);
  ASSERT_TRUE(SplitChannelName("bearing1(Z)", &sensor, &axis));
  EXPECT_EQ(sensor, "bearing1");
  EXPECT_EQ(axis, Axis::kZ);
  ASSERT_TRUE(SplitChannelName("A3x", &sensor, &axis));
  EXPECT_EQ(sensor, "A3");
  EXPECT_FALSE(SplitChannelName("Gearbox", &sensor, &axis));
  EXPECT_EQ(sensor, "Gearbox");
}

}  // namespace
}  // namespace gearpath
