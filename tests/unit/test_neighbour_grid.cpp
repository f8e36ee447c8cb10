// Cell-linked neighbour grid against a brute-force N² search, with and without periodic axes,
// in 2D and 3D, float and double.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "server/core/cell_sort.h"
#include "server/core/neighbour_list.h"

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

  std::vector<Phase> host_phase(n);
  for (auto& p : host_phase) p = std::uniform_int_distribution<int>(0, 2)(rng) == 2 ? Phase::boundary : Phase::water;

  using Backend = OmpBackend;
  typename Backend::template Vector<Vec<Real, Dim>> position(host.begin(), host.end()), scratch;
  typename Backend::template Vector<Phase> phase(host_phase.begin(), host_phase.end()), phase_scratch;
  CellSort<Real, Dim, Backend> cells(lo, hi, periodic, 2 * h);
  cells.sort(position, phase);
  cells.reorder(position, scratch);
  cells.reorder(phase, phase_scratch);
  const auto grid = cells.view();
  std::vector<Vec<Real, Dim>> sorted(position.begin(), position.end());
  std::vector<Phase> sorted_phase(phase.begin(), phase.end());

  const bool x_periodic = periodic[0];
  const std::size_t expected_active = n - (x_periodic ? 0 : 1) - (periodic[Dim - 1] ? 0 : 1);
  ASSERT_EQ(cells.active(), expected_active);

  const Real support2 = Real(4 * h * h);
  // h/dp = 0.5: a small slot count, so that the builder has to grow it.
  NeighbourList<Real, Dim, Backend> lists(0.5);
  lists.build(grid, position, cells.moving(), nullptr, 0);
  const auto list_view = lists.view();
  // Split over processes: process 0's lists, every third particle a copy of process 1's. The
  // copies get none; the particles it owns, the lists above, entry for entry.
  std::vector<std::uint32_t> host_owner(n);
  for (int k = 0; k < n; ++k) host_owner[std::size_t(k)] = k % 3 == 1 ? 1u : 0u;
  const typename Backend::template Vector<std::uint32_t> owner(host_owner.begin(), host_owner.end());
  NeighbourList<Real, Dim, Backend> own_lists(0.5);
  own_lists.build(grid, position, cells.moving(), raw(owner), 0);
  const auto own_view = own_lists.view();
  for (std::uint32_t i = 0; i < cells.moving(); ++i) {
    if (host_owner[i] != 0) {
      ASSERT_EQ(own_view.size(i), 0u) << "the copy " << i << " has a list";
      continue;
    }
    ASSERT_EQ(own_view.size(i), list_view.size(i)) << "particle " << i;
    for (std::uint32_t k = 0; k < own_view.size(i); ++k) ASSERT_EQ(own_view.entries(i)[k], list_view.entries(i)[k]);
  }
  for (std::size_t i = 0; i < cells.active(); ++i) {
    std::set<std::uint32_t> found, found_of, found_moving;
    grid.for_each_neighbour(sorted[i], sorted.data(), [&](std::uint32_t j, const Vec<Real, Dim>& d, Real r2) {
      EXPECT_TRUE(found.insert(j).second) << "neighbour visited twice";
      EXPECT_NEAR(double(d.squaredNorm()), double(r2), 1e-12);
    });
    grid.for_each_neighbour_of(std::uint32_t(i), sorted.data(),
                               [&](std::uint32_t j, const Vec<Real, Dim>&, Real) { found_of.insert(j); });
    grid.template for_each_neighbour_in<0, 2>(sorted[i], sorted.data(), [&](std::uint32_t j, const Vec<Real, Dim>&, Real) {
      EXPECT_TRUE(found_moving.insert(j).second) << "neighbour visited twice";
    });
    std::set<std::uint32_t> expected, expected_moving;
    for (std::uint32_t j = 0; j < cells.active(); ++j) {
      Vec<Real, Dim> d = sorted[i] - sorted[j];
      for (int a = 0; a < Dim; ++a)
        if (periodic[a]) {
          const Real length = Real(hi[a] - lo[a]);
          d[a] -= length * std::rint(d[a] / length);
        }
      if (d.squaredNorm() < support2) {
        expected.insert(j);
        if (sorted_phase[j] != Phase::boundary) expected_moving.insert(j);
      }
    }
    ASSERT_EQ(found, expected) << "particle " << i;
    ASSERT_EQ(found_of, expected) << "particle " << i;  // positions equal the sorted ones here
    ASSERT_EQ(found_moving, expected_moving) << "particle " << i;
    if (sorted_phase[i] != Phase::boundary) {
      std::set<std::uint32_t> listed;
      // The list holds the neighbours within the list radius; those within the support are these.
      const std::uint32_t* entries = list_view.entries(std::uint32_t(i));
      for (std::uint32_t k = 0; k < list_view.size(std::uint32_t(i)); ++k)
        if (grid.displacement(sorted[i], sorted[entries[k]]).squaredNorm() < support2)
          EXPECT_TRUE(listed.insert(entries[k]).second);
      expected.erase(std::uint32_t(i));
      ASSERT_EQ(listed, expected) << "neighbour list of particle " << i;
    }
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
  typename Backend::template Vector<Phase> phase(5, Phase::water);
  CellSort<double, 2, Backend> cells(lo, hi, {false, false, false}, 0.2);
  cells.sort(position, phase);
  cells.reorder(position, scratch);
  // The three particles of cell (0, 0) keep their original relative order.
  EXPECT_EQ(raw(position)[0], host[1]);
  EXPECT_EQ(raw(position)[1], host[2]);
  EXPECT_EQ(raw(position)[2], host[3]);
  EXPECT_EQ(raw(position)[3], host[4]);
  EXPECT_EQ(raw(position)[4], host[0]);
}

TEST(NeighbourGrid, MovingParticlesBeforeDummies) {
  using Backend = OmpBackend;
  std::array<double, 3> lo{0, 0, 0}, hi{1, 1, 0};
  std::vector<Vec<double, 2>> host = {{0.1, 0.1}, {0.11, 0.1}, {0.12, 0.1}, {0.93, 0.1}, {0.5, 0.5}};
  std::vector<Phase> kinds = {Phase::boundary, Phase::water, Phase::boundary, Phase::soil, Phase::boundary};
  typename Backend::template Vector<Vec<double, 2>> position(host.begin(), host.end()), scratch;
  typename Backend::template Vector<Phase> phase(kinds.begin(), kinds.end()), phase_scratch;
  CellSort<double, 2, Backend> cells(lo, hi, {false, false, false}, 0.2);
  cells.sort(position, phase);
  cells.reorder(position, scratch);
  cells.reorder(phase, phase_scratch);
  // Moving particles by cell, then dummy particles by cell.
  EXPECT_EQ(raw(position)[0], host[1]);
  EXPECT_EQ(raw(position)[1], host[3]);
  EXPECT_EQ(raw(position)[2], host[0]);
  EXPECT_EQ(raw(position)[3], host[2]);
  EXPECT_EQ(raw(position)[4], host[4]);
  EXPECT_EQ(raw(phase)[2], Phase::boundary);
}

TEST(NeighbourGrid, RejectsPeriodicAxisShorterThanThreeSupports) {
  EXPECT_THROW((CellSort<double, 2, OmpBackend>({0, 0, 0}, {0.05, 1, 0}, {true, false, false}, 0.02)),
               std::invalid_argument);
}

}  // namespace
}  // namespace cascade
