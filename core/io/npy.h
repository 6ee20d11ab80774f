// NumPy .npy reader and writer, for the arrays of the FRF set format (docs/frf_format.md).
//
// Implements the .npy format as NumPy documents it (numpy.lib.format): a 6-byte magic
// "\x93NUMPY", a version (1.0: 16-bit header length; 2.0 and 3.0: 32-bit), and a Python-literal
// header dict {'descr': ..., 'fortran_order': ..., 'shape': (...)} padded so that the data starts
// on a 64-byte boundary, then the raw little-endian elements. Debian packages no C++ .npy
// library (libcnpy is not in Debian 12), and the subset needed here is small, so it lives here.
//
// Assumes a little-endian host. Reads: dtypes '<c16', '<f8', '<f4', '<i2', '<i4' ('|' or '='
// byte-order marks accepted where unambiguous), C or Fortran order (Fortran data is reordered to
// C order on read), versions 1.0, 2.0, 3.0. Writes: C order, version 1.0 (2.0 if the header is
// too long for 1.0). Every error names the file and what is wrong.
#pragma once

#include <complex>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/common/result.h"

namespace gearpath {

enum class NpyDtype { kComplex128, kFloat64, kFloat32, kInt16, kInt32 };

// NumPy's name for the dtype ("complex128", "float64", ...), for messages.
const char* NpyDtypeName(NpyDtype dtype) noexcept;

// The parsed header of a .npy file.
struct NpyHeader {
  int major_version = 1;
  int minor_version = 0;
  std::string descr;  // as written, e.g. "<c16"
  bool fortran_order = false;
  std::vector<std::size_t> shape;  // empty for a 0-d array
  std::size_t data_offset = 0;     // bytes from the start of the file to the first element

  std::size_t element_count() const;
};

// An array read from a .npy file: elements in C (row-major) order.
template <typename T>
struct NpyArray {
  std::vector<std::size_t> shape;
  std::vector<T> data;
};

// Reads and validates only the header.
Result<NpyHeader> ReadNpyHeader(const std::filesystem::path& file);

// Reads a whole array whose dtype must match T exactly: std::complex<double> <-> '<c16',
// double <-> '<f8', float <-> '<f4', std::int16_t <-> '<i2', std::int32_t <-> '<i4'.
template <typename T>
Result<NpyArray<T>> ReadNpy(const std::filesystem::path& file);

// Writes `data` (C order, product(shape) elements) as a .npy file, replacing any existing file.
template <typename T>
Status WriteNpy(const std::filesystem::path& file, std::span<const T> data,
                const std::vector<std::size_t>& shape);

}  // namespace gearpath
