// SortColumns: sorts every column of a row-major table in place, with Batcher's merge exchange
// (Knuth, TAOCP 5.2.2, Algorithm M: a sorting network for any number of rows, O(R log^2 R)
// compare-exchanges). Each compare-exchange is a min and a max over two whole rows, which
// vectorise, so a table of many columns sorts at a few lanes' width per step; afterwards row k
// holds each column's k-th smallest value (a median is a row).
//
// Assumes no NaN (a compare-exchange with a NaN leaves the pair in an unspecified order).
// Allocation-free and noexcept.
#pragma once

#include <cstddef>

namespace gearpath {

void SortColumns(double* rows, std::size_t row_count, std::size_t width) noexcept;

}  // namespace gearpath
