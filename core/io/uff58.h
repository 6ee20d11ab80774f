// Universal File Format dataset 58 ("Function at Nodal DOF"): reader and writer.
//
// UFF 58 is the interchange format in which modal test systems export measured functions
// (FRFs, time responses, spectra), one record per (response DOF, reference DOF) pair. Layout as
// documented by SDRC / UC-SDRL ("Universal Dataset Number 58") and as pyuff implements it:
//   "    -1" delimiter, "    58" (ASCII) or "    58b" + binary header fields (58b), then
//   records 1-5  five 80-column ID lines,
//   record 6     (2(I5,I10),2(1X,10A1,I10,I4)) function type, id, version, load case,
//                response entity/node/direction, reference entity/node/direction,
//   record 7     (3I10,3E13.5) ordinate data type (2 real single, 4 real double, 5 complex
//                single, 6 complex double), number of points, spacing (1 even, 0 uneven),
//                abscissa minimum, increment, z-axis value,
//   records 8-11 (I10,3I5,2(1X,20A1)) abscissa, ordinate numerator, ordinate denominator and
//                z-axis characteristics: specific data type, length/force/temperature unit
//                exponents, axis label, units label,
//   record 12    the data: ordinate values (re, im for complex), each preceded by its abscissa
//                value when the spacing is uneven. ASCII: 6E13.5 (single precision);
//                4E20.12 (double, even); 2(E13.5,E20.12) (real double, uneven);
//                E13.5,2E20.12 (complex double, uneven). 58b: the same value sequence as raw
//                IEEE 754 numbers of the ordinate precision, byte order from the header.
//   "    -1" delimiter.
// Directions: 0 scalar, 1/2/3 = +X/+Y/+Z, 4/5/6 = rotations, negative = opposite sense.
//
// Precision: the ASCII header prints abscissa minimum and increment as E13.5 (6 significant
// digits), and double-precision uneven abscissae likewise; that is the format, not a choice.
// ASCII readers here accept D exponents, fields that touch, and free-format data lines.
#pragma once

#include <array>
#include <complex>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/result.h"

namespace gearpath {

// Record 6 field 1 values used by name in gearpath (the record keeps any value).
inline constexpr int kUffGeneral = 0;
inline constexpr int kUffTimeResponse = 1;
inline constexpr int kUffAutoSpectrum = 2;
inline constexpr int kUffCrossSpectrum = 3;
inline constexpr int kUffFrequencyResponse = 4;
inline constexpr int kUffCoherence = 6;

// Human-readable name of a function type ("time response", "frequency response function"...).
std::string UffFunctionTypeName(int function_type);
// "+X", "-Z", "+RY", "scalar"...
std::string UffDirectionName(int direction);

// One axis description (records 8 to 11).
struct UffAxis {
  int specific_data_type = 0;  // 0 unknown, 1 general, ..., 8 displacement, 11 velocity,
                               // 12 acceleration, 13 excitation force, 17 time, 18 frequency
  int length_exponent = 0;
  int force_exponent = 0;
  int temperature_exponent = 0;
  std::string label = "NONE";
  std::string unit_label = "NONE";
};

struct Uff58Record {
  std::array<std::string, 5> id_lines = {"NONE", "NONE", "NONE", "NONE", "NONE"};
  // Record 6: DOF identification.
  int function_type = kUffFrequencyResponse;
  int function_id = 0;
  int version = 0;
  int load_case = 0;
  std::string response_entity = "NONE";
  int response_node = 0;
  int response_direction = 0;
  std::string reference_entity = "NONE";
  int reference_node = 0;
  int reference_direction = 0;
  // Record 7: data form.
  bool double_precision = true;
  bool complex_ordinate = true;
  bool even_abscissa = true;
  double abscissa_start = 0.0;      // even spacing only
  double abscissa_increment = 0.0;  // even spacing only
  std::vector<double> abscissa;     // uneven spacing only: one value per ordinate sample
  double z_axis_value = 0.0;
  // Records 8 to 11.
  UffAxis abscissa_axis, ordinate_axis, denominator_axis, z_axis;
  // Record 12: the samples (imaginary parts are zero for real data).
  std::vector<std::complex<double>> ordinate;

  // Record 7 field 1: 2, 4, 5 or 6.
  int ordinate_data_type() const;
  // The abscissa value of sample i, whatever the spacing.
  double AbscissaAt(std::size_t i) const;
};

enum class UffEncoding { kAscii, kBinary };

// Reads every dataset-58 record of a UFF file (ASCII 58 and binary 58b may be mixed); other
// dataset types are skipped. Errors name the file, the line and the record field at fault.
Result<std::vector<Uff58Record>> ReadUff58(const std::filesystem::path& file);

// Same, from the file contents in memory; `name` is used in messages.
Result<std::vector<Uff58Record>> ParseUff58(std::string_view contents, const std::string& name);

// Writes `records` as dataset 58 (ASCII) or 58b (binary, little-endian IEEE 754), in the
// precision each record asks for. Rejects records whose sizes disagree.
Status WriteUff58(const std::filesystem::path& file, std::span<const Uff58Record> records,
                  UffEncoding encoding);

}  // namespace gearpath
