// Cell-linked neighbour grid against a brute-force N² search, with and without periodic axes,
// in 2D and 3D, float and double.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "server/core/cell_sort.h"

namespace cascade {
namespace {

template <typename Real, int Dim>
void compare_with_brute_force(const std::array<bool, 3>& periodic, std::uint32_t seed) {
  const double h = 0.013;
  std::array<double, 3> lo{-0.1, 0.05, 0.0}, hi{0.2, 0.17, 0.11};
  std::mt19937 rng(seed);
  const int n = 1500;
  std::vector<Vec<Real, Dim>> host(n);
  for (auto& x : host)
    for (int a = 0; a < Dim; ++a) x[a] = Real(std::uniform_real_distribution<double>(lo[a], hi[a])(rng));
  // A few particles outside the domain along a non-periodic axis must drop out.
  host[7][0] = Real(hi[0] + 0.05);
  host[11][Dim - 1] = Real(lo[Dim - 1] - 0.01);

  using Backend = OmpBackend;
  typename Backend::template Vector<Vec<Real, Dim>> position(host.begin(), host.end()), scratch;
  CellSort<Real, Dim, Backend> cells(lo, hi, periodic, h);
  cells.sort(position);
  cells.reorder(position, scratch);
  const auto grid = cells.view();
  std::vector<Vec<Real, Dim>> sorted(position.begin(), position.end());

  const bool x_periodic = periodic[0];
  const std::size_t expected_active = n - (x_periodic ? 0 : 1) - (periodic[Dim - 1] ? 0 : 1);
  ASSERT_EQ(cells.active(), expected_active);

  const Real support2 = Real(4 * h * h);
  for (std::size_t i = 0; i < cells.active(); ++i) {
    std::set<std::uint32_t> found;
    grid.for_each_neighbour(sorted[i], sorted.data(), [&](std::uint32_t j, const Vec<Real, Dim>& d, Real r2) {
      EXPECT_TRUE(found.insert(j).second) << "neighbour visited twice";
      EXPECT_NEAR(double(d.squaredNorm()), double(r2), 1e-12);
    });
    std::set<std::uint32_t> expected;
    for (std::uint32_t j = 0; j < cells.active(); ++j) {
      Vec<Real, Dim> d = sorted[i] - sorted[j];
      for (int a = 0; a < Dim; ++a)
        if (periodic[a]) {
          const Real length = Real(hi[a] - lo[a]);
          d[a] -= length * std::rint(d[a] / length);
        }
      if (d.squaredNorm() < support2) expected.insert(j);
    }
    ASSERT_EQ(found, expected) << "particle " << i;
  }
}

TEST(NeighbourGrid, MatchesBruteForce2D) { compare_with_brute_force<double, 2>({false, false, false}, 1); }
TEST(NeighbourGrid, MatchesBruteForce3D) { compare_with_brute_force<double, 3>({false, false, false}, 2); }
TEST(NeighbourGrid, MatchesBruteForcePeriodicX2D) { compare_with_brute_force<double, 2>({true, false, false}, 3); }
TEST(NeighbourGrid, MatchesBruteForcePeriodicAll2D) { compare_with_brute_force<double, 2>({true, true, false}, 4); }
TEST(NeighbourGrid, MatchesBruteForcePeriodicXY3D) { compare_with_brute_force<double, 3>({true, true, false}, 5); }
TEST(NeighbourGrid, MatchesBruteForcePeriodicAll3D) { compare_with_brute_force<double, 3>({true, true, true}, 6); }
TEST(NeighbourGrid, MatchesBruteForceFloat3D) { compare_with_brute_force<float, 3>({false, true, false}, 7); }

TEST(NeighbourGrid, SortIsByCellAndStable) {
  using Backend = OmpBackend;
  std::array<double, 3> lo{0, 0, 0}, hi{1, 1, 0};
  std::vector<Vec<double, 2>> host = {{0.9, 0.9}, {0.1, 0.1}, {0.12, 0.1}, {0.11, 0.1}, {0.9, 0.1}};
  typename Backend::template Vector<Vec<double, 2>> position(host.begin(), host.end()), scratch;
  CellSort<double, 2, Backend> cells(lo, hi, {false, false, false}, 0.1);
  cells.sort(position);
  cells.reorder(position, scratch);
  // The three particles of cell (0, 0) keep their original relative order.
  EXPECT_EQ(raw(position)[0], host[1]);
  EXPECT_EQ(raw(position)[1], host[2]);
  EXPECT_EQ(raw(position)[2], host[3]);
  EXPECT_EQ(raw(position)[3], host[4]);
  EXPECT_EQ(raw(position)[4], host[0]);
}

TEST(NeighbourGrid, RejectsPeriodicAxisShorterThanThreeSupports) {
  EXPECT_THROW((CellSort<double, 2, OmpBackend>({0, 0, 0}, {0.05, 1, 0}, {true, false, false}, 0.01)),
               std::invalid_argument);
}

}  // namespace
}  // namespace cascade
