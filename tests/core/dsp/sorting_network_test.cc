#include "core/dsp/sorting_network.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <random>
#include <vector>

namespace gearpath {
namespace {

// Every column of a rows x width table (values drawn from a few levels, so that ties are
// common, plus infinities) against std::sort of that column.
void ExpectColumnsSorted(std::size_t rows, std::size_t width, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> level(-4, 4);
  std::normal_distribution<double> value(0, 1);
  std::vector<double> table(rows * width);
  for (double& x : table) x = rng() % 3 == 0 ? static_cast<double>(level(rng)) : value(rng);
  if (table.size() > 2) {
    table[1] = std::numeric_limits<double>::infinity();
    table[table.size() - 1] = -std::numeric_limits<double>::infinity();
  }
  const std::vector<double> original = table;
  SortColumns(table.data(), rows, width);
  for (std::size_t c = 0; c < width; ++c) {
    std::vector<double> column(rows);
    for (std::size_t r = 0; r < rows; ++r) column[r] = original[r * width + c];
    std::sort(column.begin(), column.end());
    for (std::size_t r = 0; r < rows; ++r) {
      ASSERT_EQ(table[r * width + c], column[r])
          << "row " << r << " of " << rows << ", column " << c << " of " << width;
    }
  }
}

TEST(SortColumns, SortsEveryColumnForAnyNumberOfRows) {
  for (std::size_t rows = 0; rows <= 70; ++rows) {
    SCOPED_TRACE(rows);
    // Widths below, at and past the vector lanes, with a tail.
    for (const std::size_t width : {1u, 3u, 8u, 37u}) {
      ExpectColumnsSorted(rows, width, static_cast<unsigned>(rows * 100 + width));
    }
  }
}

TEST(SortColumns, SortsTheLargeTablesTheGateAndTheRevolutionMedianSort) {
  ExpectColumnsSorted(32, 250, 1);  // the gate's 32-bin neighbourhoods
  ExpectColumnsSorted(50, 512, 2);  // 50 revolutions of 512 points
  ExpectColumnsSorted(127, 64, 3);
}

}  // namespace
}  // namespace gearpath
