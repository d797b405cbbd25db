// BlockArrowLU against a dense LU of the same matrix.
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "model/engine/block_arrow_lu.h"

namespace turbodyn {
namespace {

// A random, well-conditioned block-arrow matrix: diagonal blocks, border rows and columns, zeros elsewhere.
Eigen::MatrixXd block_arrow(const std::vector<int>& blocks, int border, unsigned seed) {
  int n = border;
  for (int s : blocks) n += s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  int o = 0;
  for (int s : blocks) {
    for (int i = 0; i < s; ++i)
      for (int j = 0; j < s; ++j) A(o + i, o + j) = u(rng);
    o += s;
  }
  for (int i = 0; i < n; ++i)
    for (int j = o; j < n; ++j) A(i, j) = u(rng), A(j, i) = u(rng);
  A.diagonal().array() += 4.0;
  return A;
}

TEST(BlockArrowLU, SolvesLikeADenseLUForBlocksWithAndWithoutBorder) {
  constexpr double kTolerance = 1e-12;
  const std::vector<std::pair<std::vector<int>, int>> cases = {
      {{9, 9, 9, 9, 9, 9, 9, 9}, 10}, {{9, 9, 9}, 0}, {{}, 7}, {{3, 5}, 1}};
  unsigned seed = 1;
  for (const auto& [blocks, border] : cases) {
    const Eigen::MatrixXd A = block_arrow(blocks, border, seed++);
    const int n = static_cast<int>(A.rows());
    BlockArrowLU lu(n, blocks, 4);
    ASSERT_TRUE(lu.compute(A));
    const Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, 4);
    Eigen::MatrixXd x = b;
    lu.solve_in_place(x);
    const Eigen::MatrixXd reference = A.partialPivLu().solve(b);
    EXPECT_LT((x - reference).cwiseAbs().maxCoeff(), kTolerance * reference.cwiseAbs().maxCoeff())
        << blocks.size() << " blocks, border " << border;
    Eigen::VectorXd v = b.col(0);  // one column, as the Newton solve gives it
    lu.solve_in_place(v);
    EXPECT_LT((v - reference.col(0)).cwiseAbs().maxCoeff(), kTolerance * reference.cwiseAbs().maxCoeff());
  }
}

TEST(BlockArrowLU, ReportsASingularBlock) {
  Eigen::MatrixXd A = block_arrow({4, 4}, 3, 7);
  A.block(4, 4, 4, 4).setZero();  // the second diagonal block
  BlockArrowLU lu(11, {4, 4}, 1);
  EXPECT_FALSE(lu.compute(A));
}

TEST(BlockArrowLU, RefusesBlocksLargerThanTheMatrix) { EXPECT_THROW(BlockArrowLU(5, {3, 3}, 1), std::invalid_argument); }

}  // namespace
}  // namespace turbodyn
